"""The sheet as a solid of thickness t (exact model), for the STEP adapter.

Each side of the fold is the slab between the offsets ``s = s0`` and
``s = s1`` of the exact cone (:class:`onefold_cad.geometry.thick_sheet.SideMap`:
``F(theta, r, s) = A + r u(theta) + s n(theta)``; ``sheet_surface`` INSIDE
s in [-t, 0], OUTSIDE [0, t], MID [-t/2, t/2]). F is a straight line in r
for fixed theta and s, and in s for fixed theta and r, so the slab, cut into
sectors at the polygon's vertex directions, is bounded by ruled faces only:

* the two sheet faces, ruled between the relief hole's offset curve and the
  sheet edge's offset curve;
* the relief-hole wall and the cut edge's wall, ruled between the two faces'
  curves (perpendicular to the sheet, as a laser or plasma cut leaves them).

Those curves are B-splines interpolated through points of F with theta as
their parameter, refined until their deviation at the midpoints is below a
tolerance, so each ruling of a face joins the two curves' points of the same
theta: the rulings are exact, the curves carry the interpolation error.

The crease is mitred: past each crease half the slab continues as a flat
block in the crease ruling's tangent plane (C1 with the cone), deep enough
(:func:`~onefold_cad.geometry.thick_sheet.mitre_depth`) that cutting at the
fold's plane of symmetry y = 0 leaves the whole mitre; the -y side is the
mirror image of a slab built for the mirrored sheet. The volume is area x t
for MID (the mid-surface of a developable slab) up to the mitre, and within
about t / (2 x the surface's bend radius) otherwise.

Lengths are in the design unit; angles in radians.
"""

from __future__ import annotations

import copy
import math

import build123d as bd
import numpy as np
from numpy.typing import NDArray
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakePolygon,
    BRepBuilderAPI_MakeSolid,
    BRepBuilderAPI_MakeWire,
    BRepBuilderAPI_Sewing,
)
from OCP.BRepFill import BRepFill
from OCP.GC import GC_MakeArcOfCircle
from OCP.Geom import Geom_BSplineCurve
from OCP.gp import gp_Pnt
from OCP.ShapeFix import ShapeFix_Solid
from OCP.TopAbs import TopAbs_SHELL
from OCP.TopoDS import TopoDS, TopoDS_Face

from onefold_cad.errors import ExportError
from onefold_cad.export.brep import interpolate
from onefold_cad.export.measure import measure
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.thick_sheet import SideMap, mitre_depth

__all__ = ["thick_solid"]

Array = NDArray[np.float64]


def _curve_value(curve: Geom_BSplineCurve, t: Array) -> Array:
    out = np.empty((len(t), 3))
    for i, ti in enumerate(t):
        p = curve.Value(float(ti))
        out[i] = (p.X(), p.Y(), p.Z())
    return out


def _fit(fn, phi0: float, phi1: float, tol: float) -> Geom_BSplineCurve:
    """A B-spline through ``fn(phi)`` for phi in [phi0, phi1], parameter phi,
    doubled in density until the midpoints deviate by at most ``tol``."""
    n = 17
    while True:
        phi = np.linspace(phi0, phi1, n)
        curve = interpolate(fn(phi), phi, "an edge curve of the thick sheet")
        mid = 0.5 * (phi[:-1] + phi[1:])
        err = float(np.max(np.linalg.norm(_curve_value(curve, mid) - fn(mid), axis=1)))
        if err <= tol:
            return curve
        if n > 4000:
            raise ExportError(
                f"an edge curve of the thick sheet misses the tolerance {tol:.3g} "
                f"(by {err:.3g}) with {n} points"
            )
        n = 2 * n - 1


def _side_faces(
    side: SideMap,
    hole: float,
    s_range: tuple[float, float],
    span: tuple[float, float],
    tol: float,
) -> list[TopoDS_Face]:
    """Faces of the slab of one side over the flat angles ``span`` (radians,
    within [0, pi]): ruled faces per sector between vertex directions and the
    planar cross-sections at both ends."""
    s0, s1 = s_range
    t0, t1 = span
    reach = _inner_reach(side, hole, s_range)
    cand = np.concatenate([side.vertex_angles, [reach, side.total - reach]])
    # small sectors next to the creases keep the faces that meet y = 0 small
    cand = np.sort(cand[(cand > t0 + 1e-9) & (cand < t1 - 1e-9)])
    cand = cand[np.concatenate([[True], np.diff(cand) > 1e-9])] if len(cand) else cand
    breaks = np.concatenate([[t0], cand, [t1]])
    faces: list[TopoDS_Face] = []
    for a, b in zip(breaks[:-1], breaks[1:], strict=True):

        def inner(phi: Array, s: float) -> Array:
            return side.points(phi, np.full(len(phi), hole), s)

        def outer(phi: Array, s: float) -> Array:
            return side.points(phi, side.edge_radius(phi), s)

        edges = {}
        for name, fn in (("in", inner), ("out", outer)):
            for j, s in enumerate(s_range):
                curve = _fit(lambda p, fn=fn, s=s: fn(p, s), a, b, tol)
                edges[name, j] = BRepBuilderAPI_MakeEdge(curve).Edge()
        faces.append(BRepFill.Face_s(edges["in", 0], edges["out", 0]))
        faces.append(BRepFill.Face_s(edges["in", 1], edges["out", 1]))
        faces.append(BRepFill.Face_s(edges["in", 0], edges["in", 1]))
        faces.append(BRepFill.Face_s(edges["out", 0], edges["out", 1]))
    for phi in span:
        p = np.array([phi])
        r_out = side.edge_radius(p)
        corners = [
            side.points(p, np.array([hole]), s0)[0],
            side.points(p, r_out, s0)[0],
            side.points(p, r_out, s1)[0],
            side.points(p, np.array([hole]), s1)[0],
        ]
        faces.append(_polygon_face(corners))
    return faces


