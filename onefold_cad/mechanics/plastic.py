"""Elastic-perfectly-plastic bending of a rectangular section, per face.

The law (per unit length, SI): ``M_s(k) = D k`` up to ``kappa_y = 2 sigma_y / (E' t)``,
``M_p (1 - (kappa_y / k)^2 / 3)`` beyond, ``M_p = sigma_y t^2 / 4``; unloading is
elastic with slope ``D``. A face's curvature is its second fundamental form ``b``
(the 3-vector ``(b11, b12, b22)``, parametric coordinates) and the norm of a
curvature ``|b| = sqrt(b^T K b)`` (``K``: ``material.strain_form``) is ``|kappa|``
for one-directional (developable) bending.

In a sheet the curvature is a tensor, so the law is applied as plasticity with
isotropic hardening in that norm: a face's state is its plastic rest form
``b_p`` and its accumulated plastic curvature ``alpha``; the moment follows the
elastic curvature ``b - b_p``, and while the face yields its plastic curvature
grows along the moment (normality) so that, bent from flat in one direction,
the moment is exactly the skeleton's: after a plastic curvature ``alpha`` the
face yields again at the skeleton's moment ``M_s(k*)``, ``k* - M_s(k*) / D = alpha``.
Worked through, the moment of a face at an elastic-trial curvature
``s = |b - b_p|`` is ``m(s) = min(D s, M_s(s + alpha))`` (:func:`moment`), a
continuous, increasing law: its energy is smooth enough for Newton's method
with the exact tangent (:mod:`onefold_cad.mechanics.energy`), and it reproduces
the 1D law exactly on a proportional path (forming, springback). Reverse
yielding is at ``-M_s(k*)`` in this model; a rectangular section's Bauschinger
effect would yield earlier, after a moment change of ``2 M_y``: :func:`check`
reports faces past that.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.mechanics.material import ShellMaterial

__all__ = [
    "PlasticState",
    "check",
    "equivalent_curvature",
    "form",
    "moment",
    "skeleton_curvature",
    "skeleton_moment",
    "skeleton_slope",
    "skeleton_work",
    "update",
    "virgin_state",
]

F = NDArray[np.float64]


def skeleton_moment(material: ShellMaterial, k: ArrayLike) -> F:
    """``M_s(k)`` (N m/m) at curvatures ``k >= 0`` (1/m), any shape."""
    k = np.asarray(k, dtype=float)
    ky, d = material.yield_curvature, material.bending_stiffness
    with np.errstate(divide="ignore", invalid="ignore"):
        plastic = material.plastic_moment * (1.0 - (ky / k) ** 2 / 3.0)
    return np.where(k <= ky, d * k, plastic)


def skeleton_slope(material: ShellMaterial, k: ArrayLike) -> F:
    """``dM_s/dk`` (N m) at curvatures ``k >= 0``: ``D`` in the elastic range,
    ``(2 / 3) M_p kappa_y^2 / k^3`` beyond (the tangent of the skeleton)."""
    k = np.asarray(k, dtype=float)
    ky, d = material.yield_curvature, material.bending_stiffness
    with np.errstate(divide="ignore", invalid="ignore"):
        plastic = 2.0 / 3.0 * material.plastic_moment * ky**2 / k**3
    return np.where(k <= ky, d, plastic)


def skeleton_work(material: ShellMaterial, k: ArrayLike) -> F:
    """``W_s(k) = integral_0^k M_s`` (J/m^2): the work of bending to ``k`` along the skeleton."""
    k = np.asarray(k, dtype=float)
    ky, d, mp = material.yield_curvature, material.bending_stiffness, material.plastic_moment
    with np.errstate(divide="ignore", invalid="ignore"):
        plastic = d * ky**2 / 2 + mp * (k - ky) + mp * ky**2 / 3 * (1.0 / k - 1.0 / ky)
    return np.where(k <= ky, d * k**2 / 2, plastic)


def skeleton_curvature(material: ShellMaterial, alpha: ArrayLike) -> F:
    """``k*`` (1/m) with ``k* - M_s(k*) / D = alpha``: the skeleton's curvature
    after a plastic curvature ``alpha >= 0`` (``kappa_y`` for none). Newton's
    method on the increasing ``k - M_s(k) / D`` (a few steps to rounding)."""
    a = np.asarray(alpha, dtype=float)
    ky, d = material.yield_curvature, material.bending_stiffness
    k = np.maximum(ky, a + 1.5 * ky)  # alpha + M_p / D: the asymptote
    for _ in range(60):
        f = k - skeleton_moment(material, k) / d - a
        df = 1.0 - skeleton_slope(material, k) / d
        step = np.where(df > 0, f / np.where(df > 0, df, 1.0), 0.0)
        k = np.maximum(k - step, ky)
        if np.all(np.abs(step) <= 1e-15 * k):
            break
    return np.where(a > 0, k, ky)


def moment(material: ShellMaterial, s: ArrayLike, alpha: ArrayLike) -> tuple[F, F, F]:
    """The moment law of faces with accumulated plastic curvature ``alpha`` at
    elastic-trial curvatures ``s = |b - b_p|`` (1/m).

    Returns:
        ``m = min(D s, M_s(s + alpha))`` (N m/m), its slope ``dm/ds`` (N m) and
        the energy ``integral_0^s m`` (J/m^2), each like ``s``.
    """
    s = np.asarray(s, dtype=float)
    a = np.asarray(alpha, dtype=float)
    d = material.bending_stiffness
    limit = skeleton_moment(material, skeleton_curvature(material, a)) / d  # the elastic range
    elastic = s <= limit
    m = np.where(elastic, d * s, skeleton_moment(material, s + a))
    slope = np.where(elastic, d, skeleton_slope(material, s + a))
    top = skeleton_work(material, limit + a)
    work = np.where(elastic, d * s**2 / 2, d * limit**2 / 2 + skeleton_work(material, s + a) - top)
    return m, slope, work


def equivalent_curvature(form_k: F, b: F) -> F:
    """(m,) ``sqrt(b^T K b)`` (1/m) for (m, 3, 3) forms and (m, 3) curvatures."""
    return np.sqrt(np.maximum(np.einsum("mi,mij,mj->m", b, form_k, b), 0.0))


@dataclass(frozen=True)
class PlasticState:
    """The plastic state of every face.

    Attributes:
        rest: (m, 3) the plastic rest form ``b_p`` (0 where the face never yielded).
        accumulated: (m,) the accumulated plastic curvature ``alpha`` (1/m).
        reached: (m, 3) the curvature where the face last yielded (0: never),
            the reference of the reverse-yield check.
    """

    rest: F
    accumulated: F
    reached: F

    def plastic(self, material: ShellMaterial) -> NDArray[np.bool_]:
        """(m,) bool: faces that yielded."""
        return self.accumulated > 0.0


def virgin_state(n_faces: int) -> PlasticState:
    """The state of a sheet never bent."""
    return PlasticState(np.zeros((n_faces, 3)), np.zeros(n_faces), np.zeros((n_faces, 3)))


def form(material: ShellMaterial, form_k: F, b: F, area: F) -> tuple[PlasticState, F]:
    """The forming update: bend every face from flat to ``b`` along the skeleton.

    Args:
        form_k: (m, 3, 3) the faces' quadratic forms (``Shell.form``).
        b: (m, 3) the formed second fundamental forms.
        area: (m,) reference areas (m^2).

    Returns:
        The state, and (m,) the work of forming per face (J).
    """
    state = update(material, form_k, b, virgin_state(len(b)))[0]
    return state, area * skeleton_work(material, equivalent_curvature(form_k, b))


def update(
    material: ShellMaterial, form_k: F, b: F, state: PlasticState
) -> tuple[PlasticState, NDArray[np.bool_]]:
    """The state after the faces reached the curvatures ``b`` (m, 3) from ``state``
    (the return mapping): where the elastic trial ``s = |b - b_p|`` is past the
    elastic range, the plastic curvature grows along ``b - b_p`` by ``s - m / D``.
    Returns the state and which faces yielded."""
    r = b - state.rest
    s = equivalent_curvature(form_k, r)
    m, _, _ = moment(material, s, state.accumulated)
    grow = s - m / material.bending_stiffness
    yielded = grow > 1e-12 * np.maximum(s, 1e-300)
    with np.errstate(divide="ignore", invalid="ignore"):
        step = np.where(yielded[:, None], r * (grow / np.where(s > 0, s, 1.0))[:, None], 0.0)
    reached = np.where(yielded[:, None], b, state.reached)
    new = PlasticState(state.rest + step, state.accumulated + np.where(yielded, grow, 0.0), reached)
    return new, yielded


def check(material: ShellMaterial, form_k: F, b: F, state: PlasticState) -> NDArray[np.bool_]:
    """(m,) bool: yielded faces whose moment has changed since they last yielded
    by more than ``2 M_y`` against it (a rectangular section yields in reverse
    there, which this model, with isotropic hardening, does later)."""
    d = material.bending_stiffness
    then = state.reached - state.rest
    now = b - state.rest
    change = d * equivalent_curvature(form_k, now - then)
    against = np.einsum("mi,mij,mj->m", now - then, form_k, then) < 0
    return state.plastic(material) & against & (change > 2.0 * material.yield_moment * (1 + 1e-9))
