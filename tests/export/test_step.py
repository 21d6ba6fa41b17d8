"""Round-trip tests of the STEP adapter: write, re-read with build123d, measure."""

from __future__ import annotations

import math

import build123d as bd
import numpy as np
import pytest
from OCP.collections import (
    IndexedDataMap_TopoDS_Shape_List_TopoDS_Shape_TopTools_ShapeMapHasher as EdgeFaceMap,
)
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopExp import TopExp

from onefold_cad import (
    Design,
    ExportError,
    FrameCurve,
    InvalidParameterError,
    Material,
    Sheet,
    Units,
    build_design,
)
from onefold_cad.export.step import build_shell, export_design_step, measure
from onefold_cad.geometry.frame import arc_points

TABLE1 = [  # (H_c, alpha, beta, divisions, Y+, Y-, X+, X-)
    (0, 50, 45, 90, 300, 300, 300, 300),
    (0, 50, 45, 20, 300, 300, 300, 300),
    (0, 32, 34, 90, 300, 300, 300, 300),
    (68, 32, 34, 90, 300, 96, 103, 201),
]


def _star() -> Sheet:
    ang = np.radians(np.arange(10) * 36.0 + 7.0)
    rad = np.where(np.arange(10) % 2 == 0, 260.0, 150.0)
    pts = np.stack([rad * np.cos(ang), rad * np.sin(ang)], axis=1) + [35.0, -20.0]
    return Sheet.polygon(pts)


def _designs() -> dict[str, tuple[Design, float]]:
    out: dict[str, tuple[Design, float]] = {}
    for i, (hc, a, b, n, yp, ym, xp, xm) in enumerate(TABLE1):
        d = Design(f"table1-{i}", FrameCurve(a, b, hc, 100, n), Sheet.quadrilateral(xp, xm, yp, ym))
        out[d.name] = (d, 0.0)
    out["table1-0-hole"] = (out["table1-0"][0].with_changes(name="t1h"), 8.0)
    rect = Sheet.rectangle(10 * 304.8, 24 * 304.8)
    out["rect-ft-in-mm"] = (Design("rect", FrameCurve(40, 40, 0, 1000), rect), 0.0)
    out["rect-hole"] = (Design("recth", FrameCurve(40, 40, 0, 1000), rect), 60.0)
    star = _star()
    out["star"] = (Design("star", FrameCurve(45, 40, 10, 120), star), 0.0)
    out["star-hole"] = (Design("starh", FrameCurve(45, 40, 10, 120), star), 12.0)
    out["paper-fan-hole"] = (out["table1-3"][0].with_changes(name="pf", model="paper"), 6.0)
    return out


CASES = _designs()


def _face_edge_map(shape: bd.Shape) -> EdgeFaceMap:
    m = EdgeFaceMap()
    TopExp.MapShapesAndAncestors_s(shape.wrapped, TopAbs_EDGE, TopAbs_FACE, m)
    return m


@pytest.fixture(scope="module", params=sorted(CASES))
def round_trip(request, tmp_path_factory):
    design, hole = CASES[request.param]
    folded = build_design(design)
    design = design.with_changes(material=Material(relief_hole=hole))
    path = tmp_path_factory.mktemp("step") / f"{design.name}.step"
    export_design_step(design, path, folded)
    return design, folded, hole, bd.import_step(path)


def test_valid_one_sewn_shell(round_trip):
    design, folded, _, shape = round_trip
    assert shape.is_valid
    assert len(shape.shells()) == 1
    assert len(shape.solids()) == 0
    m = _face_edge_map(shape)
    for i in range(1, m.Extent() + 1):
        assert m.FindFromIndex(i).Size() in (1, 2)  # no edge of three faces


def test_face_count_independent_of_divisions(round_trip):
    design, folded, _, shape = round_trip
    n_faces = len(shape.faces())
    if design.model.value == "paper":
        # the fan's triangles: one per sector of positive width
        assert n_faces == sum(int(np.sum(np.diff(t) > 1e-9)) for t in folded.ruling_angles)
    else:
        assert n_faces == len(design.sheet.vertices)  # one per sheet edge


def test_area_equals_flat_area(round_trip):
    design, _, hole, shape = round_trip
    flat = design.sheet.area - math.pi * hole**2 / 4.0
    assert measure(shape) == pytest.approx(flat, rel=1e-5)


def test_free_boundary_length_equals_flat_perimeter(round_trip):
    design, _, hole, shape = round_trip
    m = _face_edge_map(shape)
    free = 0.0
    for i in range(1, m.Extent() + 1):
        edge = bd.Edge(m.FindKey(i))
        if m.FindFromIndex(i).Size() == 1:
            free += edge.length
    assert free == pytest.approx(design.sheet.perimeter + math.pi * hole, rel=1e-5)


