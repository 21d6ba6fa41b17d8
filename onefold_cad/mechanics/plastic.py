"""Elastic-perfectly-plastic bending of a rectangular section, per face, on the
equivalent curvature.

The law (per unit length, SI): ``M_s(k) = D k`` up to ``kappa_y = 2 sigma_y / (E' t)``,
``M_p (1 - (kappa_y / k)^2 / 3)`` beyond, ``M_p = sigma_y t^2 / 4``; unloading is
elastic with slope ``D``. A face's curvature is its second fundamental form ``b``
(the 3-vector ``(b11, b12, b22)``, parametric coordinates); its equivalent
curvature ``k = sqrt(b^T K b)`` (``K``: ``material.strain_form``) is ``|kappa|`` for
one-directional (developable) bending. The law acts on ``k`` along the face's
path from the flat sheet; forming is taken as monotonic and proportional.

A face's state is its reached point ``b_r`` (curvature ``k_r``) and its plastic rest
form ``b_p = b_r (1 - M_s(k_r) / (D k_r))``: the form it takes with no moment,
unloading elastically from the reached point. Reverse yielding (a moment change
of more than ``2 M_y`` against the forming) is not modelled; ``check`` reports it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.mechanics.material import ShellMaterial

__all__ = [
    "PlasticCheck",
    "PlasticState",
    "check",
    "equivalent_curvature",
    "form",
    "reload",
    "skeleton_moment",
    "skeleton_work",
    "unloading_energy",
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


def skeleton_work(material: ShellMaterial, k: ArrayLike) -> F:
    """``W_s(k) = integral_0^k M_s`` (J/m^2): the work of bending to ``k`` along the skeleton."""
    k = np.asarray(k, dtype=float)
    ky, d, mp = material.yield_curvature, material.bending_stiffness, material.plastic_moment
    with np.errstate(divide="ignore", invalid="ignore"):
        plastic = d * ky**2 / 2 + mp * (k - ky) + mp * ky**2 / 3 * (1.0 / k - 1.0 / ky)
    return np.where(k <= ky, d * k**2 / 2, plastic)


def equivalent_curvature(form_k: F, b: F) -> F:
    """(m,) ``sqrt(b^T K b)`` (1/m) for (m, 3, 3) forms and (m, 3) curvatures."""
    return np.sqrt(np.maximum(np.einsum("mi,mij,mj->m", b, form_k, b), 0.0))


@dataclass(frozen=True)
class PlasticState:
    """The plastic state of every face.

    Attributes:
        reached: (m, 3) the second fundamental form at the reached point ``b_r``.
        reached_curvature: (m,) its equivalent curvature ``k_r`` (1/m).
        rest: (m, 3) the plastic rest form ``b_p`` (0 where the face never yielded).
    """

    reached: F
    reached_curvature: F
    rest: F

    def plastic(self, material: ShellMaterial) -> NDArray[np.bool_]:
        """(m,) bool: faces bent past the yield curvature."""
        return self.reached_curvature > material.yield_curvature


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
    k = equivalent_curvature(form_k, b)
    d = material.bending_stiffness
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(k > 0, skeleton_moment(material, k) / (d * k), 1.0)
    rest = b * (1.0 - ratio)[:, None]
    return PlasticState(np.array(b, dtype=float), k, rest), area * skeleton_work(material, k)


def reload(
    material: ShellMaterial, form_k: F, b: F, state: PlasticState, faces: NDArray[np.bool_]
) -> PlasticState:
    """A new state where ``faces`` followed the skeleton on to ``b`` (others unchanged)."""
    fresh, _ = form(material, form_k[faces], b[faces], np.zeros(int(faces.sum())))
    reached, kr, rest = state.reached.copy(), state.reached_curvature.copy(), state.rest.copy()
    reached[faces], kr[faces], rest[faces] = fresh.reached, fresh.reached_curvature, fresh.rest
    return PlasticState(reached, kr, rest)


def unloading_energy(material: ShellMaterial, form_k: F, b: F, state: PlasticState, area: F) -> F:
    """(m,) elastic energy ``Abar D/2 k(b - b_p)^2`` of each face about its rest form (J)."""
    k = equivalent_curvature(form_k, b - state.rest)
    return area * material.bending_stiffness / 2 * k**2


@dataclass(frozen=True)
class PlasticCheck:
    """Faces whose current curvature leaves the elastic range of their state.

    Attributes:
        beyond: (m,) bool, equivalent curvature past the reached one (and past
            ``kappa_y``): the face follows the skeleton again.
        reverse: (m,) bool, yielded faces whose moment changed by more than ``2 M_y``
            against their forming (reverse yielding, not modelled).
    """

    beyond: NDArray[np.bool_]
    reverse: NDArray[np.bool_]


def check(
    material: ShellMaterial, form_k: F, b: F, state: PlasticState, rtol: float = 1e-6
) -> PlasticCheck:
    """Check (m, 3) curvatures ``b`` against the faces' states."""
    ky = material.yield_curvature
    k = equivalent_curvature(form_k, b)
    limit = np.maximum(state.reached_curvature, ky)
    along = np.einsum("mi,mij,mj->m", b - state.reached, form_k, state.reached)
    beyond = (k > limit * (1 + rtol)) & ((along >= 0) | (state.reached_curvature <= ky))
    change = equivalent_curvature(form_k, b - state.reached)
    reverse = state.plastic(material) & ~beyond & (change > 2 * ky * (1 + rtol)) & (along < 0)
    return PlasticCheck(beyond, reverse)
