"""The Hops server answers as Hops expects and as the commands do: metadata on
GET, geometry rhino3dm decodes and the numbers of ``onefold solve --json`` and
``onefold fit --json`` on POST, the commands' one-line messages as Hops errors."""

from __future__ import annotations

import contextlib
import io
import json
import math

import numpy as np
import pytest
import rhino3dm

from onefold_cad.cli.main import main
from onefold_cad.hops.components import Answer, HopsOutput
from onefold_cad.hops.inputs import FIT_INPUTS, SOLVE_INPUTS, hops_request
from onefold_cad.hops.server import Component, OneFoldHops
from tests.hops.client import cli_error, data, get, outputs, post, shoelace
from tests.nurbs_area import surface_area

#: The paper-square template (200 x 200 mm, 0.1 mm paper) at alpha 40, beta 35.
SOLVE = {"template": "paper-square", "alpha": 40.0, "beta": 35.0}
SOLVE_ARGS = ["solve", "paper-square", "--alpha", "40", "--beta", "35", "--json"]
SIDE = 200.0


def _json_of(*args: str) -> dict:
    """``onefold ARGS --json``'s JSON, in this process."""
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(list(args)) == 0
    return json.loads(out.getvalue())


@pytest.fixture(scope="module")
def solved(url):
    status, answer = post(f"{url}/solve", hops_request("onefold/solve", SOLVE_INPUTS, SOLVE))
    assert status == 200, answer
    return answer, outputs(answer)


@pytest.fixture(scope="module")
def reference():
    return _json_of(*SOLVE_ARGS)


# -- metadata ------------------------------------------------------------------------
def test_root_lists_both_components(url):
    status, listing = get(f"{url}/")
    assert status == 200
    assert sorted(c["Uri"] for c in listing) == ["/onefold/fit", "/onefold/solve"]


def test_solve_metadata_names_the_design_flags_and_the_outputs(url):
    status, meta = get(f"{url}/onefold/solve")
    assert status == 200 and meta["Uri"] == "/onefold/solve"
    inputs = {i["Name"]: i for i in meta["Inputs"]}
    assert [i["Name"] for i in meta["Inputs"]] == [i.name for i in SOLVE_INPUTS]
    for name in ("alpha", "beta", "hc", "radius", "thickness", "bend_radius", "apex_fraction"):
        assert inputs[name]["ParamType"] == "Number", name
    assert inputs["sheet"]["ParamType"] == "Curve"
    assert inputs["template"]["ParamType"] == "Text"
    assert inputs["divisions"]["ParamType"] == "Integer"
    assert "(0, 90)" in inputs["alpha"]["Description"]
    # every solve input is optional (Hops makes an input optional for AtLeast 0 only)
    assert {(i["AtLeast"], i["AtMost"]) for i in meta["Inputs"]} == {(0, 1)}
    out = {o["Name"]: o for o in meta["Outputs"]}
    assert out["breps"]["ParamType"] == "Brep" and out["creases"]["ParamType"] == "Line"
    assert out["apex"]["ParamType"] == "Point" and out["outline"]["ParamType"] == "Curve"
    for name in ("fold_angles", "height", "span", "tipping_margin"):
        assert out[name]["ParamType"] == "Number"
    assert out["warnings"]["ParamType"] == "Text"


def test_fit_metadata_requires_height_and_span(url):
    _, meta = get(f"{url}/onefold/fit")
    at_least = {i["Name"]: i["AtLeast"] for i in meta["Inputs"]}
    assert at_least == {"template": 0, "height": 1, "span": 1, "depth": 0,
                        "min_tipping_margin": 0}  # fmt: skip
    assert [o["Name"] for o in meta["Outputs"]][:3] == ["alpha", "beta", "hc"]


