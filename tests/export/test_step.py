"""Round-trip tests of the STEP adapter: write, re-read with build123d, measure."""

from __future__ import annotations

import math

import build123d as bd
import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from OCP.BRep import BRep_Tool
from OCP.collections import (
    IndexedDataMap_TopoDS_Shape_List_TopoDS_Shape_TopTools_ShapeMapHasher as EdgeFaceMap,
)
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopExp import TopExp
from OCP.TopoDS import TopoDS

from onefold_cad import (
    Design,
    ExportError,
    FrameCurve,
    InvalidParameterError,
    Material,
    Sheet,
    SheetSurface,
    Units,
    build_design,
)
from onefold_cad.design import relief_hole_diameter
from onefold_cad.export.flat_pattern import flat_pattern
from onefold_cad.export.report import design_report
from onefold_cad.export.step import (
    build_shell,
    default_body,
    export_design_step,
    measure,
    min_relief_hole,
    sheet_offsets,
)
from onefold_cad.geometry.frame import arc_points
from onefold_cad.geometry.thick_sheet import slab_volume

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
    foot = design.with_changes(units=Units.FT, name="foot")
    e = export_design_step(foot, tmp_path / "e.step")
    assert "CONVERSION_BASED_UNIT('FOOT'" in e.read_text()
    # the re-read shape is in the file's unit converted to mm by the reader
    re_in = bd.import_step(c)
    re_mm = bd.import_step(a)
    assert measure(re_in) == pytest.approx(measure(re_mm) * 25.4**2, rel=1e-6)
    assert measure(bd.import_step(e)) == pytest.approx(measure(re_mm) * 304.8**2, rel=1e-6)
    # the writer's unit setting is restored: a mm file afterwards is in mm again
    assert export_design_step(design, tmp_path / "f.step").read_bytes() == a.read_bytes()


@settings(max_examples=15, deadline=None)
@given(
    alpha=st.floats(5, 85),
    beta=st.floats(5, 85),
    frac=st.floats(-0.95, 0.95),
    sides=st.lists(st.floats(50, 500), min_size=4, max_size=4),
    hole=st.sampled_from([0.0, 10.0]),
)
@example(alpha=68.0, beta=85.0, frac=0.0, sides=[50.0] * 4, hole=0.0)  # long thin faces
@example(  # one cone face spans more than pi of the frame circle
    alpha=65.41593439132384,
    beta=52.359561249426015,
    frac=0.43,
    sides=[497.61656232, 353.07728238, 421.74139278, 421.74139278],
    hole=0.0,
)
def test_shell_of_random_designs_is_valid_with_the_flat_area(alpha, beta, frac, sides, hole):
    h_c = frac * 100.0 * math.cos(math.radians(alpha))
    design = Design("r", FrameCurve(alpha, beta, h_c), Sheet.quadrilateral(*sides))
    folded = build_design(design)
    shell = build_shell(folded, relief_hole=hole)
    assert shell.is_valid and len(shell.faces()) == 4
    # the free edges, unfolded, lie on the flat outline (or the hole's circle)
    v = design.sheet.vertices
    m = _face_edge_map(shell)
    for i in range(1, m.Extent() + 1):
        edge = bd.Edge(m.FindKey(i))
        if m.FindFromIndex(i).Size() != 1 or edge.length < 1e-9:
            continue
        pts = np.array([tuple(edge.position_at(t)) for t in np.linspace(0.0, 1.0, 21)])
        flat, _ = folded.unfold(pts)
        gap = np.abs(np.hypot(flat[:, 0], flat[:, 1]) - 0.5 * hole) if hole else np.inf
        for a, b in zip(v, np.roll(v, -1, axis=0), strict=True):
            t = np.clip((flat - a) @ (b - a) / ((b - a) @ (b - a)), 0.0, 1.0)
            gap = np.minimum(gap, np.linalg.norm(flat - (a + t[:, None] * (b - a)), axis=1))
        assert float(np.max(gap)) < 1e-6 * design.sheet.size
    flat_area = design.sheet.area - math.pi * hole**2 / 4.0
    assert measure(shell) == pytest.approx(flat_area, rel=1e-5)


