"""The README's and the docs' ``onefold build templates/...`` commands, run as
written (the shell's glob expanded from the repository's root) by the
installed ``onefold``: the output folder is the test's, and ``--formats
json`` is added to keep it to seconds (what made them fail was reading the
folder's site file; the writers are tested in tests/export/)."""

from __future__ import annotations

import glob
import re
import shlex
import subprocess

import pytest

from tests.cli.test_main import ONEFOLD, REPO
from tests.shipped import DESIGN_TEMPLATES, REPO_TEMPLATES

PAGES = [REPO / "README.md", *sorted((REPO / "docs").glob("*.md"))]
SITE_FILES = sorted(p.name for p in REPO_TEMPLATES.glob("site-*.toml"))


def _commands() -> list[tuple[str, str]]:
    """``(page, line)`` of each ``onefold build`` line of a ``sh`` block that
    names files of ``templates/``."""
    out = []
    for page in PAGES:
        text = page.read_text(encoding="utf-8")
        for block in re.findall(r"```sh\n(.*?)```", text, flags=re.S):
            for line in block.replace("\\\n", " ").splitlines():
                if "templates/" not in line or " build " not in line:
                    continue
                words = shlex.split(line, comments=True)
                if len(words) > 2 and words[0].endswith("onefold") and words[1] == "build":
                    if any(w.startswith("templates/") for w in words):
                        out.append((page.name, line.strip()))
    return out


COMMANDS = _commands()


def test_the_docs_show_the_commands_this_file_runs():
    pages = {page for page, _ in COMMANDS}
    assert {"README.md", "cli.md", "fabrication.md"} <= pages, COMMANDS


@pytest.mark.parametrize(("page", "line"), COMMANDS, ids=[f"{p}:{c}" for p, c in COMMANDS])
def test_a_docs_build_command_of_the_templates_folder_runs_as_written(page, line, tmp_path):
    words = shlex.split(line, comments=True)
    args: list[str] = []
    for w in words[1:]:
        args.extend(sorted(glob.glob(w, root_dir=REPO)) if "*" in w else [w])
    out = tmp_path / "out"
    args[args.index("-o") + 1] = str(out)
    proc = subprocess.run(
        [ONEFOLD, *args, "--formats", "json"],
        cwd=REPO, capture_output=True, text=True, timeout=300, check=False,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    assert sorted(p.stem for p in out.glob("*.json")) == DESIGN_TEMPLATES
    # the site file is named, once, as what it is; nothing else is said
    lines = [ln for ln in proc.stderr.splitlines() if not ln.startswith("[")]
    assert len(lines) == len(SITE_FILES), proc.stderr
    for name, ln in zip(SITE_FILES, lines, strict=True):
        assert ln.startswith(f"onefold: warning: skipped templates/{name}: a site file")
        assert f"onefold site templates/{name}" in ln
