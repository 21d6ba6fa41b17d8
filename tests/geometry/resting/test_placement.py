"""The resting placement: exact ground contact, stability, and the written STEP."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st
from scipy.optimize import minimize_scalar

from onefold_cad import (
    Design,
    FrameCurve,
    InvalidParameterError,
    Material,
    Sheet,
    fold,
    fold_design,
    solve,
)
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.resting.body import FoldedBody
from onefold_cad.geometry.resting.body_mass import mass_properties
from onefold_cad.geometry.resting.placement import (
    TIPPING_WARNING_DEG,
    RestingPlacement,
    rest_form,
    stability_warnings,
)
from onefold_cad.templates import find_template, load_template
from tests.angles import OPEN_ANGLE, cos_deg, refused_below_bound
from tests.geometry.conftest import sheets
from tests.geometry.folds import fold_or_none

SETTINGS = settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
# alpha, beta over the whole of (0, 90) deg open (below the angle bound a
# frame is refused, tests/angles.py)
ANGLE = OPEN_ANGLE
#: beta anywhere in (0, 90) deg, and as often within 1e-3 to 1e-14 deg of 90,
#: where the apex nears the frame plane and the exact cone folds back on
#: itself along two rulings
BETA = st.one_of(
    ANGLE,
    st.floats(3.0, 14.0).map(lambda k: 90.0 - 10.0**-k).filter(lambda b: 0.0 < b < 90.0),
)


@st.composite
def frames(draw: st.DrawFn) -> FrameCurve:
    """Frame curves over the whole admissible range: alpha, beta in (0, 90)
    deg (beta favouring the last 1e-3 deg), H anywhere strictly inside the
    f-line."""
    alpha, beta = draw(ANGLE), draw(BETA)
    radius = draw(st.floats(1.0, 1000.0))
    frac = draw(st.floats(-0.999, 0.999))

    def make() -> FrameCurve:
        return FrameCurve(alpha, beta, frac * radius * cos_deg(alpha), radius, 90)

    assume(not refused_below_bound(alpha, beta, make))  # the refusal is that draw's answer
    return make()


def _placed_height(rest: RestingPlacement, folded, a: np.ndarray, b: np.ndarray):
    """Height above the ground of the folded sheet edge a -> b at fractions s."""

    def height(s):
        q = a + np.atleast_1d(s)[:, None] * (b - a)
        return rest.apply(folded.map_points(q))[:, 2]

    return height


def _edge_minima(rest: RestingPlacement, folded) -> list[tuple[float, np.ndarray]]:
    """The folded boundary's lowest points, independently of the placement's
    own search: dense samples of every edge, then scipy's bounded Brent at
    the four lowest sampled local minima of each (ends included): a list of
    (height, placed point)."""
    v = folded.sheet.vertices
    out = []
    for k in range(len(v)):
        a, b = v[k], v[(k + 1) % len(v)]
        height = _placed_height(rest, folded, a, b)
        s = np.linspace(0.0, 1.0, 801)
        z = height(s)
        padded = np.concatenate([[np.inf], z, [np.inf]])
        minima = np.flatnonzero((padded[1:-1] <= padded[:-2]) & (padded[1:-1] <= padded[2:]))
        for i in minima[np.argsort(z[minima])[:4]]:
            res = minimize_scalar(
                lambda t, h=height: float(h(t)[0]),
                bounds=(s[max(i - 1, 0)], s[min(i + 1, 800)]),
                method="bounded",
                options={"xatol": 1e-14},
            )
            t, zt = (float(res.x), float(res.fun)) if res.fun < z[i] else (float(s[i]), z[i])
            out.append((float(zt), rest.apply(folded.map_points((a + t * (b - a))[None, :]))[0]))
    return out


def _lowest_on_edges(rest: RestingPlacement, folded) -> float:
    """The folded boundary's lowest height (:func:`_edge_minima`)."""
    return min(z for z, _ in _edge_minima(rest, folded))


def _check_rigid(rest: RestingPlacement) -> None:
    r = rest.rotation
    assert np.allclose(r @ r.T, np.eye(3), atol=1e-12)
    assert abs(np.linalg.det(r) - 1.0) < 1e-12


