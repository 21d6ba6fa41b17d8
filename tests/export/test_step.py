"""Round-trip tests of the STEP adapter: write, re-read with build123d, measure
against values derived independently (flat area and perimeter, fold angles,
the cone's equation, the integrated slab volume, area x t for MID)."""

from __future__ import annotations

import math

import build123d as bd
import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st
from OCP.BRep import BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
from OCP.BRepExtrema import BRepExtrema_DistShapeShape
from OCP.collections import (
    IndexedDataMap_TopoDS_Shape_List_TopoDS_Shape_TopTools_ShapeMapHasher as EdgeFaceMap,
)
from OCP.gp import gp_Dir, gp_Pln, gp_Pnt
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopExp import TopExp
from OCP.TopoDS import TopoDS

from onefold_cad import (
    Design,
    ExportError,
    FrameCurve,
    InvalidParameterError,
    Material,
    NoSolutionError,
    Sheet,
    SheetSurface,
    Units,
    fold_design,
)
from onefold_cad.errors import FabricationError
from onefold_cad.export.fan_faces import PRECISION
from onefold_cad.export.measure import measure
from onefold_cad.export.part import SOLID_TOLERANCE, build_part, build_shell, build_solid
from onefold_cad.export.step import export_design_step
from onefold_cad.export.step_checks import BOUNDARY_TOLERANCE
from onefold_cad.fabrication.bend_checks import bend_error, check_bends
from onefold_cad.fabrication.flat_pattern import flat_pattern
from onefold_cad.fabrication.relief_hole import relief_hole_diameter, solid_min_relief_hole
from onefold_cad.fabrication.report import design_report
from onefold_cad.fabrication.rules import default_body, resting_placement
from onefold_cad.geometry.arc import arc_points
from onefold_cad.geometry.material import sheet_offsets
from onefold_cad.geometry.slab_volume import slab_volume
from tests.angles import cos_deg, frame_unless_on_end, refused_below_bound

TABLE1 = [  # (H_c, alpha, beta, divisions, Y+, Y-, X+, X-)
    (0, 50, 45, 90, 300, 300, 300, 300),
    (0, 50, 45, 20, 300, 300, 300, 300),
    (0, 32, 34, 90, 300, 300, 300, 300),
    (68, 32, 34, 90, 300, 96, 103, 201),
]
#: Solid volume against the volume integrated from the geometry: the edge
#: curves lie within 1e-6 of the sheet's size of the exact ones, and the
#: volume they enclose agrees to a few 1e-6 (the build itself refuses 1e-4).
SOLID_VOLUME_AGREEMENT = 2e-5


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


def _free_length(shape: bd.Shape) -> float:
    m = _face_edge_map(shape)
    return sum(
        bd.Edge(m.FindKey(i)).length
        for i in range(1, m.Extent() + 1)
        if m.FindFromIndex(i).Size() == 1
    )


def _boundary_tolerance(design: Design) -> float:
    """How far (length) the exact shell's boundary curves may lie from the
    sheet's edges mapped onto the cone: the stated tolerance (0 for the fan,
    which is exact)."""
    return BOUNDARY_TOLERANCE * design.sheet.size if design.model.value == "exact" else 0.0


@pytest.fixture(scope="module", params=sorted(CASES))
def round_trip(request, tmp_path_factory):
    design, hole = CASES[request.param]
    folded = fold_design(design)
    design = design.with_changes(material=Material(relief_hole=hole))
    path = tmp_path_factory.mktemp("step") / f"{design.name}.step"
    export_design_step(design, path, folded, placement="frame")
    return design, folded, hole, bd.import_step(path)


def test_shell_reads_back_as_one_valid_shell(round_trip):
    _, _, _, shape = round_trip
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
    """Developable: the folded area is the flat one; a boundary within ``tol``
    of the exact curve moves it by at most tol x perimeter (OCC integrates
    to 1e-9)."""
    design, _, hole, shape = round_trip
    flat = design.sheet.area - math.pi * hole**2 / 4.0
    perimeter = design.sheet.perimeter + math.pi * hole
    bound = _boundary_tolerance(design) * perimeter / flat + 1e-8
    assert measure(shape) == pytest.approx(flat, rel=bound)


def test_free_boundary_length_equals_flat_perimeter(round_trip):
    design, _, hole, shape = round_trip
    assert _free_length(shape) == pytest.approx(design.sheet.perimeter + math.pi * hole, rel=1e-7)


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
            assert ang == pytest.approx(half.fold_angle_deg, abs=1e-6)
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
    """Exact model: on the exact cone (a rational B-spline holds it to
    rounding); paper model: on the fan's plane through the apex."""
    design, folded, _, shape = round_trip
    tol = 1e-9 * design.sheet.size
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
    assert measure(re_in) == pytest.approx(measure(re_mm) * 25.4**2, rel=1e-9)
    assert measure(bd.import_step(e)) == pytest.approx(measure(re_mm) * 304.8**2, rel=1e-9)
    # the writer's unit setting is restored: a mm file afterwards is in mm again
    assert export_design_step(design, tmp_path / "f.step").read_bytes() == a.read_bytes()


#: (0, 90) deg: from 0 (below the angle bound the frame is refused, and a
#: NoSolutionError leaves nothing to write: neither is a STEP matter) to the
#: largest double below 90.
_ANGLE = st.floats(0.0, 90.0, exclude_min=True, exclude_max=True)


