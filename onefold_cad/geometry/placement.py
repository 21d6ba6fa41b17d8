"""Stand a folded form on the ground: its resting placement and how stable it is.

:func:`rest_form` sets the body the STEP holds (the reference surface, or the
solid of the sheet's thickness: :class:`onefold_cad.geometry.body.FoldedBody`) down
as it was solved (apex above H), lets it topple to rest, and makes the ground
plane exact (:mod:`onefold_cad.geometry.ground`): its lowest point lies on
z = 0 to rounding, found on the exact curves where it can lie, never on
samples alone. The resting frame has the centre of mass above the origin;
its rotation is the smallest one from the fold frame.

Stability: the centre of mass of the sheet with its thickness, the contacts,
their convex hull on the ground (the support polygon) and the tipping margin
(the smallest tilt about a support edge that tips the form over),
:func:`stability_warnings` below 5 deg. A form resting on two points rocks on
a curved edge: its margin is 0.

Lengths are in the design unit; angles in degrees at the API.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from onefold_cad.choices import Body
from onefold_cad.errors import NoSolutionError
from onefold_cad.geometry.body import FoldedBody
from onefold_cad.geometry.body_mass import mass_properties
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.ground import (
    CONTACT_TOLERANCE,
    Samples,
    exact_features,
    features,
    holds,
    sample_spacing,
    settle,
    touching,
)
from onefold_cad.geometry.hull import convex_hull_2d, edge_distances
from onefold_cad.geometry.lows import bound_directions, exact_bounds, exact_lows
from onefold_cad.geometry.material import Material
from onefold_cad.geometry.numeric import Array, cross3, polygon_area
from onefold_cad.geometry.topple import com_depth, com_outside, roll

__all__ = [
    "RestingPlacement",
    "rest_form",
    "rotation_to_up",
    "stability_warnings",
    "tipping_margin",
    "TIPPING_WARNING_DEG",
]

#: Below this tipping margin (deg) a form gets a stability warning.
TIPPING_WARNING_DEG = 5.0


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
        com_outside: 0, or a lower bound on how far (length) the thick
            sheet's centre of mass lies outside the convex hull of the
            body's points (the thickness reaches beyond them, e.g. on a
            sheet narrower across than it is thick): no rest of the body
            holds it, so the form is stood and rated with the zero-thickness
            reference surface's centre of mass (``centre_of_mass`` is that
            one), with a warning (:func:`stability_warnings`).
        settled: False when toppling on the samples and making the ground
            plane exact did not come to agree (the exact plane leaves the
            contacts' hull short of the centre of mass, or cuts the body):
            the form stands where they stopped, with a warning.
    """

    rotation: Array
    translation: Array
    body: Body
    tilt_deg: float
    centre_of_mass: Array
    contacts: Array
    support_polygon: Array
    tipping_margin_deg: float
    tipping_edge: tuple[int, int]
    bounds: Array
    footprint: Array
    size: float
    com_outside: float = 0.0
    settled: bool = True

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
    tipping margin is at least :data:`TIPPING_WARNING_DEG` and its centre of
    mass lies within its body's hull (else :attr:`RestingPlacement.com_outside`
    says the reference surface's centre of mass stood in)."""
    u = f" {units}" if units else ""
    out: list[str] = []
    if rest.com_outside > 0.0:
        out.append(
            f"the centre of mass of the thick sheet lies at least {rest.com_outside:.3g}{u} "
            f"outside the convex hull of the {rest.body} (the thickness reaches beyond its "
            "reference surface, as on a sheet narrower across than it is thick): no rest of "
            "it holds that centre of mass, so it is placed and "
            "its stability rated with the centre of mass of the zero-thickness "
            "reference surface"
        )
    if not rest.settled:
        out.append(
            f"the {rest.body}'s rest is not settled: toppling on its samples and the exact "
            "ground plane did not agree within the contact tolerance (1e-9 of the sheet's "
            "size); it stands where they stopped"
        )
    return out + _tipping_warnings(rest, u)


