"""The installed ``onefold`` command, run as a user runs it (subprocess), and
``main()`` in this process where a failure has to be injected."""

from __future__ import annotations

import csv
import fcntl
import importlib.metadata
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from onefold_cad import ExportError, fold_design
from onefold_cad.cli.main import main
from onefold_cad.fabrication.report import design_report
from onefold_cad.templates import list_templates, load_template
from tests.processes import interruptible
from tests.shipped import REPO_TEMPLATES

REPO = Path(__file__).resolve().parents[2]
BIN = Path(sys.executable).parent / "onefold"
ONEFOLD = str(BIN) if BIN.exists() else shutil.which("onefold")
SUFFIXES = (
    ".step", ".dxf", "-cut.dxf", "-bends.csv", ".fold", ".glb", ".3dm", ".json", "-3d.png",
    "-flat.svg",
)  # fmt: skip
HEAVY = ("build123d", "OCP", "matplotlib", "ezdxf", "scipy.spatial", "typer", "rich", "pydantic",
         "pyarrow", "dask", "distributed")  # fmt: skip


def run(*args: str, cwd: Path | None = None, env: dict | None = None):
    assert ONEFOLD, "the onefold console script is not installed"
    return subprocess.run(
        [ONEFOLD, *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=300,
        check=False,
        env=None if env is None else {**os.environ, **env},
    )


def no_traceback(proc: subprocess.CompletedProcess[str]) -> None:
    assert "Traceback" not in proc.stderr and "Traceback" not in proc.stdout


def refused(proc: subprocess.CompletedProcess[str], param: str, words: str, folder: Path) -> None:
    """Bad input: exit 2, one error line naming ``param`` with ``words``, no
    traceback, nothing on stdout, nothing written in ``folder``."""
    assert proc.returncode == 2, (proc.stdout, proc.stderr)
    no_traceback(proc)
    lines = [ln for ln in proc.stderr.splitlines() if not ln.startswith("onefold: warning: ")]
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith("onefold: error: ")
    assert param in lines[0] and words in lines[0], lines[0]
    assert proc.stdout == ""
    assert list(folder.iterdir()) == []


@pytest.fixture
def solve_json(cli):
    def call(*args: str) -> dict:
        rc, out, err = cli("solve", *args, "--json")
        assert rc == 0, err
        return json.loads(out)

    return call


def staging_dirs(folder: Path) -> list[Path]:
    return sorted(folder.glob(".onefold-*"))


# -- help, version, start-up -----------------------------------------------------------
def test_version_is_the_installed_package_s():
    proc = run("--version")
    assert proc.returncode == 0
    assert proc.stdout.strip() == f"onefold {importlib.metadata.version('onefold_cad')}"


@pytest.mark.parametrize(
    ("cmd", "usage"),
    [
        ([], "usage: onefold [-h] [--version] COMMAND [ARGS]"),
        (["build"], "usage: onefold build [TEMPLATE ...] [options]"),
        (["solve"], "usage: onefold solve [TEMPLATE] [options]"),
        (["templates"], "usage: onefold templates"),
        (
            ["sweep"],
            "usage: onefold sweep [TEMPLATE] --vary NAME=SPEC [--vary ...] -o DIR [options]",
        ),
    ],
)
def test_help_has_a_clean_usage_line(cmd, usage):
    proc = run(*cmd, "--help")
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.splitlines()[0] == usage
    assert "<bool>" not in proc.stdout and "[[" not in proc.stdout
    if cmd == ["build"]:
        for flag in ("--alpha", "--x-minus", "--polygon", "--rectangle", "--relief-hole", "--name",
                     "--formats", "--jobs", "--quiet", "--compensation", "--units"):  # fmt: skip
            assert flag in proc.stdout


def test_build_help_names_every_file_it_writes_and_its_format():
    text = run("build", "--help").stdout
    files = text[text.index("files (--formats") :].splitlines()[1:]
    formats = ("step", "dxf", "cut", "bends", "fold", "glb", "3dm", "json", "png", "svg")
    # one line each, and the cones' forming sheet's (written when named, or
    # by default where the cones are formed past their springback)
    assert len(files) == len(SUFFIXES) + 1 == len(formats) + 1
    (cones,) = [ln for ln in files if " NAME-cones.csv " in ln]
    assert cones.split()[0] == "cones" and "springback" in cones
    for suffix in SUFFIXES:  # the files a build writes (see the build tests)
        (line,) = [ln for ln in files if f" NAME{suffix} " in ln]
        fmt = line.split()[0]
        assert fmt in formats and len(line.split(f"NAME{suffix}", 1)[1].strip()) > 20


def test_no_arguments_prints_the_help():
    proc = run()
    assert proc.returncode == 0 and proc.stdout.startswith("usage: onefold")


@pytest.mark.parametrize(
    "argv",
    [["--help"], ["templates"], ["sweep", "--help"], ["solve", "table1-row4"], ["solve", "--json"]],
)
def test_solve_templates_and_help_import_no_cad_library(argv):
    """Issue 14: the quick commands load numpy and the geometry core only."""
    code = (
        "import io, contextlib, json, sys\n"
        "from onefold_cad.cli.main import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        f"    rc = main({argv!r})\n"
        "print(json.dumps([rc, sorted(sys.modules)]))\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    rc, modules = json.loads(proc.stdout.splitlines()[-1])
    assert rc == 0, proc.stderr
    # scipy.spatial still comes with geometry/resting/placement.py's ConvexHull until the
    # resting placement's own hull (owner: stand) replaces it; nothing else may load.
    pending = {"scipy.spatial"} if argv[0] == "solve" else set()
    loaded = sorted(
        m for m in modules if any(m == h or m.startswith(h + ".") for h in HEAVY) and not any(
            m == p or m.startswith(p + ".") for p in pending)
    )  # fmt: skip
    assert loaded == []
    if argv[0] != "solve":
        assert "numpy" not in modules  # --help and templates need no numpy at all


@pytest.mark.parametrize("template", ["patkau-one-fold", "table1-row4"])
def test_solve_loads_none_of_the_writers_standard_modules(template):
    """solve writes no file: the atomic writer's tempfile and shutil, the bend
    sheet's csv and the derived names' hashlib (with OpenSSL, the slowest of
    them) stay unloaded, and so do json for the text summary and numpy.ma
    (np.unique loads it: the core uses validate.sorted_unique)."""
    code = (
        "import io, contextlib, sys\n"
        "from onefold_cad.cli.main import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        f"    rc = main(['solve', {template!r}])\n"
        "unwanted = ('tempfile', 'shutil', 'csv', 'hashlib', 'json', 'numpy.ma')\n"
        "print(rc, *sorted(m for m in unwanted if m in sys.modules))\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.stdout.split() == ["0"], proc.stderr


def test_python_dash_m_is_the_same_command():
    proc = subprocess.run(
        [sys.executable, "-m", "onefold_cad", "templates"], capture_output=True, text=True
    )
    assert proc.returncode == 0
    assert proc.stdout == run("templates").stdout


def test_templates_lists_one_line_each():
    proc = run("templates")
    assert proc.returncode == 0
    designs, sites = proc.stdout.split("\n\n")
    lines = designs.splitlines()
    infos = list_templates()
    assert len(lines) == len(infos) >= 8
    for line, info in zip(lines, infos, strict=True):
        name, desc = line.split(maxsplit=1)
        assert name == info.name and desc == info.description
    # then the shipped site files, under a heading saying how to build them
    heading, *site_lines = sites.splitlines()
    assert heading == "sites (several sheets on one site: onefold site NAME):"
    shipped = sorted(p.stem for p in REPO_TEMPLATES.glob("site-*.toml"))
    assert [line.split()[0] for line in site_lines] == shipped and shipped
    for line in site_lines:
        name, desc = line.split(maxsplit=1)
        data = tomllib.loads((REPO_TEMPLATES / f"{name}.toml").read_text())
        assert desc == data["description"]


# -- solve -------------------------------------------------------------------------------
def test_solve_json_matches_the_library(tmp_path):
    proc = run("solve", "table1-row4", "--json", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    rep = json.loads(proc.stdout)
    design = load_template("table1-row4")
    lib = design_report(design, fold_design(design))
    for key in ("direction_surface", "fold_angles_deg", "bend", "flat_size", "resting"):
        assert rep[key] == lib[key], key
    assert rep["name"] == "table1-row4" and rep["warnings"] == []
    assert rep["files"] == [] and list(tmp_path.iterdir()) == []


def test_solve_flags_override_the_template(solve_json, cli):
    # Table 1 row 1 with row 3's angles is row 3 (same square sheet).
    a = solve_json("table1-row1", "--alpha", "32", "--beta", "34")
    b = solve_json("table1-row3")
    assert a["direction_surface"] == b["direction_surface"]
    assert a["fold_angles_deg"] == b["fold_angles_deg"]
    assert a["name"] == "table1-row1-alpha32-beta34"  # not table1-row1: it is another design
    c = solve_json("table1-row1", "--sheet-surface", "outside")
    assert c["inputs"]["material"]["sheet_surface"] == "OUTSIDE"
    assert c["sources"]["material.sheet_surface"] == "--sheet-surface"
    assert b["inputs"]["material"]["sheet_surface"] == "MID"


def test_units_convert_the_template_paper_square_in_inches(solve_json, cli):
    """Issue 13: 200 mm = 200 / 25.4 in = 7.874015748 in; every length follows."""
    mm = solve_json("paper-square")
    inch = solve_json("paper-square", "--units", "in")
    assert inch["units"] == "in"
    assert inch["sheet"]["size"] == pytest.approx([7.874015748031496] * 2, rel=1e-12)
    assert inch["inputs"]["frame"]["radius"] == pytest.approx(100 / 25.4, rel=1e-15)
    assert inch["inputs"]["material"]["thickness"] == pytest.approx(0.1 / 25.4, rel=1e-15)
    h_mm, h_in = mm["direction_surface"]["apex_height"], inch["direction_surface"]["apex_height"]
    assert h_in == pytest.approx(h_mm / 25.4, rel=1e-9)
    assert inch["resting"]["height"] == pytest.approx(mm["resting"]["height"] / 25.4, rel=1e-9)
    for half in ("plus_x", "minus_x"):
        assert abs(inch["fold_angles_deg"][half] - mm["fold_angles_deg"][half]) < 1e-9
    # The same paper weighs the same: kg in mm designs, lb (0.45359237 kg) in inch ones.
    assert mm["mass"]["unit"] == "kg" and inch["mass"]["unit"] == "lb"
    assert inch["mass"]["value"] == pytest.approx(mm["mass"]["value"] / 0.45359237, rel=1e-9)


def test_units_ft_without_a_template_is_a_10_by_24_ft_sheet(solve_json, cli):
    rc, out, _ = cli("solve", "--units", "ft")
    assert rc == 0
    assert "rectangle, 10 x 24 ft" in out
    rep = solve_json("--units", "ft")
    # 3048 mm / 304.8 = 10 ft; 7315.2 mm / 304.8 = 24 ft.
    assert rep["sheet"]["size"] == pytest.approx([10.0, 24.0], rel=1e-12)
    assert rep["name"] == "onefold-ft"


def test_flag_values_are_read_in_the_chosen_unit(solve_json, cli):
    rep = solve_json("paper-square", "--units", "in", "--thickness", "0.01", "--rectangle", "8x10")
    assert rep["inputs"]["material"]["thickness"] == 0.01
    assert rep["sheet"]["size"] == pytest.approx([8.0, 10.0], rel=1e-12)
    assert rep["inputs"]["sheet"]["rectangle"]["apex_fraction"] == 0.5


def test_apex_height_is_the_direction_surface_s_not_the_form_s(solve_json, cli):
    """Issue 13: the paper's h is 102.5 for a 1 x 2 mm sheet and for a 2 km one
    (it depends on R = 100 only); the form's height scales with the sheet."""
    # zero thickness: the resting form is then the sheet's alone and scales with it
    small = solve_json("--rectangle", "1x2", "--thickness", "0")
    large = solve_json("--rectangle", "1000000x2000000", "--thickness", "0")
    h = small["direction_surface"]["apex_height"]
    assert h == pytest.approx(large["direction_surface"]["apex_height"], rel=1e-12)
    assert round(h, 1) == 102.5 and small["direction_surface"]["frame_radius"] == 100.0
    ratio = large["resting"]["height"] / small["resting"]["height"]
    assert ratio == pytest.approx(1e6, rel=1e-9)
    text = cli("solve", "--rectangle", "1x2")[1]
    assert f"direction-surface apex height h at frame radius R = 100 mm: {h:.6g} mm" in text
    assert re.search(r"folded form \(resting\) +height \S+ mm, span \S+ mm, footprint", text)


def test_solve_prints_the_material_and_where_it_came_from(solve_json, cli):
    text = cli("solve")[1]
    assert "304 stainless steel, 10 gauge (assumed)" in text
    assert "t 3.57 mm, r 6 mm, K 0.44, reference surface MID" in text
    assert "values: inherited from template patkau-one-fold" in text
    text = cli("solve", "table1-row1", "--thickness", "2")[1]
    assert "t 2 mm, r 0 mm" in text and "t: --thickness" in text
    assert "(unnamed material)" in text and "values: default" in text
    rep = solve_json("--thickness", "2")
    assert rep["sources"]["material.thickness"] == "--thickness"
    assert rep["sources"]["material.bend_radius"] == "inherited from template patkau-one-fold"


def test_solve_always_answers_build_refuses():
    """Issue 11 item 4: the inherited material's bend zone reaches a sheet corner.
    solve gives the geometry with a warning (exit 0); build refuses (exit 2)."""
    args = ["--rectangle", "40x100", "--alpha", "60", "--beta", "70"]
    proc = run("solve", *args, "--json")
    assert proc.returncode == 0, proc.stderr
    rep = json.loads(proc.stdout)
    assert rep["direction_surface"]["apex_height"] > 0
    assert rep["flat_pattern"]["compensation"] == "none"
    # the bend warning, and this narrow solid's own: it rocks on a curved edge
    rocks, w = rep["warnings"]
    assert rep["resting"]["warnings"] == [rocks] and "rocks on a curved edge" in rocks
    assert w.startswith("bend_radius: ") and "build refuses the DXF" in w
    assert proc.stderr.splitlines() == [f"onefold: warning: {x}" for x in (rocks, w)]
    text = run("solve", *args)
    assert text.returncode == 0
    why = "(uncompensated: past the bend model's limits, see the warnings; build refuses the DXF)"
    assert why in text.stdout


def test_a_zero_thickness_flat_pattern_is_not_called_a_refusal(tmp_path, cli):
    """star-polygon has t = 0: its blank is the designed outline because there is
    nothing to compensate, with no warning, and build writes its DXF."""
    rc, out, err = cli("solve", "star-polygon")
    assert rc == 0 and err == ""
    (line,) = [ln for ln in out.splitlines() if "flat pattern size" in ln]
    assert line.endswith("(t = 0: nothing to compensate)")
    assert "refuses" not in out and "warnings" not in out
    rc, out, err = cli("build", "star-polygon", "--formats", "dxf", "-o", str(tmp_path), "-q")
    assert rc == 0 and err == ""
    assert (tmp_path / "star-polygon.dxf").is_file()


def test_a_blank_left_uncompensated_on_request_says_so():
    from onefold_cad.cli.summary import summary
    from onefold_cad.fabrication.flat_pattern import flat_pattern

    design = load_template("paper-square")  # t = 0.1 mm, within the bend model's limits
    folded = fold_design(design)
    report = design_report(design, folded, pattern=flat_pattern(design, folded, "none"))
    assert report["flat_pattern"]["bend_problems"] == [] and report["warnings"] == []
    (line,) = [ln for ln in summary(report).splitlines() if "flat pattern size" in ln]
    assert line.endswith("(uncompensated, as asked)")


def test_a_flags_only_build_s_files_claim_no_inherited_gauge_or_description(tmp_path, cli):
    args = ["--rectangle", "1000x400", "--alpha", "30", "--beta", "30", "--thickness", "1"]
    rc, out, err = cli("build", *args, "--formats", "dxf,bends,json", "-o", str(tmp_path), "-q")
    assert rc == 0, err
    stem = "onefold-alpha30-beta30-1000x400-t1"
    marked = "304 stainless steel (from template patkau-one-fold), t from flags"
    for suffix in (".dxf", "-bends.csv", ".json"):
        text = (tmp_path / f"{stem}{suffix}").read_text(encoding="utf-8")
        assert "gauge" not in text and "Patkau Architects'" not in text, suffix
        assert marked in text, suffix
    rep = json.loads((tmp_path / f"{stem}.json").read_text(encoding="utf-8"))
    assert rep["inputs"]["material"]["thickness"] == 1.0
    assert rep["description"].startswith("from flags --alpha 30 --beta 30 --rectangle 1000x400")


def test_build_refuses_what_solve_warns_about(tmp_path):
    out = tmp_path / "out"
    proc = run("build", "--rectangle", "40x100", "--alpha", "60", "--beta", "70", "-o", str(out))
    assert proc.returncode == 2
    no_traceback(proc)
    errors = [ln for ln in proc.stderr.splitlines() if ln.startswith("onefold: error: ")]
    assert len(errors) == 1 and errors[0].startswith("onefold: error: bend_radius: ")
    assert "--compensation none" in errors[0]
    assert not out.exists()


#: The reviewers' asymmetric reproducer: the halves fold to 115 and 79 deg.
ASYMMETRIC = ["--alpha", "5", "--beta", "60", "--hc", "-60", "--x-plus", "3000", "--x-minus",
              "1000", "--y-plus", "2000", "--y-minus", "1500", "--thickness", "10",
              "--bend-radius", "10"]  # fmt: skip


def test_an_asymmetric_blank_past_the_width_limit_is_refused_unless_none(cli, tmp_path):
    """The one rigid blank is 6.72 mm too wide across plus_x (bend sheet: width error
    +6.7205), past 0.1 t = 1 mm: build refuses the flat pattern (exit 2, nothing
    written), solve answers with the warning, --compensation none writes the designed
    outline and says, in the warning, what it wrote."""
    out = tmp_path / "out"
    rc, _, err = cli("build", *ASYMMETRIC, "--formats", "dxf,bends,json", "-o", str(out), "-q")
    assert rc == 2 and not out.exists()
    (line,) = err.splitlines()
    assert line.startswith("onefold: error: hc: plus_x (fold angle 115.27 deg")
    assert "the blank is +6.72 mm too wide across it" in line and "limit +-1 mm" in line
    rc, _, err = cli("solve", *ASYMMETRIC)
    assert rc == 0 and "+6.72 mm too wide" in err and "build refuses the DXF, cut DXF" in err
    rc, _, err = cli("build", *ASYMMETRIC, "--formats", "dxf,bends,json", "-o", str(out), "-q",
                     "--compensation", "none")  # fmt: skip
    assert rc == 0, err
    (report,) = out.glob("*.json")
    (w,) = json.loads(report.read_text())["warnings"]
    assert w.endswith("; with --compensation none build writes the uncompensated blank (the "
                      "designed outline; its notes say so) and the STEP as designed")  # fmt: skip
    assert "refuses" not in w and err.strip().endswith(w)


def test_density_in_kg_per_cubic_metre_and_mass_in_kg_or_lb(solve_json, cli):
    rep = solve_json("paper-square")
    flat = rep["flat_area"]  # mm^2, net of the hole
    # 800 kg/m^3 x 0.1 mm x area, with 1 mm^3 = 1e-9 m^3.
    assert rep["mass"]["value"] == pytest.approx(800 * 0.1 * flat * 1e-9, rel=1e-14)
    vault = solve_json("broken-vault")
    # 7850 kg/m^3 x 0.0478 in x area (in^2), 1 in^3 = 16.387064 cm^3, in lb.
    kg = 7850 * 0.0478 * vault["flat_area"] * 16.387064e-6
    assert vault["mass"] == {
        "value": pytest.approx(kg / 0.45359237, rel=1e-13),
        "unit": "lb",
        "density": 7850.0,
    }
    assert re.search(r"mass +\S+ lb \(density 7850 kg/m\^3\)", cli("solve", "broken-vault")[1])
    rc, _, err = cli("solve", "--density", "8e-6")
    assert rc == 0
    assert "onefold: warning: density: 8e-06 kg/m^3" in err


def test_negative_values_after_flags(solve_json, cli):
    rep = solve_json("--polygon", "-200,100;-200,-100;100,-200;300,0;100,200", "--hc", "-10")
    assert rep["sheet"]["vertices"][0] == [300.0, 0.0]
    assert rep["inputs"]["frame"]["h_c"] == -10.0


def test_a_non_finite_report_is_an_error_naming_the_key(monkeypatch, capfd):
    import onefold_cad.fabrication.report as report

    real = report.resting_numbers

    def broken(design, folded, body=None):
        return {**real(design, folded, body), "height": float("nan")}

    monkeypatch.setattr(report, "resting_numbers", broken)
    for extra in ([], ["--json"]):
        assert main(["solve", "table1-row1", *extra]) == 2
        out, err = capfd.readouterr()
        assert out == ""
        assert err.splitlines() == [
            "onefold: error: the report of 'table1-row1' has resting.height = nan: not a finite "
            "number (the computation failed for this design); nothing written"
        ]


# -- build ---------------------------------------------------------------------------------
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
    assert set(rep["timings_s"]) >= {"direction_surface", "final_surface", "step", "dxf", "png"}


def test_every_template_builds_in_parallel_with_progress(tmp_path):
    names = [t.name for t in list_templates()]
    proc = run("build", *names, "-o", str(tmp_path), "-j", "2")
    assert proc.returncode == 0, proc.stderr
    written = {p.name for p in tmp_path.iterdir()}
    assert written == {f"{n}{s}" for n in names for s in SUFFIXES}
    lines = proc.stderr.splitlines()
    for i, n in enumerate(names, 1):
        mine = [ln[len(f"[{i}/{len(names)}] {n}: ") :] for ln in lines if ln.startswith(f"[{i}/")]
        assert mine[0].startswith("started: ")  # before any stage of the design
        stages = [re.fullmatch(r"(.+) (\d+\.\d\d) s", ln) for ln in mine]
        done = [m.group(1) for m in stages if m]
        assert done[0] == "solve" and "flat pattern" in done
        for label in ("STEP (", "DXF", "3D preview", "flat preview", "report"):
            assert any(d.startswith(label) for d in done), (n, label, mine)
        assert re.fullmatch(r"done in \d+\.\d s", mine[-1])
        rep = json.loads((tmp_path / f"{n}.json").read_text())
        assert rep["angle_condition_error_deg"] <= 1e-9
        assert rep["warnings"] == []


def test_placement_frame_writes_the_part_in_the_fold_frame_and_rest_stands_it(tmp_path, cli):
    """--placement frame: the STEP holds the folded sheet's corners where the fold puts
    them (apex above H), the report says which part it wrote; by default the same part
    stands on the ground (its lowest point at z = 0, no corner where the fold puts it)."""
    import build123d as bd
    import numpy as np

    design = load_template("star-polygon")  # zero thickness: the shell, no relief hole
    corners = fold_design(design).map_points(design.sheet.vertices)
    size = design.sheet.size
    gaps = {}
    for placement in ("frame", "rest"):
        out = tmp_path / placement
        rc, _, err = cli("build", "star-polygon", "--formats", "step,glb,png,json",
                         "--placement", placement, "-o", str(out), "-q")  # fmt: skip
        assert rc == 0, err
        shape = bd.import_step(out / "star-polygon.step")
        verts = np.array([tuple(v) for v in shape.vertices()])
        gaps[placement] = np.linalg.norm(corners[:, None] - verts[None], axis=2).min(axis=1)
        rep = json.loads((out / "star-polygon.json").read_text())
        assert rep["step"]["placement"] == placement and rep["step"]["body"] == "shell"
        low = shape.bounding_box(optimal=True).min.Z
        if placement == "rest":
            assert abs(low) <= 1e-6 * size
    assert gaps["frame"].max() <= 1e-9 * size
    assert gaps["rest"].min() > 1e-3 * size


def test_formats_choose_the_files_and_quiet_prints_nothing(tmp_path):
    proc = run("build", "table1-row1", "--formats", "json,dxf", "-o", str(tmp_path), "-q")
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    assert sorted(p.name for p in tmp_path.iterdir()) == ["table1-row1.dxf", "table1-row1.json"]
    rep = json.loads((tmp_path / "table1-row1.json").read_text())
    assert rep["files"] == ["table1-row1.dxf", "table1-row1.json"]  # the report comes last


def test_a_flags_only_build_is_not_named_after_the_default_template(tmp_path):
    (tmp_path / "patkau-one-fold.json").write_text("the real template's file\n")
    args = ["--rectangle", "3048x7315.2", "--alpha", "35", "--formats", "json", "-o"]
    proc = run("build", *args, str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "patkau-one-fold.json").read_text() == "the real template's file\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "onefold-alpha35-3048x7315.2.json",
        "patkau-one-fold.json",
    ]
    rep = json.loads((tmp_path / "onefold-alpha35-3048x7315.2.json").read_text())
    assert rep["inputs"]["frame"]["alpha"] == 35.0
    assert "material: 304 stainless steel" in proc.stderr  # the inherited material, said
    assert "inherited from template patkau-one-fold" in proc.stderr


def test_two_builds_are_byte_identical_but_for_the_timings(tmp_path):
    """STEP, 3DM, PNG, SVG and JSON (without timings) repeat byte for byte, each
    build its own process (the DXF's header dates are the DXF writer's business)."""
    for d in ("a", "b"):
        args = ["paper-square", "--formats", "step,3dm,png,svg,json", "-q"]
        assert run("build", *args, "-o", str(tmp_path / d)).returncode == 0
    names = sorted(p.name for p in (tmp_path / "a").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "b").iterdir()) and len(names) == 5
    for name in names:
        a, b = (tmp_path / d / name for d in "ab")
        if name.endswith(".json"):
            ja, jb = json.loads(a.read_text()), json.loads(b.read_text())
            assert ja.pop("timings_s").keys() == jb.pop("timings_s").keys()
            assert json.dumps(ja) == json.dumps(jb)
        else:
            assert a.read_bytes() == b.read_bytes(), name


def test_compensation_none_reaches_the_dxf_writer_or_is_refused(tmp_path):
    import inspect

    from onefold_cad.export.dxf.pattern import export_design_dxf

    proc = run("build", "patkau-one-fold", "--compensation", "none", "--formats", "dxf",
               "-q", "-o", str(tmp_path))  # fmt: skip
    if "compensation" in inspect.signature(export_design_dxf).parameters:
        assert proc.returncode == 0, proc.stderr
        assert "compensation" in (tmp_path / "patkau-one-fold.dxf").read_text().lower()
    else:  # refused, never silently ignored
        assert proc.returncode == 2
        assert proc.stderr.startswith("onefold: error: --compensation: 'none' is not supported")
        assert list(tmp_path.iterdir()) == []


# -- bad input: exit 2, one line, no file ------------------------------------------------------
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
    (["--relief-hole", "-1"], "relief-hole", ">= 0"),
    (["--density", "0"], "density", "in [1e-15, 1e+15] kg/m^3"),
    (["--density", "1e-320"], "density", "in [1e-15, 1e+15] kg/m^3"),
    (["--youngs-modulus", "-193"], "youngs-modulus", "in [1e-06, 10000] GPa"),
    (["--poisson", "0.5"], "poisson", "> -1 and < 0.5"),
    (["--poisson", "-1"], "poisson", "> -1 and < 0.5"),
    (["--yield-stress", "0"], "yield-stress", "in [0.001, 193000] MPa"),
    (["--yield-stress", "1e-320"], "yield-stress", "in [0.001, 193000] MPa"),
    (["--units", "furlong"], "units", "mm, m, in, ft"),
    (["--sheet-surface", "TOP"], "sheet-surface", "INSIDE"),
    (["--model", "fan"], "model", "exact"),
    (["--alpah", "3"], "no such option", "--alpah"),
    (["no-such-template"], "template", "no such file"),
    (["--name", "a b"], "--name", "letters"),
]

#: The reviewers' relief-hole reproducer: the material's default 3 t = 30 mm fits the 150 mm
#: square, the hole raised for the solid (190 mm) does not.
SQUARE_150 = ("--alpha 45 --beta 85 --rectangle 150x150 --thickness 10 --bend-radius 0 "
              "--compensation none --formats dxf").split()  # fmt: skip

# Only build writes the blank and the solid, which refuse what the geometry allows.
BUILD_ONLY = [
    (["--body", "mesh"], "body", "auto, solid, shell"),
    (["--placement", "floor"], "--placement", "rest, frame"),
    (["--formats", "step,pdf"], "--formats", "unknown format 'pdf' (allowed: step, dxf"),
    (["--jobs", "0"], "--jobs", ">= 1"),
    (["--relief-hole", "1e6"], "relief_hole", "must be <"),
    (["table1-row1", "--model", "exact", "--thickness", "150"], "thickness", "too thick"),
    (["paper-square", "--body", "solid", "--formats", "step"], "relief_hole", "got 0"),
    (["table1-row1", "--thickness", "3", "--body", "solid"], "model", "'exact'"),
    # the hole every writer cuts (the default raised for the solid), checked once
    (SQUARE_150, "thickness: 10 mm", "the default relief hole 190 mm"),
    (["--kerf", "99999", "--formats", "dxf"], "--kerf: must be < 3045.43 mm", "got 99999 mm"),
]

# build runs every case (it is the command that writes files); solve a sample of them.
CASES = [("build", *b) for b in BAD + BUILD_ONLY] + [("solve", *b) for b in BAD[::4]]


@pytest.mark.parametrize(
    ("command", "args", "param", "words"), CASES, ids=[f"{c[0]} {' '.join(c[1])}" for c in CASES]
)
def test_bad_input_exits_2_with_one_line_and_no_file(tmp_path, command, args, param, words):
    out = tmp_path / "out"
    extra = ["-o", str(out), "-q"] if command == "build" else []
    refused(run(command, *args, *extra, cwd=tmp_path), param, words, tmp_path)


def test_a_value_refused_after_the_fold_is_one_line_even_with_progress(tmp_path):
    """--kerf against the relief hole, which the fold sizes: checked after the
    solve, refused before its progress lines (not -q) are printed."""
    out = tmp_path / "out"
    proc = run("build", "patkau-one-fold", "--kerf", "90", "--formats", "dxf", "-o", str(out))
    assert proc.returncode == 2 and proc.stderr.count("\n") == 1, proc.stderr
    assert proc.stderr.startswith("onefold: error: --kerf: must be < the relief hole's diameter")
    assert not out.exists()


def test_solve_warns_where_build_refuses_a_relief_hole():
    proc = run("solve", "--relief-hole", "1e6")
    assert proc.returncode == 0
    assert proc.stderr.splitlines() == [
        "onefold: warning: relief_hole: diameter 1e+06 mm must be < 3048 mm (twice the distance "
        "from H to the nearest sheet edge); build refuses the DXF and STEP"
    ]  # 3048: the 10 ft rectangle's width, H at its centre


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


def test_name_needs_one_template(tmp_path):
    two = run("build", "table1-row1", "table1-row2", "--name", "x", "-o", str(tmp_path / "o"))
    assert two.returncode == 2 and "--name" in two.stderr
    assert list(tmp_path.iterdir()) == []


def test_unknown_command_and_main_exit_codes(capfd):
    assert main(["frobnicate"]) == 2
    assert capfd.readouterr().err == (
        "onefold: error: unknown command 'frobnicate' "
        "(choose from build, solve, templates, explore, fit, hops, sweep, simulate, compensate, "
        "site, loads)\n"
    )
    assert main(["templates"]) == 0
    assert main(["solve", "--beta", "90"]) == 2
    assert main(["--help"]) == 0
    assert main([]) == 0


# -- all or nothing, in this process (failures injected) --------------------------------------
def test_a_failing_export_leaves_no_file_of_that_design(tmp_path, monkeypatch, capfd):
    """STEP succeeds, then the DXF fails: nothing of the design may stay behind."""
    import onefold_cad.export.dxf.pattern as dxf

    def boom(*args, **kwargs):
        raise ExportError("disk full (simulated)")

    monkeypatch.setattr(dxf, "export_design_dxf", boom)
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("mine")
    assert main(["build", "table1-row1", "-o", str(out), "-q"]) == 2
    err = capfd.readouterr().err.strip().splitlines()
    # any warnings first, then the one error line
    assert [e for e in err if not e.startswith("onefold: warning: ")] == [
        "onefold: error: disk full (simulated)"
    ]
    assert sorted(p.name for p in out.iterdir()) == ["keep.txt"]  # no staging folder either


def test_a_late_failure_leaves_no_file_of_any_design(tmp_path, monkeypatch, capfd):
    """The second design's export fails: the first design's files must not appear either."""
    import onefold_cad.export.pictures.preview as preview

    real = preview.render_folded_preview

    def second_fails(folded, path, **kw):
        if "star" in str(path):
            raise ExportError("preview failed (simulated)")
        return real(folded, path, **kw)

    monkeypatch.setattr(preview, "render_folded_preview", second_fails)
    out = tmp_path / "new"
    assert main(["build", "table1-row1", "star-polygon", "-o", str(out), "-q"]) == 2
    assert capfd.readouterr().err.strip().splitlines()[-1].endswith("(simulated)")
    assert not out.exists()  # the folder the command created is gone again


def test_a_folder_in_the_way_is_refused_before_anything_moves(tmp_path, capfd):
    out = tmp_path / "out"
    (out / "table1-row2.json").mkdir(parents=True)
    (out / "table1-row1.json").write_text("old\n")
    argv = ["build", "table1-row1", "table1-row2", "--formats", "dxf,json", "-o", str(out), "-q"]
    assert main(argv) == 2
    assert capfd.readouterr().err.splitlines() == [
        f"onefold: error: cannot write {str(out / 'table1-row2.json')!r}: a folder is in the "
        "way (remove or rename it)"
    ]
    assert sorted(p.name for p in out.iterdir()) == ["table1-row1.json", "table1-row2.json"]
    assert (out / "table1-row1.json").read_text() == "old\n"


def test_an_unwritable_output_folder_is_one_line_naming_it(tmp_path, monkeypatch, capfd):
    import onefold_cad.export.atomic as atomic

    def denied(**kwargs):
        raise PermissionError(13, "Permission denied", kwargs.get("dir"))

    monkeypatch.setattr(atomic.tempfile, "mkdtemp", denied)
    out = tmp_path / "ro"
    out.mkdir()
    assert main(["build", "table1-row1", "--formats", "json", "-o", str(out), "-q"]) == 2
    assert capfd.readouterr().err.splitlines() == [
        f"onefold: error: cannot write into {str(out)!r}: Permission denied"
    ]
    assert list(out.iterdir()) == []
    (tmp_path / "file").write_text("")
    assert main(["build", "table1-row1", "-o", str(tmp_path / "file"), "-q"]) == 2
    assert "--outdir: cannot write into" in capfd.readouterr().err


def test_a_failed_move_is_finished_by_the_next_build(tmp_path, monkeypatch, capfd):
    """An OSError between the moves: exit 2 naming the file; the journal stays and
    the next build into the folder moves the rest in before its own files."""
    import onefold_cad.export.atomic as atomic

    out = tmp_path / "out"
    real = os.replace
    moves = []

    def second_move_fails(src, dst):
        if Path(dst).parent == out:
            moves.append(dst)
            if len(moves) == 2:
                raise OSError(5, "Input/output error")
        return real(src, dst)

    monkeypatch.setattr(atomic.os, "replace", second_move_fails)
    argv = ["build", "table1-row1", "table1-row2", "--formats", "dxf,json", "-o", str(out), "-q"]
    assert main(argv) == 2
    (err,) = capfd.readouterr().err.splitlines()
    assert err.startswith(f"onefold: error: cannot move 'table1-row1.json' into {str(out)!r}: ")
    assert "next build into this folder moves them" in err
    assert sorted(p.name for p in out.iterdir() if not p.name.startswith(".")) == [
        "table1-row1.dxf", "table1-row1.incomplete", "table1-row2.incomplete"
    ]  # fmt: skip
    monkeypatch.setattr(atomic.os, "replace", real)
    assert main(["build", "paper-square", "--formats", "json", "-o", str(out), "-q"]) == 0
    assert sorted(p.name for p in out.iterdir()) == [
        "paper-square.json", "table1-row1.dxf", "table1-row1.json", "table1-row2.dxf",
        "table1-row2.json",
    ]  # fmt: skip
    assert json.loads((out / "table1-row2.json").read_text())["name"] == "table1-row2"


# -- all or nothing under signals (real processes, paused at a named point) ----------------------
def start_paused(out: Path, point: str, *extra: str) -> subprocess.Popen[bytes]:
    """``onefold build`` of two designs (four files) that stops at ``point`` and
    waits for a line on stdin; returns once it says it is there."""
    argv = [ONEFOLD, "build", "table1-row1", "table1-row2", "--formats", "dxf,json", "-q"]
    proc = subprocess.Popen(
        [*argv, "-o", str(out), *extra],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env={**os.environ, "ONEFOLD_TEST_PAUSE": point},
        preexec_fn=interruptible,
    )
    assert proc.stderr is not None
    line = proc.stderr.readline().decode()
    assert line == f"onefold-test: paused at {point}\n", line
    return proc


EXPECTED = ["table1-row1.dxf", "table1-row1.json", "table1-row2.dxf", "table1-row2.json"]


def visible(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if not p.name.startswith(".onefold-"))


def test_sigkill_between_the_moves_is_finished_by_the_next_build(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("mine")
    proc = start_paused(out, "commit:2")
    proc.kill()
    proc.wait(timeout=60)
    # two of the four files are in place; each design's marker says that its
    # set is incomplete
    assert visible(out) == [
        "keep.txt", "table1-row1.dxf", "table1-row1.incomplete", "table1-row1.json",
        "table1-row2.incomplete",
    ]  # fmt: skip
    (stage,) = staging_dirs(out)
    assert (stage / "commit.json").exists()  # the journal of the interrupted commit
    nxt = run("build", "paper-square", "--formats", "json", "-o", str(out), "-q")
    assert nxt.returncode == 0, nxt.stderr
    assert "finished an interrupted earlier build" in nxt.stderr
    assert visible(out) == sorted(["keep.txt", "paper-square.json", *EXPECTED])
    assert staging_dirs(out) == []
    assert json.loads((out / "table1-row2.json").read_text())["files"] == EXPECTED[2:]


def test_sigterm_during_the_moves_finishes_the_commit_then_exits(tmp_path):
    out = tmp_path / "out"
    proc = start_paused(out, "commit:2")
    proc.send_signal(signal.SIGTERM)  # held back until the last file is in place
    _, err = proc.communicate(b"\n", timeout=60)
    assert proc.returncode == 128 + signal.SIGTERM
    assert err.decode().splitlines() == [
        "onefold: stopped by SIGTERM; every file of the build had been written"
    ]
    assert visible(out) == EXPECTED and staging_dirs(out) == []


@pytest.mark.parametrize(("sig", "code", "words"), [
    (signal.SIGTERM, 143, "stopped by SIGTERM"), (signal.SIGINT, 130, "interrupted")])  # fmt: skip
def test_a_signal_before_the_commit_writes_nothing(tmp_path, sig, code, words):
    out = tmp_path / "out"
    out.mkdir()
    (out / "table1-row1.json").write_text("old\n")
    proc = start_paused(out, "staged")
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == code
    assert err.decode() == (
        f"onefold: {words}; nothing was written (the output folder is as it was)\n"
    )
    assert visible(out) == ["table1-row1.json"] and staging_dirs(out) == []
    assert (out / "table1-row1.json").read_text() == "old\n"


def test_staging_folders_of_dead_runs_are_removed_live_ones_kept(tmp_path):
    """Issue 38: a dead run's staging folder (its lock free, no journal: it
    stopped before its commit) is removed by the next build into the folder,
    which says so in one line with its size; a live run's is left alone."""
    out = tmp_path / "out"
    dead = out / ".onefold-dead1234.partial"
    live = out / ".onefold-live1234.partial"
    for d in (dead, live):
        (d / "1").mkdir(parents=True)
        (d / "lock").write_text("")
        (d / "1" / "x.step").write_bytes(b"half a file" * 200_000)  # 2.2 MB
    with open(live / "lock") as fh:  # a running build holds its lock
        fcntl.flock(fh, fcntl.LOCK_EX)
        proc = run("build", "table1-row1", "--formats", "json", "-o", str(out), "-q")
        assert proc.returncode == 0, proc.stderr
        assert staging_dirs(out) == [live]
    assert proc.stderr.splitlines() == [
        f"onefold: warning: removed {str(dead)!r} (2.2 MB), the staging folder of an earlier "
        "run that stopped before its commit"
    ]
    assert visible(out) == ["table1-row1.json"]


def test_solve_and_build_warn_below_five_degrees_of_tipping_margin(tmp_path, solve_json):
    """Issue 17: a shell at alpha 35, beta 45, h_c 8 stands with a margin of
    about 4 deg: `solve` (text and JSON) and `build` warn with the report's
    margin; the default design (about 15.7 deg) gets no such warning."""
    flags = ["--alpha", "35", "--beta", "45", "--hc", "8", "--thickness", "0"]
    rep = solve_json(*flags)
    margin = rep["resting"]["tipping_margin_deg"]
    assert 0.0 < margin < 5.0
    line = f"tipping margin of only {margin:.3g} deg (below 5 deg)"
    assert [w for w in rep["warnings"] if line in w] == rep["resting"]["warnings"] != []
    proc = run("solve", *flags)
    assert proc.returncode == 0 and line in proc.stderr
    proc = run("build", *flags, "--formats", "json", "-o", str(tmp_path), "-q")
    assert proc.returncode == 0 and line in proc.stderr
    default = solve_json()
    assert default["resting"]["tipping_margin_deg"] > 5.0
    assert not any("tipping margin" in w for w in default["warnings"])


@pytest.mark.parametrize("as_process", [True, False])
def test_only_the_program_freezes_the_garbage_collector(tmp_path, as_process):
    """``onefold`` as its own process (main() without argv) moves what a
    writer's library imported out of the collector's way and freezes the rest
    at the end; main(argv), as other programs call it, leaves the collector
    as it was. The files are the same either way."""
    out = tmp_path / "out"
    argv = ["build", "paper-square", "--formats", "png,json", "-o", str(out), "-q"]
    call = "main()" if as_process else f"main({argv!r})"
    code = (
        "import gc, sys, io, contextlib\n"
        f"sys.argv = ['onefold', *{argv!r}]\n"
        "from onefold_cad.cli import build as cli\n"
        "from onefold_cad.cli.main import main\n"
        "seen = []\n"
        "real = cli._freeze_imports\n"
        "cli._freeze_imports = lambda done: (real(done), seen.append(gc.get_freeze_count()))\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        f"    rc = {call}\n"
        "print(rc, bool(seen) and min(seen) > 0, gc.get_freeze_count() > 0)\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.stdout.split() == ["0", str(as_process), str(as_process)], proc.stderr
    assert sorted(p.name for p in out.iterdir()) == ["paper-square-3d.png", "paper-square.json"]


def test_the_fold_files_crease_is_the_designs_and_nothing_is_said(tmp_path):
    """The FOLD file's tangent-ended fan folds patkau-one-fold's crease as the
    design (its onefold:crease against the report's, to 1e-9 deg; before, its
    10 equal divisions folded it 16 deg shallower and the build said so on
    stderr): no line about the file on stderr, no note in the file or the
    report (the first build of a new user printed it on every run)."""
    out = tmp_path / "out"
    proc = run("build", "patkau-one-fold", "--formats", "fold,json", "-o", str(out))
    assert proc.returncode == 0, proc.stderr
    fold = json.loads((out / "patkau-one-fold.fold").read_text())
    report = json.loads((out / "patkau-one-fold.json").read_text())
    for c in fold["onefold:crease"]:
        key = c["name"]
        assert c["fold_angle_deg"] == pytest.approx(report["fold_angles_deg"][key], abs=1e-9)
    assert "warning" not in proc.stderr and ".fold file" not in proc.stderr
    assert fold["onefold:notes"] == [] and report["warnings"] == []


def test_cones_formed_past_their_springback_add_their_forming_sheet(tmp_path, cli):
    """With the cones formed past their springback, the default formats add
    NAME-cones.csv; named formats are written as named; the forming sheet of
    a design formed as designed is written when named, its radii the cone's."""
    rc, _, err = cli("build", "patkau-one-fold", "--cone-forming", "compensated", "--formats",
                     "dxf,json", "-o", str(tmp_path / "a"), "-q")  # fmt: skip
    assert rc == 0, err
    assert sorted(p.name for p in (tmp_path / "a").iterdir()) == [
        "patkau-one-fold-cones-compensated.dxf",
        "patkau-one-fold-cones-compensated.json",
    ]
    # the DXF's notes name the forming sheet the named formats leave out: said
    name = "patkau-one-fold-cones-compensated"
    assert err.strip().splitlines() == [
        f"onefold: warning: {name}: its cones are formed past their springback and its notes "
        f"name {name}-cones.csv, which --formats leaves out: add cones"
    ]
    rc, _, err = cli("build", "patkau-one-fold", "--cone-forming", "compensated", "--formats",
                     "dxf,cones", "-o", str(tmp_path / "c"), "-q")  # fmt: skip
    assert rc == 0 and err.strip() == ""
    rc, _, err = cli("build", "patkau-one-fold", "--formats", "cones,json", "-o",
                     str(tmp_path / "b"), "-q")  # fmt: skip
    assert rc == 0, err
    rows = list(csv.DictReader((tmp_path / "b" / "patkau-one-fold-cones.csv").open()))
    assert len(rows) > 100
    assert all(r["form_radius [0.01 mm]"] == r["cone_radius [0.01 mm]"] for r in rows)


def test_all_names_the_cone_sheet_only_where_the_cones_are_compensated():
    from onefold_cad.export.writers import parse_formats

    plain = load_template("patkau-one-fold")
    past = plain.with_changes(material=plain.material.with_changes(cone_forming="compensated"))
    every = parse_formats(None)
    assert "cones" not in every and parse_formats("all", designs=[plain]) == every
    got = parse_formats(None, designs=[plain, past])
    assert got == (*every[:4], "cones", *every[4:]) and got[-1] == "json"
    assert parse_formats("dxf,json", designs=[past]) == ("dxf", "json")


def test_the_paper_model_s_cone_sheet_is_refused_before_any_file(tmp_path):
    proc = run("build", "table1-row1", "--formats", "cones,json", "-o", str(tmp_path / "o"))
    refused(proc, "model", "must be 'exact' for the cones' forming sheet", tmp_path)
