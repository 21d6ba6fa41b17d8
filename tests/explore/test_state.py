"""One page state: the resting mesh, the crease, the numbers and the messages."""

from __future__ import annotations

import base64
import json
import math

import numpy as np
import pytest

from onefold_cad.cli.main import main
from onefold_cad.design import fold_design
from onefold_cad.explore.controls import design_from_params
from onefold_cad.explore.server import load_templates
from onefold_cad.explore.state import MESH_ANGULAR, MESH_RADIAL, design_state
from onefold_cad.fabrication.report import design_report
from onefold_cad.fabrication.rules import resting_placement


@pytest.fixture(scope="module")
def templates():
    return load_templates(None)


def _decode(form):
    pos = np.frombuffer(base64.b64decode(form["positions"]), dtype="<f4").reshape(-1, 3)
    kind = {"uint16": "<u2", "uint32": "<u4"}[form["index_type"]]
    idx = np.frombuffer(base64.b64decode(form["indices"]), dtype=kind).reshape(-1, 3)
    return pos, idx


@pytest.mark.parametrize("name", ["patkau-one-fold", "table1-row4", "star-polygon"])
def test_the_form_is_the_folded_mesh_standing_as_it_rests(templates, name):
    data, _ = templates
    design = design_from_params({"template": name}, data, name)
    state = design_state(design)
    json.dumps(state, allow_nan=False)  # the page gets strict JSON
    assert state["ok"] and state["messages"] == []
    pos, idx = _decode(state["form"])
    folded = fold_design(design)
    verts, faces = folded.mesh(MESH_ANGULAR, MESH_RADIAL)
    place = resting_placement(design, folded)  # the STEP body's placement, as the report's
    expected = place.apply(verts)
    size = float(np.ptp(expected, axis=0).max())
    assert state["numbers"]["height"] == place.height
    assert expected[:, 2].min() >= -1e-9 * size  # the sheet's surface lies in the body: not below
    assert pos.shape == expected.shape == (state["form"]["vertex_count"], 3)
    np.testing.assert_allclose(pos, expected, rtol=0, atol=2.0**-22 * size)  # float32
    np.testing.assert_array_equal(idx, faces)
    assert idx.max() < len(pos)


def test_the_crease_halves_keep_their_flat_lengths(templates):
    """A rectangle W x H folded along its diagonal with H at fraction f: the +x half
    (towards the corner (W, H)) is (1 - f) * hypot(W, H) long, the -x half f * hypot(W, H),
    on the folded form as on the flat sheet."""
    data, key = templates
    w, h, f = 1200.0, 2600.0, 0.35
    params = {"width": str(w), "height": str(h), "apex_fraction": str(f), "alpha": "41"}
    state = design_state(design_from_params(params, data, key))
    lengths = {
        c["half"]: math.dist(*c["points"]) for c in state["form"]["crease"]
    }  # both start at the apex
    diag = math.hypot(w, h)
    assert lengths["plus_x"] == pytest.approx((1 - f) * diag, rel=1e-12)
    assert lengths["minus_x"] == pytest.approx(f * diag, rel=1e-12)
    for c in state["form"]["crease"]:
        assert c["points"][0] == state["form"]["apex"]


def test_the_numbers_are_the_reports(templates):
    data, key = templates
    design = design_from_params({"alpha": "37", "beta": "41"}, data, key)
    n = design_state(design)["numbers"]
    r = design_report(design, fold_design(design))
    assert n["units"] == "mm"
    assert {k: v["deg"] for k, v in n["fold_angles"].items()} == r["fold_angles_deg"]
    assert {k: v["bend"] for k, v in n["fold_angles"].items()} == r["bend"]
    assert n["apex_height"] == r["direction_surface"]["apex_height"]
    assert n["height"] == r["resting"]["height"]
    assert n["span"] == r["resting"]["span"]
    assert n["width"] == r["resting"]["footprint"]["width"]
    assert n["depth"] == r["resting"]["footprint"]["depth"]
    assert n["flat_size"] == r["flat_size"]
    assert n["footprint_area"] == r["resting"]["footprint"]["area"]
    assert n["tilt_deg"] == r["resting"]["tilt_deg"]
    assert n["stable"] == r["resting"]["stable"]
    assert n["relief_hole"] == r["relief_hole_diameter"]
    assert n["angle_condition_error_deg"] == r["angle_condition_error_deg"]


@pytest.mark.parametrize(
    "params",
    [{"beta": "80"}, {"bend_radius": "400"}, {"beta": "80", "bend_radius": "400"}],
    ids=["tipping", "bend-limits", "both"],
)
def test_the_warnings_are_the_reports(templates, params):
    """The page's warnings are the report's, in its order, but for one that repeats
    the flat pattern's refusal already shown as the error (a nearly tipping form;
    bends past the model's limits: refused, the report measures the uncompensated
    blank)."""
    data, key = templates
    design = design_from_params(params, data, key)
    state = design_state(design)
    r = design_report(design, fold_design(design))
    errors = [m["text"] for m in state["messages"] if m["level"] == "error"]
    expected = [w for w in r["warnings"] if not any(w.startswith(e) for e in errors)]
    assert r["warnings"] and len(errors) == ("bend_radius" in params)
    assert [m["text"] for m in state["messages"] if m["level"] == "warning"] == expected
    assert state["numbers"]["flat_size"] == r["flat_size"]


