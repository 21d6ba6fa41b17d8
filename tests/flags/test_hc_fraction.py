"""Issue 37 item 4: ``--hc-fraction``, where H sits on the f-line as a
fraction of the half f-line R cos(alpha), over its whole range whatever R and
alpha; ``--hc`` stays for the paper's tables. The README's sweep runs clean."""

from __future__ import annotations

import json
import math
import re
import shlex

import pytest

from onefold_cad.cli.main import main
from onefold_cad.explore.controls import design_from_params, page_values
from onefold_cad.flags.overrides import Overrides
from onefold_cad.templates import design_from_data, find_template, read_template
from tests.cli.test_main import REPO, run


def load_template_data(name: str) -> dict:
    return read_template(find_template(name))


def _design(**flags):
    data, names = Overrides(**flags).apply(load_template_data("patkau-one-fold"))
    return design_from_data(data, key_names=names)


@pytest.mark.parametrize(
    ("alpha", "radius", "fraction"), [(60.0, 50.0, 0.4), (30.0, 100.0, -0.75), (80.0, 100.0, 0.9)]
)
def test_the_fraction_places_h_on_the_half_f_line(alpha, radius, fraction):
    """h_c = F R cos(alpha): at alpha 60 and R 50 the half f-line is 25, so
    F = 0.4 is h_c = 10; the other rows against the cosine worked here."""
    d = _design(alpha=alpha, radius=radius, hc_fraction=fraction)
    want = fraction * radius * math.cos(math.radians(alpha))
    assert d.frame.h_c == pytest.approx(want, rel=1e-14, abs=1e-13)
    if (alpha, radius, fraction) == (60.0, 50.0, 0.4):
        assert d.frame.h_c == pytest.approx(10.0, rel=1e-14)


def test_a_fraction_reaches_where_the_papers_h_c_cannot(capfd):
    """alpha 80 (half f-line 17.4 at R = 100): --hc 50 is refused, --hc-fraction
    0.9 solves (exit 0), H 90 % of the way to the +x end."""
    assert main(["solve", "patkau-one-fold", "--alpha", "80", "--hc", "50"]) == 2
    assert "--hc" in capfd.readouterr().err
    assert (
        main(["solve", "patkau-one-fold", "--alpha", "80", "--hc-fraction", "0.9", "--json"]) == 0
    )
    report = json.loads(capfd.readouterr().out)
    half = 100.0 * math.cos(math.radians(80.0))
    assert report["inputs"]["frame"]["h_c"] == pytest.approx(0.9 * half, rel=1e-14)


@pytest.mark.parametrize("value", ["1", "-1", "1.5", "-7", "nan", "inf"])
def test_a_fraction_outside_the_open_range_is_one_line_naming_it(value, tmp_path):
    """Exit 2, one line naming --hc-fraction and its range (-1, 1), nothing written."""
    proc = run("build", "patkau-one-fold", "--hc-fraction", value, "-o", "out", cwd=tmp_path)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr and proc.stdout == ""
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith("onefold: error: --hc-fraction: must be inside (-1, 1)")
    assert not (tmp_path / "out").exists()


def test_the_fraction_and_hc_together_are_refused(capfd):
    assert main(["solve", "patkau-one-fold", "--hc", "1", "--hc-fraction", "0.1"]) == 2
    err = capfd.readouterr().err.strip()
    assert err == "onefold: error: --hc-fraction: cannot be combined with --hc"


def test_the_explorer_sends_the_fraction_and_gets_the_template_back():
    """The page's control is the fraction (h_c / R cos(alpha)); table1-row4's
    h_c (not 0) comes back to the bit; a moved alpha keeps the fraction."""
    data = {"table1-row4": load_template_data("table1-row4")}
    design = design_from_params({}, data, "table1-row4")
    assert design.frame.h_c != 0.0
    values = page_values(design)["values"]
    assert "hc" not in values
    assert float(values["hc_fraction"]) == design.frame.h_c / design.frame.half_chord
    again = design_from_params({**values}, data, "table1-row4")
    assert again.frame.h_c == design.frame.h_c
    moved = design_from_params({**values, "alpha": "70"}, data, "table1-row4")
    assert moved.frame.h_c / moved.frame.half_chord == pytest.approx(float(values["hc_fraction"]))


def test_the_readmes_sweep_example_runs_clean(tmp_path):
    """The README's `onefold sweep` line, as written but for the output
    folder and no thumbnails: every one of its 45 designs solves and stands
    (before, with --vary hc=-50,0,50, 10 of 45 failed: h_c beyond R cos(alpha))."""
    text = (REPO / "README.md").read_text(encoding="utf-8")
    (line,) = [ln for ln in text.splitlines() if re.match(r"onefold sweep .*--vary", ln)]
    words = shlex.split(line, comments=True)
    assert "hc-fraction=-0.5,0,0.5" in " ".join(words)
    args = words[1:]
    args[args.index("-o") + 1] = str(tmp_path / "sweep")
    proc = run(*args, "--no-images", "--quiet")
    assert proc.returncode == 0, proc.stderr
    rows = [json.loads(r) for r in (tmp_path / "sweep" / "journal.jsonl").read_text().splitlines()]
    assert len(rows) == 45
    assert [r["error"] for r in rows if r["status"] != "ok"] == []


def test_hops_solve_takes_the_fraction_as_its_last_input():
    """Grasshopper's onefold/solve: ``hc_fraction`` (as --hc-fraction) after
    every input it had, so a definition made before keeps its wiring."""
    from onefold_cad.hops.inputs import SOLVE_INPUTS

    last = SOLVE_INPUTS[-1]
    assert (last.name, last.kind, last.flag) == ("hc_fraction", "number", "--hc-fraction")
    assert "R cos(alpha)" in last.description and "(-1, 1)" in last.description
    assert [i.name for i in SOLVE_INPUTS].count("hc") == 1