@SETTINGS
@given(frame=frames(), sheet=sheets)
@example(  # beta within 1e-9 deg of 90: the apex in the frame plane, unfold ill-conditioned
    frame=FrameCurve(1.0, 89.999999999, 0.0, 1.0, 90), sheet=Sheet.rectangle(10, 10, 0.5)
)
@example(  # balanced on its rocking line, a third contact 0.07 from the second (hypothesis)
    frame=FrameCurve(1.0, 86.0, 0.0, 1.0, 90),
    sheet=Sheet.polygon(np.array([
        [20.0, 0.0], [19.813718920726615, 2.7233329819249317],
        [153.79549281836793, 93.52511100637804], [-33.019606854196304, 14.342439234464704],
        [-30.61510775, 0.0], [-8.871513737407275, -129.69693999477008],
        [230.26602952527867, -140.02787453454934],
    ])),
)  # fmt: skip
def test_shell_lowest_point_lies_exactly_on_the_ground(frame: FrameCurve, sheet: Sheet) -> None:
    folded = fold_or_none(frame, sheet, "exact")
    if folded is None:
        return
    rest = rest_form(folded)
    size = sheet.size
    _check_rigid(rest)
    # nothing of the folded surface lies below z = 0, and its lowest point is on it
    apex_z = float(rest.apply(folded.apex[None, :])[0, 2])
    lowest = min(_lowest_on_edges(rest, folded), apex_z)
    assert lowest >= -1e-9 * size
    assert lowest <= 1e-9 * size
    assert abs(rest.bounds[0, 2]) <= 1e-12 * size
    # every contact is a point of the folded boundary (or the apex) on the ground
    assert len(rest.contacts) >= 2
    assert np.all(np.abs(rest.contacts[:, 2]) <= 1e-9 * size)
    back = (rest.contacts - rest.translation) @ rest.rotation  # into the fold frame
    # unfold projects from the apex onto the frame plane: well-conditioned only
    # while the apex stands clear of that plane (h cos(beta); beta within 1e-9
    # deg of 90 puts it in the plane)
    if folded.apex[2] * math.cos(math.radians(frame.beta)) >= 1e-3 * size:
        flat, off = folded.unfold(back)
        assert np.all(off <= 1e-9 * size)
        on_edge = np.array([_distance_to_boundary(p, sheet.vertices) for p in flat])
        at_apex = np.linalg.norm(back - folded.apex, axis=1)
        assert np.all(np.minimum(on_edge, at_apex) <= 1e-9 * size)
    # stability values are finite; a form at rest holds its centre of mass
    # over three or more contacts, or rocks on a line with it above the line:
    # two contacts, or three or more with it on an edge (a third point on the
    # rocking line, `tipping_margin`'s documented case)
    assert np.all(np.isfinite(rest.centre_of_mass))
    assert math.isfinite(rest.tipping_margin_deg)
    rocks = len(rest.support_polygon) >= 2 and rest.tipping_margin_deg == 0.0
    assert rocks or (rest.stable and len(rest.support_polygon) >= 3)


def _distance_to_boundary(p: np.ndarray, poly: np.ndarray) -> float:
    a, b = poly, np.roll(poly, -1, axis=0)
    d = b - a
    t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.einsum("ij,ij->i", d, d), 0.0, 1.0)
    return float(np.min(np.linalg.norm(a + t[:, None] * d - p, axis=1)))


@SETTINGS
@given(frame=frames(), sheet=sheets)
@example(  # a side within 2e-6 deg of flat: 150 ruling ends on one plane (was O(k^4))
    frame=FrameCurve(81.60226013002016, 89.99999821608623, -13.1430529826616, 100.0, 157),
    sheet=Sheet.quadrilateral(24.435404656484586, 514.2228608084539, 361.19105109521, 322.408),
)
def test_paper_model_rests_on_ruling_ends_and_vertices(frame: FrameCurve, sheet: Sheet) -> None:
    # the paper fan is straight between its ruling ends and the sheet's
    # vertices folded (a vertex within 1e-12 rad of a division shares its
    # ruling, whose end can then fall short of it): they and the apex are its corners
    folded = fold_or_none(frame.with_changes(divisions=24), sheet, "paper")
    if folded is None:
        return
    _check_paper_corners(folded)


def _check_paper_corners(folded) -> None:
    rest = rest_form(folded)
    size = folded.sheet.size
    vertices = folded.map_points(folded.sheet.vertices)
    corners = rest.apply(np.vstack([folded.rulings_3d[:, 1], vertices, folded.apex]))
    assert corners[:, 2].min() >= -1e-9 * size
    assert corners[:, 2].min() <= 1e-9 * size
    for c in rest.contacts:
        assert np.min(np.linalg.norm(corners - c, axis=1)) <= 1e-9 * size


