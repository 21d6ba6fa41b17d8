"""The thick sheet's faces (exact model): each side's sheet faces and walls as
ruled :class:`~onefold_cad.geometry.thick.slab.Patch` es between boundary curves,
the input of the B-rep builder (:mod:`onefold_cad.export.brep.solid`).

Lengths are in the design unit; angles in radians.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from onefold_cad.geometry.numeric import Array
from onefold_cad.geometry.thick.slab import Boundary, Patch, Slab

__all__ = ["slab_patches"]


def slab_patches(slab: Slab) -> list[Patch]:
    """The ruled patches of both sides (see :class:`Patch`)."""
    out: list[Patch] = []
    for side in (0, 1):
        for j in (0, 1):
            out += _sheet_face(slab, side, j, slab.breaks(side, f"s{j}"))
        for which in ("in", "out"):
            out += _wall(slab, side, which, slab.breaks(side, which))
    return _share_symmetric_walls(slab, out)


def _cut(slab: Slab, plane: str, side: int, past: bool, **kw: object) -> Boundary:
    """A cut curve: on y = 0 both sides share it (the cut edge's wall
    only past the creases, where it does not depend on the sheet)."""
    shared = plane == "y" and (kw.get("radius") != "out" or past)
    kind = "K" if "level" in kw else "W"
    return Boundary(kind, plane=plane, side=-1 if shared else side, **kw)  # type: ignore[arg-type]


def _sheet_face(slab: Slab, side: int, j: int, breaks: Array) -> list[Patch]:
    s = slab.s_range[j]
    out = []
    for a, b in zip(breaks[:-1], breaks[1:], strict=True):
        mid = np.array([0.5 * (a + b)])
        region = slab.region(np.array([a, b]))
        lo, hi = float(slab.inner_radius(mid)[0]), float(slab.outer_radius(side, mid)[0])
        low = Boundary("C", "in", j, side=side)
        high = Boundary("C", "out", j, side=side)
        empty = False
        for p in slab.plane_names(region):
            al, be, ga = (float(np.asarray(v).ravel()[0]) for v in slab.coefficients(p, mid))
            if al == 0.0:
                empty |= be * s + ga < 0.0
                continue
            rho = -(be * s + ga) / al
            cut = _cut(slab, p, side, region != 0, level=j)
            if al > 0.0 and rho > lo:
                lo, low = rho, cut
            elif al < 0.0 and rho < hi:
                hi, high = rho, cut
        if not empty and hi > lo:
            out.append(Patch(side, f"s{j}", float(a), float(b), low, high))
    return out


def _wall(slab: Slab, side: int, which: str, breaks: Array) -> list[Patch]:
    out = []
    for a, b in zip(breaks[:-1], breaks[1:], strict=True):
        mid = np.array([0.5 * (a + b)])
        region = slab.region(np.array([a, b]))
        r = float(slab.radius(which, side, mid)[0])
        lo, hi = slab.s_range
        low = Boundary("C", which, 0, side=side)
        high = Boundary("C", which, 1, side=side)
        empty = False
        for p in slab.plane_names(region):
            al, be, ga = (float(np.asarray(v).ravel()[0]) for v in slab.coefficients(p, mid))
            if be == 0.0:
                empty |= al * r + ga < 0.0
                continue
            sig = -(al * r + ga) / be
            cut = _cut(slab, p, side, region != 0, radius=which)
            if be > 0.0 and sig > lo:
                lo, low = sig, cut
            elif be < 0.0 and sig < hi:
                hi, high = sig, cut
        if not empty and hi > lo:
            out.append(Patch(side, which, float(a), float(b), low, high))
    return out


def _share_symmetric_walls(slab: Slab, patches: list[Patch]) -> list[Patch]:
    """Where both sides' cut-edge walls meet y = 0 along the same curve (the
    sheet's edges symmetric about a crease half there), let them share it."""

    def own_cut(p: Patch) -> bool:
        return p.face == "out" and any(
            b.kind == "W" and b.plane == "y" and b.side >= 0 for b in (p.low, p.high)
        )

    sides: dict[tuple[float, float], set[int]] = {}
    for p in patches:
        if own_cut(p):
            sides.setdefault((p.t0, p.t1), set()).add(p.side)
    shared = set()
    for (a, b), who in sides.items():
        t = np.linspace(a, b, 9)
        r0, r1 = slab.outer_radius(0, t), slab.outer_radius(1, t)
        if who == {0, 1} and np.max(np.abs(r0 - r1)) <= 1e-12 * np.max(r0):
            shared.add((a, b))
    cut = Boundary("W", "out", plane="y", side=-1)
    out = []
    for p in patches:
        if own_cut(p) and (p.t0, p.t1) in shared:
            p = replace(p, low=cut) if p.low.kind == "W" else replace(p, high=cut)
        out.append(p)
    return out
