"""The installed ``onefold`` command, run as a user runs it (subprocess)."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from onefold_cad import ExportError, build_design
from onefold_cad.cli import main
from onefold_cad.export.report import design_report
from onefold_cad.templates import list_templates, load_template

REPO = Path(__file__).resolve().parent.parent
BIN = Path(sys.executable).parent / "onefold"
ONEFOLD = str(BIN) if BIN.exists() else shutil.which("onefold")
SUFFIXES = (".step", ".dxf", ".json", "-3d.png", "-flat.svg")


def run(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    assert ONEFOLD, "the onefold console script is not installed"
    return subprocess.run(
        [ONEFOLD, *args], capture_output=True, text=True, cwd=cwd, timeout=300, check=False
    )


def no_traceback(proc: subprocess.CompletedProcess[str]) -> None:
    assert "Traceback" not in proc.stderr and "Traceback" not in proc.stdout


# -- help and listing ------------------------------------------------------------
@pytest.mark.parametrize("cmd", [[], ["build"], ["solve"], ["templates"]])
def test_help_on_every_command(cmd):
    proc = run(*cmd, "--help")
    assert proc.returncode == 0, proc.stderr
    assert "Usage" in proc.stdout
    if cmd == ["build"]:
        for flag in ("--alpha", "--x-minus", "--polygon", "--rectangle", "--relief-hole", "--name"):
            assert flag in proc.stdout


def test_python_dash_m_is_the_same_command():
    proc = subprocess.run(
        [sys.executable, "-m", "onefold_cad", "templates"], capture_output=True, text=True
    )
    assert proc.returncode == 0
    assert proc.stdout == run("templates").stdout


def test_templates_lists_one_line_each():
    proc = run("templates")
    assert proc.returncode == 0
    lines = proc.stdout.splitlines()
    infos = list_templates()
    assert len(lines) == len(infos) >= 8
    for line, info in zip(lines, infos, strict=True):
        name, desc = line.split(maxsplit=1)
        assert name == info.name and desc == info.description


# -- solve -------------------------------------------------------------------------
def test_solve_json_matches_the_library(tmp_path):
    proc = run("solve", "table1-row4", "--json", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    rep = json.loads(proc.stdout)
    design = load_template("table1-row4")
    lib = design_report(design, build_design(design))
    for key in ("apex_height", "fold_angles_deg", "bend", "flat_size", "relief_hole_diameter"):
        assert rep[key] == pytest.approx(lib[key]) if key != "bend" else rep[key] == lib[key]
    assert rep["files"] == [] and list(tmp_path.iterdir()) == []


def test_solve_flags_override_the_template():
    # Table 1 row 1 with row 3's angles is row 3 (same square sheet).
    a = json.loads(run("solve", "table1-row1", "--alpha", "32", "--beta", "34", "--json").stdout)
    b = json.loads(run("solve", "table1-row3", "--json").stdout)
    assert a["apex_height"] == pytest.approx(b["apex_height"], rel=1e-12)
    assert a["fold_angles_deg"] == pytest.approx(b["fold_angles_deg"], rel=1e-12)
    c = json.loads(run("solve", "table1-row1", "--sheet-surface", "OUTSIDE", "--json").stdout)
    assert c["inputs"]["material"]["sheet_surface"] == "OUTSIDE"
    assert b["inputs"]["material"]["sheet_surface"] == "MID"


def test_solve_sheet_flags_units_and_human_output():
    quad = ["--x-plus", "30", "--x-minus", "20", "--y-plus", "25", "--y-minus", "15"]
    # Without a template the flags change the default template (its material included).
    proc = run("solve", "--model", "paper", *quad, "--units", "in", "--thickness", "0.05")
    assert proc.returncode == 0, proc.stderr
    assert "paper model, in" in proc.stdout and "apex height" in proc.stdout
    rep = json.loads(run("solve", "--model", "paper", *quad, "--units", "in", "--json").stdout)
    assert rep["inputs"]["sheet"] == {
        "quadrilateral": {"x_plus": 30.0, "x_minus": 20.0, "y_plus": 25.0, "y_minus": 15.0}
    }
    assert rep["units"] == "in" and len(rep["gammas_deg"]) == rep["inputs"]["frame"]["divisions"]
    poly = run("solve", "--polygon", "300,0;100,200;-200,100;-200,-100;100,-200", "--json")
    assert json.loads(poly.stdout)["sheet"]["vertices"][0] == [300.0, 0.0]
    rect = run("solve", "--rectangle", "3000x2000", "--apex-fraction", "0.3", "--json")
    rep = json.loads(rect.stdout)
    assert rep["sheet"]["size"] == pytest.approx([3000, 2000])
    assert rep["inputs"]["sheet"]["rectangle"]["apex_fraction"] == 0.3


# -- build ---------------------------------------------------------------------------
def test_build_one_template_with_a_name(tmp_path):
    out = tmp_path / "out"
    proc = run("build", "table1-row2", "-o", str(out), "--name", "row2", "--model", "exact")
    assert proc.returncode == 0, proc.stderr
    assert sorted(p.name for p in out.iterdir()) == sorted(f"row2{s}" for s in SUFFIXES)
    rep = json.loads((out / "row2.json").read_text())
    assert sorted(rep["files"]) == sorted(f"row2{s}" for s in SUFFIXES)
    assert rep["model"] == "exact" and rep["name"] == "row2"
    for p in out.iterdir():
        assert p.stat().st_size > 0
    assert proc.stdout.split() == [str(out / f) for f in rep["files"]]


def test_every_template_builds_in_one_call_with_progress(tmp_path):
    names = [t.name for t in list_templates()]
    proc = run("build", *names, "-o", str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    progress = [line for line in proc.stderr.splitlines() if line.startswith("[")]
    assert [p.split()[0] for p in progress if "done" in p] == [
        f"[{i}/{len(names)}]" for i in range(1, len(names) + 1)
    ]
    written = {p.name for p in tmp_path.iterdir()}
    assert written == {f"{n}{s}" for n in names for s in SUFFIXES}
    for n in names:
        rep = json.loads((tmp_path / f"{n}.json").read_text())
        assert rep["angle_condition_error_deg"] < 1e-6
        assert rep["developability"]["area_rel_error"] < 1e-3


# -- bad input: exit 2, one line, no file ------------------------------------------------
BAD = [
    (["--alpha", "95"], "alpha", "(0, 90)"),
    (["--beta", "0"], "beta", "(0, 90)"),
    (["--alpha", "nan"], "alpha", "finite"),
    (["--alpha", "abc"], "alpha", "number"),
    (["table1-row1", "--hc", "200"], "hc", "h_c in"),
    (["--radius", "-1"], "radius", "> 0"),
    (["--divisions", "0"], "divisions", "[1, "),
    (["table1-row1", "--x-plus", "-3"], "x-plus", "> 0"),
    (["--x-plus", "3"], "x-minus", "missing"),
    (["--polygon", "1,1;-1,-1;1,-1;-1,1"], "polygon", "self-intersects"),
    (["--polygon", "1,1;2,1;2,2"], "polygon", "inside"),
    (["--polygon", "1,2;3"], "polygon", "x,y"),
    (["--rectangle", "3x"], "rectangle", "WIDTHxHEIGHT"),
    (["--rectangle", "0x2"], "rectangle", "> 0"),
    (["--apex-fraction", "1.5"], "apex-fraction", "(0, 1)"),
    (["table1-row1", "--apex-fraction", "0.5"], "apex-fraction", "rectangle"),
    (["--polygon", "1,0;0,1;-1,0", "--rectangle", "2x2"], "rectangle", "combined"),
    (["--thickness", "-1"], "thickness", ">= 0"),
    (["--k-factor", "2"], "k-factor", "[0, 1]"),
    (["--kerf", "-0.1"], "kerf", ">= 0"),
    (["--relief-hole", "1e6"], "relief-hole", "must be <"),
    (["--density", "0"], "density", "> 0"),
    (["--units", "furlong"], "units", "mm"),
    (["--sheet-surface", "TOP"], "sheet-surface", "INSIDE"),
    (["--model", "fan"], "model", "exact"),
    (["--alpah", "3"], "alpah", "option"),
    (["no-such-template"], "template", "no such file"),
]


# Only build makes the STEP solid, whose relief hole must clear the apex.
BUILD_ONLY = [
    (["--body", "mesh"], "body", "'auto', 'solid', 'shell'"),
    (
        ["table1-row1", "--model", "exact", "--thickness", "3", "--sheet-surface", "INSIDE"]
        + ["--relief-hole", "9"],
        "relief_hole",
        "must be in (11.88",
    ),
    (["paper-square", "--body", "solid"], "relief_hole", "got 0"),
    (["table1-row1", "--thickness", "3", "--body", "solid"], "model", "'exact'"),
    (["table1-row1", "--model", "exact", "--thickness", "150"], "thickness", "too thick"),
]

# build runs every case (it is the command that writes files); solve a sample of them.
CASES = [("build", *b) for b in BAD + BUILD_ONLY] + [("solve", *b) for b in BAD[::5]]


@pytest.mark.parametrize(
    ("command", "args", "param", "words"), CASES, ids=[f"{c[0]} {' '.join(c[1])}" for c in CASES]
)
def test_bad_input_exits_2_with_one_line_and_no_file(tmp_path, command, args, param, words):
    out = tmp_path / "out"
    extra = ["-o", str(out)] if command == "build" else []
    proc = run(command, *args, *extra, cwd=tmp_path)
    assert proc.returncode == 2, (proc.stdout, proc.stderr)
    no_traceback(proc)
    lines = proc.stderr.splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith("onefold: error: ")
    assert param in lines[0] and words in lines[0], lines[0]
    assert proc.stdout == ""
    assert list(tmp_path.iterdir()) == []


def test_bad_template_file_names_the_key(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(
        (REPO / "templates" / "table1-row1.toml").read_text().replace("alpha =", "alpah =")
    )
    proc = run("build", str(bad), "-o", str(tmp_path / "out"))
    assert proc.returncode == 2
    assert proc.stderr.count("\n") == 1 and "frame.alpah: unknown key" in proc.stderr
    assert str(bad) in proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]


def test_name_needs_one_template_and_a_safe_name(tmp_path):
    two = run("build", "table1-row1", "table1-row2", "--name", "x", "-o", str(tmp_path / "o"))
    assert two.returncode == 2 and "--name" in two.stderr
    unsafe = run("build", "table1-row1", "--name", "a b", "-o", str(tmp_path / "o"))
    assert unsafe.returncode == 2 and "--name" in unsafe.stderr
    assert list(tmp_path.iterdir()) == []


def test_a_failing_export_leaves_no_file_of_that_design(tmp_path, monkeypatch, capsys):
    """STEP succeeds, then the DXF fails: nothing of the design may stay behind."""
    import onefold_cad.export.dxf as dxf

    def boom(*args, **kwargs):
        raise ExportError("disk full (simulated)")

    monkeypatch.setattr(dxf, "export_design_dxf", boom)
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("mine")
    assert main(["build", "table1-row1", "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1] == "onefold: error: disk full (simulated)"
    assert sorted(p.name for p in out.iterdir()) == ["keep.txt"]  # no staging folder either


def test_a_late_failure_leaves_no_file_of_any_design(tmp_path, monkeypatch, capsys):
    """The second design's export fails: the first design's files must not appear either."""
    import onefold_cad.export.preview as preview

    real = preview.render_folded_preview

    def second_fails(folded, path, **kw):
        if "star" in str(path):
            raise ExportError("preview failed (simulated)")
        return real(folded, path, **kw)

    monkeypatch.setattr(preview, "render_folded_preview", second_fails)
    out = tmp_path / "new"
    assert main(["build", "table1-row1", "star-polygon", "-o", str(out)]) == 2
    assert capsys.readouterr().err.strip().splitlines()[-1].endswith("(simulated)")
    assert not out.exists()  # the folder the command created is gone again


def test_main_returns_exit_codes():
    assert main(["templates"]) == 0
    assert main(["solve", "--beta", "90"]) == 2
    assert main(["--help"]) == 0
