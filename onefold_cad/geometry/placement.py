"""Stand a folded form on the ground: its resting placement and how stable it is.

The form is set down as it was solved (apex above H) and let go: it tips
about the contact points (one, then an edge) towards its centre of mass until
the centre of mass lies over the convex hull of three or more contacts
(quasi-static toppling on the body's convex hull, each step lowering the
centre of mass). That is done on samples of the body's extreme pieces
(:class:`onefold_cad.geometry.body.Body`); then the ground plane is made
exact: each contact is moved to the exact lowest point of its piece near it
(a tangency of a boundary curve, a corner, the apex) and the plane is put
through three of them, alternately, until it no longer moves (the points
move along their curves, in the plane to first order: the plane converges
quadratically). Last, every piece's exact lowest point is checked against
the plane, and the form is lifted so that its lowest point lies on z = 0.

Lengths are in the design unit; angles in degrees at the API.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from itertools import combinations
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.errors import NoSolutionError
from onefold_cad.geometry.body import Body
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.hull import convex_hull_2d, edge_distances, polygon_area
from onefold_cad.geometry.material import Material
from onefold_cad.geometry.validate import cross3

__all__ = [
    "RestingPlacement",
    "rest_form",
    "stability_warnings",
    "TIPPING_WARNING_DEG",
]

Array = NDArray[np.float64]
#: Below this tipping margin (deg) a form gets a stability warning.
TIPPING_WARNING_DEG = 5.0
#: Heights within this fraction of the sheet's size count as touching the ground.
CONTACT_TOLERANCE = 1e-9


@dataclass(frozen=True, eq=False)
class RestingPlacement:
    """A rigid motion ``p' = rotation @ p + translation`` that stands a form on
    z = 0, and the form's stability there.

    Attributes:
        rotation: ``(3, 3)`` rotation matrix (fold frame to resting frame).
        translation: ``(3,)`` translation (length).
        body: the body it stands ('shell' or 'solid').
        tilt_deg: angle between the fold frame's z axis and the ground's
            normal (deg); 0 when the form stands as it was solved.
        centre_of_mass: ``(3,)`` of the sheet with its thickness (resting
            frame; length).
        contacts: ``(k, 3)`` the points that touch the ground (resting frame,
            z = 0 within 1e-9 of the sheet's size).
        support_polygon: ``(m, 2)`` the convex hull of the contacts on the
            ground, counter-clockwise (length).
        tipping_margin_deg: the smallest tilt about an edge of the support
            polygon that tips the form over, atan(d / z) with d the distance
            of the centre of mass's ground projection inside that edge and z
            its height (deg); negative when it lies outside (not stable).
        tipping_edge: indices ``(i, j)`` into ``support_polygon`` of that edge.
        bounds: ``(2, 3)`` the placed body's lowest and highest x, y, z (exact;
            length).
        footprint: ``(p, 2)`` the convex hull of the body's shadow on the
            ground, counter-clockwise, from samples of its extreme curves.
        size: the sheet's size (length), the scale of the tolerances.
    """

    rotation: Array
    translation: Array
    body: str
    tilt_deg: float
    centre_of_mass: Array
    contacts: Array
    support_polygon: Array
    tipping_margin_deg: float
    tipping_edge: tuple[int, int]
    bounds: Array
    footprint: Array
    size: float

    def apply(self, points: ArrayLike) -> Array:
        """Move fold-frame points ``(k, 3)`` into the resting placement."""
        return np.asarray(points, dtype=float) @ self.rotation.T + self.translation

    @property
    def stable(self) -> bool:
        """Whether the centre of mass lies strictly over the support polygon."""
        return self.tipping_margin_deg > 0.0

    @property
    def height(self) -> float:
        """The placed form's height (length)."""
        return float(self.bounds[1, 2] - self.bounds[0, 2])

    @property
    def width(self) -> float:
        """The placed form's extent along the resting frame's x axis (length)."""
        return float(self.bounds[1, 0] - self.bounds[0, 0])

    @property
    def depth(self) -> float:
        """The placed form's extent along the resting frame's y axis (length)."""
        return float(self.bounds[1, 1] - self.bounds[0, 1])

    @property
    def footprint_area(self) -> float:
        """Area of :attr:`footprint` (length^2)."""
        return abs(polygon_area(self.footprint))

    def to_data(self, apex: ArrayLike | None = None) -> dict[str, Any]:
        """The placement as plain JSON data (lengths in the design unit,
        angles in degrees), for the report; ``apex``: the fold frame's apex,
        reported where it stands."""
        lo, hi = self.bounds
        i, j = self.tipping_edge
        poly = self.support_polygon
        data: dict[str, Any] = {
            "body": self.body,
            "bounding_box": {"min": lo.tolist(), "max": hi.tolist()},
            "height": self.height,
            "footprint": {
                "width": self.width,
                "depth": self.depth,
                "area": self.footprint_area,
            },
            "tilt_deg": float(self.tilt_deg),
            "stable": bool(self.stable),
            "touching_points": len(self.contacts),
            "centre_of_mass": self.centre_of_mass.tolist(),
            "contacts": self.contacts.tolist(),
            "support_polygon": poly.tolist(),
            "tipping_margin_deg": float(self.tipping_margin_deg),
            "tipping_edge": [poly[i].tolist(), poly[j].tolist()] if len(poly) else [],
            "warnings": stability_warnings(self),
        }
        if apex is not None:
            data["apex"] = self.apply(np.asarray(apex, dtype=float)[None, :])[0].tolist()
        return data


