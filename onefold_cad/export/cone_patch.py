"""The exact cone held as an OCC surface: the patch of the cone from the apex
over an arc of the frame circle as a rational B-spline surface
``S(u, v) = A + v * L * (C(u) - A)`` (degree 2 rational in u along the arc,
degree 1 in v along the rulings; C the arc as rational quadratic spans), and
the point conversions the face builders share.

Lengths are in the design unit; angles in radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from OCP.collections import (
    Array1_double,
    Array1_int,
    Array2_double,
    Array2_gp_Pnt,
)
from OCP.Convert import Convert_ParameterisationType
from OCP.Geom import (
    Geom_BSplineSurface,
    Geom_Circle,
    Geom_TrimmedCurve,
)
from OCP.GeomConvert import GeomConvert
from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt

from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.numeric import Array

__all__ = ["Array", "cone_patch", "ConePatch", "pnt", "ruling_sectors"]


Convert_RationalC1 = Convert_ParameterisationType.Convert_RationalC1


def pnt(p: Array) -> gp_Pnt:
    return gp_Pnt(float(p[0]), float(p[1]), float(p[2]))


def xyz(p: gp_Pnt) -> tuple[float, float, float]:
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
        pts = np.array([xyz(self.surface.Value(float(t), 1.0)) for t in np.atleast_1d(u)])
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
    circle = Geom_Circle(gp_Ax2(pnt(centre), gp_Dir(*np.cross(ex, ey)), gp_Dir(*ex)), fr.radius)
    arc = GeomConvert.CurveToBSplineCurve_s(
        Geom_TrimmedCurve(circle, float(phi0), float(phi1)), Convert_RationalC1
    )
    c0, c1 = arc.FirstParameter(), arc.LastParameter()
    probe = ConePatch(None, c0, c1, apex, centre, ex, ey, fr.radius, 1.0, phi0, phi1)
    dmin = float(np.min(np.linalg.norm(probe.arc(np.linspace(phi0, phi1, 64)) - apex, axis=1)))
    scale = 1.02 * reach / dmin
    n = arc.NbPoles()
    poles = Array2_gp_Pnt(1, n, 1, 2)
    weights = Array2_double(1, n, 1, 2)
    for i in range(1, n + 1):
        p = np.array(xyz(arc.Pole(i)))
        w = arc.Weight(i)
        poles.SetValue(i, 1, pnt(apex))
        poles.SetValue(i, 2, pnt(apex + scale * (p - apex)))
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


def ruling_sectors(thetas: Array) -> Array:
    """The ruling angles without near-duplicates (< 1e-12 rad apart), ends kept."""
    keep = np.concatenate([np.diff(thetas) > 1e-12, [True]])
    keep[0] = True
    out = thetas[keep]
    out[-1] = thetas[-1]
    return out