def test_moving_alpha_moves_the_fold_angles(templates):
    data, key = templates
    a = design_state(design_from_params({"alpha": "30"}, data, key))["numbers"]["fold_angles"]
    b = design_state(design_from_params({"alpha": "50"}, data, key))["numbers"]["fold_angles"]
    assert a["plus_x"]["deg"] != b["plus_x"]["deg"]


def test_a_design_the_flat_pattern_refuses_keeps_its_form_and_gets_the_builds_message(
    capfd, tmp_path
):
    """Bend zones reaching the corners: no flat pattern, the CLI's words, the form still shown."""
    data, key = load_templates("paper-square")
    args = {"thickness": "5", "bend_radius": "150"}
    capfd.readouterr()
    status = main(
        ["build", "paper-square", "--thickness", "5", "--bend-radius", "150", "-o", str(tmp_path)]
    )
    err = capfd.readouterr().err.strip().splitlines()
    assert status == 2 and err[-1].startswith("onefold: error: ")
    state = design_state(design_from_params(args, data, key))
    assert state["ok"] and state["flat_svg"] is None
    assert [m["text"] for m in state["messages"] if m["level"] == "error"] == [
        err[-1][len("onefold: error: ") :]
    ]
    assert state["form"]["vertex_count"] > 0
    assert state["numbers"]["fold_angles"]["plus_x"]["deg"] > 0.0


@pytest.mark.parametrize(
    ("name", "flags", "material", "params"),
    [  # bend zones reaching the corners (page controls)
        ("paper-square", ["--thickness", "5", "--bend-radius", "150"], {},
         {"thickness": "5", "bend_radius": "150"}),
        ("paper-square", ["--relief-hole", "300"], {"relief_hole": 300.0}, {}),
        ("paper-square", ["--relief-hole", "3", "--kerf", "5"],
         {"relief_hole": 3.0, "kerf": 5.0}, {}),
        # the default hole max(3 t, 2 (t + r)) wider than the 3048 mm sheet: named after t
        ("patkau-one-fold", ["--thickness", "1100"], {}, {"thickness": "1100"}),
    ],
    ids=["bend-limits", "relief-hole", "kerf", "default-hole"],
)  # fmt: skip
def test_a_refused_flat_pattern_is_one_message_the_builds(
    capfd, tmp_path, name, flags, material, params
):
    """The refusal `onefold build` prints is shown once: as the error, not again as
    the report's warning with a tail (`...; build refuses the DXF ...`)."""
    capfd.readouterr()
    assert main(["build", name, *flags, "-o", str(tmp_path), "-q"]) == 2
    err = capfd.readouterr().err.strip().splitlines()[-1].removeprefix("onefold: error: ")
    # the command names a value given by a flag after the flag (--kerf); the page,
    # where the value came from the template, after the parameter (kerf)
    err = err.removeprefix("--")
    data, key = load_templates(name)
    template = dict(data[key])
    template["material"] = {**template["material"], **material}
    state = design_state(design_from_params(params, {key: template}, key))
    texts = [m["text"] for m in state["messages"]]
    assert [m["text"] for m in state["messages"] if m["level"] == "error"] == [err]
    core = err.split(" (", 1)[0]  # the problem, without its numbers' explanation
    assert sum(core in t for t in texts) == 1, texts
    # nor in other words: no other message about the same parameter or the hole
    others = [t.split(":", 1)[0] for t in texts if t != err]
    assert not {err.split(":", 1)[0], "relief_hole"} & set(others), texts


def test_the_triangles_the_page_has_are_not_sent_again(templates):
    """A move that keeps the mesh's triangles sends its positions only; another
    key (a page with other triangles) gets them again."""
    data, key = templates
    first = design_state(design_from_params({"alpha": "30"}, data, key))["form"]
    moved = design_from_params({"alpha": "31"}, data, key)
    again = design_state(moved, known_mesh=first["mesh_key"])["form"]
    assert again["mesh_key"] == first["mesh_key"] and again["indices"] is None
    assert again["positions"] != first["positions"]
    full = design_state(moved, known_mesh="0-0-0")["form"]
    _, idx = _decode(full)
    np.testing.assert_array_equal(idx, fold_design(moved).mesh(MESH_ANGULAR, MESH_RADIAL)[1])
    star = design_state(design_from_params({"template": "star-polygon"}, data, key))["form"]
    assert star["mesh_key"] != first["mesh_key"]