@settings(max_examples=15, deadline=None)
@given(
    alpha=_ANGLE,
    beta=_ANGLE,
    frac=st.floats(-1.0, 1.0, exclude_min=True, exclude_max=True),
    sides=st.lists(st.floats(50, 500), min_size=4, max_size=4),
    hole=st.sampled_from([0.0, 10.0]),
)
@example(alpha=68.0, beta=85.0, frac=0.0, sides=[50.0] * 4, hole=0.0)  # long thin faces
# within 3e-14 deg of 90 the crease's two halves lie along one ray (to rounding)
@example(alpha=89.99999999999997, beta=45.0, frac=0.5, sides=[200.0, 150.0, 300.0, 250.0], hole=0.0)
@example(
    alpha=math.nextafter(90.0, 0.0),
    beta=math.nextafter(90.0, 0.0),
    frac=0.5,
    sides=[200.0, 150.0, 300.0, 250.0],
    hole=10.0,
)
@example(  # one cone face spans more than pi of the frame circle
    alpha=65.41593439132384,
    beta=52.359561249426015,
    frac=0.43,
    sides=[497.61656232, 353.07728238, 421.74139278, 421.74139278],
    hole=0.0,
)
@example(alpha=5.0, beta=89.9, frac=0.9, sides=[300.0, 50.0, 300.0, 50.0], hole=0.0)  # beta near 90
# the hole's curve on a face across the rational arc's C1 knot was 1.2e-4 off between the
# fit's nodes while right at their midpoints (checked at the quarters since)
@example(alpha=45.5, beta=89.0, frac=0.5625, sides=[50.0, 50.0, 50.0, 109.0], hole=10.0)
def test_shell_of_random_designs_is_valid_and_develops_onto_the_sheet(
    alpha, beta, frac, sides, hole
):
    if refused_below_bound(alpha, beta, lambda: FrameCurve(alpha, beta)):
        return
    half = 100.0 * cos_deg(alpha)
    h_c = frac * half
    frame = frame_unless_on_end(lambda: FrameCurve(alpha, beta, h_c), h_c, half)
    assume(frame is not None)  # H on an end of the f-line by rounding: refused
    design = Design("r", frame, Sheet.quadrilateral(*sides))
    try:
        folded = fold_design(design)
    except NoSolutionError:
        assume(False)  # no fold to write (the solver's matter)
    try:
        shell = build_shell(folded, relief_hole=hole)
    except ExportError as err:
        # refused only where the cone folds back onto itself (alpha and beta near
        # 90): two neighbouring vertices of a face land within the kernel's precision
        assert "folds back onto itself" in str(err) and "beta" in str(err)
        assert _closest_neighbours_on_the_cone(folded, hole) <= PRECISION * (1.0 + 1e-6)
        return
    assert shell.is_valid and len(shell.faces()) == 4
    assert shell.fit_deviation <= shell.fit_tolerance == BOUNDARY_TOLERANCE * design.sheet.size
    _free_edges_develop_onto_the_outline(folded, shell, hole)
    perimeter = design.sheet.perimeter + math.pi * hole
    assert _free_length(shell) == pytest.approx(perimeter, rel=1e-7)


def _closest_neighbours_on_the_cone(folded, hole: float) -> float:
    """The smallest 3D distance between the images of two neighbouring
    corners of one side's faces on the sheet: its vertices (crease ends
    included) or, with a hole, the hole's points on their rays, mapped by
    the fold."""
    v = folded.sheet.vertices
    best = math.inf
    for upper in (True, False):
        pts = v[v[:, 1] >= 0.0] if upper else v[v[:, 1] <= 0.0]
        ang = np.arctan2(np.abs(pts[:, 1]), pts[:, 0])
        pts = pts[np.argsort(ang)]
        rings = [pts]
        if hole:
            rings.append(0.5 * hole * pts / np.hypot(pts[:, 0], pts[:, 1])[:, None])
        for ring in rings:
            mapped = folded.map_points(ring)
            best = min(best, float(np.min(np.linalg.norm(np.diff(mapped, axis=0), axis=1))))
    return best


def _free_edges_develop_onto_the_outline(folded, shell, hole: float) -> None:
    """Each free edge of the shell is a sheet edge developed onto the cone
    (the development is an isometry that keeps distances from the apex):
    its ends are the sheet's vertices mapped onto the cone, and its point at
    a fraction t of its length lies as far from the apex as the flat edge's
    point at t lies from H; a hole edge lies the hole's radius from the
    apex. No unfolding: within ~3e-14 deg of alpha = 90 the crease's two
    halves run along one ray (to rounding) and a point on it has no one
    flat image."""
    tol = 2.0 * shell.fit_tolerance
    v = folded.sheet.vertices
    corners = folded.map_points(v)
    apex = folded.apex
    m = _face_edge_map(shell)
    for i in range(1, m.Extent() + 1):
        edge = bd.Edge(m.FindKey(i))
        if m.FindFromIndex(i).Size() != 1 or edge.length < 1e-9:
            continue
        t = np.linspace(0.0, 1.0, 21)
        pts = np.array([tuple(edge.position_at(x)) for x in t])
        r = np.linalg.norm(pts - apex, axis=1)
        if hole and float(np.max(np.abs(r - 0.5 * hole))) < tol:
            continue  # a piece of the hole's circle
        ends = np.linalg.norm(corners[:, None, :] - pts[[0, -1]][None, :, :], axis=2)
        k = int(np.argmin(ends[:, 0]))  # the vertex at the edge's start
        nxt, prv = (k + 1) % len(v), (k - 1) % len(v)
        j = nxt if ends[nxt, 1] <= ends[prv, 1] else prv
        assert ends[k, 0] < tol and ends[j, 1] < tol
        flat = v[k] + t[:, None] * (v[j] - v[k])
        assert float(np.max(np.abs(r - np.hypot(flat[:, 0], flat[:, 1])))) < tol


