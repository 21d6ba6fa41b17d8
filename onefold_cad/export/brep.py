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
from OCP.BRep import BRep_Builder
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakePolygon,
    BRepBuilderAPI_MakeVertex,
    BRepBuilderAPI_MakeWire,
    BRepBuilderAPI_Sewing,
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
from OCP.Geom import Geom_BSplineCurve, Geom_BSplineSurface, Geom_Circle, Geom_TrimmedCurve
from OCP.Geom2d import Geom2d_BSplineCurve, Geom2d_Line
from OCP.Geom2dAPI import Geom2dAPI_Interpolate
from OCP.GeomAbs import GeomAbs_C2
from OCP.GeomAPI import GeomAPI_Interpolate
from OCP.GeomConvert import GeomConvert
from OCP.gp import gp_Ax2, gp_Circ, gp_Dir, gp_Dir2d, gp_Pnt, gp_Pnt2d, gp_Vec
from OCP.ShapeFix import ShapeFix_Shape
from OCP.TopAbs import TopAbs_REVERSED
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape, TopoDS_Vertex

from onefold_cad.errors import ExportError
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.folding import FoldedSheet

__all__ = ["ConePatch", "cone_patch", "ruled_faces", "fan_faces", "sew", "interpolate"]

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


def _fit_pcurve(
    patch: ConePatch, u0: float, u1: float, radius_at, tol: float
) -> tuple[object, float]:
    """A pcurve through the points at distance ``radius_at(phi)`` from A, for
    u in [u0, u1], refined until its deviation along the rulings is below
    ``tol`` (length). Returns ``(Geom2d curve, deviation reached)``."""
    n = 9
    while True:
        us = np.linspace(u0, u1, n)
        phi = patch.phi_of_u(us)
        uv = np.stack([us, patch.v_of(phi, radius_at(phi))], axis=1)
        curve = interpolate(uv, us, "a boundary curve on the cone")
        # deviation at the midpoints between the interpolation nodes
        um = 0.5 * (us[:-1] + us[1:])
        got = np.array([[curve.Value(float(t)).X(), curve.Value(float(t)).Y()] for t in um])
        pm = patch.phi_of_u(got[:, 0])
        dist = patch.scale * np.linalg.norm(patch.arc(pm) - patch.apex, axis=1)
        err = float(np.max(np.abs(got[:, 1] - patch.v_of(pm, radius_at(pm))) * dist))
        if err <= tol or n > 2000:
            return curve, err
        n = 2 * n - 1


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


def ruled_faces(
    folded: FoldedSheet, hole_radius: float, tol: float
) -> tuple[list[TopoDS_Face], float]:
    """The exact-cone faces, one per sheet edge per side (top normals outward).

    Args:
        folded: an exact-model fold.
        hole_radius: relief hole radius about the apex (0 = none; length).
        tol: allowed deviation of the boundary curves along the cone (length).

    Returns:
        ``(faces, deviation)``: the faces and the largest boundary deviation reached.
    """
    cone = folded.solution.surface
    if not isinstance(cone, ExactCone):
        raise ExportError("ruled faces need the exact model's cone")
    sheet = folded.sheet
    faces: list[TopoDS_Face] = []
    worst = 0.0
    for side, angles in enumerate(folded.ruling_angles):
        thetas = _sectors(angles)
        sgn = 1.0 if side == 0 else -1.0
        phis = cone.phi_of_theta(thetas)
        ends = sheet.ray_lengths(sgn * thetas)
        for k in range(len(thetas) - 1):
            ta, tb = thetas[k], thetas[k + 1]
            pa = np.array([math.cos(ta), sgn * math.sin(ta)]) * ends[k]
            pb = np.array([math.cos(tb), sgn * math.sin(tb)]) * ends[k + 1]
            patch = cone_patch(cone, phis[k], phis[k + 1], side == 1, max(ends[k], ends[k + 1]))

            outer = partial(_outer_radius, cone, pa, pb, (ta, tb), sgn)
            face, err = _patch_face(patch, outer, hole_radius, tol)
            tm = 0.5 * (ta + tb)
            top = folded.normals(np.array([[math.cos(tm), sgn * math.sin(tm)]]))[0]
            worst = max(worst, err)
            faces.append(_orient(face, top))
    return faces, worst


