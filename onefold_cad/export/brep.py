"""B-rep faces of the folded surface (OCP), for the build123d adapter in :mod:`.step`.

Two kinds of face, both one per flat sector between consecutive rulings of a side:

* ``ruled`` (exact model): a patch of the exact cone from the apex A over the
  circular frame arc. The cone is held exactly as a rational B-spline surface
  ``S(u, v) = A + v * L * (C(u) - A)`` (degree 2 rational in u along the arc,
  degree 1 in v along the rulings; C the arc as rational quadratic spans). The
  patch is trimmed by the sheet's edge mapped onto the cone, given as a
  parameter-space curve (pcurve) interpolated to a stated tolerance, so every
  point of the face lies on the cone to machine precision; only the position
  of the boundary curve along the cone carries the interpolation error.
* ``fan`` (paper model): the paper's planar triangles; with a relief hole the
  hole's boundary in each triangle is an exact circular arc about A.

Lengths are in the design unit; angles in radians.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

import numpy as np
from numpy.typing import NDArray
from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Curve2d, BRepAdaptor_Surface
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakeVertex,
)
from OCP.BRepLib import BRepLib
from OCP.collections import (
    Array1_double,
    Array1_int,
    Array2_double,
    Array2_gp_Pnt,
    HArray1_double,
    HArray1_gp_Pnt,
    HArray1_gp_Pnt2d,
)
from OCP.Convert import Convert_ParameterisationType
from OCP.GC import GC_MakeArcOfCircle
from OCP.Geom import (
    Geom_BSplineCurve,
    Geom_BSplineSurface,
    Geom_Circle,
    Geom_Line,
    Geom_TrimmedCurve,
)
from OCP.Geom2d import Geom2d_BSplineCurve, Geom2d_Line
from OCP.Geom2dAPI import Geom2dAPI_Interpolate
from OCP.GeomAbs import GeomAbs_C2
from OCP.GeomAPI import GeomAPI_Interpolate
from OCP.GeomConvert import GeomConvert
from OCP.gp import gp_Ax2, gp_Circ, gp_Dir, gp_Dir2d, gp_Pln, gp_Pnt, gp_Pnt2d, gp_Vec
from OCP.TopAbs import TopAbs_FORWARD, TopAbs_REVERSED
from OCP.TopExp import TopExp
from OCP.TopoDS import (
    TopoDS,
    TopoDS_Edge,
    TopoDS_Face,
    TopoDS_Shell,
    TopoDS_Vertex,
    TopoDS_Wire,
)

from onefold_cad.errors import ExportError
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.folding import FoldedSheet

__all__ = [
    "ConePatch",
    "FoldedBackError",
    "cone_patch",
    "ruled_shell",
    "fan_shell",
    "interpolate",
    "arc_length_nodes",
    "probe_points",
    "DENSE",
    "MAX_NODES",
    "PROBES",
]

Convert_RationalC1 = Convert_ParameterisationType.Convert_RationalC1
Array = NDArray[np.float64]


def _pnt(p: Array) -> gp_Pnt:
    return gp_Pnt(float(p[0]), float(p[1]), float(p[2]))


def _xyz(p: gp_Pnt) -> tuple[float, float, float]:
    return p.X(), p.Y(), p.Z()


@dataclass(frozen=True)
class ConePatch:
    """The cone from the apex over an arc of the frame circle, held exactly.

    Attributes:
        surface: ``S(u, v) = A + v * scale * (C(u) - A)`` with C the arc as an
            exact rational C1 B-spline (OCC's ``Convert_RationalC1``); u in
            [u0, u1], v in [0, 1].
        u0, u1: the u range.
        apex: ``(3,)`` A.
        centre, ex, ey: ``(3,)`` the circle's centre and in-plane unit axes:
            ``C(phi) = centre + R (cos(phi) ex + sin(phi) ey)``.
        radius: R.
        scale: the ruling length factor L (v = 1 is L times the arc's distance).
        phi0, phi1: the arc parameters at u0 and u1 (radians).
    """

    surface: Geom_BSplineSurface
    u0: float
    u1: float
    apex: Array
    centre: Array
    ex: Array
    ey: Array
    radius: float
    scale: float
    phi0: float
    phi1: float

    def arc(self, phi: Array) -> Array:
        """Arc points ``(k, 3)`` at arc parameters ``phi``."""
        p = np.asarray(phi, dtype=float)[:, None]
        return self.centre + self.radius * (np.cos(p) * self.ex + np.sin(p) * self.ey)

    def phi_of_u(self, u: Array) -> Array:
        """Arc parameters (radians) of the rulings at surface parameters ``u``."""
        pts = np.array([_xyz(self.surface.Value(float(t), 1.0)) for t in np.atleast_1d(u)])
        d = (pts - self.apex) / self.scale + self.apex - self.centre
        phi = np.arctan2(d @ self.ey, d @ self.ex)
        # the branch next to the linear map u -> phi (an arc may span more
        # than pi, where one atan2 branch cannot hold it)
        t = (np.atleast_1d(np.asarray(u, dtype=float)) - self.u0) / (self.u1 - self.u0)
        near = self.phi0 + t * (self.phi1 - self.phi0)
        return phi + 2.0 * np.pi * np.round((near - phi) / (2.0 * np.pi))

    def v_of(self, phi: Array, r: Array) -> Array:
        """Surface parameter v of the point at distance ``r`` from A on ruling ``phi``."""
        d = np.linalg.norm(self.arc(phi) - self.apex, axis=1)
        return np.asarray(r, dtype=float) / (self.scale * d)


def cone_patch(cone: ExactCone, phi0: float, phi1: float, mirror: bool, reach: float) -> ConePatch:
    """The exact cone over the arc [phi0, phi1] (radians), long enough to reach ``reach``.

    Args:
        cone: the solved exact cone (upper side).
        phi0, phi1: arc parameter range, phi0 < phi1.
        mirror: the lower side (mirror image in the xz-plane).
        reach: the largest distance from A the patch must cover (length).
    """
    fr = cone.frame
    a, b = math.radians(fr.alpha), math.radians(fr.beta)
    s = -1.0 if mirror else 1.0
    centre = np.array(
        [-fr.h_c, s * fr.radius * math.sin(a) * math.cos(b), fr.radius * math.sin(a) * math.sin(b)]
    )
    ex = np.array([1.0, 0.0, 0.0])
    ey = np.array([0.0, s * math.cos(b), math.sin(b)])
    apex = cone.apex
    circle = Geom_Circle(gp_Ax2(_pnt(centre), gp_Dir(*np.cross(ex, ey)), gp_Dir(*ex)), fr.radius)
    arc = GeomConvert.CurveToBSplineCurve_s(
        Geom_TrimmedCurve(circle, float(phi0), float(phi1)), Convert_RationalC1
    )
    c0, c1 = arc.FirstParameter(), arc.LastParameter()
    probe = ConePatch(None, c0, c1, apex, centre, ex, ey, fr.radius, 1.0, phi0, phi1)  # type: ignore[arg-type]
    dmin = float(np.min(np.linalg.norm(probe.arc(np.linspace(phi0, phi1, 64)) - apex, axis=1)))
    scale = 1.02 * reach / dmin
    n = arc.NbPoles()
    poles = Array2_gp_Pnt(1, n, 1, 2)
    weights = Array2_double(1, n, 1, 2)
    for i in range(1, n + 1):
        p = np.array(_xyz(arc.Pole(i)))
        w = arc.Weight(i)
        poles.SetValue(i, 1, _pnt(apex))
        poles.SetValue(i, 2, _pnt(apex + scale * (p - apex)))
        weights.SetValue(i, 1, w)
        weights.SetValue(i, 2, w)
    nk = arc.NbKnots()
    uk, um = Array1_double(1, nk), Array1_int(1, nk)
    for i in range(1, nk + 1):
        uk.SetValue(i, arc.Knot(i))
        um.SetValue(i, arc.Multiplicity(i))
    vk, vm = Array1_double(1, 2), Array1_int(1, 2)
    for i in range(2):
        vk.SetValue(i + 1, float(i))
        vm.SetValue(i + 1, 2)
    surface = Geom_BSplineSurface(poles, weights, uk, vk, um, vm, arc.Degree(), 1)
    return ConePatch(surface, c0, c1, apex, centre, ex, ey, fr.radius, scale, phi0, phi1)


def interpolate(points: Array, params: Array, what: str) -> Geom_BSplineCurve | Geom2d_BSplineCurve:
    """The B-spline through ``points`` ``(k, 2)`` (a pcurve) or ``(k, 3)`` at the
    parameters ``params`` ``(k,)``, by OCC's interpolation.

    Raises:
        ExportError: the interpolation failed (``what`` names the curve).
    """
    pts = np.asarray(points, dtype=float)
    plane = pts.shape[1] == 2
    arr = (HArray1_gp_Pnt2d if plane else HArray1_gp_Pnt)(1, len(pts))
    par = HArray1_double(1, len(pts))
    point = gp_Pnt2d if plane else gp_Pnt
    for i, (p, t) in enumerate(zip(pts, params, strict=True)):
        arr.SetValue(i + 1, point(*map(float, p)))
        par.SetValue(i + 1, float(t))
    interp = (Geom2dAPI_Interpolate if plane else GeomAPI_Interpolate)(arr, par, False, 1e-12)
    interp.Perform()
    if not interp.IsDone():
        raise ExportError(f"could not interpolate {what}")
    return interp.Curve()


#: Relative parameters of the dense sample that places a curve's nodes:
#: uniform, and graded towards both ends.
DENSE = np.unique(
    np.concatenate(
        [np.linspace(0.0, 1.0, 257), np.geomspace(1e-9, 0.1, 64), 1.0 - np.geomspace(1e-9, 0.1, 64)]
    )
)
#: The most nodes a fitted curve may have.
MAX_NODES = 4000


#: Where a fitted curve is checked between two neighbouring nodes, as fractions
#: of the interval's length: at its quarters, not only its middle (a curve
#: whose parameterisation has a kink, as the rational arc's C1 knots give the
#: cone's pcurves, can meet the tolerance at an interval's middle and miss it
#: beside it).
PROBES = np.array([0.25, 0.5, 0.75])


def probe_points(t: Array, at_length, length_at) -> Array:
    """``(len(t) - 1, len(PROBES))`` parameters inside each interval of the
    nodes ``t`` at the :data:`PROBES` fractions of its length (of its
    parameter range where the length cannot place them inside)."""
    lo, hi = length_at(t[:-1]), length_at(t[1:])
    probe = at_length(lo[:, None] + (hi - lo)[:, None] * PROBES)
    even = t[:-1, None] + (t[1:] - t[:-1])[:, None] * PROBES
    inside = (probe > t[:-1, None]) & (probe < t[1:, None])
    return np.where(inside, probe, even)


def refine(probe: Array, err: Array, tol: float) -> tuple[Array, float]:
    """The nodes to add (the worst probe of each interval that misses ``tol``)
    and the largest deviation, from ``err`` at ``probe`` (both ``(n, p)``)."""
    worst = np.argmax(err, axis=1)
    rows = np.arange(len(err))
    bad = err[rows, worst] > tol
    return probe[rows[bad], worst[bad]], float(np.max(err))


def arc_length_nodes(points: Array, params: Array, count: int) -> tuple[Array, object, object]:
    """``count`` parameters evenly spread along the polyline ``points`` ``(k, 3)``
    sampled at ``params`` ``(k,)``, and the maps length -> parameter and
    parameter -> length."""
    cum = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])
    length = float(cum[-1])

    def at_length(x: Array) -> Array:
        return np.interp(x, cum, params)

    def length_at(t: Array) -> Array:
        return np.interp(t, params, cum)

    t = (
        at_length(np.linspace(0.0, length, count))
        if length > 0.0
        else np.linspace(params[0], params[-1], count)
    )
    t[0], t[-1] = params[0], params[-1]
    return t, at_length, length_at


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
        thetas = _sectors(angles)
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
            line = Geom_Line(_pnt(apex), gp_Dir(*map(float, rays[k])))
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
    return BRepBuilderAPI_MakeVertex(_pnt(p)).Vertex()


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


def _sectors(thetas: Array) -> Array:
    """The ruling angles without near-duplicates (< 1e-12 rad apart), ends kept."""
    keep = np.concatenate([np.diff(thetas) > 1e-12, [True]])
    keep[0] = True
    out = thetas[keep]
    out[-1] = thetas[-1]
    return out


#: OCC's precision (Precision::Confusion): points closer are one point.
PRECISION = 1e-7
#: Ruling ends closer than 3 x NEAR (length) are one ruling (OCC cannot make
#: an edge much shorter than 10 x its precision).
NEAR = 1e-6


def _distinct(points: Array, gap: float) -> NDArray[np.bool_]:
    """Which of the rulings to keep so that no two kept neighbours' points
    ``(n, 3)`` lie within ``gap`` (the first and last, on the crease, always
    kept): a ruling closer than that to the last one kept is left out, and
    the two triangles beside it become one."""
    keep = np.zeros(len(points), dtype=bool)
    keep[0] = True
    last = 0
    for k in range(1, len(points) - 1):
        if np.linalg.norm(points[k] - points[last]) > gap:
            keep[k], last = True, k
    if len(points) > 2 and np.linalg.norm(points[-1] - points[last]) <= gap and last > 0:
        keep[last] = False
    keep[-1] = True
    return keep


def fan_shell(
    folded: FoldedSheet, hole_radius: float, check: Callable[[], None] | None = None
) -> TopoDS_Shell:
    """The paper model's planar triangles (with an exact arc of the relief
    hole) as one shell, built with shared topology: one vertex per ruling end
    (and one apex), one edge per ruling shared by the triangles on either
    side of it (the two crease rulings by both sides), so no sewing is
    needed and the work grows linearly with the number of triangles. Face
    normals are the top side's. ``check`` is called every 256 triangles (a
    time budget that raises)."""
    b = BRep_Builder()
    apex = folded.apex
    tol = 1e-7

    def vertex(p: Array, tolerance: float = tol) -> TopoDS_Vertex:
        v = TopoDS_Vertex()
        b.MakeVertex(v, _pnt(p), tolerance)
        return v

    def line(v0: TopoDS_Vertex, v1: TopoDS_Vertex) -> TopoDS_Edge:
        return BRepBuilderAPI_MakeEdge(v0, v1).Edge()

    sides = []
    for side, angles in enumerate(folded.ruling_angles):
        thetas = _sectors(angles)
        sgn = 1.0 if side == 0 else -1.0
        dirs = np.stack([np.cos(thetas), sgn * np.sin(thetas)], axis=-1)
        rho = folded.sheet.ray_lengths(sgn * thetas)
        outer = folded.map_points(dirs * rho[:, None])
        unit = folded.map_points(dirs) - apex
        keep = _distinct(outer, 3.0 * NEAR)
        if hole_radius > 0.0:  # and the hole's points (arcs need a few x OCC's precision)
            keep &= _distinct(apex + hole_radius * unit, 4.0 * PRECISION)
        sides.append((outer[keep], unit[keep]))
    # the crease rulings (first and last of each side) are shared by both sides
    apex_v = vertex(apex) if hole_radius <= 0.0 else None
    crease_ends = [vertex(sides[0][0][i]) for i in (0, -1)]
    crease_inner = [
        apex_v if apex_v is not None else vertex(apex + hole_radius * sides[0][1][i])
        for i in (0, -1)
    ]
    crease_rulings = [line(crease_inner[i], crease_ends[i]) for i in (0, 1)]
    shell = TopoDS_Shell()
    b.MakeShell(shell)
    for side, (outer, unit) in enumerate(sides):
        n = len(outer)
        ends = [crease_ends[0]] + [vertex(p) for p in outer[1:-1]] + [crease_ends[1]]
        if apex_v is not None:
            inner = [apex_v] * n
        else:
            inner = (
                [crease_inner[0]]
                + [vertex(apex + hole_radius * u) for u in unit[1:-1]]
                + [crease_inner[1]]
            )
        rulings = (
            [crease_rulings[0]]
            + [line(inner[k], ends[k]) for k in range(1, n - 1)]
            + [crease_rulings[1]]
        )
        for k in range(n - 1):
            if check is not None and k % 256 == 255:
                check()
            p, q = outer[k], outer[k + 1]
            arc_edge = apex_v is None
            origin = apex
            # (p - A) x (q - p), not (p - A) x (q - A): the same normal, but a
            # thin triangle's two long sides cancel in the latter, leaving its
            # far vertex off the plane by |q| eps / (its angle at A) (2.5e-6 on
            # a sheet of 1.3e7 with 1e-3 rad triangles, 25 x the kernel's
            # precision); the short side is nearly square to the ruling
            normal = np.cross(p - origin, q - p)
            if side == 1:
                normal = -normal
            edges = [rulings[k], line(ends[k], ends[k + 1]), rulings[k + 1].Reversed()]
            if arc_edge:
                hp, hq = apex + hole_radius * unit[k], apex + hole_radius * unit[k + 1]
                axis = np.cross(p - apex, q - apex)
                circle = gp_Circ(gp_Ax2(_pnt(apex), gp_Dir(*axis), gp_Dir(*unit[k])), hole_radius)
                arc = GC_MakeArcOfCircle(circle, _pnt(hp), _pnt(hq), True).Value()
                edges.append(BRepBuilderAPI_MakeEdge(arc, inner[k], inner[k + 1]).Edge().Reversed())
            if side == 1:  # the mirror image: the same loop, the other way round
                edges = [e.Reversed() for e in reversed(edges)]
            wire = TopoDS_Wire()
            b.MakeWire(wire)
            for e in edges:
                b.Add(wire, e)
            plane = gp_Pln(_pnt(origin), gp_Dir(*normal))
            mk = BRepBuilderAPI_MakeFace(plane, wire, True)
            if not mk.IsDone():
                raise ExportError("could not make a planar fan face")
            face = mk.Face()
            for e in edges:
                BRepLib.BuildPCurveForEdgeOnPlane_s(TopoDS.Edge(e), face)
            b.Add(shell, face)
    shell.Closed(False)
    return shell
