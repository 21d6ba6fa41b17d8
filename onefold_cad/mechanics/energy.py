"""The total energy of a shell and its exact gradient and sparse Hessian.

``E = membrane + bending + crease + gravity`` (J), all vectorised over elements:

- membrane (CST, St Venant-Kirchhoff, plane stress):
  ``Abar E' t / 2 * Q(eps)``, ``eps = (a - abar) / 2``;
- bending (mid-edge directors): per face ``b = 2 [[u0 + u1, u0], [u0, u0 + u2]]``,
  ``u_i = h_i tan(phi_i)``; ``phi_i = psi_e / 2 +- xi_e`` on interior edges (``+`` in
  ``T0``), ``xi_e`` on boundary edges, the face's own angle on crease edges,
  ``psi_e + xi_e`` on clamped edges (``psi_e`` towards the clamp's ghost); energy
  ``Abar D / 2 Q(b - bbar)``;
- crease hinges: ``k_c / 2 * lbar * (psi - xi+ - xi- - psi_set)^2``;
- gravity: ``-sum m_i g . x_i``.

``Q(s) = s^T K s`` is the isotropic form of ``material.strain_form``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from onefold_cad.mechanics.assembly import pattern_of
from onefold_cad.mechanics.kinematics import METRIC_HESSIAN, dihedral, face_heights, face_metric
from onefold_cad.mechanics.mesh import INTERIOR
from onefold_cad.mechanics.shell import Shell, unpack

__all__ = ["Evaluation", "evaluate", "second_fundamental_form"]

F = NDArray[np.float64]
#: b = B u
_B = np.array([[2.0, 2.0, 0.0], [2.0, 0.0, 0.0], [2.0, 0.0, 2.0]])


@dataclass(frozen=True)
class Evaluation:
    """The energy at one state.

    Attributes:
        energy: total (J).
        parts: the terms ``membrane``, ``bending``, ``crease``, ``gravity`` (J).
        gradient: (N,) dE/dq (N for coordinates, N m for director angles), or None.
        hessian: (N, N) CSC, or None.
        ghost_gradient: (kcl, 3) dE/d(ghost vertex) of the clamped edges (N), with the
            gradient: minus the force the sheet puts on each clamp's ghost.
        crease_stress: with the Hessian, its part ``k_c lbar (psi - ...) d2psi`` from
            the creases' misfit (indefinite; Newton drops it when the Hessian is not
            positive definite), or None without creases.
    """

    energy: float
    parts: dict[str, float]
    gradient: F | None = None
    hessian: sp.csc_matrix | None = None
    ghost_gradient: F | None = None
    crease_stress: sp.csc_matrix | None = None


def _face_angles(shell: Shell, x: F, xi: F, order: int) -> tuple[F, ...]:
    """Director angles phi (m, 3) and the dihedrals they use, with derivatives.

    Returns phi; dpsi (m, 3, 12) per face edge (0 where phi uses no dihedral);
    d2psi (k_int, 12, 12) of the interior edges and (kcl, 12, 12) of the clamped
    ones; ``dphi/dpsi`` (m, 3) (1/2 interior, 1 clamped, else 0) and ``dphi/dxi``
    (m, 3) (+-1). A clamped edge's dihedral is taken with its fixed ghost vertex
    (no derivative towards it).
    """
    mesh = shell.mesh
    interior = np.flatnonzero(mesh.edge_kind == INTERIOR)
    clamped = shell.clamp_edges
    verts = np.concatenate([mesh.edges[interior], mesh.edge_opposite[interior]], axis=1)
    cverts = np.concatenate([mesh.edges[clamped], mesh.edge_opposite[clamped, :1]], axis=1)
    pts = np.concatenate([x[verts], np.concatenate([x[cverts], shell.clamp_ghosts[:, None]], 1)])
    psi, dpsi, d2psi = dihedral(pts, order)
    ni = len(interior)
    edge_psi = np.zeros(mesh.n_edges)
    edge_psi[interior], edge_psi[clamped] = psi[:ni], psi[ni:]
    fe = mesh.face_edges
    factor = np.zeros(mesh.n_edges)
    factor[interior], factor[clamped] = 0.5, 1.0
    half = factor[fe]
    sign = np.where((mesh.edge_kind[fe] == INTERIOR) & (mesh.face_edge_side == 1), -1.0, 1.0)
    phi = half * edge_psi[fe] + sign * xi[mesh.face_directors]
    if order == 0:
        return phi, None, None, None, None, half, sign
    slot = np.full(mesh.n_edges, -1)
    slot[interior] = np.arange(ni)
    slot[clamped] = ni + np.arange(len(clamped))
    ghost_dpsi = dpsi[ni:, 9:].copy()
    dpsi[ni:, 9:] = 0.0
    face_dpsi = np.where((half > 0)[:, :, None], dpsi[np.maximum(slot[fe], 0)], 0.0)
    d2_int = d2_clamp = None
    if order >= 2:
        d2psi[ni:, 9:, :] = 0.0
        d2psi[ni:, :, 9:] = 0.0
        d2_int, d2_clamp = d2psi[:ni], d2psi[ni:]
    return phi, face_dpsi, d2_int, d2_clamp, ghost_dpsi, half, sign


def second_fundamental_form(shell: Shell, q: F) -> F:
    """(m, 3) the faces' second fundamental forms ``(b11, b12, b22)`` at state ``q`` (m)."""
    x, xi = unpack(shell.mesh, q)
    phi = _face_angles(shell, x, xi, 0)[0]
    h = face_heights(x[shell.mesh.triangles], 0)[0]
    return (h * np.tan(phi)) @ _B.T