def test_unreachable_boundary_fit_is_an_export_error(monkeypatch):
    """The shell never silently misses its stated tolerance: with too few
    points allowed the fit cannot reach it, and the build says so."""
    import onefold_cad.export.cone_faces as brep

    folded = fold_design(CASES["star"][0])
    monkeypatch.setattr(brep, "MAX_NODES", 20)
    with pytest.raises(ExportError, match="more than .* points to stay within"):
        build_shell(folded)


@pytest.mark.parametrize("hole", [0.0, 4.0])
def test_fan_shell_shares_its_topology(hole):
    """1000 divisions: one apex vertex (or one hole vertex per ruling), every
    ruling an edge of the two triangles beside it (the crease rulings of both
    sides), the free edges the sheet's outline (and the hole)."""
    frame = FrameCurve(50, 45, 20, 100, 1000)
    design = Design("fan", frame, Sheet.quadrilateral(300, 200, 250, 150), model="paper")
    folded = fold_design(design)
    shell = build_shell(folded, relief_hole=hole)
    assert shell.is_valid
    rulings = sum(len(a) for a in folded.ruling_angles) - 2  # the crease rulings once
    triangles = sum(len(a) - 1 for a in folded.ruling_angles)
    assert len(shell.faces()) == triangles
    ends = rulings
    assert len(shell.vertices()) == ends + (1 if hole == 0.0 else rulings)
    m = _face_edge_map(shell)
    uses = [m.FindFromIndex(i).Size() for i in range(1, m.Extent() + 1)]
    assert uses.count(2) == rulings  # every ruling between two triangles
    assert uses.count(1) == triangles * (2 if hole else 1)  # outline (and hole) pieces
    assert _free_length(shell) == pytest.approx(
        design.sheet.perimeter + math.pi * hole, rel=1e-12 if hole == 0.0 else 1e-6
    )


def _tiny_sharp_fan(scale: float) -> Design:
    """A fan of 385 divisions folded almost flat onto itself (beta near 90
    deg) on a sheet ``scale`` x a couple of millimetres: neighbouring ruling
    ends and hole points come within micrometres (from the STEP corpus)."""
    sheet = Sheet.quadrilateral(
        1.278336 * scale, 1.568703 * scale, 1.781668 * scale, 0.869489 * scale
    )
    frame = FrameCurve(6.734977187126817, 89.98568127260206, 26.219145054933023, 100, 385)
    return Design("tiny", frame, sheet, model="paper")


@pytest.mark.parametrize(("scale", "hole"), [(0.01, 0.0), (1.0, 0.014)])
def test_fan_leaves_out_rulings_closer_than_the_kernel_resolves(scale, hole):
    """Ruling ends closer than 3 x NEAR, or hole points closer than 4 x OCC's
    precision (1e-7), are one ruling (OCC cannot make edges that short): the
    two triangles beside a left-out ruling become one, and the outline and
    the hole's boundary shorten by less than twice those gaps per ruling."""
    from onefold_cad.export.fan_faces import NEAR, PRECISION

    design = _tiny_sharp_fan(scale)
    folded = fold_design(design)
    triangles = sum(len(a) - 1 for a in folded.ruling_angles)
    shell = build_shell(folded, relief_hole=hole)
    assert shell.is_valid
    assert len(shell.faces()) < triangles  # some rulings left out
    dropped = triangles - len(shell.faces())
    outline = design.sheet.perimeter + math.pi * hole
    # leaving out a point within g of the last kept one shortens a chain by < 2 g
    gaps = 3 * NEAR + (4 * PRECISION if hole else 0.0)
    assert _free_length(shell) == pytest.approx(outline, abs=2 * gaps * dropped)


def test_relief_hole_below_the_kernel_resolution_is_refused_with_what_to_change():
    with pytest.raises(ExportError, match=r"below what the CAD kernel resolves.*--relief-hole 0"):
        build_shell(fold_design(CASES["table1-0"][0]), relief_hole=5e-5)


def test_kernel_time_budget_is_an_export_error_naming_what_to_reduce():
    paper = Design("fan", FrameCurve(50, 45, 0, 100, 3000), Sheet.quadrilateral(300, 300, 300, 300))
    folded = fold_design(paper.with_changes(model="paper"))
    with pytest.raises(ExportError, match="time budget .* fewer divisions"):
        build_shell(folded, budget=0.0)
    thick = CASES["table1-0"][0]
    folded = fold_design(thick)
    m = Material(thickness=3.0, relief_hole=20.0)
    with pytest.raises(ExportError, match="time budget .* thinner sheet"):
        build_solid(folded, m, budget=0.0)


# -- the part as it stands ----------------------------------------------------
def _lowest(shape: bd.Shape, size: float) -> tuple[float, float]:
    """Distances from ``shape`` to the planes z = 0 and z = -size (exact
    extrema): 0 and ``size`` when its lowest point lies on z = 0."""
    out = []
    for z in (0.0, -size):
        plane = BRepBuilderAPI_MakeFace(
            gp_Pln(gp_Pnt(0.0, 0.0, z), gp_Dir(0.0, 0.0, 1.0)), -1e6, 1e6, -1e6, 1e6
        ).Face()
        out.append(BRepExtrema_DistShapeShape(shape.wrapped, plane).Value())
    return out[0], out[1]


def _vertices(shape: bd.Shape) -> np.ndarray:
    return np.array([tuple(v) for v in shape.vertices()])


