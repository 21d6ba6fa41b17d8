"""The stresses in a shell state: membrane and bending, at the sheet's faces.

Per triangle, in an orthonormal frame of its reference triangle:

- membrane: the Green strain ``E = J^-T (a - abar) J^-1 / 2`` (``a``: the
  metric in the face's parametric coordinates, ``J`` their Jacobian), the
  force per length ``N = E' t [(1 - nu) E + nu tr(E) I]``;
- bending: the curvature change ``K = J^-T (b - bbar) J^-1``, the moment per
  length ``M = D [(1 - nu) K + nu tr(K) I]``;
- at the two faces of the sheet ``sigma = N / t +- 6 M / t^2``; the stress is
  its von Mises value (plane stress), the larger of the two faces.

A face that yielded in forming is not elastic about its rest form: its
outer fibre was at the yield stress when it was formed and unloads
elastically from there, so its bending stress at the surface is
``sigma_y - 6 (M_r - M) / t^2`` along the curvature it last yielded in
(``M_r`` the moment it yields at now, ``M`` the one it carries, both in the
law's norm); the membrane's von Mises stress is added to it (a bound: the two
act in directions this does not resolve). Stresses in Pa.
"""

from __future__ import annotations

import numpy as np

from onefold_cad.geometry.numeric import Array
from onefold_cad.mechanics import plastic
from onefold_cad.mechanics.energy import second_fundamental_form
from onefold_cad.mechanics.kinematics.triangles import face_metric
from onefold_cad.mechanics.shell import Shell, unpack

__all__ = ["face_stress", "von_mises"]


def von_mises(s: Array) -> Array:
    """``(m,)`` the von Mises stress of plane-stress tensors ``(m, 2, 2)``."""
    xx, yy, xy = s[:, 0, 0], s[:, 1, 1], s[:, 0, 1]
    return np.sqrt(np.maximum(xx**2 + yy**2 - xx * yy + 3.0 * xy**2, 0.0))


def _cartesian(shell: Shell, covariant: Array) -> Array:
    """``(m, 2, 2)`` tensors given by their covariant components ``(m, 3)``
    (``11, 12, 22`` in the faces' parametric coordinates) in an orthonormal
    frame of each reference triangle."""
    p = shell.reference[shell.mesh.triangles]
    d1, d2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    e1 = d1 / np.linalg.norm(d1, axis=1)[:, None]
    n = np.cross(d1, d2)
    e2 = np.cross(n / np.linalg.norm(n, axis=1)[:, None], e1)
    jac = np.empty((len(p), 2, 2))
    jac[:, 0, 0], jac[:, 0, 1] = np.einsum("ij,ij->i", e1, d1), np.einsum("ij,ij->i", e1, d2)
    jac[:, 1, 0], jac[:, 1, 1] = 0.0, np.einsum("ij,ij->i", e2, d2)
    inv = np.linalg.inv(jac)
    c = np.empty((len(p), 2, 2))
    c[:, 0, 0], c[:, 0, 1], c[:, 1, 1] = covariant[:, 0], covariant[:, 1], covariant[:, 2]
    c[:, 1, 0] = c[:, 0, 1]
    return np.einsum("mji,mjk,mkl->mil", inv, c, inv)


def _isotropic(k: Array, nu: float) -> Array:
    """``(1 - nu) K + nu tr(K) I`` for ``(m, 2, 2)`` tensors."""
    tr = k[:, 0, 0] + k[:, 1, 1]
    return (1.0 - nu) * k + nu * tr[:, None, None] * np.eye(2)


def face_stress(shell: Shell, q: Array, state: plastic.PlasticState | None = None) -> Array:
    """``(m,)`` the largest stress at the sheet's two faces in each triangle (Pa)
    of the state ``q``, about the shell's rest form (``state``: the faces'
    plastic states, for a sheet formed from flat; None: elastic about it)."""
    mat = shell.material
    t, nu = mat.thickness, mat.poisson
    x = unpack(shell.mesh, q)[0]
    a = face_metric(x[shell.mesh.triangles])[0]
    strain = _cartesian(shell, 0.5 * (a - shell.ref_metric))
    n_t = mat.plane_modulus * _isotropic(strain, nu)  # N / t
    b = second_fundamental_form(shell, q)
    m_6t2 = (
        6.0
        * mat.bending_stiffness
        / t**2
        * _isotropic(_cartesian(shell, b - shell.rest_curvature), nu)
    )
    out = np.maximum(von_mises(n_t + m_6t2), von_mises(n_t - m_6t2))
    if state is None:
        return out
    yielded = state.plastic(mat)
    if not yielded.any():
        return out
    form = shell.form[yielded]
    change = b[yielded] - state.rest[yielded]
    carried = mat.bending_stiffness * plastic.equivalent_curvature(form, change)
    then = state.reached[yielded] - state.rest[yielded]
    along = np.einsum("mi,mij,mj->m", change, form, then)
    at = plastic.skeleton_curvature(mat, state.accumulated[yielded])
    limit = plastic.skeleton_moment(mat, at)
    surface = mat.yield_stress - 6.0 * (limit - np.where(along >= 0, carried, -carried)) / t**2
    out[yielded] = np.abs(surface) + von_mises(n_t[yielded])
    return out