def evaluate(shell: Shell, q: F, order: int = 2) -> Evaluation:
    """The energy (order 0), its gradient (1) and Hessian (2) at state ``q`` ((N,))."""
    mesh, mat = shell.mesh, shell.material
    x, xi = unpack(mesh, q)
    m = mesh.n_faces
    xf = x[mesh.triangles]
    area, kform = shell.ref_area, shell.form

    # Membrane.
    a, da = face_metric(xf)
    eps = (a - shell.ref_metric) / 2
    keps = np.einsum("mij,mj->mi", kform, eps)
    cm = area * mat.membrane_stiffness / 2
    e_mem = float(np.sum(cm * np.einsum("mi,mi->m", eps, keps)))

    # Bending.
    phi, dpsi, d2psi, d2clamp, ghost_dpsi, half, sign = _face_angles(shell, x, xi, order)
    h, dh, d2h = face_heights(xf, order)
    tan = np.tan(phi)
    u = h * tan
    r = u @ _B.T - shell.rest_curvature
    kr = np.einsum("mij,mj->mi", kform, r)
    d = mat.bending_stiffness
    e_bend = float(np.sum(area * d / 2 * np.einsum("mi,mi->m", r, kr)))

    # Crease hinges.
    kc = len(mesh.crease_edges)
    cverts = np.concatenate(
        [mesh.edges[mesh.crease_edges], mesh.edge_opposite[mesh.crease_edges]], axis=1
    )
    cpsi, cdpsi, cd2psi = dihedral(x[cverts], order) if kc else (np.zeros(0), None, None)
    xi_plus, xi_minus = xi[mesh.crease_edges], xi[mesh.n_edges :]
    delta = cpsi - xi_plus - xi_minus - shell.crease_angle
    ck = shell.crease_stiffness * shell.crease_length
    e_crease = float(np.sum(ck * delta**2 / 2))

    # Gravity.
    weight = -shell.node_mass[:, None] * shell.gravity[None, :]  # dE/dx, (n, 3)
    e_grav = float(np.sum(weight * x))
    parts = {"membrane": e_mem, "bending": e_bend, "crease": e_crease, "gravity": e_grav}
    total = e_mem + e_bend + e_crease + e_grav
    if order == 0:
        return Evaluation(total, parts)

    pattern = pattern_of(mesh)
    # Local variables z = (X 9, phi 3) of each face.
    sec2 = 1.0 + tan**2
    dq_du = 2 * kr @ _B  # (m, 3)
    w_u = (area * d / 2)[:, None] * dq_du
    du = np.zeros((m, 3, 12))
    du[:, :, :9] = tan[:, :, None] * dh
    du[:, [0, 1, 2], [9, 10, 11]] = h * sec2
    g_z = np.einsum("mi,mij->mj", w_u, du)
    g_z[:, :9] += np.einsum("mi,mij->mj", keps * cm[:, None], da)

    # Map z -> the 21-DOF stencil.
    # dz/d(stencil) = [[I 0], [dphi]]: only the phi rows (m, 3, 21) are stored.
    dphi = np.zeros((m, 3, 21))
    blocks = 3 * pattern.psi_slots[:, :, :, None] + np.arange(3)  # (m, 3, 4, 3)
    rows = np.arange(m)[:, None, None]
    for i in range(3):
        dphi[rows[:, :, 0], i, blocks[:, i].reshape(m, 12)] = half[:, i, None] * dpsi[:, i]
        dphi[:, i, 18 + i] = sign[:, i]
    g_face = (g_z[:, None, 9:] @ dphi)[:, 0]
    g_face[:, :9] += g_z[:, :9]
    g_crease = np.zeros((kc, 14))
    if kc:
        g_crease[:, :12] = (ck * delta)[:, None] * cdpsi
        g_crease[:, 12:] = -(ck * delta)[:, None]
    gradient = pattern.vector(g_face, g_crease)
    gradient[: 3 * mesh.n_nodes] += weight.ravel()
    # Each face's dW/dphi, and the dihedral coefficient sum dW/dphi dphi/dpsi per edge.
    coeff = np.bincount(
        mesh.face_edges.ravel(), (g_z[:, 9:] * half).ravel(), minlength=mesh.n_edges
    )
    ghost = coeff[shell.clamp_edges, None] * ghost_dpsi
    if order == 1:
        return Evaluation(total, parts, gradient, ghost_gradient=ghost)

    # Face Hessians in z.
    q_uu = 2 * (_B.T @ kform @ _B)
    w_uu = (area * d / 2)[:, None, None] * q_uu
    h_z = du.transpose(0, 2, 1) @ (w_uu @ du)
    h_z[:, :9, :9] += ((w_u * tan)[:, None, :] @ d2h.reshape(m, 3, 81)).reshape(m, 9, 9)
    for i in range(3):
        cross = w_u[:, i, None] * sec2[:, i, None] * dh[:, i]
        h_z[:, :9, 9 + i] += cross
        h_z[:, 9 + i, :9] += cross
        h_z[:, 9 + i, 9 + i] += w_u[:, i] * 2 * h[:, i] * sec2[:, i] * tan[:, i]
    h_z[:, :9, :9] += cm[:, None, None] * (
        0.5 * (da.transpose(0, 2, 1) @ (kform @ da))
        + (keps @ METRIC_HESSIAN.reshape(3, 81)).reshape(m, 9, 9)
    )
    h_face = dphi.transpose(0, 2, 1) @ (h_z[:, 9:, 9:] @ dphi)
    mixed = h_z[:, :9, 9:] @ dphi
    h_face[:, :9, :] += mixed
    h_face[:, :, :9] += mixed.transpose(0, 2, 1)
    h_face[:, :9, :9] += h_z[:, :9, :9]
    h_edge = coeff[pattern.interior, None, None] * d2psi
    if len(shell.clamp_edges):
        face = mesh.edge_faces[shell.clamp_edges, 0]
        local = np.argmax(mesh.face_edges[face] == shell.clamp_edges[:, None], axis=1)
        idx = blocks[face, local].reshape(-1, 12)
        h_face[face[:, None, None], idx[:, :, None], idx[:, None, :]] += (
            coeff[shell.clamp_edges, None, None] * d2clamp
        )
    h_crease = np.zeros((kc, 14, 14))
    stress = None
    if kc:
        dd = np.concatenate([cdpsi, -np.ones((kc, 2))], axis=1)
        h_crease = ck[:, None, None] * dd[:, :, None] * dd[:, None, :]
        h_stress = np.zeros((kc, 14, 14))
        h_stress[:, :12, :12] = (ck * delta)[:, None, None] * cd2psi
        h_crease += h_stress
        stress = pattern.matrix(np.zeros((m, 21, 21)), np.zeros((0, 12, 12)), h_stress)
    hessian = pattern.matrix(h_face, h_edge, h_crease)
    return Evaluation(total, parts, gradient, hessian, ghost, stress)