# -- a solve -------------------------------------------------------------------------
def test_solve_numbers_are_onefold_solve_json_s(solved, reference):
    answer, out = solved
    rest = reference["resting"]
    angles = reference["fold_angles_deg"]
    assert data(out["fold_angles"]) == [angles["plus_x"], angles["minus_x"]]
    assert data(out["height"]) == [rest["height"]]
    assert data(out["span"]) == [rest["span"]]
    assert data(out["tipping_margin"]) == [rest["tipping_margin_deg"]]
    assert data(out["bends"]) == [reference["bend"]["plus_x"], reference["bend"]["minus_x"]]
    assert data(out["warnings"]) == reference["warnings"] == answer["warnings"]
    assert answer["errors"] == []
    (text,) = data(out["report"])
    report = json.loads(text)
    report.pop("timings_s"), reference.pop("timings_s")
    assert report == reference


def test_solve_geometry_decodes_with_rhino3dm(solved, reference):
    _, out = solved
    assert {i["type"] for i in out["breps"]} == {"Rhino.Geometry.Brep"}
    breps = [rhino3dm.CommonObject.Decode(d) for d in data(out["breps"])]
    assert all(isinstance(b, rhino3dm.Brep) and b.IsValid for b in breps)
    assert len(breps) == 2  # one Brep a side
    hole = reference["relief_hole_diameter"]
    area = sum(surface_area(b.Surfaces[i]) for b in breps for i in range(len(b.Surfaces)))
    assert area == pytest.approx(SIDE * SIDE - math.pi * hole**2 / 4.0, rel=1e-6)

    (apex,) = data(out["apex"])
    want = reference["resting"]["apex"]
    assert [apex["X"], apex["Y"], apex["Z"]] == pytest.approx(want, abs=1e-12 * SIDE)
    creases = data(out["creases"])
    assert [out["creases"][0]["type"]] == ["Rhino.Geometry.Line"]
    for line, half in zip(creases, ("plus_x", "minus_x"), strict=True):
        a = np.array([line["From"][k] for k in "XYZ"])
        b = np.array([line["To"][k] for k in "XYZ"])
        assert a == pytest.approx(want, abs=1e-12 * SIDE)
        length = reference["crease"][half]["length"]
        assert float(np.linalg.norm(b - a)) == pytest.approx(length, rel=1e-12)
        assert b[2] >= -1e-9 * SIDE  # the form rests on the ground z = 0

    (outline,) = [rhino3dm.CommonObject.Decode(d) for d in data(out["outline"])]
    assert isinstance(outline, rhino3dm.PolylineCurve) and outline.IsClosed
    pts = np.array([[(p := outline.Point(i)).X, p.Y, p.Z] for i in range(outline.PointCount)])
    assert np.all(pts[:, 2] == 0.0)
    holes = [rhino3dm.CommonObject.Decode(d) for d in data(out["relief_hole"])]
    cut = reference["flat_pattern"]["cut_hole_diameter"]
    assert len(holes) == (1 if cut > 0 else 0)
    net = shoelace(pts[:-1, :2]) - math.pi * cut**2 / 4.0
    assert net == pytest.approx(reference["flat_area"], rel=1e-12)
    bends = [rhino3dm.CommonObject.Decode(d) for d in data(out["bend_lines"])]
    assert len(bends) == 2 and all(isinstance(b, rhino3dm.LineCurve) for b in bends)
    start = [b.PointAtStart for b in bends]
    assert start[0].DistanceTo(start[1]) == 0.0  # both halves start at H


def test_a_closed_polyline_sheet_is_the_polygon_flag(solve):
    vertices = [(250.0, 0.0), (80.0, 190.0), (-300.0, 0.0), (0.0, -260.0)]
    pts = [rhino3dm.Point3d(x, y, 0.0) for x, y in vertices]
    curve = rhino3dm.PolylineCurve([*pts, pts[0]])
    status, answer = solve(model_units="Inches", sheet=curve.Encode(), alpha=35.0)
    assert status == 200, answer
    text = ";".join(f"{x},{y}" for x, y in vertices)
    reference = _json_of("solve", "--polygon", text, "--alpha", "35", "--json")
    (got,) = data(outputs(answer)["report"])
    report = json.loads(got)
    assert report["sheet"]["vertices"] == reference["sheet"]["vertices"]
    assert report["fold_angles_deg"] == reference["fold_angles_deg"]
    # a Rhino document in inches, a design in mm: said, not converted
    (units,) = [w for w in answer["warnings"] if "Rhino document's in Inches" in w]
    assert "design's lengths are in millimetres (units 'mm')" in units
    assert units not in reference["warnings"]