def stability_warnings(rest: RestingPlacement, units: str = "") -> list[str]:
    """The warnings (one line each) a resting form deserves: none when its
    tipping margin is at least :data:`TIPPING_WARNING_DEG`."""
    margin = rest.tipping_margin_deg
    if margin >= TIPPING_WARNING_DEG:
        return []
    i, j = rest.tipping_edge
    poly = rest.support_polygon
    u = f" {units}" if units else ""
    if len(poly) >= 2:
        a, b = poly[i], poly[j]
        edge = (
            f" about the support edge from ({a[0]:.4g}, {a[1]:.4g}) to ({b[0]:.4g}, {b[1]:.4g}){u}"
        )
    else:
        edge = ""
    if len(poly) == 2:
        return [
            f"the {rest.body} rests on two points only and rocks on a curved edge{edge}: "
            "it has no margin against tipping about the line through them"
        ]
    if margin <= 0.0:
        return [
            f"the {rest.body} does not stand stably: its centre of mass lies "
            f"{-margin:.3g} deg outside its support polygon{edge}"
        ]
    return [
        f"the {rest.body} stands with a tipping margin of only {margin:.3g} deg (below "
        f"{TIPPING_WARNING_DEG:g} deg): a tilt of {margin:.3g} deg{edge} tips it over"
    ]