@pytest.mark.parametrize("body", ["shell", "solid"])
def test_step_stands_on_the_ground_moved_by_the_resting_placement(tmp_path, body):
    design = CASES["table1-0"][0]
    if body == "solid":
        design = design.with_changes(material=Material(thickness=3.0))
    folded = fold_design(design)
    rest = bd.import_step(export_design_step(design, tmp_path / "rest.step", folded, body=body))
    frame = bd.import_step(
        export_design_step(design, tmp_path / "frame.step", folded, body=body, placement="frame")
    )
    assert rest.is_valid and frame.is_valid
    size = design.sheet.size
    # the lowest point on the ground, nothing below it
    on, below = _lowest(rest, size)
    assert on < 1e-7 * size
    assert below == pytest.approx(size, abs=1e-7 * size)
    # the same part moved by the design's resting placement of this body (the
    # report's): rotation and translation, then at most a lift of the B-rep's
    # own lowest point onto the ground, within the curves' fit tolerance
    place = resting_placement(design, folded, body)
    turned = _vertices(frame) @ place.rotation.T + place.translation
    moved = _vertices(rest)
    shift = moved.mean(axis=0) - turned.mean(axis=0)
    gap = np.linalg.norm(turned[:, None, :] + shift - moved[None, :, :], axis=2).min(axis=1)
    assert float(gap.max()) < 1e-9 * size
    t = design.material.thickness
    tol = min(SOLID_TOLERANCE * size, 1e-3 * t) if body == "solid" else BOUNDARY_TOLERANCE * size
    assert np.all(np.abs(shift[:2]) < 1e-9 * size)
    assert abs(shift[2]) <= tol
    with pytest.raises(InvalidParameterError, match="placement"):
        build_part(design, folded, placement="floor")


def _corner_design() -> Design:
    """A 40 x 100 sheet folded to about 160 deg, 3.57 mm thick, inside radius 6: the
    bend's set-back is far beyond the flanges beside it (past the bend model's limits)."""
    return Design("corner", FrameCurve(60, 70), Sheet.rectangle(40, 100, 0.5),
                  material=Material(thickness=3.57, bend_radius=6.0))  # fmt: skip


def test_a_solid_past_the_bend_limits_is_refused_unless_compensation_none(tmp_path):
    """The solid stands for the bent part only inside the bend model's limits: past
    them build_part and export_design_step refuse it with the bend model's own error
    (the same one ``build`` gives before writing) and leave no file; 'none' builds it
    as designed; the shell, the designed surface, is never refused for it."""
    design = _corner_design()
    folded = fold_design(design)
    half = folded.crease[0]
    t, r = design.material.thickness, design.material.bend_radius
    # by hand: MID reference, so the set-back is (r + t / 2) tan(psi / 2)
    setback = (r + t / 2) * math.tan(math.radians(half.fold_angle_deg) / 2)
    expected = bend_error(
        tuple(q for q in check_bends(folded, design.material, design.units) if q.kind != "width")
    )
    assert expected is not None
    with pytest.raises(FabricationError) as err:
        build_part(design, folded)  # the default body is the solid
    assert str(err.value) == str(expected) and err.value.parameter == "bend_radius"
    assert f"{half.name} (fold angle {half.fold_angle_deg:.2f} deg" in str(err.value)
    assert f"set-back SB = {setback:.3g} mm" in str(err.value)
    with pytest.raises(FabricationError, match="^bend_radius: "):
        export_design_step(design, tmp_path / "corner.step", folded)
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(InvalidParameterError, match="compensation"):
        build_part(design, folded, compensation="bent")
    solid = build_part(design, folded, compensation="none")
    assert isinstance(solid, bd.Solid) and solid.is_valid
    assert isinstance(build_part(design, folded, body="shell"), bd.Shell)


# -- the sheet as a solid of thickness t ------------------------------------
SOLID_CASES = {  # name: (case, thickness, sheet_surface, relief hole; None = default)
    "table1-0-mid": ("table1-0", 3.0, SheetSurface.MID, None),
    "table1-0-inside": ("table1-0", 3.0, SheetSurface.INSIDE, 15.0),
    "table1-0-outside": ("table1-0", 3.0, SheetSurface.OUTSIDE, None),
    "table1-3-outside": ("table1-3", 2.0, SheetSurface.OUTSIDE, None),
    "rect-ft-in-mm-mid": ("rect-ft-in-mm", 3.57, SheetSurface.MID, None),
    "star-inside": ("star", 2.5, SheetSurface.INSIDE, 15.0),
}


_SOLIDS: dict[str, tuple[Design, object, bd.Shape]] = {}


def _solid_trip(name: str, tmp_path_factory) -> tuple[Design, object, bd.Shape]:
    """Write solid case ``name`` as STEP (fold frame) and read it back, once."""
    if name not in _SOLIDS:
        case, t, surface, hole = SOLID_CASES[name]
        design = CASES[case][0]
        folded = fold_design(design)
        material = Material(thickness=t, sheet_surface=surface, relief_hole=hole)
        design = design.with_changes(material=material)
        path = tmp_path_factory.mktemp("solid") / f"{design.name}.step"
        export_design_step(design, path, folded, placement="frame")  # default body: the solid
        m = material.with_changes(relief_hole=relief_hole_diameter(design, folded))
        _SOLIDS[name] = (design.with_changes(material=m), folded, bd.import_step(path))
    return _SOLIDS[name]


@pytest.fixture(params=sorted(SOLID_CASES))
def solid_trip(request, tmp_path_factory):
    return _solid_trip(request.param, tmp_path_factory)


@pytest.fixture(params=sorted(k for k, v in SOLID_CASES.items() if v[2] is SheetSurface.MID))
def mid_trip(request, tmp_path_factory):
    return _solid_trip(request.param, tmp_path_factory)


