"""Strain paths of one section under mixed control, for the closed-form tests:
some of the six generalised strains ``(e11, e22, g12, k11, k22, 2 k12)``
prescribed, the resultants ``(N, M)`` conjugate to the others held at given
values (a narrow strip: ``N22 = M22 = 0``; a wide strip in cylindrical
bending: ``k22 = 0``), solved by Newton's method with the section's tangent."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from onefold_cad.mechanics.j2.law import J2Law, J2State
from onefold_cad.mechanics.j2.section import SectionResponse, ThicknessRule, section_update

#: The generalised strains of a narrow strip left free: transverse, shear, twist.
NARROW_FREE = (1, 2, 4, 5)
#: A wide strip (plane strain): only the transverse membrane strain and shear free.
WIDE_FREE = (1, 2, 5)


@dataclass
class Section:
    """One section with its state, stepped along a path."""

    law: J2Law
    rule: ThicknessRule
    free: Sequence[int]

    def __post_init__(self) -> None:
        self.state = J2State.virgin((self.rule.points,))
        self.strain = np.zeros(6)

    def step(self, prescribed: dict[int, float], targets: dict[int, float] | None = None
             ) -> SectionResponse:  # fmt: skip
        """Move to the prescribed strains, the free ones found so that their
        resultants are ``targets`` (default 0); the state moves on."""
        e = self.strain.copy()
        for i, v in prescribed.items():
            e[i] = v
        free = list(self.free)
        want = np.zeros(6)
        for i, v in (targets or {}).items():
            want[i] = v
        for _ in range(60):
            r = section_update(self.law, self.rule, e[:3], e[3:], self.state)
            res = np.concatenate([r.force, r.moment])[free] - want[free]
            t, sy = self.rule.thickness, self.law.yield_stress
            scale = np.array([sy * t] * 3 + [sy * t * t] * 3)[free]
            if np.max(np.abs(res) / scale) < 1e-12:
                break
            k = r.tangent[np.ix_(free, free)]
            e[free] -= np.linalg.solve(k, res)
        else:
            raise AssertionError(f"section path did not converge: {res}")
        self.strain = e
        self.state = r.state
        return r
