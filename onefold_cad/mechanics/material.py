"""The sheet's material and the isotropic quadratic forms of the strain energies.

SI units throughout (Pa, m, kg/m^3). The plane-stress energy density of a
mixed (``abar^-1``-raised) strain tensor ``M`` is proportional to
``nu tr(M)^2 + (1 - nu) tr(M^2)``; with the symmetric covariant strain stored
as the 3-vector ``(s11, s12, s22)`` that is the quadratic form ``s^T K s``
built by ``strain_form``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from onefold_cad.errors import InvalidParameterError

__all__ = ["ShellMaterial", "check_hardening", "invert_metric", "strain_form"]

F = NDArray[np.float64]
STANDARD_GRAVITY = 9.80665  # m/s^2


@dataclass(frozen=True)
class ShellMaterial:
    """An isotropic elastic-perfectly-plastic sheet.

    Attributes:
        youngs_modulus: E (Pa).
        poisson: nu, in (-1, 0.5).
        thickness: t (m).
        density: rho (kg/m^3).
        yield_stress: sigma_y (Pa); ``inf`` for a sheet that never yields.
        hardening_iso, hardening_kin: the linear isotropic and kinematic
            hardening moduli (Pa, >= 0; both 0: perfectly plastic), read by
            the J2 law (:mod:`onefold_cad.mechanics.j2.law`).
    """

    youngs_modulus: float
    poisson: float
    thickness: float
    density: float = 0.0
    yield_stress: float = math.inf
    hardening_iso: float = 0.0
    hardening_kin: float = 0.0

    def __post_init__(self) -> None:
        for name in ("youngs_modulus", "thickness"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise InvalidParameterError(name, f"must be finite and > 0, got {value!r}")
        if not (-1.0 < self.poisson < 0.5):
            raise InvalidParameterError("poisson", f"must lie in (-1, 0.5), got {self.poisson!r}")
        if not (math.isfinite(self.density) and self.density >= 0):
            raise InvalidParameterError("density", f"must be finite and >= 0, got {self.density!r}")
        if not self.yield_stress > 0:
            raise InvalidParameterError("yield_stress", f"must be > 0, got {self.yield_stress!r}")
        check_hardening(self.hardening_iso, self.hardening_kin)

    def with_changes(self, **changes: float) -> ShellMaterial:
        """A copy with some fields replaced."""
        return replace(self, **changes)

    @property
    def plane_modulus(self) -> float:
        """E' = E / (1 - nu^2) (Pa)."""
        return self.youngs_modulus / (1.0 - self.poisson**2)

    @property
    def bending_stiffness(self) -> float:
        """D = E t^3 / (12 (1 - nu^2)) (N m)."""
        return self.plane_modulus * self.thickness**3 / 12.0

    @property
    def membrane_stiffness(self) -> float:
        """E' t (N/m)."""
        return self.plane_modulus * self.thickness

    @property
    def yield_curvature(self) -> float:
        """kappa_y = 2 sigma_y / (E' t) (1/m): the outer fibres reach sigma_y."""
        return 2.0 * self.yield_stress / (self.plane_modulus * self.thickness)

    @property
    def yield_moment(self) -> float:
        """M_y = D kappa_y = sigma_y t^2 / 6 (N m/m)."""
        return self.yield_stress * self.thickness**2 / 6.0

    @property
    def plastic_moment(self) -> float:
        """M_p = sigma_y t^2 / 4 (N m/m)."""
        return self.yield_stress * self.thickness**2 / 4.0

    @property
    def areal_weight(self) -> float:
        """q = rho g t (N/m^2) under standard gravity."""
        return self.density * STANDARD_GRAVITY * self.thickness


def check_hardening(hardening_iso: float, hardening_kin: float) -> None:
    """Refuse a hardening modulus (Pa) that is negative or not finite, naming it.

    Raises:
        InvalidParameterError: ('hardening_iso' or 'hardening_kin').
    """
    for name, value in (("hardening_iso", hardening_iso), ("hardening_kin", hardening_kin)):
        if not (math.isfinite(value) and value >= 0):
            raise InvalidParameterError(name, f"must be finite and >= 0 Pa, got {value!r}")


def invert_metric(abar: F) -> F:
    """(m, 3) metrics ``(a11, a12, a22)`` -> (m, 3) their inverses, same layout."""
    det = abar[:, 0] * abar[:, 2] - abar[:, 1] ** 2
    return np.stack([abar[:, 2], -abar[:, 1], abar[:, 0]], axis=1) / det[:, None]


def strain_form(abar: F, poisson: float) -> F:
    """(m, 3, 3) ``K`` with ``s^T K s = nu tr(A s)^2 + (1 - nu) tr((A s)^2)``, ``A = abar^-1``.

    ``s = (s11, s12, s22)`` holds a symmetric covariant tensor, ``abar`` the (m, 3)
    reference metrics.
    """
    inv = invert_metric(abar)
    a = np.empty((len(abar), 2, 2))
    a[:, 0, 0], a[:, 0, 1], a[:, 1, 0], a[:, 1, 1] = inv[:, 0], inv[:, 1], inv[:, 1], inv[:, 2]
    basis = np.array([[[1.0, 0.0], [0.0, 0.0]], [[0.0, 1.0], [1.0, 0.0]], [[0.0, 0.0], [0.0, 1.0]]])
    raised = np.einsum("mij,bjk->mbik", a, basis)  # A E_b
    trace = np.einsum("mbii->mb", raised)
    both = np.einsum("mbij,mcji->mbc", raised, raised)
    return poisson * trace[:, :, None] * trace[:, None, :] + (1.0 - poisson) * both