# -- the sheet as a solid of thickness t ------------------------------------
SOLID_CASES = {  # name: (case, thickness, sheet_surface, relief hole; None = default)
    "table1-0-mid": ("table1-0", 3.0, SheetSurface.MID, None),
    "table1-0-inside": ("table1-0", 3.0, SheetSurface.INSIDE, 14.0),
    "table1-0-outside": ("table1-0", 3.0, SheetSurface.OUTSIDE, None),
    "table1-3-outside": ("table1-3", 2.0, SheetSurface.OUTSIDE, None),
    "rect-ft-in-mm-mid": ("rect-ft-in-mm", 3.57, SheetSurface.MID, None),
    "star-inside": ("star", 2.5, SheetSurface.INSIDE, 15.0),
}


@pytest.fixture(scope="module", params=sorted(SOLID_CASES))
def solid_trip(request, tmp_path_factory):
    case, t, surface, hole = SOLID_CASES[request.param]
    design = CASES[case][0]
    folded = build_design(design)
    material = Material(thickness=t, sheet_surface=surface, relief_hole=hole)
    design = design.with_changes(material=material)
    path = tmp_path_factory.mktemp("solid") / f"{design.name}.step"
    export_design_step(design, path, folded)  # default body: the solid
    return design, folded, bd.import_step(path)


def test_solid_is_one_valid_solid(solid_trip):
    _, _, shape = solid_trip
    assert shape.is_valid
    assert len(shape.solids()) == 1
    assert len(shape.shells()) == 1
    m = _face_edge_map(shape)
    for i in range(1, m.Extent() + 1):  # closed: every edge joins two faces
        edge = TopoDS.Edge(m.FindKey(i))
        assert m.FindFromIndex(i).Size() == 2 or BRep_Tool.Degenerated_s(edge)


def test_solid_volume_is_area_times_thickness(solid_trip):
    design, folded, shape = solid_trip
    m = design.material
    area = measure(build_shell(folded, relief_hole=m.relief_hole_diameter))
    volume = measure(shape, "volume")
    assert volume == pytest.approx(area * m.thickness, rel=0.01)  # the criterion
    if m.sheet_surface is SheetSurface.MID:  # the mid-surface of a developable slab
        assert volume == pytest.approx(area * m.thickness, rel=1e-3)
    # the volume computed from the geometry (curvature of the offsets, mitre)
    assert volume == pytest.approx(slab_volume(folded, m, m.relief_hole_diameter), rel=2e-3)


def test_solid_lies_on_the_side_sheet_surface_names(solid_trip):
    """Points off the reference surface along its top normal are inside the
    solid between the offsets sheet_offsets(material) and outside beyond them."""
    design, folded, shape = solid_trip
    m = design.material
    s0, s1 = sheet_offsets(m)
    t = m.thickness
    r_hole = 0.5 * m.relief_hole_diameter
    sheet = design.sheet
    pts, checked = [], 0
    for psi in np.concatenate([np.linspace(0.3, math.pi - 0.3, 5), -np.linspace(0.3, 2.8, 5)]):
        edge = float(sheet.ray_lengths(np.array([psi]))[0])
        for frac in (0.3, 0.7):
            r = r_hole + 3 * t + frac * (edge - r_hole - 6 * t)
            pts.append([r * math.cos(psi), r * math.sin(psi)])
    xy = np.array(pts)
    base = folded.map_points(xy)
    normal = folded.normals(xy)
    for p, n in zip(base, normal, strict=True):
        inside = [0.5 * (s0 + s1), s0 + 0.05 * t, s1 - 0.05 * t]
        outside = [s0 - 0.1 * t, s1 + 0.1 * t]
        for s in inside:
            assert shape.is_inside(bd.Vector(*(p + s * n)))
        for s in outside:
            assert not shape.is_inside(bd.Vector(*(p + s * n)))
        checked += 1
    assert checked == 20


