"""The folded form's faces for the .3dm (a rhino3dm adapter): one NURBS face
per side, whose natural boundary is the part's edge (rhino3dm can neither
trim a curved face nor join faces into one Brep), fitted sector by sector
(between consecutive vertex rulings) and joined at the sheet's corners by
knots of full multiplicity, so the face keeps the boundary's kinks exactly.

A face is the ruled surface ``S(s, v) = (1 - v) I(s) + v O(s)`` between two
cubic B-splines with one knot vector: ``I`` runs along the relief hole's edge
(all its control points at the apex when there is no hole) and ``O`` along
the sheet's edge mapped onto the cone. Both interpolate points of the fold
(:meth:`~onefold_cad.geometry.folding.FoldedSheet.map_points` of the flat
points at the hole's radius and at the sheet's boundary on one ray) at the
same parameters ``s``, so the segment between ``I(s)`` and ``O(s)`` is within
the curves' own error of the ruling at that angle, a straight line on the
cone: every point of the face is at most ``max(|I - I*|, |O - O*|)`` from the
exact cone. That distance is measured at three probes per interval between
nodes and an interval split while it exceeds the tolerance (the STEP's,
:data:`~onefold_cad.export.brep.step_checks.BOUNDARY_TOLERANCE` x the sheet's size).

``s`` runs against the flat polar angle and ``v`` outwards, so the face
normal ``dS/ds x dS/dv`` is the sheet's top side (as the STEP's shell).

A side's face (:func:`side_nets`) strings its sectors' curves together in
that order: its parameter ``u`` is the flat angle swept from the side's
first crease half (the -x one on the +y side, the +x one on the -y side, in
radians), and at each sheet corner the cubic's knot is triple (C0 there, the
control point the corner's fold). Each span is a sector's own, so the face
is as close to the cone as its sectors.

Lengths are in the design unit; angles in radians.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import rhino3dm
from scipy.interpolate import BSpline, make_interp_spline

from onefold_cad.errors import ExportError
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import Array

__all__ = [
    "FIRST_NODES",
    "MAX_NODES",
    "FaceNet",
    "SideNet",
    "face_nets",
    "nurbs_surface",
    "render_mesh",
    "side_nets",
]

#: Interpolation nodes a sector starts with (evenly spread in angle).
FIRST_NODES = 9
#: Most nodes one sector's curves may take before the fit gives up.
MAX_NODES = 4097
#: The render mesh: most turn of a ruling between two columns (radians), rows.
MESH_ANGLE = math.radians(2.0)
MESH_ROWS = 8
#: Probe positions inside each interval between nodes.
_PROBES = np.array([0.25, 0.5, 0.75])

#: A rigid placement of fold-frame points ``(k, 3) -> (k, 3)``.
Place = Callable[[Array], Array]


@dataclass(frozen=True)
class FaceNet:
    """The control net of one face, in the fold frame.

    Attributes:
        side: 0 for the +y side, 1 for the -y side.
        sector: index of the sector on its side, from the +x crease half.
        theta: ``(2,)`` the sector's flat angles from +x (radians; theta on
            the +y side, -theta on the -y side).
        knots: ``(n + 2,)`` the cubic's knots as openNURBS holds them (the
            clamped vector without its first and last knot).
        inner: ``(n, 3)`` control points along the relief hole (or the apex).
        outer: ``(n, 3)`` control points along the sheet's edge.
        nodes: ``(m,)`` the interpolation parameters in [0, 1].
        deviation: the largest distance from the exact cone measured at the
            probes (length).
    """

    side: int
    sector: int
    theta: Array
    knots: Array
    inner: Array
    outer: Array
    nodes: Array
    deviation: float


@dataclass(frozen=True)
class SideNet:
    """The control net of one side's face, in the fold frame: its sectors'
    nets strung together (see the module docstring).

    Attributes:
        side: 0 for the +y side, 1 for the -y side.
        sectors: the side's sector nets, in the order ``u`` runs through them.
        knots: ``(n + 2,)`` the cubic's knots as openNURBS holds them, in
            radians of flat angle from the side's first crease half; triple
            at each corner between sectors.
        inner: ``(n, 3)`` control points along the relief hole (or the apex).
        outer: ``(n, 3)`` control points along the sheet's edge.
        corners: ``(k,)`` the parameters ``u`` where the sectors meet (the
            sheet's corners and the paper model's divisions).
        deviation: the sectors' largest distance from the exact cone (length).
    """

    side: int
    sectors: tuple[FaceNet, ...]
    knots: Array
    inner: Array
    outer: Array
    corners: Array
    deviation: float


def _angles(net_theta: Array, side: int, s: Array) -> Array:
    """Flat polar angles psi at parameters ``s``: against psi as s grows."""
    ta, tb = net_theta
    theta = tb + (ta - tb) * s if side == 0 else ta + (tb - ta) * s
    return theta if side == 0 else -theta


def _targets(folded: FoldedSheet, psi: Array, hole_radius: float) -> tuple[Array, Array]:
    """The fold's points ``(k, 3)`` on the hole's edge and on the sheet's edge at ``psi``."""
    d = np.stack([np.cos(psi), np.sin(psi)], axis=1)
    rho = folded.sheet.ray_lengths(psi)
    inner = (
        folded.map_points(hole_radius * d)
        if hole_radius > 0.0
        else np.repeat(folded.apex[None, :], len(psi), axis=0)
    )
    return inner, folded.map_points(rho[:, None] * d)


