"""What the J2 stages say about the steel, face by face and as the report's
numbers: the von Mises stress at the sheet's two surfaces, the equivalent
plastic strain (PEEQ), where each is largest, the area shares that yielded,
the work of forming and the resultants through the thickness.

The surfaces are integration points of the section rule (composite Simpson
from ``-t/2`` to ``t/2``, :class:`~onefold_cad.mechanics.section.ThicknessRule`),
so the surface values are the law's own, never extrapolated: the stress there
is at most the flow stress of the law.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from onefold_cad.geometry.numeric import Array
from onefold_cad.mechanics.j2 import J2Law, elastic_matrix, von_mises
from onefold_cad.mechanics.j2_stages import J2Stage
from onefold_cad.mechanics.layered import Plasticity
from onefold_cad.mechanics.model import SheetModel

__all__ = [
    "Surfaces",
    "flow_stress",
    "forming_work",
    "largest_at",
    "radius_from_h",
    "surfaces",
    "yielded_after",
]


@dataclass(frozen=True)
class Surfaces:
    """A stage's values at the sheet's two surfaces, per face.

    Attributes:
        stress: ``(m, 2)`` von Mises stress at the surfaces ``z = -t/2, +t/2`` (Pa).
        plastic_strain: ``(m, 2)`` equivalent plastic strain there.
        flow: ``(m, 2)`` the flow stress there (Pa): the yield stress grown
            by isotropic hardening; the radius of the yield surface about the
            back stress.
        force: ``(m, 3)`` membrane forces ``(N11, N22, N12)`` (N/m) on each
            face's reference frame (its first edge along the first axis).
        moment: ``(m, 3)`` bending moments ``(M11, M22, M12)`` (N m / m).
    """

    stress: Array
    plastic_strain: Array
    flow: Array
    force: Array
    moment: Array

    @property
    def face_stress(self) -> Array:
        """``(m,)`` the larger surface stress of each face (Pa)."""
        return self.stress.max(axis=1)

    @property
    def face_plastic_strain(self) -> Array:
        """``(m,)`` the larger surface PEEQ of each face."""
        return self.plastic_strain.max(axis=1)


def flow_stress(law: J2Law, equivalent: Array) -> Array:
    """The flow stress (Pa) at accumulated plastic strain ``equivalent``:
    ``sigma_y + H_iso alpha`` (kinematic hardening moves the surface, it does
    not grow it)."""
    return law.yield_stress + law.hardening_iso * np.asarray(equivalent, dtype=float)


def surfaces(stage: J2Stage) -> Surfaces:
    """The stage's surface values and resultants (see :class:`Surfaces`)."""
    p = stage.plasticity
    sigma = stage.response.stress  # (m, points, 3), in the increment's end state
    back = p.state.back_stress
    alpha = p.state.equivalent
    outer = [0, -1]
    # the von Mises stress of sigma itself (what a gauge reads); with kinematic
    # hardening it may pass sigma_y + H_iso alpha by |beta|, as the law allows.
    vm = von_mises(sigma[:, outer])
    flow = flow_stress(p.law, alpha[:, outer]) + von_mises(back[:, outer])
    return Surfaces(
        stress=vm,
        plastic_strain=alpha[:, outer],
        flow=flow,
        force=stage.response.force,
        moment=stage.response.moment,
    )


def yielded_after(before: Plasticity, after: Plasticity) -> Array:
    """``(m,)`` bool: faces where either surface's plastic strain grew from
    ``before`` to ``after`` (yielded again)."""
    a = before.state.equivalent[:, [0, -1]]
    b = after.state.equivalent[:, [0, -1]]
    return np.any(b > a + 1e-12, axis=1)


def forming_work(model: SheetModel, stage: J2Stage) -> float:
    """The work (J) of forming the flat sheet into ``stage`` along a monotone
    path: the elastic energy stored, plus the hardening energy stored, plus the
    plastic dissipation ``sigma_y alpha``, integrated through the thickness
    and over the faces' reference areas."""
    p = stage.plasticity
    law, st = p.law, p.state
    c = elastic_matrix(law)
    s_inv = np.linalg.inv(c)
    sigma = stage.response.stress
    elastic = 0.5 * np.einsum("fki,ij,fkj->fk", sigma, s_inv, sigma)
    # the back stress's stored energy, H_kin / 3 eps_p : eps_p (3D norm)
    e = st.plastic_strain
    e11, e22, g12 = e[..., 0], e[..., 1], e[..., 2]
    kin = law.hardening_kin / 3.0 * (e11**2 + e22**2 + (e11 + e22) ** 2 + g12**2 / 2.0)
    alpha = st.equivalent
    density = elastic + kin + law.hardening_iso * alpha**2 / 2.0 + law.yield_stress * alpha
    per_area = density @ p.rule.weights  # J/m^2
    return float(per_area @ model.shell.ref_area)


def largest_at(model: SheetModel, values: Array) -> tuple[float, Array | None]:
    """The largest of per-face ``values`` and its face's centroid on the flat
    sheet (design unit, fold frame: H at the origin); ``(0, None)`` when all are 0."""
    if len(values) == 0 or not np.any(values > 0):
        return 0.0, None
    i = int(np.argmax(values))
    at = model.mesh.nodes[model.mesh.triangles[i]].mean(axis=0) / model.scale
    return float(values[i]), at


def radius_from_h(model: SheetModel, faces: Array) -> float:
    """The largest distance from H of the centroids of ``faces`` ((m,) bool),
    design unit (0 when there are none)."""
    if not np.any(faces):
        return 0.0
    c = model.mesh.nodes[model.mesh.triangles[faces]].mean(axis=1)
    return float(np.hypot(c[:, 0], c[:, 1]).max() / model.scale)