def test_solid_reads_back_as_one_valid_closed_solid(solid_trip):
    _, _, shape = solid_trip
    assert shape.is_valid
    assert len(shape.solids()) == 1
    assert len(shape.shells()) == 1
    m = _face_edge_map(shape)
    for i in range(1, m.Extent() + 1):  # closed: every edge joins two faces
        edge = TopoDS.Edge(m.FindKey(i))
        assert m.FindFromIndex(i).Size() == 2 or BRep_Tool.Degenerated_s(edge)


def test_solid_volume_matches_the_volume_integrated_from_the_geometry(solid_trip):
    design, folded, shape = solid_trip
    m = design.material
    expected = slab_volume(folded, m, m.relief_hole_diameter)
    assert measure(shape, "volume") == pytest.approx(expected, rel=SOLID_VOLUME_AGREEMENT)


def test_mid_solid_volume_is_area_times_thickness_up_to_the_mitre(mid_trip):
    """A developable mid-surface slab holds area x t; the mitre adds a wedge
    on the convex side of each crease half and takes about as much off the
    concave side, so the difference is less than those wedges:
    2 sides x length x (t/2) x (t/2) tan(psi/2) / 2 per crease half."""
    design, folded, shape = mid_trip
    m = design.material
    t = m.thickness
    area = design.sheet.area - math.pi * m.relief_hole_diameter**2 / 4.0
    wedges = sum(
        2.0
        * h.length
        * (t / 2.0)
        * (t / 2.0)
        * math.tan(math.radians(h.fold_angle_deg) / 2.0)
        / 2.0
        for h in folded.crease
    )
    assert abs(measure(shape, "volume") - area * t) < wedges


def test_solid_lies_on_the_side_sheet_surface_names(solid_trip):
    """Points off the reference surface along its top normal are inside the
    solid between the offsets sheet_offsets(material) and outside beyond them."""
    design, folded, shape = solid_trip
    m = design.material
    s0, s1 = sheet_offsets(m)
    t = m.thickness
    r_hole = 0.5 * m.relief_hole_diameter
    sheet = design.sheet
    pts = []
    for psi, frac in zip(
        np.concatenate([np.linspace(0.3, math.pi - 0.3, 3), -np.linspace(0.3, 2.8, 3)]),
        (0.3, 0.7, 0.5, 0.7, 0.3, 0.5),
        strict=True,
    ):
        edge = float(sheet.ray_lengths(np.array([psi]))[0])
        r = r_hole + 3 * t + frac * (edge - r_hole - 6 * t)
        pts.append([r * math.cos(psi), r * math.sin(psi)])
    xy = np.array(pts)
    for p, n in zip(folded.map_points(xy), folded.normals(xy), strict=True):
        for s in (0.5 * (s0 + s1), s0 + 0.05 * t, s1 - 0.05 * t):
            assert shape.is_inside(bd.Vector(*(p + s * n)))
        for s in (s0 - 0.1 * t, s1 + 0.1 * t):
            assert not shape.is_inside(bd.Vector(*(p + s * n)))


def test_mid_solid_mitre_meets_on_the_plane_of_symmetry(mid_trip):
    """On the plane y = 0, across a crease half, the two sides' slabs of
    thickness t meet at the fold angle psi: the mitre reaches
    (t / 2) / cos(psi / 2) from the crease line to either side."""
    design, folded, shape = mid_trip
    m = design.material
    apex = folded.apex
    for half in folded.crease:
        u = (half.end_3d - apex) / np.linalg.norm(half.end_3d - apex)
        w = np.cross(u, [0.0, 1.0, 0.0])
        w /= np.linalg.norm(w)
        reach = 0.5 * m.thickness / math.cos(math.radians(half.fold_angle_deg) / 2.0)
        on_crease = apex + 0.5 * half.length * u
        for sign in (1.0, -1.0):
            assert shape.is_inside(bd.Vector(*(on_crease + sign * 0.9 * reach * w)))
            assert not shape.is_inside(bd.Vector(*(on_crease + sign * 1.1 * reach * w)))


@pytest.mark.parametrize("t", [0.5, 1.5, 6.0])
def test_ten_by_twenty_four_foot_sheet_builds_its_solid(t):
    """Issue 11: the 10 x 24 ft sheet at bend radius 1.5 for t from 0.5 to 6."""
    design = Design(
        "big",
        FrameCurve(30, 30),
        Sheet.rectangle(3048.0, 7315.2),
        material=Material(thickness=t, bend_radius=1.5),
    )
    folded = fold_design(design)
    m = design.material.with_changes(relief_hole=relief_hole_diameter(design, folded))
    solid = build_solid(folded, m)
    assert solid.is_valid
    expected = slab_volume(folded, m, m.relief_hole_diameter)
    assert measure(solid, "volume") == pytest.approx(expected, rel=SOLID_VOLUME_AGREEMENT)


def test_solid_past_the_mitre_limits_is_refused_with_what_to_change():
    square = Sheet.quadrilateral(300, 300, 300, 300)
    flat = Design("flat", FrameCurve(0.01, 0.01), square, material=Material(thickness=0.5))
    folded = fold_design(flat)
    m = flat.material.with_changes(relief_hole=relief_hole_diameter(flat, folded))
    with pytest.raises(ExportError, match=r"nearly flat .*--body shell"):
        build_solid(folded, m)
    closed = Design("shut", FrameCurve(89.0, 89.9), square, material=Material(thickness=0.3))
    folded = fold_design(closed)
    assert min(h.fold_angle_deg for h in folded.crease) > 179.0
    m = closed.material.with_changes(sheet_surface=SheetSurface.OUTSIDE, relief_hole=1.0)
    with pytest.raises(ExportError, match=r"nearly closed .* thinner sheet"):
        build_solid(folded, m)


