"""What a simulation says in words: its warnings, and the coarse preview's
"stands" once its reserve check is done.

:func:`simulation_warnings` is the one home of ``Simulation.warnings`` (what
the law could not honour, whether it stands, how far its weight moved it,
its stress against the yield stress). :func:`with_reserve` turns a coarse
standing into the check's verdict (a plain yes only with
:data:`~onefold_cad.mechanics.reserve.COARSE_RESERVE`), and
:func:`settle_reserve` runs a check :func:`~onefold_cad.mechanics.simulate.run`
left for later (``reserve=False``: the explorer's Steel view shows the form
first; until then its standing is "uncertain", :data:`RESERVE_PENDING`) and
gives the simulation a run with the check would have given.
:func:`convergence_report` is the convergence check's section of the report
and its warning.
"""

from __future__ import annotations

import math
import time
from dataclasses import replace
from typing import Any

from onefold_cad.mechanics.newton import Progress
from onefold_cad.mechanics.reserve import COARSE_RESERVE, ReserveCheck
from onefold_cad.mechanics.results import Released, Simulation, Standing

__all__ = [
    "CONVERGED",
    "RESERVE_PENDING",
    "convergence_report",
    "past_converged",
    "settle_reserve",
    "simulation_warnings",
    "with_reserve",
]

#: The convergence check's bound: a larger relative change is warned about.
CONVERGED = 0.02

#: A coarse standing's ``uncertain`` while its reserve check is left for later:
#: until the check is done it is never a plain "stands".
RESERVE_PENDING = "its reserve check is not done yet"


def with_reserve(standing: Standing, reserve: float) -> Standing:
    """A coarse standing with its reserve check's answer (``reserve``: the
    multiple of its weight it was shown to carry)."""
    uncertain = ""
    if reserve < COARSE_RESERVE:
        uncertain = (
            f"the coarse preview does not carry {COARSE_RESERVE:g} times its weight, the "
            "margin its stiff mesh calls for: run --mesh normal"
        )
    return replace(standing, reserve=reserve, uncertain=uncertain)


def _law_warnings(law: str, released: Released | None, standing: Standing, reverse: int
                  ) -> list[str]:  # fmt: skip
    """What the law could not honour (the moment law: elastic unloading and
    membrane) or what the steel does that a user must know (J2: its weight
    makes it yield)."""
    out = []
    if law == "j2":
        if standing.reloaded_area_share > 0:
            out.append(
                f"standing, its weight makes {100 * standing.reloaded_area_share:.3g} % of the "
                "sheet's area yield again (largest plastic strain "
                f"{standing.max_plastic_strain or 0:.3g})"
            )
        return out
    if released is not None and released.reloaded_area_share > 0:
        out.append(
            f"in springback {100 * released.reloaded_area_share:.3g} % of the sheet's area bends "
            "past its elastic range; the moment law unloads every face elastically, so the "
            "springback is underestimated (on the steel templates by a third to two fifths "
            "against CalculiX, docs/mechanics.md; --law j2 follows the law)"
        )
    if standing.reloaded_area_share > 0:
        out.append(
            f"standing, {100 * standing.reloaded_area_share:.3g} % of the sheet's area is bent "
            "past its elastic range (springback and weight together; taken elastically, so the "
            "form there is an estimate)"
        )
    if reverse:
        out.append(
            f"{reverse} faces unload in springback by more than 2 M_y, past a rectangular "
            "section's reverse yield (kept elastic: the springback there is an estimate)"
        )
    return out


