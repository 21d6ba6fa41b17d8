"""The shell's faces as J2 sections: the law, the rule through the thickness
and every face's internal variables, and the map from a face's covariant
strains to the Cartesian ones the law reads.

A face's membrane strain ``eps = (a - abar) / 2`` and curvature ``b - bbar``
are covariant 3-vectors ``(s11, s12, s22)`` in the face's parametric
coordinates (:mod:`onefold_cad.mechanics.energy`). On the orthonormal frame
of its reference triangle (first axis along its first edge) the same tensor
has Cartesian components ``G^-T S G^-1``, ``abar = G^T G`` (Cholesky); in the
law's Voigt form ``(e11, e22, 2 e12)`` that is a linear map ``L`` per face
(:func:`cartesian_map`), with ``s^T K s = (L s)^T C (L s) / E'`` for the
strain energy's form ``K`` (``material.strain_form``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from onefold_cad.mechanics.j2.law import J2Law, J2State
from onefold_cad.mechanics.j2.section import SectionResponse, ThicknessRule, section_update

__all__ = ["Plasticity", "cartesian_map", "form_along"]

F = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class Plasticity:
    """J2 plasticity through the thickness of every face.

    Attributes:
        law: the material law.
        rule: the points through the thickness.
        state: the faces' internal variables, shape ``(m, points)``, at the
            start of the current load increment.
    """

    law: J2Law
    rule: ThicknessRule
    state: J2State

    @classmethod
    def virgin(cls, law: J2Law, rule: ThicknessRule, n_faces: int) -> Plasticity:
        """Faces never strained plastically."""
        return cls(law, rule, J2State.virgin((n_faces, rule.points)))

    def moved_on(self, state: J2State) -> Plasticity:
        """The same law with the internal variables after an increment."""
        return Plasticity(self.law, self.rule, state)

    def respond(self, membrane: F, curvature: F, faces: slice | None = None) -> SectionResponse:
        """The sections of ``faces`` (all: None) at Cartesian ``membrane`` and
        ``curvature`` strains (``(c, 3)`` each) from their state."""
        s = self.state
        if faces is not None:
            s = J2State(s.plastic_strain[faces], s.back_stress[faces], s.equivalent[faces])
        return section_update(self.law, self.rule, membrane, curvature, s)


def cartesian_map(abar: F) -> F:
    """(m, 3, 3) ``L``: covariant ``(s11, s12, s22)`` -> Cartesian Voigt
    ``(e11, e22, 2 e12)`` on the reference triangle's orthonormal frame, for
    the (m, 3) reference metrics ``abar = (a11, a12, a22)``."""
    a11, a12, a22 = abar[:, 0], abar[:, 1], abar[:, 2]
    g11 = np.sqrt(a11)
    g12 = a12 / g11
    g22 = np.sqrt(np.maximum(a22 - g12**2, 0.0))
    # G = [[g11, g12], [0, g22]] (columns: the parametric basis in the frame);
    # H = G^-1 = [[1/g11, -g12/(g11 g22)], [0, 1/g22]];  E = H^T S H.
    h11, h12, h22 = 1.0 / g11, -g12 / (g11 * g22), 1.0 / g22
    out = np.zeros((len(abar), 3, 3))
    # E11 = h11^2 S11
    out[:, 0, 0] = h11**2
    # E22 = h12^2 S11 + 2 h12 h22 S12 + h22^2 S22
    out[:, 1, 0], out[:, 1, 1], out[:, 1, 2] = h12**2, 2 * h12 * h22, h22**2
    # E12 = h11 h12 S11 + h11 h22 S12; Voigt 2 E12
    out[:, 2, 0], out[:, 2, 1] = 2 * h11 * h12, 2 * h11 * h22
    return out


def form_along(plasticity: Plasticity, membrane: F, curvature: F, steps: int) -> SectionResponse:
    """Every face strained from its state to ``membrane`` and ``curvature``
    ((m, 3) Cartesian) proportionally in ``steps`` equal increments at the
    material points (a forming machine's path: the form imposed as a whole,
    no equilibrium to solve); the last increment's response, whose state is
    the formed one."""
    resp = None
    p = plasticity
    for i in range(1, steps + 1):
        s = i / steps
        resp = p.respond(s * membrane, s * curvature)
        p = p.moved_on(resp.state)
    assert resp is not None
    return resp
