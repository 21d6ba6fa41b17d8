"""A SIGKILL at every step of a commit leaves the output folder whole.

``onefold build`` and ``onefold site`` run as real processes that send
themselves SIGKILL (``ONEFOLD_TEST_KILL``) at one pause point, for every
pause point the command passes (listed first by a run with
``ONEFOLD_TEST_PAUSE=*``). After each kill, the files of every design (and of
the site) in the output folder all come from one build, the old one or the
new one; a set without its marker ``NAME.incomplete`` is complete; the user's
own file is untouched. The next run into the folder finishes the commit (or
drops a commit that had not begun), says so in one line, and leaves no
staging folder.

The processes are forked from one Python process that has imported the
package and its CAD libraries once (:class:`Forker`), so that each run costs
its own work only (a fresh ``onefold site`` spends seconds importing
build123d); each is still a process of its own, killed by the kernel.
"""

from __future__ import annotations

import json
import os
import select
import shutil
import subprocess
import sys
from collections.abc import Iterator, Sequence
from pathlib import Path

import pytest

#: Run in the forking process: import once, then fork a child per request line.
_FORKER = r"""
import json, os, sys, traceback
for name in sys.argv[1:]:
    __import__(name)
from onefold_cad.cli.main import main
for line in sys.stdin:
    req = json.loads(line)
    pid = os.fork()
    if pid == 0:
        os.environ.update(req["env"])
        fd = os.open(os.devnull, os.O_RDONLY)
        os.dup2(fd, 0)
        for k, suffix in ((1, ".stdout"), (2, ".stderr")):
            fd = os.open(req["log"] + suffix, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
            os.dup2(fd, k)
        rc = 70  # a traceback: the child must never go on to read the requests
        try:
            rc = main(req["argv"])
            sys.stdout.flush()
        except BaseException:
            traceback.print_exc()
        finally:
            os._exit(rc)
    _, status = os.waitpid(pid, 0)
    print(json.dumps({"code": os.waitstatus_to_exitcode(status)}), flush=True)
os._exit(0)  # no clean-up of the imported libraries: nothing to keep
"""


class Forker:
    """A Python process that has imported ``modules``; :meth:`run` forks a
    child of it that runs ``onefold ARGV`` (``main``) and returns its exit
    code (negative: killed by that signal), stdout and stderr."""

    def __init__(self, logs: Path, modules: Sequence[str]) -> None:
        env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
        env.pop("ONEFOLD_TEST_PAUSE", None)
        env.pop("ONEFOLD_TEST_KILL", None)
        self.proc = subprocess.Popen(
            [sys.executable, "-c", _FORKER, *modules],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
            env=env,
        )
        self.logs = logs
        self.count = 0

    def run(self, *argv: str, **env: str) -> tuple[int, str, str]:
        self.count += 1
        log = self.logs / f"run{self.count}"
        assert self.proc.stdin is not None and self.proc.stdout is not None
        self.proc.stdin.write(json.dumps({"argv": argv, "env": env, "log": str(log)}) + "\n")
        self.proc.stdin.flush()
        ready, _, _ = select.select([self.proc.stdout], [], [], 300)
        assert ready, f"onefold {' '.join(argv)} ran for over 300 s"
        line = self.proc.stdout.readline()
        assert line, "the forking process died"
        code = json.loads(line)["code"]
        out = Path(f"{log}.stdout").read_text(encoding="utf-8")
        err = Path(f"{log}.stderr").read_text(encoding="utf-8")
        return code, out, err

    def close(self) -> None:
        assert self.proc.stdin is not None
        self.proc.stdin.close()
        try:
            self.proc.wait(timeout=60)
        except subprocess.TimeoutExpired:  # a child hangs: the test has failed already
            self.proc.kill()
            self.proc.wait()


@pytest.fixture
def forker(tmp_path: Path, request: pytest.FixtureRequest) -> Iterator[Forker]:
    logs = tmp_path / "logs"
    logs.mkdir()
    f = Forker(logs, request.param)
    try:
        yield f
    finally:
        f.close()


# -- what a reader of the folder sees ------------------------------------------------------
def _content(path: Path) -> bytes | object:
    """A file's content, the JSON reports without their timings (the one part
    two builds of one design do not share)."""
    if path.suffix == ".json":
        data = json.loads(path.read_text(encoding="utf-8"))
        data.pop("timings_s", None)
        return data
    return path.read_bytes()


def files_of(folder: Path, stem: str) -> dict[str, object]:
    """The files of the design (or site) ``stem`` in ``folder``, by name:
    ``STEM.*`` and ``STEM-*`` except its marker."""
    if not folder.is_dir():
        return {}
    return {
        p.name: _content(p)
        for p in folder.iterdir()
        if p.is_file()
        and (p.name.startswith(f"{stem}.") or p.name.startswith(f"{stem}-"))
        and p.name != f"{stem}.incomplete"
    }