def test_paper_vertex_sharing_a_division_ruling_is_not_below_the_ground() -> None:
    # fuzz design 2329: a symmetric frame with 36 divisions puts a division
    # within 4.4e-16 rad of the vertex (0, y_plus); the edge beside it passes
    # 4.8e-10 from H, so the division's ruling end lay 1.5e-7 short of the
    # vertex, and the folded corner was 5.8e-8 (1.5e-7 of the size) below the
    # ground. Expected: every folded corner (map of the flat vertices, in
    # the triangle's plane) on or above z = 0, the lowest on it
    frame = FrameCurve(87.6629202700267, 83.65787575517929, 0.0, 0.34394662800892756, 36)
    sheet = Sheet.quadrilateral(
        4.808818122518489e-10, 0.16252063456701793, 0.377742368613623, 0.2969066664200494
    )
    folded = fold(solve(frame, "paper"), sheet)
    y_plus = np.array([[0.0, 0.377742368613623]])
    # the fold now ends that division's ruling at the vertex (tests/geometry/
    # test_folding.py); the body's corners include the vertices either way
    _check_paper_corners(folded)
    rest = rest_form(folded, Material(thickness=1.1367344980419707e-05, relief_hole=0.0))
    assert rest.apply(folded.map_points(y_plus))[0, 2] >= -1e-9 * sheet.size


#: fuzz-found sheet (H at the origin) on which the exact shell met the apex
#: while rocking on two curved edges and was left on one contact
_SPIKE = [
    (19.989, -0.664),
    (385.832, 56.867),
    (12.982, 15.214),
    (28.253, 78.043),
    (-87.722, 45.890),
    (-175.007, -42.103),
    (-18.851, -71.559),
    (29.233, -27.303),
]


@pytest.mark.parametrize("model", ["paper", "exact"])
@pytest.mark.parametrize("thickness", [0.0, 0.5])
def test_rests_on_three_contacts_that_hold_the_centre_of_mass(model: str, thickness: float):
    frame = FrameCurve(68.0, 27.0, 0.0, 1.0, 90)
    folded = fold(solve(frame, model), Sheet.polygon(_SPIKE))
    rest = rest_form(folded, Material(thickness=thickness, relief_hole=0.0))
    size = folded.sheet.size
    # the ground points found here: Brent minima of every folded edge, the
    # apex and the corners (paper: the ruling ends, between which a side
    # of a triangle can lie along the ground), those within 1e-9 of the size
    # of z = 0
    corners = rest.apply(np.vstack([folded.apex, folded.rulings_3d[:, 1]]))
    found = [*_edge_minima(rest, folded), *((float(p[2]), p) for p in corners)]
    assert min(z for z, _ in found) >= -1e-9 * size
    ground = np.array([p for z, p in found if z <= 1e-9 * size])
    ground[:, 2] = 0.0
    assert abs(float(np.min([z for z, _ in found]))) <= 1e-9 * size
    # three or more of them, their hull holding the centre of mass: at rest
    assert len(rest.support_polygon) >= 3 and rest.stable
    from scipy.spatial import ConvexHull

    hull = ConvexHull(ground[:, :2])
    assert len(hull.vertices) >= 3
    margin = _margin_deg(rest.centre_of_mass, ground[:, :2])
    assert margin > 0.0
    # the placement counts as contacts every point within 1e-9 of the size
    # of the ground: near a tangency that reaches sqrt(2e-9 size / curvature)
    # along the edge (~1e-3 here), which moves the margin by ~1e-3 deg
    assert abs(rest.tipping_margin_deg - margin) <= 2e-3


def test_symmetric_form_balanced_on_its_crease_ends_tips_to_a_stable_rest() -> None:
    # Patkau's sheet, H at the diagonal's middle, h_c = 0: the form is symmetric
    # under a half turn about z, so in the fold frame it balances on its two
    # crease ends with the centre of mass exactly above the line between them
    design = load_template(find_template("patkau-one-fold"))
    folded = fold_design(design)
    ends = np.array([h.end_3d for h in folded.crease])
    assert abs(ends[0, 2] - ends[1, 2]) <= 1e-9 * folded.sheet.size
    rest = rest_form(folded)
    assert rest.stable and rest.tilt_deg > 1.0
    assert len(rest.support_polygon) >= 3
    # it rests on both crease ends: that edge keeps touching as it tips
    placed = rest.apply(ends)
    assert np.all(np.abs(placed[:, 2]) <= 1e-9 * folded.sheet.size)