def test_bad_input_is_a_clear_error_and_leaves_no_file(tmp_path):
    design = CASES["table1-0"][0]
    folded = fold_design(design)
    with pytest.raises(InvalidParameterError, match="relief_hole"):
        build_shell(folded, relief_hole=1e6)
    with pytest.raises(InvalidParameterError, match="faces"):
        build_shell(folded, faces="fan")
    thick = design.with_changes(material=Material(thickness=1.0))
    need = solid_min_relief_hole(folded, thick.material)
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
    with pytest.raises(InvalidParameterError, match="placement"):
        export_design_step(thick, tmp_path / "thick.step", folded, placement="frames")
    assert list(tmp_path.iterdir()) == []
    # a design with thickness but no hole falls back to the reference surface
    flat_hole = thick.with_changes(material=thick.material.with_changes(relief_hole=0.0))
    assert default_body(flat_hole) == "shell" and default_body(thick) == "solid"
    written = export_design_step(flat_hole, tmp_path / "thick.step", folded)
    assert written.stat().st_size > 0 and [p.name for p in tmp_path.iterdir()] == ["thick.step"]
    assert len(bd.import_step(written).solids()) == 0


def test_default_relief_hole_fits_the_solid_and_every_export_cuts_it(tmp_path):
    """INSIDE on Table 1's square at t = 3: the default max(3 t, 2 (t + r)) =
    9 is too small for the solid, so the hole is raised to 1.1 x the
    smallest one, rounded up to two significant digits; the STEP, the DXF's
    flat pattern and the report all use it."""
    design = CASES["table1-0"][0].with_changes(
        material=Material(thickness=3.0, sheet_surface=SheetSurface.INSIDE)
    )
    folded = fold_design(design)
    need = solid_min_relief_hole(folded, design.material)
    hole = relief_hole_diameter(design, folded)
    assert design.material.relief_hole_diameter == 9.0 < need
    step = 10.0 ** (math.floor(math.log10(hole)) - 1)  # two significant digits
    assert 1.1 * need <= hole < 1.1 * need + step
    assert hole / step == pytest.approx(round(hole / step), abs=1e-9)
    assert flat_pattern(design, folded).hole_diameter == hole
    assert design_report(design, folded)["relief_hole_diameter"] == hole
    shape = bd.import_step(export_design_step(design, tmp_path / "d.step", folded))
    assert shape.is_valid and len(shape.solids()) == 1
    m = design.material.with_changes(relief_hole=hole)
    expected = slab_volume(folded, m, hole)
    assert measure(shape, "volume") == pytest.approx(expected, rel=SOLID_VOLUME_AGREEMENT)
    # an explicit hole is kept as it is (and this one is too small for a solid)
    fixed = design.with_changes(material=design.material.with_changes(relief_hole=9.0))
    assert relief_hole_diameter(fixed, folded) == 9.0


def test_kernel_failure_is_an_export_error_and_leaves_no_file(tmp_path, monkeypatch):
    import onefold_cad.export.part as part

    def broken(*args, **kwargs):
        raise RuntimeError("simulated OCC failure")

    design = CASES["table1-0"][0].with_changes(material=Material(thickness=3.0))
    monkeypatch.setattr(part, "thick_solid", broken)
    with pytest.raises(ExportError, match="simulated OCC failure"):
        export_design_step(design, tmp_path / "x.step")
    monkeypatch.setattr(part, "ruled_shell", broken)
    with pytest.raises(ExportError, match="simulated OCC failure"):
        export_design_step(design, tmp_path / "x.step", body="shell")
    assert list(tmp_path.iterdir()) == []


# -- H near the sheet's edge: what the CAD kernel can hold, and the refusals --
def _h_near_side(frame: FrameCurve, w: float, h: float, gap: float) -> Design:
    """A w x h rectangle with H on its diagonal ``gap`` from the nearest side
    (H at (f w, f h): 1 - f = gap / h, h the shorter side)."""
    sheet = Sheet.rectangle(width=w, height=h, apex_fraction=1.0 - gap / h)
    return Design("near", frame, sheet, material=Material(thickness=0.0, bend_radius=0.0))


def _reread_area(design: Design, tmp_path) -> float:
    shape = bd.import_step(export_design_step(design, tmp_path / "near.step"))
    assert shape.is_valid and len(shape.faces()) == 4
    return measure(shape)


@pytest.mark.parametrize(
    "frame",
    [FrameCurve(50.0, 45.0, 100.0, 300.0, 32), FrameCurve(70.0, 20.0, 100.0, 300.0, 32)],
)
def test_an_edge_just_outside_the_boundary_tolerance_of_h_writes_the_sheet(frame, tmp_path):
    """An edge 1.2 x BOUNDARY_TOLERANCE x size from H (a face 0.0012 wide and
    5000 long): the STEP reads back valid with the rectangle's area w h
    (within the boundary tolerance along the perimeter, 2 (w + h) x 1e-7 x
    size / (w h) = 6e-7). These failed the re-read before the boundary
    curves' 3D curves were fitted to a tenth of the kernel's precision."""
    w, h = 9000.0, 5000.0
    design = _h_near_side(frame, w, h, 1.2 * BOUNDARY_TOLERANCE * math.hypot(w, h))
    bound = 2.0 * (w + h) * BOUNDARY_TOLERANCE * design.sheet.size
    assert _reread_area(design, tmp_path) == pytest.approx(w * h, abs=bound)


