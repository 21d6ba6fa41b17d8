"""The site's overlap check from the cheap geometry, before any sheet is built.

Building a site's sheets (their solids, their files) takes most of a minute;
the exact clearance (:mod:`onefold_cad.export.site_clearance`) needs the
solids. Sheets whose folded surfaces cross are refused before that: each
sheet's surface mesh (:meth:`~onefold_cad.geometry.folding.FoldedSheet.mesh`)
stands where the site puts it (its resting placement, then the site's
motion), and an edge of one mesh that passes through a triangle of the other,
its ends more than :func:`margin` on either side of the triangle's plane, and
the same the other way round (each passes through the other by more than
the margin), is a crossing no mesh error explains. Sheets that come close without crossing are
left to the exact check after the build.

Lengths are in the site's unit.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from onefold_cad.design import Design, fold_design
from onefold_cad.errors import InvalidParameterError
from onefold_cad.fabrication.rules import resting_placement
from onefold_cad.geometry.numeric import Array
from onefold_cad.site.clearance import convex_overlap
from onefold_cad.site.placement import SitePlacement

__all__ = ["Crossing", "check_plan", "crossing", "margin", "placed_mesh"]

#: The mesh the check uses: rays of each side, points along each ray.
ANGULAR, RADIAL = 120, 12


@dataclass(frozen=True)
class Crossing:
    """Two sheets whose surfaces cross.

    Attributes:
        a, b: the sheets' names, in the site file's order.
        point: ``(3,)`` where an edge of ``a``'s mesh passes through ``b``'s.
        footprint_overlap: the area their footprints' convex hulls share (length^2).
    """

    a: str
    b: str
    point: Array
    footprint_overlap: float


def margin(design: Design) -> float:
    """How far (length) an edge's ends must lie on either side of a triangle's
    plane to count: the sheet's thickness or a thousandth of its size, which
    is larger (the mesh's chords stray from the surface by less)."""
    return max(design.material.thickness, 1e-3 * design.sheet.size)


def placed_mesh(design: Design, site: SitePlacement) -> tuple[Array, NDArray[np.int64]]:
    """``(vertices (k, 3), faces (m, 3))``: the sheet's folded surface standing
    where the site puts it (its body's resting placement, then ``site``)."""
    folded = fold_design(design)
    rest = resting_placement(design, folded)
    verts, faces = folded.mesh(angular=ANGULAR, radial=RADIAL)
    return site.apply(rest.apply(verts)), faces


def _edges(faces: NDArray[np.int64]) -> NDArray[np.int64]:
    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    return np.unique(np.sort(e, axis=1), axis=0)


def crossing(
    a: tuple[Array, NDArray[np.int64]], b: tuple[Array, NDArray[np.int64]], gap: float
) -> Array | None:
    """A point where an edge of mesh ``a`` passes through a triangle of mesh
    ``b``, its ends more than ``gap`` on either side of the triangle's plane;
    None when there is none. Meshes are ``(vertices (k, 3), faces (m, 3))``."""
    (va, fa), (vb, fb) = a, b
    lo = np.maximum(va.min(axis=0), vb.min(axis=0)) - gap
    hi = np.minimum(va.max(axis=0), vb.max(axis=0)) + gap
    if np.any(lo > hi):
        return None  # their boxes are apart
    seg = va[_edges(fa)]  # (E, 2, 3)
    tri = vb[fb]  # (T, 3, 3)
    seg = seg[np.all((seg.max(axis=1) >= lo) & (seg.min(axis=1) <= hi), axis=1)]
    tri = tri[np.all((tri.max(axis=1) >= lo) & (tri.min(axis=1) <= hi), axis=1)]
    if not len(seg) or not len(tri):
        return None
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(normal, axis=1)
    keep = length > 0.0
    tri, normal = tri[keep], normal[keep] / length[keep, None]
    for start in range(0, len(seg), 256):  # (256, T) at a time
        s = seg[start : start + 256]
        d0 = np.einsum("tk,etk->et", normal, s[:, None, 0, :] - tri[None, :, 0, :])
        d1 = np.einsum("tk,etk->et", normal, s[:, None, 1, :] - tri[None, :, 0, :])
        e, t = np.nonzero(((d0 > gap) & (d1 < -gap)) | ((d0 < -gap) & (d1 > gap)))
        if not len(e):
            continue
        w = (d0[e, t] / (d0[e, t] - d1[e, t]))[:, None]
        p = s[e, 0] + (s[e, 1] - s[e, 0]) * w  # where each edge meets the plane
        corners = tri[t]
        inside = np.ones(len(e), dtype=bool)
        for i in range(3):  # on the inner side of each of the triangle's sides
            side = np.cross(corners[:, (i + 1) % 3] - corners[:, i], p - corners[:, i])
            inside &= np.einsum("nk,nk->n", side, normal[t]) >= 0.0
        if inside.any():
            return p[np.argmax(inside)]
    return None


def _hull(points: Array) -> Array:
    """The convex hull of ``points`` ``(k, 2)``, counter-clockwise (Andrew's chain)."""
    pts = sorted(map(tuple, np.round(points, 12)))
    if len(pts) < 3:
        return np.array(pts)

    def half(seq: list[tuple[float, float]]) -> list[tuple[float, float]]:
        out: list[tuple[float, float]] = []
        for p in seq:
            while (
                len(out) >= 2
                and (
                    (out[-1][0] - out[-2][0]) * (p[1] - out[-2][1])
                    - (out[-1][1] - out[-2][1]) * (p[0] - out[-2][0])
                )
                <= 0.0
            ):
                out.pop()
            out.append(p)
        return out

    return np.array(half(pts)[:-1] + half(pts[::-1])[:-1])


def check_plan(
    sheets: Sequence[tuple[str, Design, SitePlacement]], units: str, allow_touching: bool = False
) -> Crossing | None:
    """Refuse the first pair of sheets whose surfaces cross, before building
    them (unless ``allow_touching``, which returns the crossing instead).

    Raises:
        InvalidParameterError: parameter ``sheets``, naming both sheets,
            where they cross and how much their footprints overlap.
    """
    meshes = [placed_mesh(d, s) for _, d, s in sheets]
    for i in range(len(sheets)):
        for j in range(i + 1, len(sheets)):
            gap = max(margin(sheets[i][1]), margin(sheets[j][1]))
            # as deep one way as the other: each mesh passes through the other
            p = crossing(meshes[i], meshes[j], gap)
            if p is None or crossing(meshes[j], meshes[i], gap) is None:
                continue
            feet = [_hull(m[0][:, :2]) for m in (meshes[i], meshes[j])]
            found = Crossing(sheets[i][0], sheets[j][0], p, convex_overlap(*feet))
            if allow_touching:
                return found
            at = ", ".join(f"{v:.1f}" for v in p)
            raise InvalidParameterError(
                "sheets",
                f"{found.a!r} and {found.b!r} touch or overlap (distance 0 {units}: their "
                f"surfaces cross at ({at}) {units}, found before building them); their "
                f"footprints overlap by {found.footprint_overlap:.6g} {units}^2; move them "
                "apart or give --allow-touching for sheets meant to lean on each other",
            )
    return None