def test_bad_input_is_a_clear_error_and_leaves_no_file(tmp_path):
    design = CASES["table1-0"][0]
    folded = build_design(design)
    with pytest.raises(InvalidParameterError, match="relief_hole"):
        build_shell(folded, relief_hole=1e6)
    with pytest.raises(InvalidParameterError, match="faces"):
        build_shell(folded, faces="fan")
    thick = design.with_changes(material=Material(thickness=1.0))
    need = min_relief_hole(folded, thick.material)
    assert 0.0 < need < thick.material.relief_hole_diameter  # the default hole is wide enough
    for hole in (0.0, 0.9 * need):  # no hole, or one too small for the mitre
        small = thick.with_changes(material=thick.material.with_changes(relief_hole=hole))
        with pytest.raises(InvalidParameterError, match=r"relief_hole: diameter must be in \("):
            export_design_step(small, tmp_path / "thick.step", folded, body="solid")
    with pytest.raises(InvalidParameterError, match="thickness"):
        export_design_step(design, tmp_path / "thick.step", folded, body="solid")
    paper = thick.with_changes(model="paper")
    with pytest.raises(InvalidParameterError, match="model"):
        export_design_step(paper, tmp_path / "thick.step", body="solid")
    with pytest.raises(InvalidParameterError, match="body"):
        export_design_step(thick, tmp_path / "thick.step", folded, body="mesh")
    assert list(tmp_path.iterdir()) == []
    # a design with thickness but no hole falls back to the reference surface
    flat_hole = thick.with_changes(material=thick.material.with_changes(relief_hole=0.0))
    assert default_body(flat_hole) == "shell" and default_body(thick) == "solid"
    written = export_design_step(flat_hole, tmp_path / "thick.step", folded)
    assert written.stat().st_size > 0 and [p.name for p in tmp_path.iterdir()] == ["thick.step"]
    assert len(bd.import_step(written).solids()) == 0


def test_default_relief_hole_fits_the_solid_and_every_export_cuts_it(tmp_path):
    """INSIDE on Table 1's square at t = 3 needs a hole > 11.88; the default
    max(3 t, 2 (t + r)) = 9 is raised to 1.1 x that, rounded up (14), and the
    STEP, the DXF's flat pattern and the report all use it."""
    design = CASES["table1-0"][0].with_changes(
        material=Material(thickness=3.0, sheet_surface=SheetSurface.INSIDE)
    )
    folded = build_design(design)
    need = min_relief_hole(folded, design.material)
    hole = relief_hole_diameter(design, folded)
    assert design.material.relief_hole_diameter == 9.0 < need < hole == 14.0
    assert flat_pattern(design, folded).hole_diameter == hole
    assert design_report(design, folded)["relief_hole_diameter"] == hole
    shape = bd.import_step(export_design_step(design, tmp_path / "d.step", folded))
    assert shape.is_valid and len(shape.solids()) == 1
    area = measure(build_shell(folded, relief_hole=hole))
    assert measure(shape, "volume") == pytest.approx(area * 3.0, rel=0.01)
    # an explicit hole is kept as it is (and this one is too small for a solid)
    fixed = design.with_changes(material=design.material.with_changes(relief_hole=9.0))
    assert relief_hole_diameter(fixed, folded) == 9.0


def test_kernel_failure_is_an_export_error_and_leaves_no_file(tmp_path, monkeypatch):
    import onefold_cad.export.step as step

    def broken(*args, **kwargs):
        raise RuntimeError("simulated OCC failure")

    design = CASES["table1-0"][0].with_changes(material=Material(thickness=3.0))
    monkeypatch.setattr(step, "thick_solid", broken)
    with pytest.raises(ExportError, match="simulated OCC failure"):
        export_design_step(design, tmp_path / "x.step")
    monkeypatch.setattr(step, "ruled_faces", broken)
    with pytest.raises(ExportError, match="simulated OCC failure"):
        export_design_step(design, tmp_path / "x.step", body="shell")
    assert list(tmp_path.iterdir()) == []