def _polygon_face(corners: list[Array]) -> TopoDS_Face:
    poly = BRepBuilderAPI_MakePolygon()
    for c in corners:
        poly.Add(gp_Pnt(*map(float, c)))
    poly.Close()
    return BRepBuilderAPI_MakeFace(poly.Wire(), True).Face()


def _mitre_block(
    side: SideMap, hole: float, s_range: tuple[float, float], end: int
) -> list[TopoDS_Face]:
    """Faces of the flat block that continues the slab past crease half ``end``
    (0: theta = 0, 1: theta = pi) in the crease ruling's tangent plane, as deep
    as :func:`mitre_depth` (a closed solid's faces).

    In that plane, x runs along the crease ruling and d away from the sheet;
    the block spans the hole's circle to the crease's length in x, [0, depth]
    in d and ``s_range`` along the normal.
    """
    depth = mitre_depth(side, s_range)
    theta = 0.0 if end == 0 else side.total
    u, e, n = side.crease_frame(end)
    away = -e if end == 0 else e  # past the crease, away from this side's sheet
    length = float(side.edge_radius(np.array([theta]))[0])
    if not depth < hole:
        raise ExportError("the relief hole is too small to mitre the thick sheet at the crease")
    x_in = math.sqrt(hole * hole - depth * depth)
    half = 0.5 * math.asin(depth / hole)  # the middle of the hole's arc

    def at(x: float, d: float, s: float) -> gp_Pnt:
        return gp_Pnt(*map(float, side.apex + x * u + d * away + s * n))

    faces = []
    arcs = []
    for s in s_range:
        arc = GC_MakeArcOfCircle(
            at(hole, 0.0, s),
            at(hole * math.cos(half), hole * math.sin(half), s),
            at(x_in, depth, s),
        ).Value()
        arcs.append(BRepBuilderAPI_MakeEdge(arc).Edge())
        lines = [
            BRepBuilderAPI_MakeEdge(at(hole, 0.0, s), at(length, 0.0, s)).Edge(),
            BRepBuilderAPI_MakeEdge(at(length, 0.0, s), at(length, depth, s)).Edge(),
            BRepBuilderAPI_MakeEdge(at(length, depth, s), at(x_in, depth, s)).Edge(),
        ]
        wire = BRepBuilderAPI_MakeWire()
        for edge in (*lines, arcs[-1]):
            wire.Add(edge)
        faces.append(BRepBuilderAPI_MakeFace(wire.Wire(), True).Face())
    s0, s1 = s_range
    faces.append(BRepFill.Face_s(arcs[0], arcs[1]))  # the hole's wall
    crease = ((hole, 0.0, length, 0.0), (length, 0.0, length, depth), (length, depth, x_in, depth))
    for x0, d0, x1, d1 in crease:
        corners = [at(x0, d0, s0), at(x1, d1, s0), at(x1, d1, s1), at(x0, d0, s1)]
        faces.append(_polygon_face([np.array([c.X(), c.Y(), c.Z()]) for c in corners]))
    return faces


def _inner_reach(side: SideMap, hole: float, s_range: tuple[float, float]) -> float:
    """How far inside the cone (radians from either crease) the slab still
    reaches below the plane y = 0: the concave side's mitre."""
    reach = 0.0
    for start, step in ((0.0, 1.0), (side.total, -1.0)):
        for k in range(1, 158):
            t = np.array([start + step * 0.01 * k])
            r_out = float(side.edge_radius(t)[0])
            y = min(side.points(t, np.array([r]), s)[0, 1] for r in (hole, r_out) for s in s_range)
            if y > 0.0:
                reach = max(reach, 0.01 * k)
                break
    return reach