def _patch_face(
    patch: ConePatch, outer: Callable[[Array], Array], hole_radius: float, tol: float
) -> tuple[TopoDS_Face, float]:
    """One trimmed cone face: hole arc (or the apex), ruling, outer edge, ruling."""
    surf = patch.surface
    u0, m = patch.u0, patch.u1
    c_out, err = _fit_pcurve(patch, u0, m, outer, tol)
    phi_ends = patch.phi_of_u(np.array([u0, m]))
    v_out = patch.v_of(phi_ends, outer(phi_ends))
    if hole_radius > 0.0:
        c_in, err_in = _fit_pcurve(patch, u0, m, lambda p: np.full_like(p, hole_radius), tol)
        err = max(err, err_in)
        v_in = patch.v_of(phi_ends, np.full(2, hole_radius))
    else:
        v_in = np.zeros(2)

    def vert(u: float, v: float) -> TopoDS_Vertex:
        return BRepBuilderAPI_MakeVertex(surf.Value(u, v)).Vertex()

    a_in, b_in = vert(u0, v_in[0]), vert(m, v_in[1])
    a_out, b_out = vert(u0, v_out[0]), vert(m, v_out[1])
    up = gp_Dir2d(0.0, 1.0)
    edges = []
    if hole_radius > 0.0:
        edges.append(BRepBuilderAPI_MakeEdge(c_in, surf, a_in, b_in, u0, m).Edge())
    else:
        apex_v = a_in
        b_in = apex_v
        line = Geom2d_Line(gp_Pnt2d(0.0, 0.0), gp_Dir2d(1.0, 0.0))
        deg = BRepBuilderAPI_MakeEdge(line, surf, apex_v, apex_v, u0, m).Edge()
        BRep_Builder().Degenerated(deg, True)
        edges.append(deg)
    edges.append(
        BRepBuilderAPI_MakeEdge(
            Geom2d_Line(gp_Pnt2d(m, 0.0), up), surf, b_in, b_out, float(v_in[1]), float(v_out[1])
        ).Edge()
    )
    e_out = BRepBuilderAPI_MakeEdge(c_out, surf, a_out, b_out, u0, m).Edge()
    edges.append(TopoDS.Edge(e_out.Reversed()))
    edges.append(
        BRepBuilderAPI_MakeEdge(
            Geom2d_Line(gp_Pnt2d(u0, 0.0), up), surf, a_in, a_out, float(v_in[0]), float(v_out[0])
        )
        .Edge()
        .Reversed()
    )
    wire = BRepBuilderAPI_MakeWire()
    for e in edges:
        wire.Add(TopoDS.Edge(e))
    if not wire.IsDone():
        raise ExportError("could not close the boundary of a cone face")
    mk = BRepBuilderAPI_MakeFace(surf, wire.Wire(), True)
    if not mk.IsDone():
        raise ExportError("could not make a cone face")
    face = mk.Face()
    BRepLib.BuildCurves3d_s(face, 1e-3 * tol, GeomAbs_C2, 8, 2000)
    BRepLib.SameParameter_s(face, 1e-3 * tol, True)
    return face, err


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


def fan_faces(folded: FoldedSheet, hole_radius: float) -> list[TopoDS_Face]:
    """The paper model's planar triangles (with an exact arc of the relief hole)."""
    faces: list[TopoDS_Face] = []
    apex = folded.apex
    for side, angles in enumerate(folded.ruling_angles):
        thetas = _sectors(angles)
        sgn = 1.0 if side == 0 else -1.0
        dirs = np.stack([np.cos(thetas), sgn * np.sin(thetas)], axis=-1)
        rho = folded.sheet.ray_lengths(sgn * thetas)
        outer = folded.map_points(dirs * rho[:, None])
        unit = folded.map_points(dirs) - apex
        for k in range(len(thetas) - 1):
            p, q = outer[k], outer[k + 1]
            if hole_radius > 0.0:
                hp, hq = apex + hole_radius * unit[k], apex + hole_radius * unit[k + 1]
                axis = np.cross(p - apex, q - apex)
                circle = gp_Circ(gp_Ax2(_pnt(apex), gp_Dir(*axis), gp_Dir(*unit[k])), hole_radius)
                arc = GC_MakeArcOfCircle(circle, _pnt(hp), _pnt(hq), True).Value()
                mw = BRepBuilderAPI_MakeWire()
                mw.Add(BRepBuilderAPI_MakeEdge(arc).Edge())
                for a, b in ((hq, q), (q, p), (p, hp)):
                    mw.Add(BRepBuilderAPI_MakeEdge(_pnt(a), _pnt(b)).Edge())
                wire = mw.Wire()
            else:
                wire = BRepBuilderAPI_MakePolygon(_pnt(apex), _pnt(p), _pnt(q), True).Wire()
            mk = BRepBuilderAPI_MakeFace(wire, True)
            if not mk.IsDone():
                raise ExportError("could not make a planar fan face")
            tm = 0.5 * (thetas[k] + thetas[k + 1])
            top = folded.normals(np.array([[math.cos(tm), sgn * math.sin(tm)]]))[0]
            faces.append(_orient(mk.Face(), top))
    return faces


def sew(faces: list[TopoDS_Face], tol: float) -> TopoDS_Shape:
    """Sew ``faces`` into one shell with sewing tolerance ``tol`` (length)."""
    sewing = BRepBuilderAPI_Sewing(tol)
    for f in faces:
        sewing.Add(f)
    sewing.Perform()
    shape = sewing.SewedShape()
    if sewing.NbFreeEdges() < 0 or shape.IsNull():
        raise ExportError("sewing the faces failed")
    fix = ShapeFix_Shape(shape)
    fix.SetPrecision(tol * 1e-3)
    fix.Perform()
    return fix.Shape()