def _fit_sector(
    folded: FoldedSheet, side: int, sector: int, theta: Array, hole_radius: float, tol: float
) -> FaceNet:
    s = np.linspace(0.0, 1.0, FIRST_NODES)
    while True:
        inner_t, outer_t = _targets(folded, _angles(theta, side, s), hole_radius)
        fit_in = make_interp_spline(s, inner_t, k=3)
        fit_out = make_interp_spline(s, outer_t, k=3)
        probe = (s[:-1, None] + np.diff(s)[:, None] * _PROBES[None, :]).ravel()
        want_in, want_out = _targets(folded, _angles(theta, side, probe), hole_radius)
        err = np.maximum(
            np.linalg.norm(fit_in(probe) - want_in, axis=1),
            np.linalg.norm(fit_out(probe) - want_out, axis=1),
        ).reshape(-1, len(_PROBES))
        worst = err.max(axis=1)
        bad = worst > tol
        if not bad.any() or len(s) + int(bad.sum()) > MAX_NODES:
            break
        s = np.sort(np.concatenate([s, 0.5 * (s[:-1] + s[1:])[bad]]))
    deviation = float(worst.max())
    if deviation > tol:
        raise ExportError(
            f"a face of the .3dm stays {deviation:.3g} from the exact cone with "
            f"{len(s)} nodes, more than the tolerance {tol:.3g}"
        )
    assert isinstance(fit_in, BSpline) and isinstance(fit_out, BSpline)
    return FaceNet(
        side,
        sector,
        np.asarray(theta, dtype=float),
        np.asarray(fit_in.t[1:-1], dtype=float),
        np.asarray(fit_in.c, dtype=float),
        np.asarray(fit_out.c, dtype=float),
        s,
        deviation,
    )


def face_nets(folded: FoldedSheet, hole_radius: float, tol: float) -> list[FaceNet]:
    """Every face of the folded form: per side, one per sector between
    consecutive rulings of :attr:`FoldedSheet.ruling_angles` (the sheet's
    corners, and the paper model's divisions), from the +x crease half.

    Args:
        folded: the fold.
        hole_radius: the relief hole's radius about the apex (0 = none; length).
        tol: the largest distance allowed from the exact cone (length).

    Raises:
        ExportError: a sector whose curves need more than :data:`MAX_NODES`
            nodes to reach ``tol``.
    """
    nets = []
    for side, angles in enumerate(folded.ruling_angles):
        theta = np.asarray(angles, dtype=float)
        keep = np.concatenate([[True], np.diff(theta) > 1e-12])
        theta = theta[keep]
        for k in range(len(theta) - 1):
            nets.append(_fit_sector(folded, side, k, theta[k : k + 2], hole_radius, tol))
    return nets