def test_rocking_form_has_two_contacts_and_no_margin() -> None:
    # alpha 60, beta 80 on a 600 x 200 sheet: the form lies on a corner and
    # along a curved edge, with its centre of mass above the line through them
    frame = FrameCurve(60.0, 80.0, 0.0, 100.0, 90)
    folded = fold(solve(frame, "exact"), Sheet.rectangle(600.0, 200.0, 0.5))
    rest = rest_form(folded)
    size = folded.sheet.size
    assert len(rest.support_polygon) == 2
    a, b = rest.support_polygon
    c = rest.centre_of_mass[:2]
    d = b - a
    t = float((c - a) @ d / (d @ d))
    assert 0.0 < t < 1.0
    assert float(np.hypot(*(a + t * d - c))) <= 1e-6 * size
    assert rest.tipping_margin_deg == 0.0 and not rest.stable
    assert _lowest_on_edges(rest, folded) >= -1e-9 * size
    (warning,) = stability_warnings(rest)
    assert "rocks" in warning and "two" in warning


def test_tiny_sheet_on_a_huge_frame_gives_finite_numbers() -> None:
    # a fuzzed design: a 0.01-unit sheet on a frame of radius 83 000
    frame = FrameCurve(82.90168514383389, 30.61985654143723, -10273.916792606657, 83143.13345090406)
    sheet = Sheet.quadrilateral(
        0.0010034710883311268, 0.0022882157409330533, 0.009722176126498587, 0.0005024616634494154
    )
    folded = fold(solve(frame, "exact"), sheet)
    rest = rest_form(folded)
    values = [rest.tipping_margin_deg, rest.tilt_deg, rest.footprint_area]
    values += [*rest.bounds.ravel(), *rest.centre_of_mass, *rest.contacts.ravel()]
    assert np.all(np.isfinite(values))
    assert abs(rest.bounds[0, 2]) <= 1e-9 * sheet.size
    assert rest.height > 0.0 and len(rest.contacts) >= 2


def _fan_centre(folded: FoldedSheet) -> np.ndarray:
    """The paper fan's centre of mass by hand: its triangles (apex, two
    consecutive ruling ends of a side), area-weighted centroids."""
    apex, ends = folded.apex, folded.rulings_3d[:, 1]
    first = len(folded.ruling_angles[0])
    area, moment = 0.0, np.zeros(3)
    for side in (ends[:first], ends[first:]):
        for a, b in zip(side[:-1], side[1:], strict=True):
            w = 0.5 * float(np.linalg.norm(np.cross(a - apex, b - apex)))
            area, moment = area + w, moment + w * (apex + a + b) / 3.0
    return moment / area


def test_needle_thicker_than_wide_lies_on_its_side_with_a_warning() -> None:
    # fuzz design 6849 (it rolled for ever), rounded, 60 divisions: a
    # kite 5.5e-5 long and 1.7e-11 wide folded into a needle, 6.9e-8 thick.
    # The thick sheet's centre of mass lies ~1.4e-8 off the shell (its slab
    # is cut at the crease): no rest of the shell holds it, so the shell is
    # stood by its own centre of mass, with a warning
    frame = FrameCurve(88.58212537094371, 52.20096833699451, 1.915087505793e-4, 0.0185922706, 60)
    sheet = Sheet.quadrilateral(5.525791810518125e-05, 4.9e-12, 1.58399228367015e-11, 9.6e-13)
    folded = fold(solve(frame, "paper"), sheet)
    rest = rest_form(folded, Material(thickness=6.85136721461188e-08, relief_hole=0.0))
    size = sheet.size
    # the fan's corners (ruling ends, apex) bound it: none below the ground
    corners = np.vstack([folded.rulings_3d[:, 1], folded.apex])
    placed = rest.apply(corners)
    assert -1e-9 * size <= placed[:, 2].min() <= 1e-9 * size
    assert len(rest.contacts) >= 3
    assert np.all(np.abs(rest.contacts[:, 2]) <= 1e-9 * size)
    for c in rest.contacts:
        assert np.min(np.linalg.norm(placed - c, axis=1)) <= 1e-9 * size
    # it stands by the surface's centre of mass, computed here by hand
    centre = _fan_centre(folded)
    assert np.all(np.abs(rest.apply(centre[None, :])[0] - rest.centre_of_mass) <= 1e-9 * size)
    height = float(rest.centre_of_mass[2])
    # lying on either wide side (the corners' thinnest principal axes) puts the
    # centre of mass no lower: 5e-12 to 1.4e-11 there, 5.5e-5 long
    _, _, vt = np.linalg.svd(corners - corners.mean(axis=0))
    sides = [s * n for n in vt[1:] for s in (1.0, -1.0)]
    lying = min(float(centre @ n - np.min(corners @ n)) for n in sides)
    assert 0.0 < height <= lying
    assert rest.stable and rest.settled
    assert rest.com_outside > 1e3 * lying
    assert any("outside the convex hull" in w for w in stability_warnings(rest))