def test_design_warnings_are_hops_warnings(solve, cli):
    status, answer = solve(bend_radius=500.0)
    rc, _, err = cli("solve", "--bend-radius", "500")
    assert status == 200 and rc == 0
    lines = [ln.removeprefix("onefold: warning: ") for ln in err.splitlines()]
    assert lines and answer["warnings"] == lines
    assert data(outputs(answer)["warnings"]) == lines
    assert len(outputs(answer)["breps"]) == 2  # never refused for fabrication reasons


# -- errors: the command's one-line message ------------------------------------------
@pytest.mark.parametrize(
    ("values", "args", "name"),
    [
        ({"alpha": 95.0}, ["solve", "--alpha", "95"], "alpha"),
        ({"beta": 0.0}, ["solve", "--beta", "0"], "beta"),
        ({"radius": -1.0}, ["solve", "--radius", "-1"], "radius"),
        ({"model": "foo"}, ["solve", "--model", "foo"], "model"),
        ({"divisions": 0, "model": "paper"}, ["solve", "--divisions", "0", "--model", "paper"],
         "divisions"),
        ({"sheet_width": 100.0}, ["solve", "--rectangle", "100.0x"], "rectangle"),
        ({"apex_fraction": 1.5}, ["solve", "--apex-fraction", "1.5"], "apex-fraction"),
        ({"placement": "up"}, ["build", "--placement", "up"], "placement"),
    ],
)  # fmt: skip
def test_a_bad_value_is_a_hops_error_with_the_command_s_message(solve, cli, values, args, name):
    status, answer = solve(**values)
    rc, out, err = cli(*args)
    assert rc == 2 and out == ""
    assert status == 500
    assert answer["values"] == [] and answer["errors"] == [cli_error(err)]
    assert name in answer["errors"][0]


def test_a_sheet_without_h_inside_is_the_polygon_flag_s_error(solve, cli):
    pts = [rhino3dm.Point3d(x, y, 0.0) for x, y in [(300, 0), (0, 300), (-300, 0), (300, 0)]]
    status, answer = solve(sheet=rhino3dm.PolylineCurve(pts).Encode())
    rc, _, err = cli("solve", "--polygon", "300.0,0.0;0.0,300.0;-300.0,0.0")
    assert status == 500 and rc == 2
    assert answer["errors"] == [cli_error(err)]


@pytest.mark.parametrize(
    ("curve", "words"),
    [
        (rhino3dm.PolylineCurve([rhino3dm.Point3d(x, y, 0) for x, y in [(1, 0), (0, 1), (-1, 0)]]),
         "open"),
        (rhino3dm.Circle(rhino3dm.Point3d(0, 0, 0), 100.0).ToNurbsCurve(), "straight segments"),
        (rhino3dm.PolylineCurve([rhino3dm.Point3d(x, y, z) for x, y, z in
                                 [(1, 0, 0), (0, 1, 2), (-1, 0, 0), (0, -1, 0), (1, 0, 0)]]),
         "XY plane"),
    ],
)  # fmt: skip
def test_a_sheet_that_is_no_closed_flat_polyline_is_refused_by_name(solve, curve, words):
    status, answer = solve(sheet=curve.Encode())
    assert status == 500
    (error,) = answer["errors"]
    assert error.startswith("sheet: ") and words in error


def test_two_values_on_one_input_are_refused(url):
    body = hops_request("onefold/solve", SOLVE_INPUTS, {"alpha": 30.0})
    entry = next(v for v in body["values"] if v["ParamName"] == "alpha")
    entry["InnerTree"]["{0}"].append({"type": "System.Double", "data": "40.0"})
    status, answer = post(f"{url}/solve", body)
    assert status == 500 and answer["errors"][0].startswith("alpha: takes one value")


