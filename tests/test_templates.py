"""The TOML templates: loading, validation errors naming the key, and every shipped one."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from onefold_cad import InvalidParameterError, InvalidSheetError, Model, Units, fold_design
from onefold_cad.fabrication.rules import fabrication_warnings
from onefold_cad.geometry.developability import developability
from onefold_cad.geometry.resting.placement import rest_form
from onefold_cad.templates import (
    DEFAULT_TEMPLATE,
    design_from_data,
    design_to_data,
    find_template,
    list_templates,
    load_template,
    read_template,
    read_toml,
)
from tests.shipped import DESIGN_TEMPLATES, REPO_TEMPLATES

# site-*.toml are site files (onefold site), not design templates
SHIPPED = DESIGN_TEMPLATES

# The paper's Table 1: (H_c, alpha, beta, divisions, Y+, Y-, X+, X-).
TABLE1 = {
    "table1-row1": (0, 50, 45, 90, 300, 300, 300, 300),
    "table1-row2": (0, 50, 45, 20, 300, 300, 300, 300),
    "table1-row3": (0, 32, 34, 90, 300, 300, 300, 300),
    "table1-row4": (68, 32, 34, 90, 300, 96, 103, 201),
}


def base() -> dict:
    return {
        "name": "t",
        "frame": {"alpha": 40.0, "beta": 40.0},
        "sheet": {"quadrilateral": {"x_plus": 3, "x_minus": 3, "y_plus": 3, "y_minus": 3}},
    }


def test_the_issue_s_templates_are_shipped():
    expected = {
        *TABLE1,
        "patkau-one-fold",
        "broken-vault",
        "paper-square",
        "star-polygon",
    }
    assert expected <= set(SHIPPED)
    assert {t.name for t in list_templates()} == set(SHIPPED)
    assert DEFAULT_TEMPLATE in SHIPPED


@pytest.mark.parametrize("name", SHIPPED)
def test_every_template_loads_folds_and_documents_itself(name):
    path = REPO_TEMPLATES / f"{name}.toml"
    text = path.read_text()
    design = load_template(path)
    assert design.name == name
    assert design.description and "\n" not in design.description
    # Comments on sources and on what is assumed.
    comments = " ".join(line for line in text.splitlines() if line.startswith("#")).lower()
    assert "source" in comments and "assum" in comments
    assert design.units.value == read_template(path)["units"]  # every template states it
    folded = fold_design(design)
    m = developability(folded)
    # The fold keeps the sheet: area, boundary length and ruling lengths survive. The
    # paper model's fan is exact to rounding; the exact model's boundary is measured on
    # 4000 samples (a chord error below 1e-6 of the length or area).
    tol = 1e-12 if design.model is Model.PAPER else 1e-6
    assert m.area_rel_error < tol
    assert m.boundary_length_rel_error < tol
    assert m.max_ruling_length_error < 1e-9 * design.sheet.size
    assert abs(m.angle_sum_deg - 360.0) <= 1e-9
    assert folded.solution.angle_condition_error_deg <= 1e-9
    for half in folded.crease:
        assert 0.0 < half.fold_angle_deg < 180.0
    assert rest_form(folded).stable


@pytest.mark.parametrize("name", sorted(TABLE1))
def test_table1_templates_hold_the_paper_s_inputs(name):
    hc, alpha, beta, div, yp, ym, xp, xm = TABLE1[name]
    d = load_template(name)
    assert (d.frame.h_c, d.frame.alpha, d.frame.beta, d.frame.divisions) == (hc, alpha, beta, div)
    assert d.sheet.inputs == {"x_plus": xp, "x_minus": xm, "y_plus": yp, "y_minus": ym}
    assert d.model is Model.PAPER


def test_patkau_is_a_10_by_24_ft_sheet_folded_along_its_diagonal():
    d = load_template("patkau-one-fold")
    ft = Units.FT.mm
    assert d.units is Units.MM
    assert d.sheet.kind == "rectangle"
    assert math.isclose(d.sheet.inputs["width"], 10 * ft)
    assert math.isclose(d.sheet.inputs["height"], 24 * ft)
    # The crease is the diagonal: its two halves add up to the diagonal's length.
    xp, xm = d.sheet.crease_lengths
    assert math.isclose(xp + xm, math.hypot(10 * ft, 24 * ft), rel_tol=1e-12)
    assert d.material.thickness > 0 and "stainless" in d.material.name


def test_broken_vault_is_5_by_12_ft_18_gauge():
    d = load_template("broken-vault")
    assert d.units is Units.IN
    # 5 x 12 ft = 60 x 144 in; 18 gauge sheet steel = 0.0478 in (manufacturers' gauge).
    assert (d.sheet.inputs["width"], d.sheet.inputs["height"]) == (60.0, 144.0)
    assert d.material.thickness == 0.0478
    # In millimetres: 0.0478 x 25.4 = 1.21412 mm, 60 in = 1524 mm.
    mm = d.in_units("mm")
    assert mm.material.thickness == pytest.approx(1.21412, rel=1e-14)
    assert mm.sheet.inputs["width"] == pytest.approx(1524.0, rel=1e-15)
    assert d.material.density == 7850.0  # kg/m^3, mild steel


def test_star_polygon_has_h_off_centre():
    d = load_template("star-polygon")
    v = np.array(read_template(find_template("star-polygon"))["sheet"]["polygon"])
    assert len(v) >= 8
    assert np.linalg.norm(v.mean(axis=0)) > 0.05 * d.sheet.size
    assert d.sheet.kind == "polygon"


@pytest.mark.parametrize("name", SHIPPED)
def test_design_to_data_round_trips(name):
    d = load_template(name)
    again = design_from_data(design_to_data(d))
    assert design_to_data(again) == design_to_data(d)
    np.testing.assert_array_equal(again.sheet.vertices, d.sheet.vertices)


def test_cone_forming_round_trips_and_is_left_out_when_unset():
    d = load_template("patkau-one-fold")
    assert "cone_forming" not in design_to_data(d)["material"]
    past = d.with_changes(material=d.material.with_changes(cone_forming="compensated"))
    data = design_to_data(past)
    assert data["material"]["cone_forming"] == "compensated"
    assert design_from_data(data).material.cones_compensated


def test_find_template_by_name_and_by_path(tmp_path):
    assert find_template("table1-row1") == find_template(REPO_TEMPLATES / "table1-row1.toml")
    with pytest.raises(InvalidParameterError, match="template: no such file") as exc:
        find_template(tmp_path / "missing.toml")
    assert exc.value.parameter == "template"


def _error(data: dict) -> InvalidParameterError:
    with pytest.raises(InvalidParameterError) as exc:
        design_from_data(data)
    return exc.value


@pytest.mark.parametrize(
    ("edit", "key", "words"),
    [
        (lambda d: d["frame"].update(alpah=3), "frame.alpah", "unknown key"),
        (lambda d: d.update(colour="red"), "colour", "unknown key"),
        (
            lambda d: d.update(material={"thickness": 1, "thicknes": 2}),
            "material.thicknes",
            "unknown",
        ),
        (lambda d: d["frame"].update(alpha="50"), "frame.alpha", "must be a number"),
        (lambda d: d["frame"].update(alpha=True), "frame.alpha", "must be a number"),
        (lambda d: d["frame"].update(divisions=9.5), "frame.divisions", "must be an integer"),
        (lambda d: d.update(name=3), "name", "must be a string"),
        (lambda d: d["frame"].update(alpha=95), "frame.alpha", "(0, 90)"),
        (lambda d: d["frame"].pop("beta"), "frame.beta", "missing"),
        (lambda d: d["frame"].update(h_c=99), "frame.h_c", "h_c in"),
        (
            lambda d: d["sheet"]["quadrilateral"].update(x_plus=-1),
            "sheet.quadrilateral.x_plus",
            "> 0",
        ),
        (
            lambda d: d["sheet"]["quadrilateral"].pop("y_minus"),
            "sheet.quadrilateral.y_minus",
            "missing",
        ),
        (lambda d: d["sheet"]["quadrilateral"].update(z=1), "sheet.quadrilateral.z", "unknown key"),
        (lambda d: d["sheet"].update(polygon=[[1, 0], [0, 1], [-1, 0]]), "sheet", "exactly one"),
        (lambda d: d.pop("sheet"), "sheet", "missing"),
        (lambda d: d.update(sheet={"circle": {}}), "sheet.circle", "unknown key"),
        (lambda d: d.update(sheet={"polygon": [[1, 0], [0, "a"]]}), "sheet.polygon[1]", "pair"),
        (
            lambda d: d.update(sheet={"rectangle": {"width": 2, "height": 1, "apex_fraction": 1}}),
            "sheet.rectangle.apex_fraction",
            "(0, 1)",
        ),
        (lambda d: d.update(material={"k_factor": 2}), "material.k_factor", "[0, 1]"),
        (lambda d: d.update(material={"relief_hole": -1}), "material.relief_hole", ">= 0"),
        (
            lambda d: d.update(material={"cone_forming": "tight"}),
            "material.cone_forming",
            "design, compensated",
        ),  # fmt: skip
        (lambda d: d.update(units="furlong"), "units", "mm, m, in, ft"),
        (lambda d: d.update(model="fan"), "model", "paper, exact"),
        (lambda d: d.update(name="no spaces"), "name", "letters"),
    ],
)
def test_bad_template_data_names_the_full_key(edit, key, words):
    data = base()
    edit(data)
    err = _error(data)
    assert err.parameter == key
    assert str(err).startswith(f"{key}: ")
    assert words in str(err)


def test_a_self_intersecting_polygon_is_a_sheet_error():
    data = base()
    data["sheet"] = {"polygon": [[1, 1], [-1, -1], [1, -1], [-1, 1]]}
    err = _error(data)
    assert isinstance(err, InvalidSheetError)
    assert err.parameter == "sheet.polygon"


def test_key_names_rename_flag_values():
    data = base()
    data["frame"]["alpha"] = 100
    err = _error_with_names(data, {"frame.alpha": "--alpha"})
    assert str(err).startswith("--alpha: must be in (0, 90)")


def _error_with_names(data, names):
    with pytest.raises(InvalidParameterError) as exc:
        design_from_data(data, key_names=names)
    return exc.value


def test_read_template_reports_bad_toml(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text("name = \n")
    with pytest.raises(InvalidParameterError, match="not valid TOML"):
        read_template(p)


def test_a_template_that_is_not_utf8_names_the_byte(tmp_path):
    p = tmp_path / "latin1.toml"
    p.write_bytes('name = "t"\ndescription = "caf\u00e9"\n'.encode("latin-1"))
    offset = p.read_bytes().index(b"\xe9")
    with pytest.raises(InvalidParameterError) as err:
        read_template(p)
    assert err.value.parameter == "template"
    assert f"not UTF-8 text (byte 0xe9 at offset {offset})" in str(err.value)


@pytest.mark.parametrize(
    ("nesting", "words"),
    [
        ("[" * 2000 + "]" * 2000, "nested too deeply to read"),  # the parser's RecursionError
        ("{b=" * 3000 + "1" + "}" * 3000, "nested too deeply to read"),
        ("[" * 100 + "]" * 100, "nested 101 levels deep"),  # parsed, then measured
    ],
)
def test_deeply_nested_data_is_refused_as_it_is_read(tmp_path, nesting, words):
    p = tmp_path / "deep.toml"
    p.write_text(f"a = {nesting}\n")
    with pytest.raises(InvalidParameterError, match=words) as err:
        read_toml(p, "SITE")
    assert err.value.parameter == "SITE"
    assert "at most 64" in str(err.value)


def test_the_deepest_shipped_nesting_is_read(tmp_path):
    p = tmp_path / "ok.toml"
    p.write_text("a = " + "[" * 63 + "]" * 63 + "\n")  # 64 levels with the file's table
    assert read_toml(p, "template")["a"] is not None


def test_a_relief_hole_larger_than_the_sheet_is_a_design_with_a_warning():
    """Fabrication limits are not template errors: the design is made and
    solved; the warning says what build will refuse."""
    data = base()
    data["material"] = {"relief_hole": 50}
    d = design_from_data(data)
    assert d.material.relief_hole == 50
    (w,) = fabrication_warnings(d, fold_design(d))
    # The square's vertices are 3 from H on the axes: its edges are 3 / sqrt(2) away.
    assert w.startswith(f"relief_hole: diameter 50 mm must be < {2 * 3 / math.sqrt(2):.6g} mm")


def test_a_template_file_without_units_is_refused(tmp_path):
    p = tmp_path / "no-units.toml"
    p.write_text((REPO_TEMPLATES / "table1-row1.toml").read_text().replace('units = "mm"\n', ""))
    with pytest.raises(InvalidParameterError, match="units: missing") as exc:
        load_template(p)
    assert str(p) in exc.value.parameter


def test_templates_state_density_in_kg_per_cubic_metre():
    densities = {info.name: load_template(info.path).material.density for info in list_templates()}
    assert densities["patkau-one-fold"] == 8000.0  # 304 stainless, 8.0 g/cm^3
    assert densities["paper-square"] == 800.0  # office paper, 0.8 g/cm^3
    assert densities["broken-vault"] == 7850.0  # mild steel


def test_templates_are_valid_toml_data_only():
    for p in (REPO_TEMPLATES / f"{name}.toml" for name in SHIPPED):
        data = tomllib.loads(p.read_text())
        assert set(data) <= {"name", "description", "units", "model", "frame", "sheet", "material"}
