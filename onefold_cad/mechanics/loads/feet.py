"""The sheet's feet and the rigid-body checks of its supports.

The feet are the ground contacts grouped by the mesh's edges (contacts joined
by an edge are one foot). The checks take the sheet as a rigid body on its
feet (the ground at z = 0), under the external loads' resultant: force ``F``
and moment ``M`` about the origin (N, N m). The ground's vertical reaction
``V = -F_z`` then acts at the centre of pressure ``e = (M_y, -M_x) / V``:

- it *lifts off* when ``V <= 0``;
- it *tips* when ``e`` leaves the support polygon (the feet's convex hull);
  the margin is ``e``'s distance inside it (length, negative outside);
- on friction feet it *slides* when ``|F_h| > mu V`` (Coulomb, the same
  coefficient at every foot);
- a foot *lifts* when the elastic model's anchor there pulls (a free foot
  cannot: the check the elastic reactions rest on fails), and *slips* when
  its own horizontal force passes ``mu`` times its vertical one (the feet
  spread under the sheet's thrust even where the whole does not slide;
  ``cases``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from onefold_cad.geometry.hull import convex_hull_2d, edge_distances
from onefold_cad.geometry.numeric import Array

__all__ = [
    "RigidCheck",
    "centre_of_pressure",
    "feet_of",
    "resultant",
    "rigid_check",
    "three_feet_reactions",
    "tipping_load",
]


def feet_of(contacts: Array, edges: Array) -> list[Array]:
    """The feet: ``contacts`` (node ids) grouped by ``edges`` ``(e, 2)``
    joining two of them (connected components), ordered by first node."""
    ids = [int(i) for i in np.asarray(contacts).ravel()]
    parent = {i: i for i in ids}

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b in np.asarray(edges):
        if int(a) in parent and int(b) in parent:
            parent[root(int(a))] = root(int(b))
    groups: dict[int, list[int]] = {}
    for i in sorted(ids):
        groups.setdefault(root(i), []).append(i)
    return [np.array(g) for g in sorted(groups.values(), key=lambda g: g[0])]


def resultant(points: Array, forces: Array) -> tuple[Array, Array]:
    """``(3,)`` the total force (N) and ``(3,)`` its moment about the origin
    (N m) of ``forces`` ``(n, 3)`` at ``points`` ``(n, 3)`` (m)."""
    f = np.asarray(forces, dtype=float)
    return f.sum(axis=0), np.cross(np.asarray(points, dtype=float), f).sum(axis=0)


def centre_of_pressure(force: Array, moment: Array) -> Array | None:
    """``(2,)`` where the ground's vertical reaction acts (m), None when the
    loads lift the body (``V <= 0``)."""
    v = -float(force[2])
    if v <= 0.0:
        return None
    return np.array([moment[1] / v, -moment[0] / v])


@dataclass(frozen=True)
class RigidCheck:
    """The rigid-body checks of one load case.

    Attributes:
        vertical_N: ``V``, the ground's total vertical reaction (N).
        horizontal_N: ``|F_h|``, the horizontal load (N).
        slide_ratio: ``|F_h| / (mu V)`` (inf when ``V <= 0``); it slides past 1.
        tip_margin: the centre of pressure's distance inside the support
            polygon (m; negative: outside), None when it lifts off.
        lifts_off: ``V <= 0``.
    """

    vertical_N: float
    horizontal_N: float
    slide_ratio: float
    tip_margin: float | None
    lifts_off: bool

    @property
    def slides(self) -> bool:
        return self.slide_ratio > 1.0

    @property
    def tips(self) -> bool:
        return self.lifts_off or (self.tip_margin is not None and self.tip_margin < 0.0)


def rigid_check(feet_xy: Array, force: Array, moment: Array, mu: float) -> RigidCheck:
    """The checks of a body on feet at ``feet_xy`` ``(k, 2)`` (m) under the
    resultant ``force``, ``moment`` (see the module docstring)."""
    v = -float(force[2])
    h = float(math.hypot(force[0], force[1]))
    ratio = h / (mu * v) if v > 0.0 else math.inf
    e = centre_of_pressure(force, moment)
    margin = None
    if e is not None:
        margin = _inside(np.asarray(feet_xy, dtype=float), e)
    return RigidCheck(v, h, ratio, margin, e is None)


def _inside(feet_xy: Array, point: Array) -> float:
    """The distance (m) of ``point`` inside the feet's convex hull (negative
    outside; a line or a point of feet: minus the distance to it)."""
    if len(feet_xy) >= 3:
        hull = feet_xy[convex_hull_2d(feet_xy)]
        if len(hull) >= 3:
            return float(edge_distances(point, hull).min())
    if len(feet_xy) == 1:
        return -float(np.hypot(*(point - feet_xy[0])))
    a, b = feet_xy[0], feet_xy[np.argmax(np.linalg.norm(feet_xy - feet_xy[0], axis=1))]
    d = b - a
    t = float(np.clip((point - a) @ d / float(d @ d), 0.0, 1.0))
    return -float(np.hypot(*(point - a - t * d)))


def tipping_load(
    feet_xy: Array, com_xy: Array, weight_N: float, height: float, direction_deg: float
) -> float:
    """The horizontal load (N) at ``height`` (m) towards ``direction_deg`` that
    tips a rigid body of ``weight_N`` whose centre of mass is over ``com_xy``
    (m, inside the feet's convex hull): its weight's restoring moment
    ``W a`` over the lever arm ``height``, ``a`` the distance from ``com_xy``
    along the direction to the hull's edge."""
    hull = np.asarray(feet_xy, dtype=float)[convex_hull_2d(feet_xy)]
    w = np.array([math.cos(math.radians(direction_deg)), math.sin(math.radians(direction_deg))])
    d = np.roll(hull, -1, axis=0) - hull
    inward = np.column_stack([-d[:, 1], d[:, 0]]) / np.hypot(d[:, 0], d[:, 1])[:, None]
    dist = edge_distances(com_xy, hull)
    rate = inward @ w
    a = min(float(di / -ri) for di, ri in zip(dist, rate, strict=True) if ri < 0.0)
    return weight_N * a / height


def three_feet_reactions(feet_xy: Array, force: Array, moment: Array) -> Array:
    """``(3,)`` the vertical reactions (N, up) of three feet at ``feet_xy``
    ``(3, 2)`` (m) under the resultant ``force``, ``moment`` (statics:
    ``sum R = -F_z``, ``sum x R = M_y``, ``sum y R = -M_x``)."""
    p = np.asarray(feet_xy, dtype=float)
    a = np.vstack([np.ones(3), p[:, 0], p[:, 1]])
    return np.linalg.solve(a, np.array([-force[2], moment[1], -moment[0]]))