def test_stability_warning_below_five_degrees_only() -> None:
    base = rest_form(fold_design(load_template(find_template("patkau-one-fold"))))
    assert base.tipping_margin_deg > TIPPING_WARNING_DEG
    assert stability_warnings(base) == []

    def with_margin(m: float) -> RestingPlacement:
        return RestingPlacement(**{**base.__dict__, "tipping_margin_deg": m})

    (low,) = stability_warnings(with_margin(4.0), units="mm")
    assert "4 deg" in low and "5 deg" in low and "mm" in low
    (bad,) = stability_warnings(with_margin(-2.5))
    assert "does not stand" in bad and "2.5 deg" in bad


def test_solid_needs_the_exact_model_and_a_thickness() -> None:
    frame, sheet = FrameCurve(35.0, 45.0, 8.0), Sheet.rectangle(300.0, 200.0)
    paper = fold(solve(frame, "paper"), sheet)
    with pytest.raises(InvalidParameterError) as err:
        rest_form(paper, Material(thickness=2.0, relief_hole=10.0), "solid")
    assert err.value.parameter == "model"
    exact = fold(solve(frame, "exact"), sheet)
    with pytest.raises(InvalidParameterError) as err:
        rest_form(exact, None, "solid")
    assert err.value.parameter == "body"
    with pytest.raises(InvalidParameterError) as err:
        rest_form(exact, None, "stool")
    assert err.value.parameter == "body"


# -- against the written STEP --------------------------------------------------
def _step_resting(design: Design, body: str):
    """Build the design's part, stand it with the placement, and measure it with
    OCC: its lowest z (distance to a plane below), centre of mass, and the
    points of its edges within 1e-6 of the size of the ground."""
    import build123d as bd
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    from OCP.BRepGProp import BRepGProp
    from OCP.GeomAbs import GeomAbs_C2
    from OCP.gp import gp_Trsf
    from OCP.GProp import GProp_GProps
    from OCP.ShapeUpgrade import ShapeUpgrade_ShapeDivideArea, ShapeUpgrade_ShapeDivideContinuity

    from onefold_cad.export.brep.part import build_part

    folded = fold_design(design)
    material = design.material.with_changes(relief_hole=relief_hole_diameter(design, folded))
    rest = rest_form(folded, material, body)
    part = build_part(design, folded, body=body, placement="frame")  # placed here, by hand
    trsf = gp_Trsf()
    r, t = rest.rotation, rest.translation
    trsf.SetValues(*r[0], t[0], *r[1], t[1], *r[2], t[2])
    placed = bd.Shape.cast(BRepBuilderAPI_Transform(part.wrapped, trsf, True).Shape())
    size = folded.sheet.size
    below = bd.Face.make_rect(100 * size, 100 * size).moved(bd.Location((0, 0, -size)))
    dist = BRepExtrema_DistShapeShape(placed.wrapped, below.wrapped)
    dist.Perform()
    lowest = dist.Value() - size
    # OCC's adaptive integration to 1e-9 on faces split where they are less
    # than C2 and (surfaces) into ~200 pieces: its default rule is off by 1e-4
    split = ShapeUpgrade_ShapeDivideContinuity(placed.wrapped)
    split.SetBoundaryCriterion(GeomAbs_C2)
    split.SetPCurveCriterion(GeomAbs_C2)
    split.SetSurfaceCriterion(GeomAbs_C2)
    split.Perform()
    pieces = split.Result()
    props = GProp_GProps()
    if body == "solid":
        BRepGProp.VolumeProperties_s(pieces, props, 1e-9)
    else:
        BRepGProp.SurfaceProperties_s(pieces, props, 1e-6)
        divide = ShapeUpgrade_ShapeDivideArea(pieces)
        divide.MaxArea = props.Mass() / 200
        divide.Perform()
        props = GProp_GProps()
        BRepGProp.SurfaceProperties_s(divide.Result(), props, 1e-9)
    c = props.CentreOfMass()
    com = np.array([c.X(), c.Y(), c.Z()])
    measure = props.Mass()
    touching = []
    for edge in placed.edges():
        curve = BRepAdaptor_Curve(edge.wrapped)
        for u in np.linspace(curve.FirstParameter(), curve.LastParameter(), 4001):
            p = curve.Value(float(u))
            if p.Z() <= 1e-6 * size:
                touching.append((p.X(), p.Y()))
    body_measure, _ = mass_properties(FoldedBody(folded, material, body))
    assert abs(body_measure - measure) <= 1e-5 * measure  # volume (solid) or area (shell)
    return rest, lowest, com, np.array(touching)


