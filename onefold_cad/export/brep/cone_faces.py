"""The exact model's B-rep faces (OCP): one ``ruled`` face per flat sector
between consecutive rulings of a side, a patch of the exact cone
(:mod:`.cone_patch`) trimmed by the sheet's edge mapped onto the cone, given
as a parameter-space curve (pcurve) interpolated to a stated tolerance
(:mod:`.bspline_fit`), so every point of the face lies on the cone to machine
precision; only the position of the boundary curve along the cone carries the
interpolation error. The faces form one shell with shared topology, for the
build123d adapter in :mod:`.part`.

Lengths are in the design unit; angles in radians.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import partial

import numpy as np
from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Curve2d, BRepAdaptor_Surface
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeVertex,
)
from OCP.BRepLib import BRepLib
from OCP.collections import (
    Array1_double,
    Array1_int,
    HArray1_gp_Pnt2d,
)
from OCP.Geom import (
    Geom_Line,
)
from OCP.Geom2d import Geom2d_BSplineCurve, Geom2d_Line
from OCP.GeomAbs import GeomAbs_C2
from OCP.gp import gp_Dir, gp_Dir2d, gp_Pnt, gp_Pnt2d, gp_Vec
from OCP.TopAbs import TopAbs_FORWARD, TopAbs_REVERSED
from OCP.TopExp import TopExp
from OCP.TopoDS import (
    TopoDS_Edge,
    TopoDS_Face,
    TopoDS_Shell,
    TopoDS_Vertex,
    TopoDS_Wire,
)

from onefold_cad.errors import ExportError
from onefold_cad.export.brep.bspline_fit import (
    DENSE,
    MAX_NODES,
    arc_length_nodes,
    interpolate,
    probe_points,
    refine,
)
from onefold_cad.export.brep.cone_patch import ConePatch, cone_patch, pnt, ruling_sectors
from onefold_cad.export.brep.fan_faces import PRECISION
from onefold_cad.geometry.cone.cone import ExactCone
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import Array

__all__ = ["FoldedBackError", "ruled_shell"]


def _fit_pcurve(
    patch: ConePatch,
    u0: float,
    u1: float,
    radius_at,
    tol: float,
    end_radii: tuple[float, float] | None = None,
) -> tuple[Geom2d_BSplineCurve, float]:
    """A pcurve through the points at distance ``radius_at(phi)`` from A, for
    u in [u0, u1]: interpolated at nodes spread evenly along the curve and at
    the surface's knots inside [u0, u1] (where the rational arc's
    parameterisation is only C1), an interval split at its worst
    :data:`PROBES` point while the deviation there, measured along the
    ruling, exceeds ``tol`` (length), up to :data:`MAX_NODES` nodes. Returns
    ``(Geom2d curve, deviation reached)`` (the caller decides whether that is
    good enough). ``end_radii``: the curve's distances from A at u0 and u1
    where they are known exactly (the ruling edges' ends): the curve starts
    and ends there, not at ``radius_at`` of the arc parameter read back from
    the surface, which may miss by far more than the kernel's precision
    where the curve runs nearly along a ruling (a sheet edge passing close
    by H: d r / d phi is then r / the angle between them)."""
    dense = u0 + (u1 - u0) * DENSE
    dense[-1] = u1
    phi = patch.phi_of_u(dense)
    ray = patch.arc(phi) - patch.apex
    ray /= np.linalg.norm(ray, axis=1)[:, None]
    t, at_length, length_at = arc_length_nodes(
        patch.apex + radius_at(phi)[:, None] * ray, dense, 17
    )
    surf = patch.surface
    knots = np.array([surf.UKnot(i) for i in range(2, surf.NbUKnots())])
    knots = knots[(knots > u0) & (knots < u1)]
    if len(knots):
        span = float(length_at(np.array([u1]))[0])
        gap = np.min(np.abs(length_at(t)[:, None] - length_at(knots)[None, :]), axis=1)
        keep = (gap > 1e-3 * span / 16.0) | (t == u0) | (t == u1)
        t = np.unique(np.concatenate([t[keep], knots]))
    while True:
        ph = patch.phi_of_u(t)
        r = radius_at(ph)
        if end_radii is not None:
            r[0], r[-1] = end_radii
        uv = np.stack([t, patch.v_of(ph, r)], axis=1)
        curve = interpolate(uv, t, "a boundary curve on the cone")
        probe = probe_points(t, at_length, length_at)
        flat = probe.ravel()
        got = np.array([[curve.Value(float(x)).X(), curve.Value(float(x)).Y()] for x in flat])
        pm = patch.phi_of_u(got[:, 0])
        dist = patch.scale * np.linalg.norm(patch.arc(pm) - patch.apex, axis=1)
        err = np.abs(got[:, 1] - patch.v_of(pm, radius_at(pm))) * dist
        new, worst = refine(probe, err.reshape(probe.shape), tol)
        if not len(new) or len(t) + len(new) > MAX_NODES:
            return curve, worst
        t = np.sort(np.concatenate([t, new]))


def _edge_line(edge_p0: Array, edge_p1: Array, psi: Array) -> Array:
    """Distance from H along polar angles ``psi`` to the line through a flat edge."""
    e = edge_p1 - edge_p0
    d = np.stack([np.cos(psi), np.sin(psi)], axis=-1)
    return (edge_p0[0] * e[1] - edge_p0[1] * e[0]) / (d[:, 0] * e[1] - d[:, 1] * e[0])


def _outer_radius(
    cone: ExactCone, pa: Array, pb: Array, span: tuple[float, float], sgn: float, phi: Array
) -> Array:
    """Distance from A to the mapped flat edge pa-pb on the rulings ``phi``."""
    th = np.clip(cone.theta_of_phi(phi), span[0], span[1])
    return _edge_line(pa, pb, sgn * th)


def ruled_shell(folded: FoldedSheet, hole_radius: float, tol: float) -> tuple[TopoDS_Shell, float]:
    """The exact-cone faces, one per sheet edge per side, as one shell (top
    normals outward), built with shared topology: each ruling between two
    faces is one straight edge (the crease rulings shared by both sides),
    all faces meet at one apex vertex when there is no hole, so no sewing
    is needed.

    Args:
        folded: an exact-model fold.
        hole_radius: relief hole radius about the apex (0 = none; length).
        tol: allowed deviation of the boundary curves along the cone (length).

    Returns:
        ``(shell, deviation)``: the shell and the largest deviation its
        boundary curves reached (compare it with ``tol``: a curve that needs
        more than :data:`MAX_NODES` nodes stops short of it).
    """
    cone = folded.solution.surface
    if not isinstance(cone, ExactCone):
        raise ExportError("ruled faces need the exact model's cone")
    sheet, apex = folded.sheet, folded.apex
    b = BRep_Builder()
    shell = TopoDS_Shell()
    b.MakeShell(shell)
    apex_v = _vertex(apex) if hole_radius <= 0.0 else None
    crease: dict[int, TopoDS_Edge] = {}  # ruling index (0 or last) -> edge, shared by the sides
    worst = 0.0
    for side, angles in enumerate(folded.ruling_angles):
        thetas = ruling_sectors(angles)
        sgn = 1.0 if side == 0 else -1.0
        phis = cone.phi_of_theta(thetas)
        ends = sheet.ray_lengths(sgn * thetas)
        mirror = np.array([1.0, sgn, 1.0])
        rays = cone.directions_at(thetas) * mirror
        last = len(thetas) - 1
        rulings: list[TopoDS_Edge] = []
        for k in range(len(thetas)):
            key = 0 if k == 0 else (1 if k == last else None)
            if key is not None and key in crease:
                rulings.append(crease[key])
                continue
            r0 = hole_radius
            v_in = apex_v if apex_v is not None else _vertex(apex + r0 * rays[k])
            v_out = _vertex(apex + ends[k] * rays[k])
            line = Geom_Line(pnt(apex), gp_Dir(*map(float, rays[k])))
            _reach(v_in, line.Value(float(r0)), tol)
            _reach(v_out, line.Value(float(ends[k])), tol)
            edge = BRepBuilderAPI_MakeEdge(line, v_in, v_out, float(r0), float(ends[k])).Edge()
            rulings.append(edge)
            if key is not None:
                crease[key] = edge
        for k in range(last):
            ta, tb = thetas[k], thetas[k + 1]
            pa = np.array([math.cos(ta), sgn * math.sin(ta)]) * ends[k]
            pb = np.array([math.cos(tb), sgn * math.sin(tb)]) * ends[k + 1]
            patch = cone_patch(cone, phis[k], phis[k + 1], side == 1, max(ends[k], ends[k + 1]))
            outer = partial(_outer_radius, cone, pa, pb, (ta, tb), sgn)
            face, err = _patch_face(
                patch, outer, hole_radius, tol, rulings[k], rulings[k + 1], (ends[k], ends[k + 1])
            )
            tm = 0.5 * (ta + tb)
            top = folded.normals(np.array([[math.cos(tm), sgn * math.sin(tm)]]))[0]
            worst = max(worst, err)
            b.Add(shell, _orient(face, top))
    BRepLib.SameParameter_s(shell, 1e-3 * tol, True)
    return shell, worst


def _vertex(p: Array) -> TopoDS_Vertex:
    return BRepBuilderAPI_MakeVertex(pnt(p)).Vertex()


def _ruling_pcurve(patch: ConePatch, u: float, r0: float, r1: float) -> Geom2d_BSplineCurve:
    """The ruling at surface parameter u as a curve on the patch whose
    parameter is the distance from A (as on the ruling's straight edge)."""
    phi = patch.phi_of_u(np.array([u]))
    v0, v1 = (float(patch.v_of(phi, np.array([r]))[0]) for r in (r0, r1))
    poles = HArray1_gp_Pnt2d(1, 2)
    poles.SetValue(1, gp_Pnt2d(u, v0))
    poles.SetValue(2, gp_Pnt2d(u, v1))
    knots, mults = Array1_double(1, 2), Array1_int(1, 2)
    knots.SetValue(1, float(r0))
    knots.SetValue(2, float(r1))
    mults.SetValue(1, 2)
    mults.SetValue(2, 2)
    return Geom2d_BSplineCurve(poles.Array1(), knots, mults, 1)


def _patch_face(
    patch: ConePatch,
    outer: Callable[[Array], Array],
    hole_radius: float,
    tol: float,
    first: TopoDS_Edge,
    second: TopoDS_Edge,
    ends: tuple[float, float],
) -> tuple[TopoDS_Face, float]:
    """One trimmed cone face between the ruling edges ``first`` (at u0) and
    ``second`` (at u1), which it shares with its neighbours: hole arc (or the
    apex), ruling, outer edge, ruling."""
    b = BRep_Builder()
    surf = patch.surface
    u0, u1 = patch.u0, patch.u1
    c_out, err = _fit_pcurve(patch, u0, u1, outer, tol, ends)
    if hole_radius > 0.0:
        c_in, err_in = _fit_pcurve(patch, u0, u1, lambda p: np.full_like(p, hole_radius), tol)
        err = max(err, err_in)
    face = TopoDS_Face()
    b.MakeFace(face, surf, 1e-7)
    a_in, a_out = TopExp.FirstVertex_s(first), TopExp.LastVertex_s(first)
    b_in, b_out = TopExp.FirstVertex_s(second), TopExp.LastVertex_s(second)
    for name, ends_v in (("the sheet's edge", (a_out, b_out)), ("the relief hole", (a_in, b_in))):
        gap = BRep_Tool.Pnt_s(ends_v[0]).Distance(BRep_Tool.Pnt_s(ends_v[1]))
        if (name == "the sheet's edge" or hole_radius > 0.0) and gap <= PRECISION:
            raise FoldedBackError(
                f"{name} between two rulings {patch.phi1 - patch.phi0:.3g} rad apart on the "
                f"frame lands {gap:.3g} long on the cone, no more than the CAD kernel's "
                f"precision ({PRECISION:g}; it cannot make an edge that short): the cone "
                "folds back onto itself there"
            )
    for curve, ends_v in (
        (c_out, (a_out, b_out)),
        *(((c_in, (a_in, b_in)),) if hole_radius > 0.0 else ()),
    ):
        for v, u in zip(ends_v, (u0, u1), strict=True):
            q = curve.Value(u)
            _reach(v, surf.Value(q.X(), q.Y()), tol)
    if hole_radius > 0.0:
        low = BRepBuilderAPI_MakeEdge(c_in, surf, a_in, b_in, u0, u1).Edge()
    else:
        low = TopoDS_Edge()
        b.MakeEdge(low)
        b.Degenerated(low, True)
        b.Add(low, a_in.Oriented(TopAbs_FORWARD))
        b.Add(low, a_in.Oriented(TopAbs_REVERSED))
        b.UpdateEdge(low, Geom2d_Line(gp_Pnt2d(0.0, 0.0), gp_Dir2d(1.0, 0.0)), face, 1e-7)
        b.Range(low, face, u0, u1)
    high = BRepBuilderAPI_MakeEdge(c_out, surf, a_out, b_out, u0, u1).Edge()
    for edge, u, r_out in ((first, u0, ends[0]), (second, u1, ends[1])):
        b.UpdateEdge(edge, _ruling_pcurve(patch, u, hole_radius, r_out), face, 1e-7)
        b.Range(edge, face, float(hole_radius), float(r_out))
    wire = TopoDS_Wire()
    b.MakeWire(wire)
    for e in (low, second, high.Reversed(), first.Reversed()):
        b.Add(wire, e)
    b.Add(face, wire)
    _curves_3d(face, [high, low] if hole_radius > 0.0 else [high], tol)
    return face, err


#: Samples per edge at which a 3D curve is checked against its pcurve.
CURVE_SAMPLES = 65


def _curve_gap(edge: TopoDS_Edge, face: TopoDS_Face) -> float:
    """Largest distance between ``edge``'s 3D curve and its pcurve on ``face``
    mapped onto the surface, at :data:`CURVE_SAMPLES` common parameters."""
    c3 = BRepAdaptor_Curve(edge)
    c2 = BRepAdaptor_Curve2d(edge, face)
    surf = BRepAdaptor_Surface(face, False)
    worst = 0.0
    for t in np.linspace(c3.FirstParameter(), c3.LastParameter(), CURVE_SAMPLES):
        q = c2.Value(float(t))
        worst = max(worst, c3.Value(float(t)).Distance(surf.Value(q.X(), q.Y())))
    return worst


def _curves_3d(face: TopoDS_Face, edges: list[TopoDS_Edge], tol: float) -> float:
    """Build the 3D curves of ``edges`` (boundary curves of ``face`` given as
    pcurves) and return their largest measured distance from the pcurves.

    The 3D curves are fitted to a tenth of the kernel's precision where the
    coordinates allow it (``max(min(1e-3 x tol, PRECISION / 10), 2^-44 x
    the face's size)``), so that the edges keep the precision as their
    tolerance: a STEP file holds no tolerance per edge, and a reader that
    takes its global one (1e-7) finds an edge fitted only to ``1e-3 x tol``
    (1e-6 on a sheet of 1e4) invalid. The kernel's fit can miss its
    target (and then returns a wrong curve); each fit is measured
    (:func:`_curve_gap`) and loosened tenfold until it is within twice its
    target, up to ``1e-3 x tol``.

    Raises:
        ExportError: no fit within ``1e-3 x tol``.
    """
    box = Bnd_Box()
    BRepBndLib.Add_s(face, box)
    lo, hi = box.CornerMin(), box.CornerMax()
    extent = max(abs(lo.X()), abs(lo.Y()), abs(lo.Z()), abs(hi.X()), abs(hi.Y()), abs(hi.Z()))
    loose = 1e-3 * tol
    target = max(min(loose, 0.1 * PRECISION), 2.0**-40 * extent)
    while True:
        for e in edges:
            BRep_Builder().UpdateEdge(e, None, BRep_Tool.Tolerance_s(e))  # drop the last fit
            BRepLib.BuildCurve3d_s(e, target, GeomAbs_C2, 8, 2000)
        gap = max(_curve_gap(e, face) for e in edges)
        if gap <= 2.0 * target:
            return gap
        if target >= loose:
            raise ExportError(
                f"a boundary curve's 3D curve could not be fitted within {loose:.3g} "
                f"(1e-3 x the boundary tolerance) of the cone; the closest was {gap:.3g} off"
            )
        target = min(10.0 * target, loose)


class FoldedBackError(ExportError):
    """A face's boundary edge whose two ends land within the kernel's
    precision of each other although they are apart on the sheet: the cone
    folds back onto itself (alpha and beta both near 90 deg, where the apex
    lies in the frame's plane and the rulings turn back)."""


def _reach(vertex: TopoDS_Vertex, point: gp_Pnt, limit: float) -> None:
    """Grow ``vertex``'s tolerance to reach ``point`` (the end of a curve
    that meets it), when that is more than the tolerance it has and at most
    ``limit`` (length, the boundary curves' stated tolerance). The vertex
    and the curve's end are two computations of one point; they agree to a
    few units in the last place of the coordinates, which on a part of 1e8
    or more exceeds the kernel's precision (1e-7): the vertex then carries
    the gap as its tolerance, as the kernel's tolerance model has it.

    Raises:
        ExportError: the gap is above ``limit``.
    """
    gap = BRep_Tool.Pnt_s(vertex).Distance(point)
    if gap <= BRep_Tool.Tolerance_s(vertex):
        return
    if gap > limit:
        raise ExportError(
            f"a boundary curve ends {gap:.3g} from its vertex, more than the "
            f"boundary tolerance {limit:.3g}"
        )
    BRep_Builder().UpdateVertex(vertex, 1.01 * gap)


def _orient(face: TopoDS_Face, top: Array) -> TopoDS_Face:
    """Reverse ``face`` in place if its normal at its centre opposes ``top`` ``(3,)``."""
    ad = BRepAdaptor_Surface(face)
    u = 0.5 * (ad.FirstUParameter() + ad.LastUParameter())
    v = 0.5 * (ad.FirstVParameter() + ad.LastVParameter())
    pnt, du, dv = gp_Pnt(), gp_Vec(), gp_Vec()
    ad.D1(u, v, pnt, du, dv)
    n = du.Crossed(dv)
    nv = np.array([n.X(), n.Y(), n.Z()])
    if face.Orientation() == TopAbs_REVERSED:
        nv = -nv
    if float(np.dot(nv, top)) < 0.0:
        face.Reverse()
    return face
