"""The cones formed past their springback: the curvature each point of a cone
must be formed to so that, released, it keeps the design's.

A cone is bent across its rulings only (along a ruling the sheet stays
straight), so its sections bend in plane strain. Formed to a curvature
``kappa_f`` along ``form_to``'s proportional path and let go, a section
keeps the curvature at which its moment about the bent direction is zero
again (:func:`released_curvature`): nothing below the plane-strain first
yield, ``kappa_f - M / D'`` after an elastic unloading above it, and what
the J2 law gives where the unloading yields in reverse. The inverse
(:class:`SpringbackTable`, tabulated once per law and section) is what the
forming machine is set to: ``onefold simulate`` forms each face of a design
whose material has ``cone_forming = "compensated"`` to it
(:func:`compensated_curvatures`), and ``onefold build`` writes the radii
per ruling station (``NAME-cones.csv``).

SI units: curvatures in 1/m.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from onefold_cad.mechanics.j2.law import J2Law
from onefold_cad.mechanics.j2.layered import Plasticity, form_along
from onefold_cad.mechanics.j2.section import ThicknessRule

__all__ = [
    "SpringbackTable",
    "compensated_curvatures",
    "first_yield_curvature",
    "released_curvature",
]

F = NDArray[np.float64]

#: Bisection steps for the released curvature (the bracket halves each: 2^-60).
BISECTIONS = 60
#: The table's formed curvatures, in plane-strain first-yield curvatures.
TABLE_RANGE = (0.5, 400.0)
#: The table's points (geometric spacing).
TABLE_POINTS = 400


def first_yield_curvature(law: J2Law, thickness: float) -> float:
    """The curvature (1/m) at which a section bent in plane strain first
    yields at its surfaces: ``2 sigma_y / (E' t sqrt(1 - nu + nu^2))``."""
    nu = law.poisson
    return 2.0 * law.yield_stress / (law.plane_modulus * thickness * math.sqrt(1 - nu + nu**2))


def released_curvature(law: J2Law, rule: ThicknessRule, formed: F, steps: int) -> F:
    """``(n,)`` the curvature (1/m) a virgin section keeps when, formed in
    plane strain to ``formed`` (``(n,)``, >= 0, as ``(kappa, 0, 0)``
    Cartesian with no membrane strain) in ``steps`` return mappings
    (``form_along``'s path), it is released to no moment about the bent direction, the
    curvature along the rulings held at zero (a cone's straight rulings hold
    it) and no membrane strain. The J2 section decides, reverse yielding
    included; found by bisection to 2^-60 of the bracket."""
    formed = np.asarray(formed, dtype=float)
    n = len(formed)
    zero = np.zeros(n)
    virgin = Plasticity.virgin(law, rule, n)
    bent = np.column_stack([formed, zero, zero])
    resp = form_along(virgin, np.zeros((n, 3)), bent, steps)
    state = virgin.moved_on(resp.state)
    stiffness = law.plane_modulus * rule.thickness**3 / 12.0
    # an elastic unloading by M / D' lands in the bracket; a reverse yield
    # unloads further (at most by twice the elastic step for this law)
    lo = formed - 4.0 * np.abs(resp.moment[:, 0]) / stiffness
    hi = formed.copy()
    for _ in range(BISECTIONS):
        mid = (lo + hi) / 2
        m = state.respond(np.zeros((n, 3)), np.column_stack([mid, zero, zero])).moment[:, 0]
        hi = np.where(m > 0, mid, hi)
        lo = np.where(m > 0, lo, mid)
    return (lo + hi) / 2


@dataclass(frozen=True, eq=False)
class SpringbackTable:
    """Formed and kept curvatures of a section (1/m), from
    :func:`released_curvature` over :data:`TABLE_RANGE` first-yield
    curvatures.

    Attributes:
        formed: ``(p,)`` increasing formed curvatures.
        kept: ``(p,)`` what each keeps after release (non-decreasing: its
            running maximum, 0 up to first yield).
    """

    formed: F
    kept: F

    @classmethod
    def of(cls, law: J2Law, rule: ThicknessRule, steps: int) -> SpringbackTable:
        """The table of ``law`` for sections of ``rule`` formed in ``steps``
        return mappings (as the sheet is: ``j2.stages.FORMING_STEPS``);
        computed once per law, rule and steps (a process's simulations of one
        material share it: a compensation runs dozens)."""
        return _tabulated(law, rule, steps)

    def forming(self, kept: F) -> F:
        """The curvatures (1/m) to form to so that ``kept`` (>= 0) is kept
        after release: interpolated in the table; 0 for 0 (nothing to
        form); past the table's end, ``kept`` plus its last springback."""
        k = np.asarray(kept, dtype=float)
        inside = np.interp(k, self.kept, self.formed)
        beyond = k + (self.formed[-1] - self.kept[-1])
        return np.where(k > 0, np.where(k > self.kept[-1], beyond, inside), 0.0)


@functools.lru_cache(maxsize=16)
def _tabulated(law: J2Law, rule: ThicknessRule, steps: int) -> SpringbackTable:
    first = first_yield_curvature(law, rule.thickness)
    formed = first * np.geomspace(*TABLE_RANGE, TABLE_POINTS)
    kept = np.maximum.accumulate(released_curvature(law, rule, formed, steps))
    formed.flags.writeable = kept.flags.writeable = False  # shared: read only
    return SpringbackTable(formed, kept)


def compensated_curvatures(curvatures: F, table: SpringbackTable) -> F:
    """``(m, 3)`` Cartesian curvatures (1/m, Voigt ``(k11, k22, 2 k12)``)
    each scaled so that its principal curvature (the trace: a cone's face
    is bent one way) is the one the table forms to keep it. A face with
    no curvature stays flat."""
    k = np.abs(curvatures[:, 0] + curvatures[:, 1])
    bent = k > 0
    factor = np.ones(len(k))
    factor[bent] = table.forming(k[bent]) / k[bent]
    return curvatures * factor[:, None]
