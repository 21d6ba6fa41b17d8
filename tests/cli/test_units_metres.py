"""`--units m`: a design in metres (European architects draw in metres) is the
mm design scaled by 1000 in every file that states its unit."""

from __future__ import annotations

import json

import build123d as bd
import ezdxf
import pytest

from onefold_cad.cli.main import main


def _build(tmp_path, capfd, units: str):
    out = tmp_path / units
    argv = ["build", "paper-square", "--units", units, "-o", str(out), "-q"]
    assert main([*argv, "--formats", "step,dxf,bends,json", "--name", "p"]) == 0
    capfd.readouterr()
    return out


def test_a_metre_design_is_the_mm_design_in_metres(tmp_path, capfd):
    mm, m = _build(tmp_path, capfd, "mm"), _build(tmp_path, capfd, "m")
    rep_mm = json.loads((mm / "p.json").read_text())
    rep_m = json.loads((m / "p.json").read_text())
    assert rep_m["units"] == "m"
    # lengths / 1000, areas / 1e6 (1 m = 1000 mm), the mass the same, in kg
    assert rep_m["sheet"]["size"] == pytest.approx([x / 1000 for x in rep_mm["sheet"]["size"]])
    assert rep_m["flat_area"] == pytest.approx(rep_mm["flat_area"] / 1e6, rel=1e-9)
    assert rep_m["mass"]["value"] == pytest.approx(rep_mm["mass"]["value"], rel=1e-9)
    assert rep_m["mass"]["unit"] == rep_mm["mass"]["unit"] == "kg"
    # the DXF says metres ($INSUNITS 6) and is the same drawing / 1000
    doc_mm, doc_m = (ezdxf.readfile(d / "p.dxf") for d in (mm, m))
    assert doc_m.header["$INSUNITS"] == 6 and doc_mm.header["$INSUNITS"] == 4
    assert doc_m.header["$MEASUREMENT"] == 1  # metric
    (cut_mm,) = doc_mm.modelspace().query('LWPOLYLINE[layer=="CUT"]')
    (cut_m,) = doc_m.modelspace().query('LWPOLYLINE[layer=="CUT"]')
    got = [c for p in cut_m.get_points() for c in p[:2]]
    want = [c / 1000 for p in cut_mm.get_points() for c in p[:2]]
    assert got == pytest.approx(want, abs=1e-9)
    # the STEP file is in metres; read back (in mm) it is the same part
    assert "SI_UNIT($,.METRE.)" in (m / "p.step").read_text()
    box_mm, box_m = (bd.import_step(d / "p.step").bounding_box() for d in (mm, m))
    assert tuple(box_m.size) == pytest.approx(tuple(box_mm.size), rel=1e-6)
    # the bend sheet rounds metres to 0.00001 m (0.01 mm)
    assert "length [0.00001 m]" in (m / "p-bends.csv").read_text().splitlines()[0]