def test_an_edge_within_the_boundary_tolerance_of_h_is_refused_naming_apex_fraction():
    """0.9 x the bound: the face between that edge and the apex would be
    narrower than its boundary curve's tolerance; the message names
    apex_fraction, the distance, the bound and the apex_fraction range that
    works (the bound / the shorter side from each end)."""
    w, h = 9000.0, 5000.0
    bound = BOUNDARY_TOLERANCE * math.hypot(w, h)  # H lies 1e-3 of the diagonal from a corner
    design = _h_near_side(FrameCurve(50.0, 45.0, 100.0, 300.0, 32), w, h, 0.9 * bound)
    with pytest.raises(ExportError) as err:
        build_shell(fold_design(design))
    msg = str(err.value)
    assert "apex_fraction" in msg and f"{0.9 * bound:.3g}" in msg and f"{bound:.3g}" in msg
    assert f"[{bound / h:.3g}, 1 - {bound / h:.3g}]" in msg


def test_a_ruling_just_longer_than_the_kernel_precision_writes_the_sheet(tmp_path):
    """A 0.01 square with H 1.05e-7 from a corner (the crease's +x half that
    long): the shortest edge the kernel makes is longer than its precision
    (1e-7); the STEP reads back with the area 1e-4 (boundary tolerance 1e-7
    x size along the perimeter: 4e-2 x 1.4e-9)."""
    frame = FrameCurve(50.0, 45.0, 0.01, 0.03, 32)
    design = _h_near_side(frame, 0.01, 0.01, 1.05e-7 / math.sqrt(2.0))
    assert design.sheet.crease_lengths[0] == pytest.approx(1.05e-7, rel=1e-6)
    bound = 4.0 * 0.01 * BOUNDARY_TOLERANCE * design.sheet.size
    assert _reread_area(design, tmp_path) == pytest.approx(1e-4, abs=bound)


def test_a_ruling_no_longer_than_the_kernel_precision_is_refused_naming_apex_fraction():
    """H 0.95e-7 from a corner: the kernel takes the two ends of that ruling
    for one point (BRepLib_MakeEdge: Precision::Confusion); refused up front
    naming apex_fraction, the distance, the bound 1e-07 and the range that
    works (1e-7 / the diagonal from each end)."""
    frame = FrameCurve(50.0, 45.0, 0.01, 0.03, 32)
    design = _h_near_side(frame, 0.01, 0.01, 0.95e-7 / math.sqrt(2.0))
    with pytest.raises(ExportError) as err:
        build_shell(fold_design(design))
    msg = str(err.value)
    least = 1e-7 / math.hypot(0.01, 0.01)
    assert "apex_fraction" in msg and "9.5e-08" in msg and "(1e-07" in msg
    assert f"[{least:.3g}, 1 - {least:.3g}]" in msg


def test_a_quadrilateral_edge_near_h_is_refused_naming_its_shorter_parameter():
    """x_plus tiny: the edge from (x_plus, 0) to (0, y_plus) passes about
    x_plus from H; the message names x_plus and the x_plus that clears the
    bound, b y / sqrt(y^2 - b^2) with b = 1e-7 x size."""
    sheet = Sheet.quadrilateral(3e-4, 5000.0, 4000.0, 4500.0)
    design = Design("q", FrameCurve(50.0, 45.0, 100.0, 300.0, 32), sheet)
    with pytest.raises(ExportError) as err:
        build_shell(fold_design(design))
    b = BOUNDARY_TOLERANCE * 5000.0
    assert "(parameter x_plus)" in str(err.value)
    assert f"must exceed {b * 4000.0 / math.sqrt(4000.0**2 - b * b):.3g}" in str(err.value)


@pytest.mark.parametrize(
    ("alpha", "beta", "h_c", "radius", "divisions", "w", "h", "f"),
    [
        # fuzz design 2254: an edge 4.9e-4 from H on a sheet of 1.04e4
        (51.72775272942137, 89.90735393719785, 163.0064953321392, 383.51971948722803, 64)
        + (9030.9415169748, 5144.942040695422, 0.9999999039783121),
        # fuzz design 2678: H 1.9e-8 from a corner
        (0.017651810342493798, 0.0012660501335390237, 4897.382859053631, 14266.256201384029, 26)
        + (0.008278594966508518, 0.03623624281750027, 0.9999994865409002),
    ],
)
def test_fuzz_corner_designs_are_refused_naming_apex_fraction(
    alpha, beta, h_c, radius, divisions, w, h, f
):
    """Both once ended in 'BRep_API: command not done'."""
    sheet = Sheet.rectangle(width=w, height=h, apex_fraction=f)
    design = Design("fz", FrameCurve(alpha, beta, h_c, radius, divisions), sheet)
    with pytest.raises(ExportError, match=r"\(parameter apex_fraction\)"):
        build_part(design)


def test_a_sheet_of_a_million_kilometres_writes_a_valid_step(tmp_path):
    """Fuzz design 195 (sheet 1.7e9, coordinates whose last place, 2.4e-7,
    is coarser than the kernel's precision): vertices take the measured gap
    to their curves' ends as tolerance, and the STEP reads back valid with
    its four faces and the free boundary as long as the flat outline (the
    sum of the four edges' lengths, hypot of the quadrilateral's
    half-diagonals), to the boundary tolerance."""
    sides = dict(
        x_plus=569897052.9628764,
        x_minus=1726043236.4368892,
        y_plus=805675901.44098,
        y_minus=926490320.8207252,
    )
    frame = FrameCurve(
        0.00011867203419004292, 89.37365716043797, 8774.007547015526, 10886.263933930151, 3
    )
    design = Design("big", frame, Sheet.quadrilateral(**sides))
    shape = bd.import_step(export_design_step(design, tmp_path / "big.step"))
    assert shape.is_valid and len(shape.faces()) == 4
    xp, xm, yp, ym = sides.values()
    perimeter = math.hypot(xp, yp) + math.hypot(xm, yp) + math.hypot(xm, ym) + math.hypot(xp, ym)
    bound = 4.0 * BOUNDARY_TOLERANCE * design.sheet.size
    assert _free_length(shape) == pytest.approx(perimeter, abs=bound)