def check_one_build(out: Path, sub: str, stem: str, refs: dict[str, Path]) -> str | None:
    """The build (a key of ``refs``, each a reference output folder) that
    every file of ``stem`` in ``out/sub`` comes from (None: no file); without
    the marker, the set must be that build's whole set. Fails on a mixed set."""
    folder = out / sub
    have = files_of(folder, stem)
    sets = {label: files_of(ref / sub, stem) for label, ref in refs.items()}
    origins = {label for label, files in sets.items() if have.items() <= files.items()}
    assert origins, f"{folder}: the files of {stem} come from more than one build: {sorted(have)}"
    if not (folder / f"{stem}.incomplete").exists():
        complete = [label for label in sorted(origins) if have == sets[label]]
        assert complete, f"{folder}: {stem}'s set is incomplete and has no marker: {sorted(have)}"
        return complete[0]
    return None


def pause_points(err: str) -> list[str]:
    prefix = "onefold-test: point "
    return [line[len(prefix) :] for line in err.splitlines() if line.startswith(prefix)]


def stale(folder: Path) -> list[Path]:
    return sorted(folder.glob(".onefold-*"))


def kill_at_every_point(
    forker: Forker,
    tmp_path: Path,
    argv: Sequence[str],
    old: Path,
    new: Path,
    stems: dict[str, Sequence[str]],
    minimum: Sequence[str],
) -> list[str]:
    """Kill ``onefold ARGV -o OUT`` at each of its pause points, OUT holding
    the ``old`` build's files and a file of the user's; check what a reader
    sees (``stems``: the sets in each folder, '' for OUT itself) and
    what the next run into OUT leaves. Returns the points, listed by a first
    run that also removes a dead run's staging folder and says so."""
    refs = {"old": old, "new": new}
    for sub, names in stems.items():
        for stem in names:  # every file tells its build: the two builds share none
            was, now = files_of(old / sub, stem), files_of(new / sub, stem)
            assert was and now and all(was[n] != now[n] for n in was.keys() & now.keys())

    def fresh(name: str) -> Path:
        out = tmp_path / name / "out"
        shutil.copytree(old, out)
        (out / "mine.txt").write_text("the user's own file\n")
        return out

    trace = fresh("trace")
    dead = trace / ".onefold-dead0000.partial"  # a run that died before its commit
    (dead / "1").mkdir(parents=True)
    (dead / "lock").write_text("")
    (dead / "1" / "half.step").write_bytes(b"\0" * 3_000_000)
    code, _, err = forker.run(*argv, "-o", str(trace), ONEFOLD_TEST_PAUSE="*")
    assert code == 0, err
    said = [line for line in err.splitlines() if not line.startswith("onefold-test: ")]
    assert said[0] == (
        f"onefold: warning: removed {str(dead)!r} (3.0 MB), the staging folder of an earlier "
        "run that stopped before its commit"
    )
    # and the old files of formats the new build does not write, in one line
    gone = {
        str(trace / sub / name)
        for sub, names in stems.items()
        for stem in names
        for name in files_of(old / sub, stem).keys() - files_of(new / sub, stem).keys()
    }
    head, tail = (
        "onefold: warning: removed ",
        ": left by an earlier run, not written by this one (they would not match its files)",
    )
    assert len(said) == 2 and said[1].startswith(head) and said[1].endswith(tail), said
    assert set(said[1][len(head) : -len(tail)].split(", ")) == gone
    assert stale(trace) == []
    for sub, names in stems.items():
        for stem in names:
            assert check_one_build(trace, sub, stem, refs) == "new"
    points = pause_points(err)
    assert set(minimum) <= set(points), points
    for point in points:
        out = fresh(point.replace(":", "-"))
        code, _, err = forker.run(*argv, "-o", str(out), ONEFOLD_TEST_KILL=point)
        assert code == -9, (point, code, err)
        for sub, names in stems.items():
            for stem in names:
                check_one_build(out, sub, stem, refs)
        assert (out / "mine.txt").read_text() == "the user's own file\n"
        (stage,) = stale(out)
        # the next run into the folder (any design) finishes or drops the commit
        code, _, err = forker.run(
            "build", "paper-square", "--formats", "json", "-q", "-o", str(out)
        )
        assert code == 0, err
        lines = err.splitlines()
        assert len(lines) == 1 and str(stage.name) in lines[0], (point, lines)
        begun = point != "staged"
        words = "finished an interrupted earlier build" if begun else "stopped before its commit"
        assert lines[0].startswith("onefold: warning: ") and words in lines[0], lines
        assert stale(out) == []
        for sub, names in stems.items():
            for stem in names:
                got = check_one_build(out, sub, stem, refs)
                assert got == ("new" if begun else "old"), (point, stem, got)
        assert (out / "mine.txt").read_text() == "the user's own file\n"
    return points


