"""The sheet's section: J2 plasticity integrated through the thickness.

At height ``z`` from the mid-surface (``-t/2 .. t/2``) the strain is the
membrane strain plus ``z`` times the curvature (Kirchhoff), each point
follows the plane-stress J2 law (:mod:`onefold_cad.mechanics.j2.law`), and the
section's resultants are the integrals over the thickness (per unit length
of the mid-surface)::

    N = int sigma dz (N/m),   M = int z sigma dz (N m/m),
    d(N, M) / d(eps, kappa) = int [[1, z], [z, z^2]] C_alg dz

The rule is composite Simpson on ``points`` (odd) equally spaced heights:
it holds both surfaces (where a sheet yields first and where its stress is
reported) and the mid-surface (where a bent section's stress changes sign),
integrates an elastic section exactly, and a fully plastic one exactly too;
between them the error falls as ``points^-2`` (tests/mechanics show how the
moment converges). Membrane and bending yield together, and unloading and
reverse yielding follow the law. Vectors are Voigt on an orthonormal frame:
strains ``(e11, e22, g12)``, curvatures ``(k11, k22, 2 k12)`` (1/m).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from onefold_cad.errors import InvalidParameterError
from onefold_cad.mechanics.j2.law import J2Law, J2State, update

__all__ = ["DEFAULT_POINTS", "SectionResponse", "ThicknessRule", "section_update"]

F = NDArray[np.float64]

#: Integration points through the thickness unless told otherwise.
DEFAULT_POINTS = 9


@dataclass(frozen=True)
class ThicknessRule:
    """Composite Simpson's rule through a thickness.

    Attributes:
        thickness: t (m).
        points: the number of heights, odd, >= 3.
    """

    thickness: float
    points: int = DEFAULT_POINTS

    def __post_init__(self) -> None:
        if not (self.points >= 3 and self.points % 2 == 1):
            raise InvalidParameterError(
                "points", f"through the thickness must be odd and >= 3, got {self.points!r}"
            )
        if not self.thickness > 0:
            raise InvalidParameterError("thickness", f"must be > 0, got {self.thickness!r}")

    @property
    def heights(self) -> F:
        """(points,) z from ``-t/2`` (one surface) to ``t/2`` (the other) (m)."""
        return np.linspace(-self.thickness / 2.0, self.thickness / 2.0, self.points)

    @property
    def weights(self) -> F:
        """(points,) Simpson's weights (m), summing to ``t``."""
        h = self.thickness / (self.points - 1)
        w = np.ones(self.points)
        w[1:-1:2], w[2:-1:2] = 4.0, 2.0
        return w * h / 3.0


@dataclass(frozen=True)
class SectionResponse:
    """The response of sections (leading shape ``S``, e.g. the faces).

    Attributes:
        force: ``S + (3,)`` N (N/m).
        moment: ``S + (3,)`` M (N m/m).
        tangent: ``S + (6, 6)`` d(N, M) / d(eps, kappa).
        energy: ``S`` the incremental energy per unit area (J/m^2), whose
            gradient is ``(N, M)``.
        stress: ``S + (points, 3)`` the stress at each height (Pa).
        state: the internal variables after the step, ``S + (points,)``.
        plastic: ``S + (points,)`` bool, the points that flowed in this step.
    """

    force: F
    moment: F
    tangent: F
    energy: F
    stress: F
    state: J2State
    plastic: NDArray[np.bool_]


def section_update(
    law: J2Law, rule: ThicknessRule, membrane: F, curvature: F, state: J2State
) -> SectionResponse:
    """Sections strained to ``membrane`` and ``curvature`` (``S + (3,)`` each)
    from ``state`` (``S + (points,)``): their resultants, tangent, energy and
    new state.

    Raises:
        ConvergenceError: the return mapping failed at some point.
    """
    eps_m = np.asarray(membrane, dtype=float)
    kappa = np.asarray(curvature, dtype=float)
    z, w = rule.heights, rule.weights
    strain = eps_m[..., None, :] + z[:, None] * kappa[..., None, :]
    resp = update(law, strain, state)
    sigma, c = resp.stress, resp.tangent
    force = np.einsum("k,...ki->...i", w, sigma)
    moment = np.einsum("k,...ki->...i", w * z, sigma)
    shape = eps_m.shape[:-1]
    tangent = np.empty(shape + (6, 6))
    tangent[..., :3, :3] = np.einsum("k,...kij->...ij", w, c)
    tangent[..., :3, 3:] = np.einsum("k,...kij->...ij", w * z, c)
    tangent[..., 3:, :3] = np.swapaxes(tangent[..., :3, 3:], -1, -2)
    tangent[..., 3:, 3:] = np.einsum("k,...kij->...ij", w * z * z, c)
    energy = np.einsum("k,...k->...", w, resp.energy)
    return SectionResponse(force, moment, tangent, energy, sigma, resp.state, resp.plastic)