def test_a_fan_of_thin_triangles_on_a_sheet_of_1e7_is_valid():
    """Fuzz design 3511 (paper model, 511 divisions, a sheet of 1.3e7 on a
    frame of radius 112): its triangles are 1e-3 rad wide at H and 1.3e7
    long. Every vertex of every face lies on the face's plane within the
    kernel's precision (1e-7; it was 2.5e-6 off with the plane's normal
    taken across the two long sides), so the shell is valid, and its free
    boundary is the polygon's perimeter (the fan is exact)."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface

    poly = [
        (-383014.91274084913, 12231228.219835917),
        (-7416516.922856208, 424421.826311926),
        (-5203073.697731906, -6372384.160051148),
        (82049.69568494378, -3283727.0419761064),
        (5993217.290928922, -3088386.0653263675),
        (10499212.943356015, 7938938.989467105),
    ]
    frame = FrameCurve(84.17911518845554, 0.41783426718076844, 0.0, 111.90718552242929, 511)
    design = Design("big-fan", frame, Sheet.polygon(poly), model="paper")
    shell = build_shell(fold_design(design))
    assert shell.is_valid
    worst = 0.0
    for face in shell.faces():
        plane = BRepAdaptor_Surface(face.wrapped).Plane()
        for v in face.vertices():
            worst = max(worst, plane.Distance(gp_Pnt(*tuple(v))))
    assert worst < PRECISION
    pts = np.array(poly)
    perimeter = float(np.sum(np.linalg.norm(pts - np.roll(pts, -1, axis=0), axis=1)))
    assert _free_length(shell) == pytest.approx(perimeter, rel=1e-12)


def test_a_sheet_edge_no_longer_than_the_kernel_precision_is_refused_naming_polygon():
    """A polygon whose vertex lies 0.95e-7 from the crease's +x end (fuzz
    design 2402 had 2.7e-8): the kernel cannot make that edge; 1.05e-7
    builds, and its free boundary is the polygon's perimeter."""
    frame = FrameCurve(50.0, 45.0, 20.0, 100.0, 32)

    def poly(gap: float) -> Sheet:
        return Sheet.polygon(
            [(100.0, 0.0), (100.0 - gap, gap), (0.0, 80.0), (-90.0, 0.0), (0.0, -70.0)]
        )

    with pytest.raises(ExportError, match=r"9\.5e-08 long.*\(parameter polygon\)"):
        build_shell(fold_design(Design("p", frame, poly(0.95e-7 / math.sqrt(2.0)))))
    design = Design("p", frame, poly(1.05e-7 / math.sqrt(2.0)))
    shell = build_shell(fold_design(design))
    assert shell.is_valid
    pts = design.sheet.vertices
    perimeter = float(np.sum(np.linalg.norm(pts - np.roll(pts, -1, axis=0), axis=1)))
    assert _free_length(shell) == pytest.approx(perimeter, abs=len(pts) * shell.fit_tolerance)


def test_a_relief_hole_arc_no_longer_than_the_kernel_precision_is_refused():
    """Two vertices 1e-3 rad apart as seen from H: a hole of diameter d has an
    arc chord d sin(5e-4) between their rulings; at 0.95e-7 it is refused
    naming relief_hole and the diameter that works (1e-7 / sin(5e-4))."""
    frame = FrameCurve(50.0, 45.0, 20.0, 100.0, 32)
    t = 1e-3
    sheet = Sheet.polygon(
        [
            (100.0, 0.0),
            (60.0 * math.cos(0.8), 60.0 * math.sin(0.8)),
            (80.0 * math.cos(0.8 + t), 80.0 * math.sin(0.8 + t)),
            (-90.0, 0.0),
            (0.0, -70.0),
        ]
    )
    folded = fold_design(Design("h", frame, sheet))
    need = 1e-7 / math.sin(0.5 * t)
    with pytest.raises(ExportError, match=r"\(parameter relief_hole\)") as err:
        build_shell(folded, relief_hole=0.95 * need)
    assert f"over {need:.3g} across" in str(err.value)
    assert build_shell(folded, relief_hole=1.05 * need).is_valid


def test_a_paper_fan_with_a_ruling_no_longer_than_the_kernel_precision_is_refused():
    """Fuzz design 6794 (a paper-model sheet of 4e-8): the fan's crease
    ruling 0.95e-7 long is refused naming apex_fraction; with H 1e-3 from
    the corner the fan builds, its free boundary the square's perimeter."""
    frame = FrameCurve(50.0, 45.0, 0.01, 0.03, 64)

    def design(gap: float) -> Design:
        d = _h_near_side(frame, 0.01, 0.01, gap / math.sqrt(2.0))
        return d.with_changes(model="paper")

    with pytest.raises(ExportError, match=r"paper model.*\(parameter apex_fraction\)"):
        build_shell(fold_design(design(0.95e-7)))
    shell = build_shell(fold_design(design(1e-3)))
    assert shell.is_valid
    assert _free_length(shell) == pytest.approx(0.04, rel=1e-12)
