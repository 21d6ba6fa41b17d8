"""``onefold simulate``'s forming sequence with J2 plasticity through the
thickness (the default law): the flat sheet formed into the design, released
(springback) and stood on the ground, the sections' internal variables carried
from each stage to the next (:mod:`onefold_cad.mechanics.j2.stages`), and what
each stage says (:mod:`onefold_cad.mechanics.j2.measures`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from onefold_cad.choices import Law
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import Array
from onefold_cad.mechanics.equilibrium import PathStalled
from onefold_cad.mechanics.j2 import stages as j2_stages
from onefold_cad.mechanics.j2.measures import (
    Surfaces,
    forming_work,
    largest_at,
    radius_from_h,
    surfaces,
    yielded_after,
)
from onefold_cad.mechanics.j2.stages import J2Stage
from onefold_cad.mechanics.model import SheetModel
from onefold_cad.mechanics.newton import Progress
from onefold_cad.mechanics.reserve import ReserveCheck
from onefold_cad.mechanics.results import FormedResult, Released, Standing
from onefold_cad.mechanics.shell import Shell, unpack
from onefold_cad.mechanics.stages import place
from onefold_cad.mechanics.standing_measures import (
    aligned_deviation,
    area_share,
    stalled,
    standing_result,
)
from onefold_cad.mechanics.verdicts import RESERVE_PENDING, with_reserve

__all__ = ["J2Formed", "J2Run", "form_j2", "run_j2"]

#: ``progress_for(stage)``: the Newton progress of a named stage, or None.
ProgressFor = Callable[[str], Progress | None]


@dataclass(frozen=True)
class J2Run:
    """The stages' results and the per-face fields of each stage.

    Attributes:
        formed, released, standing: the report's values.
        released_at: ``(n, 3)`` the released nodes as the standing start
            placed them (m).
        stress_MPa: ``(m,)`` the standing sheet's larger surface von Mises
            stress, None when it does not stand.
        deviation: ``(n,)`` the standing nodes' distance from the design
            (design unit), None when it does not stand.
        fields: per stage (``formed``, ``released``, ``standing``) its
            :class:`~onefold_cad.mechanics.j2.measures.Surfaces`.
        positions: per stage its nodes (m; formed and released in the fold
            frame, standing in the resting frame).
        pending: the coarse preview's reserve check left for later
            (``reserve`` False), else None.
    """

    formed: FormedResult
    released: Released
    released_at: Array
    standing: Standing
    stress_MPa: Array | None
    deviation: Array | None
    fields: dict[str, Surfaces]
    positions: dict[str, Array]
    pending: ReserveCheck | None = None


@dataclass(frozen=True)
class J2Formed:
    """The flat sheet formed into the design with J2 sections.

    Attributes:
        shell: the model's shell with the J2 sections (virgin).
        stage: the formed stage (its internal variables).
        surfaces: its surface values.
        result: the report's values.
    """

    shell: Shell
    stage: J2Stage
    surfaces: Surfaces
    result: FormedResult


def form_j2(model: SheetModel) -> J2Formed:
    """Form ``model``'s flat sheet into the design (imposed: no equilibrium to
    solve) and measure it: where the surfaces yield, the largest plastic
    strain and where, the work of forming."""
    shell = j2_stages.j2_shell(model)
    formed = j2_stages.form(model, shell)
    f_surf = surfaces(formed)
    peeq = f_surf.face_plastic_strain
    yielded = peeq > 0
    top, at = largest_at(model, peeq)
    result = FormedResult(
        bending_energy_J=forming_work(model, formed),
        plastic_area_share=area_share(model, yielded),
        plastic_radius_max=radius_from_h(model, yielded),
        max_plastic_strain=top,
        max_plastic_strain_at=at,
        max_stress_MPa=float(f_surf.face_stress.max() / 1e6),
    )
    return J2Formed(shell, formed, f_surf, result)


def run_j2(
    model: SheetModel,
    folded: FoldedSheet,
    supports: str,
    unit: str,
    progress_for: ProgressFor,
    lap: Callable[[str], None],
    *,
    size: float,
    coarse: bool = False,
    reserve: bool = True,
) -> J2Run:
    """Form, release and stand ``model``'s sheet with J2 sections; ``lap(stage)``
    after each stage (its CPU time). On the ``coarse`` preview mesh a sheet
    that stands must carry :data:`~onefold_cad.mechanics.reserve.COARSE_RESERVE`
    times its weight to be a plain yes (a
    :class:`~onefold_cad.mechanics.reserve.ReserveCheck` with
    :func:`j2_stages.reserve_shell`), else it is "uncertain: run --mesh
    normal", as the moment law's preview; with
    ``reserve`` False the check is left for later: such a sheet stays
    "uncertain" (:data:`~onefold_cad.mechanics.verdicts.RESERVE_PENDING`) and
    the run's ``pending`` holds its check (``size``: the sheet's, design
    unit, for its warnings' wording).

    Raises:
        ConvergenceError: the release did not converge, or a return mapping
            failed (its residual named); a stand that stalls is an answer.
    """
    j2f = form_j2(model)
    shell, formed, f_surf, formed_result = j2f.shell, j2f.stage, j2f.surfaces, j2f.result
    lap("formed")
    rel = j2_stages.release(model, shell, formed, progress_for("released"))
    xr = unpack(model.mesh, rel.q)[0]
    max_dev, rms_dev = aligned_deviation(model, folded, xr)
    placed = place(model, rel.q)
    xp = unpack(model.mesh, placed.q)[0]
    assert rel.equilibrium is not None
    again = yielded_after(formed.plasticity, rel.plasticity)
    released = Released(
        max_dev,
        rms_dev,
        float(xp[:, 2].max() / model.scale),
        float(np.ptp(xp[:, 0]) / model.scale),
        rel.equilibrium.iterations,
        area_share(model, again),
    )
    lap("released")
    fields = {"formed": f_surf, "released": surfaces(rel)}
    positions = {"formed": model.designed, "released": xr}
    try:
        st = j2_stages.stand(
            model, shell, placed, rel.plasticity, supports, progress_for("standing")
        )
    except PathStalled as err:
        lap("standing")
        standing = stalled(model, placed, err, supports, unit)
        return J2Run(formed_result, released, xp, standing, None, None, fields, positions)
    assert st.equilibrium is not None
    s_surf = surfaces(st)
    stress = s_surf.face_stress / 1e6
    peeq_s = s_surf.face_plastic_strain
    top_s, at_s = largest_at(model, peeq_s)
    standing, dev = standing_result(
        model,
        folded,
        placed,
        st.equilibrium,
        stress,
        model.material.yield_stress / 1e6,
        reloaded_area_share=area_share(model, yielded_after(rel.plasticity, st.plasticity)),
        max_plastic_strain=top_s,
        max_plastic_strain_at=at_s,
        plastic_area_share=area_share(model, peeq_s > 0),
    )
    pending = None
    if coarse and standing.stands:
        moved = j2_stages.reserve_shell(shell, placed, st)
        check = ReserveCheck(model, placed, st.equilibrium, moved, supports, Law.J2.value, size)
        if reserve:
            standing = with_reserve(standing, check.carried(progress_for("standing")))
        else:
            standing, pending = replace(standing, uncertain=RESERVE_PENDING), check
    lap("standing")
    fields["standing"] = s_surf
    positions["standing"] = st.equilibrium.positions
    return J2Run(formed_result, released, xp, standing, stress, dev, fields, positions, pending)