# -- the ground ---------------------------------------------------------------
def _basis(g: Array) -> tuple[Array, Array]:
    """Two unit vectors completing ``g`` to a right-handed orthonormal frame."""
    a = np.array([1.0, 0.0, 0.0]) if abs(g[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e1 = a - (a @ g) * g
    e1 /= np.linalg.norm(e1)
    return e1, cross3(g, e1)


def _nearest_on_polygon(corners: Array) -> tuple[int, int, float]:
    """The point of a convex polygon's boundary (or segment, or point)
    ``(m, 2)`` nearest the origin: (i, j, distance), with i == j for a corner
    and (i, j) the edge's corners otherwise."""
    m = len(corners)
    if m == 1:
        return 0, 0, float(np.hypot(*corners[0]))
    best = (0, 0, math.inf)
    for i in range(m if m > 2 else 1):
        j = (i + 1) % m
        a, b = corners[i], corners[j]
        d = b - a
        t = float(np.clip(-(a @ d) / max(float(d @ d), 1e-300), 0.0, 1.0))
        dist = float(np.hypot(*(a + t * d)))
        if dist < best[2]:
            best = (i, i, dist) if t <= 0.0 else (j, j, dist) if t >= 1.0 else (i, j, dist)
    return best


def _roll_twice(points: Array, com: Array, g: Array, tol: float) -> tuple[Array, NDArray[np.int64]]:
    """:func:`_roll`, and if that goes on for long (rolling along a curved edge
    goes sample by sample) on every 16th point from where it got, then on all
    again; a form that balances falls to the side nearer the fold frame's
    upright."""

    def roll(pts: Array, g: Array, steps: int) -> tuple[Array, NDArray[np.int64], bool]:
        g, on, state = _roll(pts, com, g, tol, steps=steps)
        if state == "balanced":
            ways = [_roll(pts, com, g, tol, push, steps) for push in (1.0, -1.0)]
            g, on, state = ways[1] if ways[1][0][2] > ways[0][0][2] + 1e-12 else ways[0]
        return g, on, state == "rests"

    g, on, done = roll(points, g, 200)
    if not done and len(points) > 256:
        g, _, _ = roll(points[::16], g, 4000)
    if not done:
        g, on, _ = roll(points, g, 4000)
    return g, on


def _roll(
    points: Array, com: Array, g: Array, tol: float, push: float = 0.0, steps: int = 4000
) -> tuple[Array, NDArray[np.int64], str]:
    """Tip the point set about its lowest points until the centre of mass
    ``com`` lies over their hull. ``g`` is the ground's upward normal in the
    body's frame. Returns the final normal, the indices of the contacts, and
    how it ended: 'rests', 'balanced' (exactly above an edge or a point: an
    unstable equilibrium, as symmetric forms meet it; a ``push`` of +1 or -1
    then tips it to one side or the other) or 'rolling' (after ``steps``)."""
    on = np.zeros(0, dtype=np.int64)
    for _ in range(steps):
        h = points @ g
        on = np.flatnonzero(h <= h.min() + tol)
        e1, e2 = _basis(g)
        rel = points[on] - com
        q = np.column_stack([rel @ e1, rel @ e2])
        hull = convex_hull_2d(q, tol)
        corners = q[hull]
        if len(hull) >= 3 and float(edge_distances([0.0, 0.0], corners).min()) > tol:
            return g, on, "rests"  # the centre of mass is over the support polygon
        i, j, _ = _nearest_on_polygon(corners)
        p0 = points[on[hull[i]]]
        w = com - p0
        w -= (w @ g) * g
        if i != j:  # tip about an edge: the horizontal offset across it
            e = points[on[hull[j]]] - p0
            e /= np.linalg.norm(e)
            w -= (w @ e) * e
        wn = float(np.linalg.norm(w))
        if wn <= tol:  # balanced exactly above a contact or an edge
            if push == 0.0:
                return g, on, "balanced"
            axis = points[on[hull[j]]] - p0 if i != j else e1
            w = push * cross3(g, axis)
            push, wn = 0.0, float(np.linalg.norm(w))
        w /= wn
        a = (points - p0) @ g
        b = (points - p0) @ w
        toward = b > tol
        if not np.any(toward):
            return g, on, "rests"
        phi = float(np.min(np.arctan2(a[toward], b[toward])))
        g = math.cos(phi) * g - math.sin(phi) * w
        g /= np.linalg.norm(g)
    return g, on, "rolling"


@dataclass
class _Feature:
    """A contact being made exact: a fixed point, or a piece and a bracket."""

    piece: int
    lo: float
    hi: float
    point: Array


@dataclass(frozen=True)
class _Samples:
    """Points ``(N, 3)`` with the piece each lies on (-1: a fixed point) and
    its parameter there."""

    points: Array
    owner: NDArray[np.int64]
    param: Array

    def plus(self, more: list[tuple[int, float, Array]]) -> _Samples:
        """These samples and more (piece, parameter, point)."""
        if not more:
            return self
        return _Samples(
            np.vstack([self.points, np.array([p for _, _, p in more])]),
            np.concatenate([self.owner, np.array([k for k, _, _ in more], dtype=np.int64)]),
            np.concatenate([self.param, np.array([t for _, t, _ in more])]),
        )


def _features(body: Body, samples: _Samples, on: NDArray[np.int64]) -> list[_Feature]:
    """Group the sampled contacts ``on``: neighbouring samples of one piece are one."""
    owner, param = samples.owner[on], samples.param[on]
    out = [_Feature(-1, 0.0, 0.0, samples.points[i].copy()) for i in on[owner < 0]]
    for k in np.unique(owner[owner >= 0]):
        piece = body.pieces[int(k)]
        ts = np.unique(param[owner == k])
        idx = np.searchsorted(piece.grid, ts)
        for grp in np.split(ts, np.flatnonzero(np.diff(idx) > 2) + 1):
            lo, hi = piece.bracket(float(grp[0]), float(grp[-1]))
            out.append(_Feature(int(k), lo, hi, np.zeros(3)))
    return out


def _locate(body: Body, f: _Feature, g: Array) -> Array:
    """Move feature ``f`` to the exact lowest point of its bracket along ``g``,
    widening the bracket while the lowest point sits on an end of it."""
    if f.piece < 0:
        return f.point
    piece = body.pieces[f.piece]
    for _ in range(8):
        t, p = body.lowest(f.piece, f.lo, f.hi, g)
        width = f.hi - f.lo
        at_lo = t <= f.lo + 1e-3 * width and f.lo > piece.t0
        at_hi = t >= f.hi - 1e-3 * width and f.hi < piece.t1
        f.point = p
        if not (at_lo or at_hi):
            break
        f.lo = max(piece.t0, t - width)
        f.hi = min(piece.t1, t + width)
    return f.point


def _plane_through(pts: Array, com: Array, g: Array, tol: float) -> Array | None:
    """The upward normal of the plane through three of ``pts`` ``(k, 3)`` that
    has every point on or above it, preferring a triangle under the centre
    of mass; None when there is no such plane."""
    best: tuple[float, Array] | None = None
    for i, j, k in combinations(range(len(pts)), 3):
        n = cross3(pts[j] - pts[i], pts[k] - pts[i])
        nn = float(np.linalg.norm(n))
        if nn <= tol * tol:
            continue
        n = n / nn if n @ g > 0.0 else -n / nn
        if float(np.min((pts - pts[i]) @ n)) < -tol:
            continue
        e1, e2 = _basis(n)
        tri = np.column_stack([(pts[[i, j, k]] - com) @ e1, (pts[[i, j, k]] - com) @ e2])
        if polygon_area(tri) < 0.0:
            tri = tri[::-1]
        score = float(edge_distances([0.0, 0.0], tri).min())
        if best is None or score > best[0]:
            best = (score, n)
    return None if best is None else best[1]


def _touching(
    samples: _Samples, lows: list[tuple[int, float, Array]], g: Array, level: float, tol: float
) -> Array:
    """The points ``(k, 3)`` that touch the ground at ``level`` along ``g``
    within ``tol``: the exact lowest points, and samples of an edge that lies
    along the ground."""
    exact = [p for _, _, p in lows if float(p @ g) <= level + tol]
    near = samples.points[samples.points @ g <= level + tol]
    pts = np.vstack([np.array(exact).reshape(-1, 3), near])
    if len(pts) > 8:  # many along an edge: its hull's corners say as much
        e1, e2 = _basis(g)
        pts = pts[convex_hull_2d(np.column_stack([pts @ e1, pts @ e2]), tol)]
    return _distinct(list(pts), tol)


def _distinct(pts: list[Array], tol: float) -> Array:
    out: list[Array] = []
    for p in pts:
        if all(float(np.linalg.norm(p - q)) > tol for q in out):
            out.append(p)
    return np.array(out).reshape(-1, 3)


def _settle(
    body: Body, features: list[_Feature], com: Array, g: Array
) -> tuple[Array, float, bool]:
    """Make the ground plane through the features exact (see the module doc):
    its upward normal, the features' lowest height along it, and whether it
    rests on two features only (a curved edge touching along with a point or
    another edge: the plane on which they balance the centre of mass,
    :func:`_rock`)."""
    tol = CONTACT_TOLERANCE * body.size
    rocks = False
    for _ in range(40):
        pts = _distinct([_locate(body, f, g) for f in features], tol)
        if len(pts) == 2:
            g, rocks = _rock(body, features, com, g)
            break
        if len(pts) < 3:
            break
        n = _plane_through(pts, com, g, tol)
        if n is None:
            break
        moved = float(np.linalg.norm(n - g))
        g = n
        if moved <= 1e-15:
            break
    pts = np.array([_locate(body, f, g) for f in features])
    return g, float(np.min(pts @ g)), rocks


def _rock(body: Body, features: list[_Feature], com: Array, g: Array) -> tuple[Array, bool]:
    """The ground normal near ``g`` on which the body rests on two features
    (one of them a curve it could rock on), with the centre of mass above the
    line through their lowest points: Newton's method on the two conditions
    (equal heights; centre of mass in the vertical plane through the line),
    with a finite-difference Jacobian. Returns the normal and whether that
    converged with the centre of mass between the two points (else ``g``
    unchanged)."""
    tol = CONTACT_TOLERANCE * body.size
    pts = [_locate(body, f, g) for f in features]
    first = pts[0]
    far = max(range(len(pts)), key=lambda i: float(np.linalg.norm(pts[i] - first)))
    pair = [features[0], features[far]]

    def residual(gg: Array) -> Array:
        q1, q2 = (_locate(body, f, gg) for f in pair)
        e = q2 - q1
        e /= max(float(np.linalg.norm(e)), 1e-300)
        return np.array([gg @ (q2 - q1), (com - q1) @ cross3(gg, e)])

    start = g
    # the heights are flat at a tangency, so the point's place along the curve,
    # and with it the balance, is known to about 1e-8 of the size only
    eps = 1e-4
    for _ in range(30):
        f0 = residual(g)
        if abs(f0[0]) <= 1e-3 * tol and abs(f0[1]) <= 1e-6 * body.size:
            q1, q2 = (_locate(body, f, g) for f in pair)
            span2 = float((q2 - q1) @ (q2 - q1))
            along = float((com - q1) @ (q2 - q1)) / span2 if span2 > tol * tol else -1.0
            return (g, True) if 0.0 < along < 1.0 else (start, False)
        e1, e2 = _basis(g)
        jac = np.empty((2, 2))
        for j, d in enumerate((e1, e2)):
            gd = g + eps * d
            jac[:, j] = (residual(gd / np.linalg.norm(gd)) - f0) / eps
        try:
            step = np.linalg.solve(jac, -f0)
        except np.linalg.LinAlgError:
            return start, False
        length = float(np.linalg.norm(step))
        if length > 0.02:  # stay near the samples' rest (the residual jumps elsewhere)
            step *= 0.02 / length
        g = g + step[0] * e1 + step[1] * e2
        g /= np.linalg.norm(g)
        if float(np.linalg.norm(g - start)) > 0.1:
            return start, False
    return start, False


def _extent(body: Body, samples: _Samples, g: Array, band: float) -> list[tuple[int, float, Array]]:
    """The exact lowest point along ``g`` of every piece (and fixed point)
    whose samples come within ``band`` (length) of the lowest sample: a list
    of (piece, parameter, point), the lowest first."""
    h = samples.points @ g
    floor = float(h.min())
    found: list[tuple[int, float, Array]] = []
    fixed = samples.owner < 0
    for idx in np.flatnonzero(fixed & (h <= floor + band)):
        found.append((-1, 0.0, samples.points[idx]))
    for k in np.unique(samples.owner[~fixed & (h <= floor + band)]):
        piece = body.pieces[int(k)]
        corners = body.sections[int(k)]
        hk = np.where(np.isnan(corners[..., 0]), np.inf, corners @ g).min(axis=1)
        # the piece's sampled local minima within the band (a plateau counts once)
        left = np.concatenate([[True], hk[1:] < hk[:-1]])
        right = np.concatenate([hk[:-1] <= hk[1:], [True]])
        for tj in piece.grid[(hk <= floor + band) & left & right]:
            lo, hi = piece.bracket(float(tj), float(tj))
            tb, p = body.lowest(int(k), lo, hi, g)
            found.append((int(k), tb, p))
    found.sort(key=lambda item: float(item[2] @ g))
    return found


def _rotation_to_up(g: Array) -> Array:
    """The smallest rotation taking unit vector ``g`` to (0, 0, 1)."""
    target = np.array([0.0, 0.0, 1.0])
    axis = cross3(g, target)
    s = float(np.linalg.norm(axis))
    c = float(g @ target)
    if s < 1e-15:
        return np.eye(3) if c > 0 else np.diag([1.0, -1.0, -1.0])
    k = axis / s
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + s * kx + (1 - c) * (kx @ kx)


def _sample_spacing(body: Body) -> float:
    """The largest distance between neighbouring samples of a piece (length),
    in 3D or along the piece (on the flat sheet): no point of a piece lies
    further than that from its nearest sample, but for the offsets of a thick
    sheet (added: the thickness)."""
    worst = 0.0
    for piece, corners in zip(body.pieces, body.sections, strict=True):
        steps = np.linalg.norm(np.diff(corners, axis=0), axis=-1)
        steps = steps[~np.isnan(steps)]
        worst = max(worst, piece.step, float(steps.max()) if len(steps) else 0.0)
    return worst + body.thickness


def rest_form(
    folded: FoldedSheet, material: Material | None = None, body: str = "shell"
) -> RestingPlacement:
    """How the form written as ``body`` stands on the ground (z = 0).

    Args:
        folded: the fold.
        material: thickness, reference surface and relief hole (the hole
            the STEP is built with: pass the material with ``relief_hole``
            resolved, as :func:`onefold_cad.export.step.build_part` does);
            None: a zero-thickness sheet without a hole.
        body: 'shell' (the reference surface) or 'solid' (the thick sheet;
            exact model, thickness > 0, relief hole > 0).

    Returns:
        The placement: the lowest point of the body lies on z = 0 (found on
        the exact body, not on samples), three or more contacts in the ground
        plane, and the stability values.

    Raises:
        InvalidParameterError: a body that cannot be built ('solid' for the
            paper model or without thickness).
        NoSolutionError: the fold's points are not finite.
    """
    form = Body(folded, material, body)
    size = form.size
    _, com = form.mass_properties
    samples = _Samples(*form.samples)
    if not (np.all(np.isfinite(samples.points)) and np.all(np.isfinite(com))):
        raise NoSolutionError(
            f"the fold of alpha {folded.solution.frame.alpha:g}, beta "
            f"{folded.solution.frame.beta:g} deg is not finite in double precision "
            f"(apex height {folded.solution.apex_height:g}): it cannot stand on the ground"
        )
    tol = 1e-10 * size
    contact_tol = CONTACT_TOLERANCE * size
    band = 2.0 * _sample_spacing(form) + tol
    g = np.array([0.0, 0.0, 1.0])
    lows: list[tuple[int, float, Array]] = []
    for _ in range(8):
        g, on = _roll_twice(samples.points, com, g, tol)
        g, plane, rocks = _settle(form, _features(form, samples, on), com, g)
        lows = _extent(form, samples, g, band)
        level = float(lows[0][2] @ g)
        # roll on with the exact lowest points among the samples when the
        # exact body reaches below the plane between samples, or when the
        # exact contacts no longer hold the centre of mass (samples near an
        # exact contact can look as low as it)
        samples = samples.plus([x for x in lows if float(x[2] @ g) <= level + band])
        touching = _touching(samples, lows, g, level, contact_tol)
        if level >= plane - contact_tol and (rocks or _holds(touching, com, g, tol)):
            break
    rot = _rotation_to_up(g)
    level = float(lows[0][2] @ g)
    # stand the lowest point on z = 0, the centre of mass over the origin
    com_r = rot @ com
    shift = np.array([-com_r[0], -com_r[1], -level])
    contacts = _touching(samples, lows, g, level, contact_tol) @ rot.T + shift
    polygon = contacts[convex_hull_2d(contacts[:, :2], contact_tol), :2]
    margin, edge = _tipping(polygon, com_r + shift, contact_tol)
    bounds = _bounds(form, samples, rot, shift, band)
    shadow = samples.points @ rot.T
    footprint = shadow[convex_hull_2d(shadow[:, :2]), :2] + shift[:2]
    tilt = math.degrees(math.acos(float(np.clip(g[2], -1.0, 1.0))))
    # the body's points are relative to the apex: p' = rot (p - A) + shift
    translation = shift - rot @ form.origin
    return RestingPlacement(
        rot,
        translation,
        body,
        tilt,
        com_r + shift,
        contacts,
        polygon,
        margin,
        edge,
        bounds,
        footprint,
        size,
    )


def _holds(contacts: Array, com: Array, g: Array, tol: float) -> bool:
    """Whether the centre of mass lies over the hull of ``contacts`` ``(k, 3)``
    by more than ``tol`` (length), seen along ``g``."""
    e1, e2 = _basis(g)
    q = np.column_stack([(contacts - com) @ e1, (contacts - com) @ e2])
    hull = convex_hull_2d(q, tol)
    return len(hull) >= 3 and float(edge_distances([0.0, 0.0], q[hull]).min()) > tol


def _tipping(polygon: Array, com: Array, tol: float) -> tuple[float, tuple[int, int]]:
    """The tipping margin (deg) of a centre of mass ``(3,)`` over a support
    polygon ``(m, 2)`` and the edge it is smallest about. Two corners (a form
    that rocks on a curved edge): 0 while the centre of mass lies over the
    segment within ``tol`` (length), else minus the tilt that brings it there;
    one corner: minus the tilt that brings it over that point."""
    z = max(float(com[2]), 0.0)
    m = len(polygon)
    if m == 0:
        return -90.0, (0, 0)
    if m == 1:
        return -math.degrees(math.atan2(float(np.hypot(*(com[:2] - polygon[0]))), z)), (0, 0)
    if m == 2:
        a, b = polygon
        d = b - a
        t = float(np.clip((com[:2] - a) @ d / float(d @ d), 0.0, 1.0))
        off = float(np.hypot(*(com[:2] - a - t * d)))
        return 0.0 - math.degrees(math.atan2(max(off - tol, 0.0), z)), (0, 1)
    d = edge_distances(com[:2], polygon)
    i = int(np.argmin(d))
    return math.degrees(math.atan2(float(d[i]), z)), (i, (i + 1) % m)


def _bounds(form: Body, samples: _Samples, rot: Array, translation: Array, band: float) -> Array:
    """The placed body's exact lowest and highest x, y, z ``(2, 3)``."""
    out = np.zeros((2, 3))
    for axis in range(3):
        d = rot[axis]  # the resting frame's axis in the fold frame
        lo = float(_extent(form, samples, d, band)[0][2] @ d)
        hi = float(_extent(form, samples, -d, band)[0][2] @ d)
        out[0, axis] = lo + translation[axis]
        out[1, axis] = hi + translation[axis]
    return out
