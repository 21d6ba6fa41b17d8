"""The page's downloads are the package's own files of the current design, read back."""

from __future__ import annotations

import io
import json
import tomllib

import ezdxf
import pytest

from onefold_cad import FabricationError, InvalidParameterError
from onefold_cad.explore.controls import design_from_params
from onefold_cad.explore.downloads import make_download
from onefold_cad.explore.server import load_templates
from onefold_cad.templates import design_from_data, design_to_data


@pytest.fixture(scope="module")
def square():
    data, key = load_templates("paper-square")
    return design_from_params({"alpha": "40", "beta": "35"}, data, key)


def test_the_dxf_has_the_cut_outline(square):
    file = make_download("dxf", square)
    assert file.filename == "paper-square.dxf"
    doc = ezdxf.read(io.StringIO(file.body.decode("utf-8")))
    assert not doc.audit().has_errors
    cut = doc.modelspace().query('LWPOLYLINE[layer=="CUT"]')
    assert len(cut) == 1 and cut[0].closed
    xy = [(x, y) for x, y, *_ in cut[0].get_points()]
    size = [max(c) - min(c) for c in zip(*xy, strict=True)]
    # the flat size of this design (its fold angles set the compensation), as the report says
    report = json.loads(make_download("json", square).body)
    assert size == pytest.approx(report["flat_size"], rel=1e-9)
    assert size[0] < 200.0  # compensated: narrower than the designed square


def test_the_3dm_has_the_faces_and_the_flat_outline(square, tmp_path):
    import rhino3dm

    file = make_download("3dm", square)
    assert file.filename == "paper-square.3dm" and file.mime == "model/vnd.3dm"
    path = tmp_path / file.filename
    path.write_bytes(file.body)
    doc = rhino3dm.File3dm.Read(str(path))
    layer = {lay.Index: lay.FullPath for lay in doc.Layers}
    on = [layer[o.Attributes.LayerIndex] for o in doc.Objects]
    assert on.count("Folded::Sheet") == 2 and "Flat::CUT" in on
    assert doc.Strings["frame.alpha"] == "40.0"


def test_the_toml_is_a_template_of_the_current_values(square):
    file = make_download("toml", square)
    data = tomllib.loads(file.body.decode("utf-8"))
    assert (data["frame"]["alpha"], data["frame"]["beta"]) == (40.0, 35.0)
    assert design_to_data(design_from_data(data)) == design_to_data(square)


def test_the_json_is_the_report(square):
    report = json.loads(make_download("json", square).body)
    assert report["inputs"]["frame"]["alpha"] == 40.0
    assert set(report["fold_angles_deg"]) == {"plus_x", "minus_x"}


def test_the_step_is_the_folded_sheet(square, tmp_path):
    """The sheet folds without stretching: the STEP surface's area is the flat 200 x 200 mm."""
    import build123d as bd

    from onefold_cad.export.brep.measure import measure

    file = make_download("step", square)
    assert file.filename == "paper-square.step" and file.body.startswith(b"ISO-10303-21;")
    path = tmp_path / file.filename
    path.write_bytes(file.body)
    shape = bd.import_step(path)
    assert shape.is_valid
    assert measure(shape, "area") == pytest.approx(200.0 * 200.0, rel=1e-7)


def test_a_design_the_writer_refuses_gives_its_error_and_no_file(square):
    bad = square.with_changes(material=square.material.with_changes(thickness=5, bend_radius=150))
    with pytest.raises((InvalidParameterError, FabricationError), match="thickness"):
        make_download("dxf", bad)


def test_the_step_of_a_solid_past_the_bend_limits_is_refused_as_build_refuses_it():
    """The page's STEP is build's: a solid past the bend model's limits gets the
    error build gives before writing (the page has no --compensation none)."""
    from onefold_cad import Design, FrameCurve, Material, Sheet, fold_design
    from onefold_cad.fabrication.rules import solid_bend_problem

    design = Design("corner", FrameCurve(60, 70), Sheet.rectangle(40, 100, 0.5),
                    material=Material(thickness=3.57, bend_radius=6.0))  # fmt: skip
    expected = solid_bend_problem(design, fold_design(design))
    assert expected is not None
    with pytest.raises(FabricationError) as err:
        make_download("step", design)
    assert str(err.value) == str(expected)


@pytest.mark.parametrize("forming", ["design", "compensated"])
def test_the_cones_csv_gives_the_radii_to_form_as_the_control_says(forming):
    import csv

    data, key = load_templates("patkau-one-fold")
    design = design_from_params({"cone_forming": forming}, data, key)
    file = make_download("cones", design)
    assert file.filename == "patkau-one-fold-cones.csv" and file.mime == "text/csv"
    rows = list(csv.reader(io.StringIO(file.body.decode("utf-8"))))
    head, body = rows[0], rows[1:]
    cone, form = head.index("cone_radius [0.01 mm]"), head.index("form_radius [0.01 mm]")
    pairs = [(float(r[cone]), float(r[form])) for r in body if r[cone] != "inf"]
    assert len(pairs) > 100
    if forming == "design":  # formed to the design: the cone's own radius
        assert all(f == c for c, f in pairs)
    else:  # past the springback: tighter at every station (first yield is far below)
        assert all(f < c for c, f in pairs)
    toml = tomllib.loads(make_download("toml", design).body.decode("utf-8"))
    assert toml["material"].get("cone_forming", "design") == forming