def side_nets(nets: list[FaceNet]) -> list[SideNet]:
    """Each side's face from its sectors' nets (:func:`face_nets`): the
    sectors in the order ``s`` runs (against the flat polar angle: the +y
    side's from theta = pi down, the -y side's from theta = 0 up), each
    sector's knots moved onto its flat angles, one control point shared at
    each corner (the first sector's end, which is its fold to rounding)."""
    out = []
    for side in (0, 1):
        sectors = sorted((n for n in nets if n.side == side), key=lambda n: n.sector)
        if side == 0:
            sectors.reverse()
        top = max(float(n.theta[1]) for n in sectors)
        knots, inner, outer, corners = [], [], [], []
        for i, net in enumerate(sectors):
            ta, tb = (float(t) for t in net.theta)
            start = top - tb if side == 0 else ta - float(sectors[0].theta[0])
            k = start + (tb - ta) * net.knots
            if i == 0:
                knots.append(k)
                inner.append(net.inner)
                outer.append(net.outer)
            else:
                corners.append(float(knots[-1][-1]))
                knots.append(k[3:])  # the corner's knot three times, then the sector's own
                inner.append(net.inner[1:])
                outer.append(net.outer[1:])
        out.append(
            SideNet(
                side,
                tuple(sectors),
                np.concatenate(knots),
                np.concatenate(inner),
                np.concatenate(outer),
                np.asarray(corners, dtype=float),
                max(n.deviation for n in sectors),
            )
        )
    return out


def nurbs_surface(net: FaceNet | SideNet, place: Place) -> rhino3dm.NurbsSurface:
    """A face as a rhino3dm NURBS surface (cubic in u, linear in v), placed."""
    inner, outer = place(net.inner), place(net.outer)
    n = len(inner)
    surface = rhino3dm.NurbsSurface.Create(3, False, 4, 2, n, 2)
    for i, k in enumerate(net.knots):
        surface.KnotsU[i] = float(k)
    surface.KnotsV[0], surface.KnotsV[1] = 0.0, 1.0
    for i in range(n):
        for j, row in enumerate((inner, outer)):
            x, y, z = (float(c) for c in row[i])
            surface.Points[i, j] = rhino3dm.Point4d(x, y, z, 1.0)
    if not surface.IsValid:
        raise ExportError("rhino3dm refused a face's NURBS surface")
    return surface


def _sector_mesh(
    folded: FoldedSheet, net: FaceNet, hole_radius: float
) -> tuple[Array, list[tuple[int, ...]]]:
    """One sector's mesh in the fold frame: vertices ``(k, 3)`` on the exact
    cone and faces (triangles and quads, indices into them) facing the top."""
    ta, tb = net.theta
    cols = max(2, math.ceil((tb - ta) / MESH_ANGLE) + 1)
    psi = _angles(net.theta, net.side, np.linspace(0.0, 1.0, cols))
    d = np.stack([np.cos(psi), np.sin(psi)], axis=1)
    rho = folded.sheet.ray_lengths(psi)
    v = np.linspace(0.0, 1.0, MESH_ROWS + 1)
    r = hole_radius + v[None, :] * (rho[:, None] - hole_radius)  # (cols, rows + 1)
    first = 0 if hole_radius > 0.0 else 1  # no hole: one apex vertex for the row at v = 0
    flat = (r[:, first:, None] * d[:, None, :]).reshape(-1, 2)
    pts = folded.map_points(flat)
    if first:
        pts = np.concatenate([folded.apex[None, :], pts])
    rows = MESH_ROWS + 1 - first

    def at(i: int, j: int) -> int:
        return first + i * rows + j

    faces: list[tuple[int, ...]] = []
    for i in range(cols - 1):
        if first:
            faces.append((0, at(i + 1, 0), at(i, 0)))
        for j in range(rows - 1):
            faces.append((at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)))
    return pts, faces


def render_mesh(folded: FoldedSheet, side: SideNet, hole_radius: float, place: Place) -> Any:
    """A mesh of a side's face with every vertex on the exact cone (the
    fold's points), its faces facing the top side, placed: its sectors'
    meshes side by side (each corner's vertices twice, so the shading keeps
    the kink)."""
    mesh = rhino3dm.Mesh()
    base = 0
    for net in side.sectors:
        pts, faces = _sector_mesh(folded, net, hole_radius)
        for x, y, z in place(pts).tolist():
            mesh.Vertices.Add(x, y, z)
        for f in faces:
            mesh.Faces.AddFace(*(base + k for k in f))
        base += len(pts)
    mesh.Normals.ComputeNormals()
    return mesh