def _solid_from_faces(faces: list[TopoDS_Face], tol: float) -> bd.Solid:
    sewing = BRepBuilderAPI_Sewing(tol)
    for f in faces:
        sewing.Add(f)
    sewing.Perform()
    shell = sewing.SewedShape()
    if shell.ShapeType() != TopAbs_SHELL:
        raise ExportError(f"sewing the thick sheet gave a {shell.ShapeType().name}")
    mk = BRepBuilderAPI_MakeSolid(TopoDS.Shell(shell))
    fix = ShapeFix_Solid(mk.Solid())
    fix.Perform()
    return bd.Solid(fix.Solid())


#: The fold's plane of symmetry, facing the upper (+y) side.
_SYMMETRY = bd.Plane(origin=(0.0, 0.0, 0.0), x_dir=(1.0, 0.0, 0.0), z_dir=(0.0, 1.0, 0.0))


def _upper_half(solid: bd.Solid) -> bd.Solid:
    """The part of ``solid`` on the +y side of the plane y = 0."""
    kept = solid.split(_SYMMETRY, keep=bd.Keep.TOP)
    solids = kept.solids() if kept is not None else []
    if len(solids) != 1:
        raise ExportError(f"cutting the thick sheet at the crease gave {len(solids)} solids")
    return solids[0]


def thick_solid(
    folded: FoldedSheet, hole_diameter: float, s_range: tuple[float, float], tol: float
) -> bd.Solid:
    """The sheet between the offsets ``s_range`` of the reference surface, with a
    relief hole of ``hole_diameter`` about the apex, mitred at the crease.

    Per side: the cone's slab, and for each crease half a flat block that
    continues it past the crease (:func:`_mitre_block`), all cut at the plane
    of symmetry y = 0; each block is also cut at the plane through the apex
    that bisects the two crease halves, keeping its own half's side (on sharp
    folds the crease halves are only 13-40 deg apart and an uncut block would
    reach through the other half's sheet next to the apex). The six pieces
    are fused (the -y side built mirrored, then mirrored back).
    """
    pieces = []
    hole = 0.5 * hole_diameter
    for lower in (False, True):
        side = SideMap(folded, lower=lower)
        faces = _side_faces(side, hole, s_range, (0.0, side.total), tol)
        kept = [_upper_half(_solid_from_faces(faces, 10 * tol))]
        u0, u1 = side.crease_frame(0)[0], side.crease_frame(1)[0]
        m = (u0 - u1) / np.linalg.norm(u0 - u1)  # normal of the crease halves' bisector
        for end, normal in ((0, m), (1, -m)):
            block = _solid_from_faces(_mitre_block(side, hole, s_range, end), 10 * tol)
            for plane in (_SYMMETRY, _plane(side.apex, normal)):
                block = _keep_top(block, plane) if block is not None else None
            if block is not None:  # none when the convex side has no material
                kept.append(block)
        pieces += [k.mirror(bd.Plane.XZ) for k in kept] if lower else kept
    return _union(pieces, 10 * tol)


def _plane(origin: Array, normal: Array) -> bd.Plane:
    return bd.Plane(origin=tuple(map(float, origin)), z_dir=tuple(map(float, normal)))


def _keep_top(solid: bd.Solid, plane: bd.Plane) -> bd.Solid | None:
    """The part of ``solid`` on the side of ``plane`` its normal points to,
    or None when nothing is there."""
    kept = solid.split(plane, keep=bd.Keep.TOP)
    solids = kept.solids() if kept is not None else []
    if len(solids) > 1:
        raise ExportError(f"cutting a mitre of the thick sheet gave {len(solids)} solids")
    return solids[0] if solids else None


def _union(pieces: list[bd.Solid], tol: float) -> bd.Solid:
    """One solid of the pieces: OCC's fuse, plain, with a fuzzy tolerance, or
    side by side. Each can fail on some inputs, so the first whose result is
    one valid solid holding the pieces' total volume is kept (they only touch:
    across y = 0, at the creases' cross-sections, and the two mitres of a side
    at the plane that bisects the crease halves)."""
    total = sum(measure(p, "volume") for p in pieces)
    attempts = (
        lambda ps: ps[0].fuse(*ps[1:]),
        lambda ps: ps[0].fuse(*ps[1:], tol=tol),
        lambda ps: (
            ps[0].fuse(*ps[1 : len(ps) // 2]).fuse(ps[len(ps) // 2].fuse(*ps[len(ps) // 2 + 1 :]))
        ),
    )
    found = "no result"
    for attempt in attempts:
        try:  # on deep copies: a boolean may change its arguments' tolerances
            solids = attempt([copy.deepcopy(p) for p in pieces]).clean().solids()
        except Exception as err:  # OCC's StdFail_NotDone and friends
            found = err.__class__.__name__
            continue
        if len(solids) != 1:
            found = f"{len(solids)} solids"
            continue
        volume = measure(solids[0], "volume")
        if solids[0].is_valid and abs(volume - total) <= 1e-5 * total:
            return solids[0]
        found = f"valid {solids[0].is_valid}, volume {volume:.6g} of {total:.6g}"
    raise ExportError(f"fusing the pieces of the thick sheet failed ({found})")
