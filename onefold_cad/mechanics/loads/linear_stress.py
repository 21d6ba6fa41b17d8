"""The stresses of superposed load cases, linear in the loads.

A face's stress follows from its membrane strain and its curvature change
(Cartesian Voigt ``(e11, e22, 2 e12)`` on its reference frame,
``Shell.cartesian``): ``sigma = E' [(1 - nu) E + nu tr(E) I]`` for the
membrane and ``+- E' t / 2 [(1 - nu) K + nu tr(K) I]`` at the two faces
(``6 M / t^2``), von Mises of the larger (as ``stress.face_stress``).

The Green strain of a state moved by a superposition of linear responses is
not their superposition (a rotation of 0.1 rad strains it by 0.5 %): a case's
strain and curvature are therefore the standing state's, times the weight's
factor, plus each action's first-order change (:func:`first_order`: the
derivative along its response, by a central difference) times its factor.
"""

from __future__ import annotations

import numpy as np

from onefold_cad.geometry.numeric import Array
from onefold_cad.mechanics.energy import second_fundamental_form
from onefold_cad.mechanics.kinematics.triangles import face_metric
from onefold_cad.mechanics.shell import Shell, unpack

__all__ = ["first_order", "strains", "von_mises_faces"]


def strains(shell: Shell, q: Array) -> tuple[Array, Array]:
    """``(m, 3)`` the faces' membrane strains and ``(m, 3)`` curvature changes
    (1/m) at state ``q`` about the shell's reference and rest form."""
    x = unpack(shell.mesh, q)[0]
    a = face_metric(x[shell.mesh.triangles])[0]
    lmap = shell.cartesian
    e = np.einsum("mij,mj->mi", lmap, 0.5 * (a - shell.ref_metric))
    k = np.einsum("mij,mj->mi", lmap, second_fundamental_form(shell, q) - shell.rest_curvature)
    return e, k


def first_order(shell: Shell, q: Array, u: Array) -> tuple[Array, Array]:
    """The first-order change of :func:`strains` at ``q`` along ``u`` (per unit
    of ``u``), by a central difference of a step moving no node more than
    1e-7 m (the metric is quadratic in the positions: exact for it)."""
    largest = float(np.max(np.abs(u))) if u.size else 0.0
    if largest == 0.0:
        m = shell.mesh.n_faces
        return np.zeros((m, 3)), np.zeros((m, 3))
    h = 1e-7 / largest
    ep, kp = strains(shell, q + h * u)
    em, km = strains(shell, q - h * u)
    return (ep - em) / (2 * h), (kp - km) / (2 * h)


def von_mises_faces(shell: Shell, e: Array, k: Array) -> Array:
    """``(m,)`` the larger von Mises stress (Pa) at the sheet's two faces of
    membrane strains ``e`` and curvature changes ``k`` (Voigt, ``(m, 3)``)."""
    mat = shell.material
    nu, ep, t = mat.poisson, mat.plane_modulus, mat.thickness

    def stress(v: Array) -> Array:
        return np.column_stack([v[:, 0] + nu * v[:, 1], v[:, 1] + nu * v[:, 0],
                                0.5 * (1 - nu) * v[:, 2]])  # fmt: skip

    sm, sb = ep * stress(e), 0.5 * ep * t * stress(k)

    def vm(s: Array) -> Array:
        xx, yy, xy = s[:, 0], s[:, 1], s[:, 2]
        return np.sqrt(np.maximum(xx**2 + yy**2 - xx * yy + 3 * xy**2, 0.0))

    return np.maximum(vm(sm + sb), vm(sm - sb))
