"""The scripts of examples/ run as a user runs them and write what they say."""

from __future__ import annotations

import csv
import subprocess
import sys

from onefold_cad.cli.main import main
from onefold_cad.layers import ROOT

EXAMPLES = ROOT / "examples"


def _run(name: str, tmp_path) -> str:
    proc = subprocess.run(
        [sys.executable, str(EXAMPLES / name), str(tmp_path / "out")],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


def test_there_are_five_examples_each_with_a_docstring_and_a_test():
    scripts = sorted(p.name for p in EXAMPLES.glob("*.py"))
    assert len(scripts) == 5
    tested = (ROOT / "tests" / "test_examples.py").read_text(encoding="utf-8")
    for name in scripts:
        assert (EXAMPLES / name).read_text(encoding="utf-8").startswith('"""'), name
        assert f'_run("{name}"' in tested, name


def test_design_to_step_dxf_writes_the_command_s_files(tmp_path, capsys):
    _run("design_to_step_dxf.py", tmp_path)
    cli = tmp_path / "cli"
    args = "--rectangle 1200x2400 --apex-fraction 0.4 --alpha 35 --beta 30 --thickness 1.5"
    rest = ["--name", "my-fold", "--body", "shell", "--formats", "step,dxf", "-o", str(cli)]
    assert main(["build", *args.split(), *rest, "--quiet"]) == 0
    for name in ("my-fold.step", "my-fold.dxf"):
        assert (tmp_path / "out" / name).read_bytes() == (cli / name).read_bytes(), name


def test_parameter_study_tabulates_a_fold_that_closes_as_alpha_opens(tmp_path):
    _run("parameter_study.py", tmp_path)
    with (tmp_path / "out" / "alpha-study.csv").open() as f:
        rows = list(csv.DictReader(f))
    alphas = [float(r["alpha_deg"]) for r in rows]
    angles = [float(r["fold_angle_deg"]) for r in rows]
    assert alphas == sorted(alphas) and len(rows) == 4
    assert angles == sorted(angles)  # a wider arc folds the sheet further
    assert all(0.0 < a < 180.0 for a in angles)


def test_simulate_stress_reads_the_standing_stress(tmp_path):
    out = _run("simulate_stress.py", tmp_path)
    assert "stands: " in out
    line = next(s for s in out.splitlines() if s.startswith("largest stress standing"))
    assert float(line.split()[3]) > 0.0


def test_site_from_code_builds_the_site_s_files(tmp_path):
    out = _run("site_from_code.py", tmp_path)
    site = tmp_path / "out" / "site"
    for name in ("two-squares-plan.dxf", "two-squares-order.csv", "two-squares.json",
                 "left/left.dxf", "right/right.json"):  # fmt: skip
        assert (site / name).stat().st_size > 0, name
        assert str(site / name) in out


def test_folded_form_picture_writes_the_pictures(tmp_path):
    out = _run("folded_form_picture.py", tmp_path)
    for suffix in ("png", "svg", "glb"):
        (picture,) = (tmp_path / "out").glob(f"*.{suffix}")
        assert picture.stat().st_size > 1000 and str(picture) in out