def design_file(path: Path, name: str, alpha: float) -> Path:
    text = (Path(__file__).parents[2] / "templates" / "paper-square.toml").read_text()
    text = text.replace('name = "paper-square"', f'name = "{name}"')
    text = text.replace("alpha = 40.0", f"alpha = {alpha}")
    assert f'name = "{name}"' in text and f"alpha = {alpha}" in text
    path.write_text(text, encoding="utf-8")
    return path


#: What a build of DXF, bend sheet and report imports (the forking process imports it once).
BUILD_MODULES = [
    "ezdxf",
    "onefold_cad.cli.build",
    "onefold_cad.design",
    "onefold_cad.export.atomic",
    "onefold_cad.export.bend_csv",
    "onefold_cad.export.dxf",
    "onefold_cad.export.report_file",
    "onefold_cad.export.writers",
    "onefold_cad.fabrication.bend_table",
    "onefold_cad.fabrication.flat_pattern",
    "onefold_cad.fabrication.report",
    "onefold_cad.geometry.placement",
    "onefold_cad.sweep.measures",
]


@pytest.mark.parametrize("forker", [BUILD_MODULES], indirect=True)
def test_a_build_killed_at_any_step_of_its_commit_leaves_no_mixed_set(forker, tmp_path):
    """Two designs into one folder: the old build wrote four files each, the
    new one writes three (the cut DXF is no longer asked for, so the commit
    removes it too: it would not match the new DXF)."""
    src = tmp_path / "src"
    src.mkdir()
    old = [
        str(design_file(src / f"old-{n}.toml", n, a)) for n, a in (("left", 40.0), ("right", 41.0))
    ]
    new = [
        str(design_file(src / f"new-{n}.toml", n, a)) for n, a in (("left", 42.0), ("right", 43.0))
    ]
    ref = {}
    for label, templates, formats in (
        ("old", old, "dxf,cut,bends,json"),
        ("new", new, "dxf,bends,json"),
    ):
        ref[label] = tmp_path / f"ref-{label}"
        code, _, err = forker.run(
            "build", *templates, "--formats", formats, "-q", "-o", str(ref[label])
        )
        assert code == 0, err
    assert files_of(ref["old"], "left").keys() != files_of(ref["new"], "left").keys()
    argv = ["build", *new, "--formats", "dxf,bends,json", "-q"]
    points = kill_at_every_point(
        forker,
        tmp_path,
        argv,
        ref["old"],
        ref["new"],
        {"": ["left", "right"]},
        ["staged", "mark:2", "retire:8", "commit:6", "unmark:2"],
    )
    assert len(points) == 1 + 2 + 8 + 6 + 2


SITE = """name = "pair"
units = "mm"
[[sheet]]
name = "west"
template = "paper-square"
flags = {{ thickness = 0.0, alpha = {alpha} }}
x = 0.0
y = 0.0
rotation = 0.0
"""

#: What a site's run imports (the forking process imports it once).
SITE_MODULES = [
    *BUILD_MODULES,
    "build123d",
    "onefold_cad.export.part",
    "onefold_cad.export.site_clearance",
    "onefold_cad.export.site_writers",
    "onefold_cad.export.site_order",
    "onefold_cad.cli.site",
]


@pytest.mark.parametrize("forker", [SITE_MODULES], indirect=True)
def test_a_site_killed_at_any_step_of_its_commit_leaves_no_mixed_set(forker, tmp_path):
    """A site (one sheet, to keep it fast: its files in DIR/NAME/) and the
    site's own files: the old site wrote the sheet's bend sheet and report,
    the new one its report only (so the old bend sheet goes too)."""
    ref = {}
    for label, alpha, sheet_formats in (("old", 40.0, "bends,json"), ("new", 42.0, "json")):
        site = tmp_path / f"{label}.toml"
        site.write_text(SITE.format(alpha=alpha), encoding="utf-8")
        ref[label] = tmp_path / f"ref-{label}"
        argv = ["site", str(site), "--formats", "order,json", "--sheet-formats", sheet_formats]
        code, _, err = forker.run(*argv, "-q", "-o", str(ref[label]))
        assert code == 0, err
    assert (
        files_of(ref["old"] / "west", "west").keys() != files_of(ref["new"] / "west", "west").keys()
    )
    argv = [
        "site",
        str(tmp_path / "new.toml"),
        "--formats",
        "order,json",
        "--sheet-formats",
        "json",
        "-q",
    ]
    points = kill_at_every_point(
        forker, tmp_path, argv, ref["old"], ref["new"],
        {"": ["pair"], "west": ["west"]},
        ["staged", "mark:2", "retire:4", "commit:3", "unmark:2"],
    )  # fmt: skip
    assert len(points) == 1 + 2 + 4 + 3 + 2