def _margin_deg(com: np.ndarray, ground: np.ndarray) -> float:
    """The tipping margin from a centre of mass and ground points, computed
    here: scipy's hull of the points, distances to its edge lines."""
    from scipy.spatial import ConvexHull

    hull = ConvexHull(ground)
    eq = hull.equations  # outward normals n and offsets c: n . x + c <= 0 inside
    d = -(eq[:, :2] @ com[:2] + eq[:, 2])
    return math.degrees(math.atan2(float(d.min()), float(com[2])))


def _template(name: str, **frame: float) -> Design:
    design = load_template(find_template(name))
    return design.with_changes(frame=design.frame.with_changes(**frame))


STEP_CASES = {
    # the shell: patkau's sheet at alpha 35, beta 45, h_c 8, no thickness
    "shell-35-45-8": lambda: _template(
        "patkau-one-fold", alpha=35.0, beta=45.0, h_c=8.0
    ).with_changes(material=Material()),
    # the default template's solid (3.57 mm, MID)
    "patkau-solid": lambda: _template("patkau-one-fold"),
    # a thick square with its material above the reference surface
    "outside-solid": lambda: Design(
        "outside",
        FrameCurve(40.0, 60.0, 10.0),
        Sheet.quadrilateral(300.0, 300.0, 300.0, 300.0),
        material=Material(thickness=4.0, sheet_surface="OUTSIDE"),
    ),
}


@pytest.fixture(scope="module", params=sorted(STEP_CASES))
def step_case(request):
    design = STEP_CASES[request.param]()
    body = "solid" if design.material.thickness > 0.0 else "shell"
    return request.param, design, _step_resting(design, body)


def test_written_part_lowest_point_lies_on_the_ground(step_case):
    _, design, (rest, lowest, _, _) = step_case
    assert abs(lowest) <= 1e-6 * design.sheet.size


def test_centre_of_mass_agrees_with_the_written_part(step_case):
    _, design, (rest, _, com, _) = step_case
    assert np.linalg.norm(rest.centre_of_mass - com) <= 1e-6 * design.sheet.size


def test_tipping_margin_agrees_with_the_written_part(step_case):
    name, _, (rest, _, com, ground) = step_case
    measured = _margin_deg(com, ground)
    assert abs(rest.tipping_margin_deg - measured) <= 0.5
    if name == "shell-35-45-8":  # the warning's case: "a tipping margin of only about 4 degrees"
        assert 3.5 <= rest.tipping_margin_deg <= 4.5
        assert len(stability_warnings(rest)) == 1


def test_tipping_margin_is_zero_for_a_centre_of_mass_on_an_edge_within_tol() -> None:
    # a right triangle (0,0), (4,0), (0,3) and a centre of mass at height 2
    # below the middle of its hypotenuse, moved out across it by 0.5 and by
    # 2 x tol: balanced on the edge (margin 0), then minus atan(2 tol / 2)
    from onefold_cad.geometry.resting.placement import tipping_margin

    tri = np.array([[0.0, 0.0], [4.0, 0.0], [0.0, 3.0]])
    tol = 1e-6
    out = np.array([3.0, 4.0]) / 5.0  # the hypotenuse's outward normal
    for shift, want in ((0.5 * tol, 0.0), (2.0 * tol, -math.degrees(math.atan(tol)))):
        com = np.array([2.0, 1.5, 2.0]) + np.append(shift * out, 0.0)
        margin, edge = tipping_margin(tri, com, tol)
        assert set(edge) == {1, 2}
        assert margin == pytest.approx(want, rel=1e-9, abs=0.0)
    base = rest_form(fold_design(load_template(find_template("patkau-one-fold"))))
    balanced = RestingPlacement(**{**base.__dict__, "tipping_margin_deg": 0.0})
    (warning,) = stability_warnings(balanced)
    assert "rocks" in warning and "no margin" in warning and "does not stand" not in warning
