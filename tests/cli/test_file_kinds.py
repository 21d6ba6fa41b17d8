"""A site file given where a design template goes (``build``, ``solve``,
``sweep``, ``explore``) and a design given to ``site``: refused in one line
that says what the file is and which command builds it; nothing written."""

from __future__ import annotations

import pytest

from onefold_cad.cli.main import main
from tests.shipped import DESIGN_TEMPLATES, REPO_TEMPLATES

SITE = "site-patkau-three"
SITE_PATH = REPO_TEMPLATES / f"{SITE}.toml"
DESIGN_PATH = REPO_TEMPLATES / "paper-square.toml"


def one_error(capfd, argv: list[str]) -> str:
    """Run ``argv`` in this process: exit 2, nothing on stdout, one error line."""
    capfd.readouterr()
    rc = main(argv)
    out, err = capfd.readouterr()
    lines = [ln for ln in err.splitlines() if not ln.startswith("[")]
    assert rc == 2 and out == "", (rc, out, err)
    assert len(lines) == 1 and lines[0].startswith("onefold: error: "), err
    return lines[0]


@pytest.mark.parametrize(
    "argv",
    [
        ["build", str(SITE_PATH), "-o", "OUT"],
        ["build", str(SITE_PATH), str(SITE_PATH), "-o", "OUT"],
        ["solve", str(SITE_PATH)],
        ["sweep", str(SITE_PATH), "--vary", "alpha=20,30", "-o", "OUT"],
    ],
    ids=["build", "build-twice", "solve", "sweep"],
)
def test_a_site_file_given_as_a_design_is_named_a_site_file(capfd, tmp_path, argv):
    argv = [str(tmp_path / "out") if a == "OUT" else a for a in argv]
    line = one_error(capfd, argv)
    assert f"{SITE_PATH}: a site file (it has [[sheet]] tables)" in line
    assert line.endswith(f"build it with onefold site {SITE_PATH}")
    assert not (tmp_path / "out").exists()


def test_a_shipped_site_s_name_given_as_a_design_is_named_a_shipped_site(capfd, tmp_path):
    line = one_error(capfd, ["build", SITE, "-o", str(tmp_path / "out")])
    assert line.endswith(f"{SITE}: a shipped site, not a design template: "
                         f"build it with onefold site {SITE}")  # fmt: skip


def test_a_design_given_to_site_is_named_a_design_template(capfd, tmp_path):
    line = one_error(capfd, ["site", str(DESIGN_PATH), "-o", str(tmp_path / "out")])
    assert f"{DESIGN_PATH}: a design template" in line
    assert line.endswith(f"build it with onefold build {DESIGN_PATH}")
    name = DESIGN_TEMPLATES[0]
    line = one_error(capfd, ["site", name, "-o", str(tmp_path / "out")])
    assert line.endswith(f"{name}: a shipped design template, not a site: "
                         f"build it with onefold build {name}")  # fmt: skip
    assert not (tmp_path / "out").exists()


def test_build_leaves_a_site_file_out_of_several_with_one_warning(capfd, tmp_path):
    out = tmp_path / "out"
    capfd.readouterr()
    rc = main(["build", str(DESIGN_PATH), str(SITE_PATH), "-o", str(out), "--formats", "json"])
    stdout, err = capfd.readouterr()
    lines = [ln for ln in err.splitlines() if not ln.startswith("[")]
    assert rc == 0 and stdout.split() == [str(out / "paper-square.json")]
    assert lines == [
        f"onefold: warning: skipped {SITE_PATH}: a site file (it has [[sheet]] tables), not a "
        f"design template: build it with onefold site {SITE_PATH}"
    ]