def test_an_unknown_input_asks_hops_to_rebuild(url):
    body = hops_request("onefold/solve", SOLVE_INPUTS, {})
    body["values"].append({"ParamName": "gamma", "InnerTree": {}})
    status, answer = post(f"{url}/solve", body)
    assert status == 500
    assert answer["errors"][0] == "Bad inputs" and "gamma" in answer["errors"][1]


def test_a_body_that_is_not_json_is_an_error_not_an_empty_answer(url):
    status, answer = post(f"{url}/solve", b"{not json")
    assert status == 400 and answer["values"] == []
    assert "not Hops' JSON" in answer["errors"][0]


def test_the_component_s_own_path_solves_too(url, cli):
    body = hops_request("onefold/solve", SOLVE_INPUTS, {"alpha": 95.0})
    status, answer = post(f"{url}/onefold/solve", body)
    _, _, err = cli("solve", "--alpha", "95")
    assert status == 500 and answer["errors"] == [cli_error(err)]


# -- fit -----------------------------------------------------------------------------
def test_fit_answers_what_onefold_fit_json_says(fit, solve):
    status, answer = fit(template="paper-square", height=144.4, span=148.0)
    assert status == 200, answer
    reference = _json_of("fit", "paper-square", "--height", "144.4", "--span", "148", "--json")
    out = outputs(answer)
    frame, got = reference["frame"], reference["achieved"]
    assert data(out["alpha"]) + data(out["beta"]) + data(out["hc"]) == [
        frame["alpha"], frame["beta"], frame["h_c"]
    ]  # fmt: skip
    assert data(out["height"]) == [got["height"]] and data(out["span"]) == [got["span"]]
    assert data(out["tipping_margin"]) == [got["tipping_margin_deg"]]
    (text,) = data(out["report"])
    assert json.loads(text) == reference
    assert abs(got["height"] - 144.4) <= 0.005 * 144.4  # the fit's own tolerance
    assert abs(got["span"] - 148.0) <= 0.005 * 148.0
    # the found frame, solved: the resting form the fit measured
    frame_in = {"alpha": frame["alpha"], "beta": frame["beta"], "hc": frame["h_c"]}
    status, solved = solve(template="paper-square", **frame_in)
    assert status == 200, solved
    assert data(outputs(solved)["height"])[0] == pytest.approx(got["height"], rel=1e-9)
    assert data(outputs(solved)["span"])[0] == pytest.approx(got["span"], rel=1e-9)


def test_fit_out_of_range_height_is_the_command_s_error(fit, cli):
    status, answer = fit(template="paper-square", height=-3.0, span=148.0)
    rc, _, err = cli("fit", "paper-square", "--height", "-3", "--span", "148")
    assert status == 500 and rc == 2
    assert answer["errors"] == [cli_error(err)] and "height" in answer["errors"][0]


def test_fit_without_its_height_says_so(url):
    body = hops_request("onefold/fit", FIT_INPUTS, {"span": 148.0})
    status, answer = post(f"{url}/solve", body)
    assert status == 500 and answer["errors"][0].startswith("height: missing")


# -- a failure that is no input's fault ----------------------------------------------
def _failing(values, request):
    raise RuntimeError("a bug\nover two lines")


def _unencodable(values, request):
    return Answer((object(),))


@pytest.mark.parametrize(
    ("answer", "words"),
    [(_failing, "RuntimeError: a bug over two lines"), (_unencodable, "TypeError")],
)
def test_an_unexpected_failure_is_one_line_and_its_traceback_goes_to_stderr(capfd, answer, words):
    broken = Component(
        "/broken", "broken", "B", "fails", (), (HopsOutput("x", "number", "x"),), answer
    )
    app = OneFoldHops([broken])
    ok, text = app.solve("/solve", json.dumps({"pointer": "broken", "values": []}))
    assert not ok
    (error,) = json.loads(text)["errors"]
    assert error.startswith("internal error (") and words in error and "\n" not in error
    assert "Traceback" in capfd.readouterr().err