def simulation_warnings(
    law: str,
    released: Released | None,
    standing: Standing,
    reverse: int,
    *,
    coarse: bool,
    size: float,
    unit: str,
    yield_stress_MPa: float,
) -> tuple[str, ...]:
    """The simulation's warnings, one line each.

    Args:
        law: 'moment' or 'j2'.
        released, standing: the stages' results.
        reverse: faces past reverse yield in springback.
        coarse: the coarse preview mesh (a "does not stand" then hints at the
            normal mesh).
        size: the sheet's size (design unit).
        unit: the design's length unit.
        yield_stress_MPa: the yield stress used.
    """
    warnings = _law_warnings(law, released, standing, reverse)
    if standing.uncertain:
        warnings.append(f"whether it stands is uncertain: {standing.uncertain}")
    if not standing.stands:
        hint = ""
        if standing.max_deviation is None and coarse:
            hint = " (found on the coarse preview mesh: --mesh normal is the run to trust)"
        warnings.append(f"it does not stand: {standing.reason}{hint}")
    elif standing.max_displacement is not None and standing.max_displacement > 0.05 * size:
        warnings.append(
            f"it stands only after its weight moved it by up to {standing.max_displacement:.4g} "
            f"{unit} ({100 * standing.max_displacement / size:.2g} % of "
            "the sheet's size): a form far from the design"
        )
    elif law == "moment" and standing.utilisation is not None and standing.utilisation >= 1.0:
        at = standing.max_stress_at
        where = "" if at is None else f" {math.hypot(at[0], at[1]):.4g} {unit} from H"
        warnings.append(
            f"standing, the largest stress {standing.max_stress_MPa:.4g} MPa{where} reaches the "
            f"yield stress {yield_stress_MPa:.4g} MPa (residual bending and membrane "
            "stress, both taken elastic by the moment law: past yield it is an estimate; "
            "--law j2 gives the stress the steel can be in)"
        )
    return tuple(warnings)


def settle_reserve(
    sim: Simulation, check: ReserveCheck, progress: Progress | None = None
) -> Simulation:
    """``sim`` (a coarse run with ``reserve=False``) with its reserve check
    done: the standing's verdict and the warnings a run with the check would
    have given, the check's CPU seconds as ``timings_s['reserve']``.

    Args:
        sim: the simulation whose check was left for later.
        check: its pending check (``Simulation.pending_reserve``).
        progress: hears the check's Newton steps (may raise to give it up).
    """
    clock = time.process_time()
    reserve = check.carried(progress)
    standing = with_reserve(sim.standing, reserve)

    def said(s: Standing) -> tuple[str, ...]:
        return simulation_warnings(
            check.law, sim.released, s, sim.reverse_yield_faces, coarse=True, size=check.size,
            unit=sim.unit, yield_stress_MPa=sim.yield_stress_MPa,
        )  # fmt: skip

    later = sim.warnings[len(said(sim.standing)) :]  # simulate()'s convergence check, if run
    warnings = said(standing) + tuple(later)
    times = {**sim.timings_s, "reserve": time.process_time() - clock}
    return replace(sim, standing=standing, warnings=warnings, timings_s=times, pending_reserve=None)


def relative_change(a: float | None, b: float | None, ref: float | None) -> float | None:
    """|a - b| / |ref| (dimensionless), or None where a value is missing or
    ``ref`` is zero: the one measure of a convergence check's change."""
    if a is None or b is None or ref is None or ref == 0:
        return None
    return abs(a - b) / abs(ref)


def past_converged(a: float | None, b: float | None) -> float | None:
    """The relative change from ``a`` to ``b`` (relative to ``a``) when it is
    past :data:`CONVERGED`, else None."""
    change = relative_change(a, b, a)
    return change if change is not None and change > CONVERGED else None


def convergence_report(
    measured: tuple[str, float | None],
    checked: tuple[str, float | None],
    finer: bool,
    mesh: dict[str, Any],
    coarser_change: float | None,
) -> tuple[dict[str, Any], list[str]]:
    """The report's ``convergence`` section and its warning (none when the
    check is within :data:`CONVERGED`): ``measured`` the answer's quantity
    and value, ``checked`` the check mesh's, ``finer`` whether that mesh is
    the finer one (the change is relative to the finer mesh's value),
    ``mesh`` its ``nodes``, ``triangles`` and ``h_max``, ``coarser_change``
    the coarser mesh's change where it handed the verdict to the finer one."""
    (name, a), (other, b) = measured, checked
    change = relative_change(a, b, b if finer else a) if name == other else None
    data = {
        "quantity": name,
        "value": a,
        "check": "finer" if finer else "coarser",
        "check_mesh": mesh,
        "check_value": b if name == other else None,
        "max_deviation_change": change,
        "coarser_change": coarser_change,
    }
    if name != other:  # a standing form on one mesh, none on the other
        return data, [
            f"not mesh-converged: the check's mesh of {mesh['nodes']} nodes has {other} where "
            f"this one has {name} (a standing equilibrium on one mesh and none on the "
            f"other); a finer --mesh is closer"
        ]
    if change is not None and change > CONVERGED:
        return data, [
            f"not mesh-converged: {name} changes by {100 * change:.3g} % on a mesh of "
            f"{mesh['nodes']} nodes (more than {100 * CONVERGED:g} %); a finer --mesh is closer"
        ]
    return data, []
