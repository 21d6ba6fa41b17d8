"""The Hops server's rhino3dm objects: the .3dm's faces, placed as the .3dm
places them; the flat pattern's outline, hole and bend lines; the sheet read
from a closed polyline, anything else refused by name."""

from __future__ import annotations

import numpy as np
import pytest
import rhino3dm

from onefold_cad import Design, FrameCurve, Material, Sheet, fold_design
from onefold_cad.errors import InvalidSheetError
from onefold_cad.export.hops_geometry import (
    crease_lines,
    flat_curves,
    sheet_polygon,
)
from onefold_cad.export.rhino3dm_file import TOLERANCE
from onefold_cad.export.rhino_faces import face_nets, side_nets
from onefold_cad.export.rhino_sides import placement_of, side_breps
from onefold_cad.fabrication.flat_pattern import flat_pattern_once
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.fabrication.rules import resting_placement


@pytest.fixture(scope="module")
def holed():
    """A 2 mm sheet with its relief hole, an uneven polygon."""
    sheet = Sheet.polygon([[100, 0], [70, 90], [-40, 110], [-120, 0], [-60, -80], [80, -70]])
    design = Design("holed", FrameCurve(45, 35, h_c=5.0), sheet, material=Material(thickness=2.0))
    return design, fold_design(design)


def _net(brep) -> np.ndarray:
    n = brep.Surfaces[0].ToNurbsSurface()
    return np.array(
        [[(q := n.Points[i, j]).X, q.Y, q.Z] for i in range(n.Points.CountU) for j in range(2)]
    )


def test_breps_are_the_3dm_s_sides_moved_to_where_the_form_rests(holed):
    design, folded = holed
    hole = relief_hole_diameter(design, folded) / 2.0
    nets = side_nets(face_nets(folded, hole, TOLERANCE * folded.sheet.size))  # the .3dm's
    frame = [b for _, b in side_breps(design, folded, "frame")]
    rest = [b for _, b in side_breps(design, folded, "rest")]
    # one Brep a side, each of three sectors (two corners off the fold line a side)
    assert len(frame) == len(rest) == len(nets) == 2
    assert [len(n.sectors) for n in nets] == [3, 3]
    move = resting_placement(design, folded)
    for net, a, b in zip(nets, frame, rest, strict=True):
        want = np.stack([net.inner, net.outer], axis=1).reshape(-1, 3)
        assert np.allclose(_net(a), want, rtol=0, atol=1e-12 * folded.sheet.size)
        assert np.allclose(_net(b), move.apply(want), rtol=0, atol=1e-9 * folded.sheet.size)


def test_crease_lines_run_from_the_apex_to_the_crease_ends(holed):
    design, folded = holed
    lines = crease_lines(folded, placement_of(design, folded, "frame")[0])
    for line, half in zip(lines, folded.crease, strict=True):
        assert [line["From"][k] for k in "XYZ"] == folded.apex.tolist()
        assert [line["To"][k] for k in "XYZ"] == half.end_3d.tolist()


def test_flat_curves_are_the_flat_pattern_s(holed):
    design, folded = holed
    pattern = flat_pattern_once(design, folded)
    flat = flat_curves(pattern)
    pts = np.array(
        [[(p := flat.outline.Point(i)).X, p.Y, p.Z] for i in range(flat.outline.PointCount)]
    )
    assert flat.outline.IsClosed and np.all(pts[:, 2] == 0.0)
    assert np.array_equal(pts[:-1, :2], pattern.cut_outline)
    circle = flat.relief_hole.TryGetCircle()
    assert circle is not None
    assert circle.Radius == pytest.approx(pattern.cut_hole_diameter / 2.0, rel=1e-12)
    assert [circle.Center.X, circle.Center.Y] == pytest.approx(pattern.apex.tolist(), abs=1e-12)
    assert len(flat.bend_lines) == 2 and flat.bends == [h.bend for h in pattern.halves]
    for line, half in zip(flat.bend_lines, pattern.halves, strict=True):
        a, b = line.PointAtStart, line.PointAtEnd
        assert [a.X, a.Y, b.X, b.Y] == [*half.start.tolist(), *half.end.tolist()]
    assert flat.bend_angles_deg == [h.angle_deg for h in pattern.halves]


def test_the_paper_model_s_ruling_folds_are_bend_lines_too():
    design = Design("fan", FrameCurve(35, 40, divisions=6), Sheet.rectangle(8, 5, 0.4),
                    model="paper")  # fmt: skip
    pattern = flat_pattern_once(design, fold_design(design))
    flat = flat_curves(pattern)
    assert len(pattern.fold_rulings) > 0 and flat.relief_hole is None
    assert len(flat.bend_lines) == 2 + len(pattern.fold_rulings)
    assert flat.bends[2:] == [f.bend for f in pattern.fold_rulings]


def _polyline(*xyz) -> rhino3dm.PolylineCurve:
    return rhino3dm.PolylineCurve([rhino3dm.Point3d(*p) for p in xyz])


def test_a_closed_polyline_is_the_sheet_s_vertices():
    curve = _polyline((3, 0, 0), (0, 2, 0), (-1, 0, 0), (0, -1.5, 0), (3, 0, 0))
    assert sheet_polygon(curve) == [(3.0, 0.0), (0.0, 2.0), (-1.0, 0.0), (0.0, -1.5)]
    nurbs = rhino3dm.CommonObject.Decode(curve.ToNurbsCurve().Encode())  # degree 1: a polyline
    assert sheet_polygon(nurbs) == sheet_polygon(curve)


@pytest.mark.parametrize(
    ("thing", "words"),
    [
        (rhino3dm.Point(rhino3dm.Point3d(0, 0, 0)), "got a Point"),
        (_polyline((1, 0, 0), (0, 1, 0), (-1, 0, 0), (0, -1, 0)), "open"),
        (_polyline((1, 0, 0), (0, 1, 0), (1, 0, 0)), "open"),  # two points and back
        (rhino3dm.Circle(rhino3dm.Point3d(0, 0, 0), 1.0).ToNurbsCurve(), "straight segments"),
        (_polyline((1, 0, 0), (0, 1, 0), (-1, 0, 1e-9), (1, 0, 0)), "vertex 2 has z = 1e-09"),
    ],
)
def test_anything_else_is_refused_naming_the_sheet(thing, words):
    with pytest.raises(InvalidSheetError) as exc:
        sheet_polygon(thing, "sheet")
    assert exc.value.parameter == "sheet" and words in str(exc.value)