def _tipping_warnings(rest: RestingPlacement, u: str) -> list[str]:
    """The stability warning of :func:`stability_warnings` (``u``: the units
    suffix of lengths)."""
    margin = rest.tipping_margin_deg
    if margin >= TIPPING_WARNING_DEG:
        return []
    i, j = rest.tipping_edge
    poly = rest.support_polygon
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
    if margin == 0.0:
        return [
            f"the {rest.body} is balanced with its centre of mass above the support "
            f"edge{edge}: it rocks, with no margin against tipping about that edge"
        ]
    if margin < 0.0:
        return [
            f"the {rest.body} does not stand stably: its centre of mass lies "
            f"{-margin:.3g} deg outside its support polygon{edge}"
        ]
    return [
        f"the {rest.body} stands with a tipping margin of only {margin:.3g} deg (below "
        f"{TIPPING_WARNING_DEG:g} deg): a tilt of {margin:.3g} deg{edge} tips it over"
    ]


def rest_form(
    folded: FoldedSheet, material: Material | None = None, body: Body = Body.SHELL
) -> RestingPlacement:
    """How the form written as ``body`` stands on the ground (z = 0).

    Args:
        folded: the fold.
        material: thickness, reference surface and relief hole (the hole
            the STEP is built with: pass the material with ``relief_hole``
            resolved, as :func:`onefold_cad.export.part.build_part` does);
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
    form = FoldedBody(folded, material, body)
    size = form.size
    _, com = mass_properties(form)
    samples = Samples(*form.samples)
    if not (np.all(np.isfinite(samples.points)) and np.all(np.isfinite(com))):
        raise NoSolutionError(
            f"the fold of alpha {folded.solution.frame.alpha:g}, beta "
            f"{folded.solution.frame.beta:g} deg is not finite in double precision "
            f"(apex height {folded.solution.apex_height:g}): it cannot stand on the ground"
        )
    tol = 1e-10 * size
    contact_tol = CONTACT_TOLERANCE * size
    band = 2.0 * sample_spacing(form) + tol
    g = np.array([0.0, 0.0, 1.0])
    lows: list[tuple[int, float, Array]] = []
    # the thick sheet's centre of mass can lie outside the hull of the body's
    # points (a sheet narrower across than its thickness): no rest holds it;
    # the body is then stood by its reference surface's (a warning says so)
    outside = com_outside(samples.points, com)
    if outside > tol:
        com = _surface_centre(folded, material)
    rolled: list[Array] = []
    ahead, ahead_g = [], None
    rocks = settled = False
    last: Array | None = None  # the contacts the loop's last look found
    for _ in range(8):
        g, on = roll(samples.points, com, g, tol)
        depth = com_depth(samples.points, com, g)
        if depth > tol and outside <= tol:  # the topple found it outside
            outside, com = depth, _surface_centre(folded, material)
            g, on = roll(samples.points, com, np.array([0.0, 0.0, 1.0]), tol)
        if any(math.sqrt(float((g - r) @ (g - r))) <= 1e-12 for r in rolled):
            # the samples' rest comes back while the exact plane leaves it (a
            # body lying almost flat, whose lowest points jump along nearly
            # straight edges at the slightest tilt): make that rest exact
            g, lows, samples = _cut(form, samples, com, g, band, tol)
            rocks, settled, ahead_g = False, True, None
            break
        rolled.append(g)
        found = features(form, samples, on)
        for _ in range(4):
            g, plane, rocks = settle(form, found, com, g)
            # and the bounds' five directions (the rest mostly ends here): one search
            dirs = np.vstack([g, bound_directions(rotation_to_up(g))])
            lows, *ahead = exact_lows(form, samples, dirs, np.array([plane] + [-np.inf] * 5))
            ahead_g = g
            level = float(lows[0][2] @ g)
            # the exact plane cuts the body: on its way there (rocking along
            # two curved edges, say) the body met another point first, the
            # apex or a corner the sampled rest kept clear; it rests on that
            # too: settle again with it
            below = [x for x in lows if float(x[2] @ g) < plane - contact_tol]
            if not below:
                break
            found = found + exact_features(form, below)
        # roll on with the exact lowest points among the samples when the
        # exact body reaches below the plane between samples, or when the
        # exact contacts no longer hold the centre of mass (samples near an
        # exact contact can look as low as it)
        samples = samples.plus([x for x in lows if float(x[2] @ g) <= level + band])
        on_ground = touching(samples, lows, g, level, contact_tol)
        if level >= plane - contact_tol and (rocks or holds(on_ground, com, g, tol)):
            settled, last = True, on_ground
            break
    rot = rotation_to_up(g)
    level = float(lows[0][2] @ g)
    # stand the lowest point on z = 0, the centre of mass over the origin
    com_r = rot @ com
    shift = np.array([-com_r[0], -com_r[1], -level])
    if last is None:
        last = touching(samples, lows, g, level, contact_tol)
    contacts = last @ rot.T + shift
    polygon = contacts[convex_hull_2d(contacts[:, :2], contact_tol), :2]
    # a rocking form balances its centre of mass over the line through two
    # tangencies, whose places along their curves are known to about 1e-8 of
    # the size (ground.rock settles for 1e-6 of it)
    margin, edge = tipping_margin(polygon, com_r + shift, 1e-6 * size if rocks else contact_tol)
    bounds = exact_bounds(form, samples, rot, shift, lows[0][2], ahead if ahead_g is g else None)
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
        outside if outside > tol else 0.0,
        settled,
    )


def _cut(
    form: FoldedBody, samples: Samples, com: Array, g: Array, band: float, tol: float
) -> tuple[Array, list[tuple[int, float, Array]], Samples]:
    """Cutting planes on the samples' rest along ``g``: the exact lowest
    points below its plane (by more than the contact tolerance) join the
    samples and the body rolls on them, until none is below. Returns the
    normal, the exact lowest points there and the samples."""
    contact_tol = CONTACT_TOLERANCE * form.size
    lows: list[tuple[int, float, Array]] = []
    for _ in range(8):
        lows = exact_lows(form, samples, g)[0]
        floor = float(np.min(samples.points @ g))
        below = [x for x in lows if float(x[2] @ g) < floor - contact_tol]
        if not below:
            break
        samples = samples.plus(below)
        g, _ = roll(samples.points, com, g, tol)
    return g, lows, samples


def _surface_centre(folded: FoldedSheet, material: Material | None) -> Array:
    """The centre of mass ``(3,)`` of the zero-thickness reference surface
    (relative to the apex, as :func:`~onefold_cad.geometry.body_mass.mass_properties`)."""
    thin = None if material is None else material.with_changes(thickness=0.0, bend_radius=0.0)
    return mass_properties(FoldedBody(folded, thin, Body.SHELL))[1]


def rotation_to_up(g: Array) -> Array:
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


def tipping_margin(polygon: Array, com: Array, tol: float) -> tuple[float, tuple[int, int]]:
    """The tipping margin (deg) of a centre of mass ``(3,)`` over a support
    polygon ``(m, 2)`` and the edge it is smallest about. Two corners (a form
    that rocks on a curved edge): 0 while the centre of mass lies over the
    segment within ``tol`` (length), else minus the tilt that brings it there;
    one corner: minus the tilt that brings it over that point; three or more:
    0 when it lies outside an edge by at most ``tol`` (a form balanced on its
    rocking line that a third point also touches)."""
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
    inside = float(d[i])
    if -tol <= inside < 0.0:  # on the edge within tol: balanced on it
        inside = 0.0
    return math.degrees(math.atan2(inside, z)), (i, (i + 1) % m)