def test_crease_dihedral_equals_fold_angle(round_trip):
    design, folded, _, shape = round_trip
    apex = folded.apex
    m = _face_edge_map(shape)
    found = 0
    for half in folded.crease:
        axis = (half.end_3d - apex) / np.linalg.norm(half.end_3d - apex)
        for i in range(1, m.Extent() + 1):
            faces = m.FindFromIndex(i)
            if faces.Size() != 2:
                continue
            edge = bd.Edge(m.FindKey(i))
            mid = np.array(tuple(edge.position_at(0.5)))
            w = (mid - apex) / np.linalg.norm(mid - apex)
            if np.linalg.norm(np.cross(w, axis)) > 1e-9 or np.dot(w, axis) < 0:
                continue
            f1, f2 = (bd.Face(f) for f in faces)
            n1 = np.array(tuple(f1.normal_at(bd.Vector(*mid))))
            n2 = np.array(tuple(f2.normal_at(bd.Vector(*mid))))
            ang = math.degrees(math.atan2(np.linalg.norm(np.cross(n1, n2)), np.dot(n1, n2)))
            assert ang == pytest.approx(half.fold_angle_deg, abs=0.01)
            found += 1
    assert found == 2


def _cone_distance(design: Design, apex: np.ndarray, pts: np.ndarray) -> np.ndarray:
    """Distance of points to the cone from ``apex`` over the frame circle (either side)."""
    fr = design.frame
    out = np.full(len(pts), np.inf)
    for mirror in (1.0, -1.0):
        c3 = arc_points(fr, np.array([0.0, 0.5 * math.pi, math.pi])) * [1.0, mirror, 1.0]
        centre = 0.5 * (c3[0] + c3[2])
        normal = np.cross(c3[0] - centre, c3[1] - centre)
        normal /= np.linalg.norm(normal)
        d = pts - apex
        s = np.dot(centre - apex, normal) / (d @ normal)
        q = apex + s[:, None] * d
        off = np.abs(np.linalg.norm(q - centre, axis=1) - fr.radius) / np.abs(s)
        out = np.minimum(out, off)
    return out


def test_face_points_lie_on_the_surface(round_trip):
    """Exact model: on the exact cone; paper model: on the fan plane through the apex."""
    design, folded, _, shape = round_trip
    tol = 1e-6 * design.sheet.size
    if design.model.value == "paper":
        for face in shape.faces():
            n = np.array(tuple(face.normal_at()))
            for u in np.linspace(0.1, 0.9, 3):
                p = np.array(tuple(face.position_at(u, u)))
                assert abs(float(np.dot(p - folded.apex, n))) < tol
        return
    pts = []
    for face in shape.faces():
        for u in np.linspace(0.05, 0.95, 7):
            for v in np.linspace(0.05, 0.95, 7):
                p = np.array(tuple(face.position_at(u, v)))
                if np.linalg.norm(p - folded.apex) > 1e-6 * design.sheet.size:
                    pts.append(p)
    dist = _cone_distance(design, folded.apex, np.array(pts))
    assert float(np.max(dist)) < tol


def test_face_kinds(round_trip):
    design, _, _, shape = round_trip
    kind = bd.GeomType.PLANE if design.model.value == "paper" else bd.GeomType.BSPLINE
    assert {face.geom_type for face in shape.faces()} == {kind}


def test_deterministic_bytes_units_and_name(tmp_path):
    design = CASES["table1-3"][0]
    a = export_design_step(design, tmp_path / "a.step")
    b = export_design_step(design, tmp_path / "b.step")
    assert a.read_bytes() == b.read_bytes()
    text = a.read_text()
    assert "PRODUCT('table1-3'" in text
    inch = design.with_changes(units=Units.IN, name="inch")
    c = export_design_step(inch, tmp_path / "c.step")
    assert "INCH" in c.read_text().upper()
    assert "INCH" not in text.upper()
    # the re-read shape is in the file's unit converted to mm by the reader
    re_in = bd.import_step(c)
    re_mm = bd.import_step(a)
    assert measure(re_in) == pytest.approx(measure(re_mm) * 25.4**2, rel=1e-6)


def test_bad_input_is_a_clear_error_and_leaves_no_file(tmp_path):
    design = CASES["table1-0"][0]
    folded = build_design(design)
    with pytest.raises(InvalidParameterError, match="relief_hole"):
        build_shell(folded, relief_hole=1e6)
    with pytest.raises(InvalidParameterError, match="faces"):
        build_shell(folded, faces="fan")
    thick = design.with_changes(material=Material(thickness=1.0))
    with pytest.raises((ExportError, InvalidParameterError)):
        export_design_step(thick, tmp_path / "thick.step", folded, body="solid")
    with pytest.raises(InvalidParameterError, match="body"):
        export_design_step(thick, tmp_path / "thick.step", folded, body="mesh")
    assert list(tmp_path.iterdir()) == []
    # the default body is the reference surface, which works with thickness too
    written = export_design_step(thick, tmp_path / "thick.step", folded)
    assert written.stat().st_size > 0 and [p.name for p in tmp_path.iterdir()] == ["thick.step"]
