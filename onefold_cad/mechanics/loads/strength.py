"""The STR cases' verdict: each case's design actions ramped on the designed
form with J2 sections (:mod:`.plastic_limit`, EN 1993-1-6 GMNA), its load
ratio ``r_R`` and the plastic strain the case leaves; the linear elastic
stress peak kept as information only (it is singular at the relief hole's rim
and near H, and grows as the mesh is refined).

The sections start virgin on the designed form taken as stress-free, as the
rest of ``onefold loads``: the forming sequence's residual stresses (``onefold
simulate --law j2``) are not carried. Self-equilibrated residual stresses do
not change a perfectly plastic structure's small-deflection plastic limit
(the limit analysis theorems); they change first yield and the plastic
strain reported.
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np

from onefold_cad.geometry.numeric import Index
from onefold_cad.mechanics.loads.cases import Actions
from onefold_cad.mechanics.loads.combinations import Case
from onefold_cad.mechanics.loads.plastic_limit import (
    GAMMA_M1,
    R_MAX,
    STRAIN_LIMIT,
    ideal_plastic,
    load_ratio,
)
from onefold_cad.mechanics.loads.results import CaseResult, StrengthCheck
from onefold_cad.mechanics.model import GRAVITY

__all__ = ["STRENGTH_METHOD", "str_verdicts", "strength_check"]

#: The report's sentence on how the STR verdict is reached.
STRENGTH_METHOD = (
    "STR: each case's design actions ramped by a load ratio r on the designed form taken as "
    "stress-free (the forming sequence's residual stresses not carried), every face a J2 "
    "section (9 Simpson points through the thickness) of an ideal elastic-plastic material "
    "at f_yd = f_y / gamma_M0, Newton on the full shell (GMNA, EN 1993-1-6:2007 6.2.3, the "
    "perfect shell: no imperfections); r_R the ratio at the path's limit point or where the "
    f"largest equivalent plastic strain reaches {100 * STRAIN_LIMIT:g} % (EN 1993-1-5 C.8 "
    f"Note 1), taken no further than {R_MAX:g}; it stands when r_R >= gamma_M1 = {GAMMA_M1:g} "
    "(r_Rd = r_Rk / gamma_M1, EN 1993-1-6 8.7.2 and 8.5.2(2)). The linear elastic peak "
    "stress is information only"
)


def strength_check(act: Actions, case: Case, fixed: Index, size: float) -> StrengthCheck:
    """``case``'s J2 load path from the placed (stress-free) designed form,
    ``fixed`` held (the standing contacts), ``size`` the sheet's size (m)."""
    start = time.process_time()
    fac = case.factor
    g = fac.get("G", 0.0)
    load = act.variable_load(case)
    shell = ideal_plastic(act.shell)
    weight = float(-act.weight_load[:, 2].sum())

    def shell_at(r: float):
        return shell.with_changes(gravity=np.array([0.0, 0.0, -GRAVITY * r * g]), load=r * load)

    res = load_ratio(shell_at, act.q_placed, fixed, weight, size, R_MAX)
    e = res.plasticity.state.equivalent
    peeq = np.maximum(e[:, 0], e[:, -1])
    mesh = shell.mesh
    at = None
    if np.any(peeq > 0):
        i = int(np.argmax(peeq))
        at = mesh.nodes[mesh.triangles[i]].mean(axis=0) / act.scale
    area = shell.ref_area
    return StrengthCheck(
        case=case.name,
        ratio=res.ratio,
        capped=res.carried,
        limit=res.limit,
        stands=res.ratio >= GAMMA_M1,
        plastic_at=res.at,
        max_plastic_strain=float(peeq.max()) if peeq.size else 0.0,
        max_plastic_strain_at=at,
        plastic_area_share=float(area[peeq > 0].sum() / area.sum()),
        cpu_s=time.process_time() - start,
    )


def _reason(chk: StrengthCheck) -> str:
    """Why a checked case does not stand ('' when it does)."""
    if chk.stands:
        return ""
    if chk.limit == "strain":
        how = (f"reaches {100 * STRAIN_LIMIT:g} % plastic strain at {chk.ratio:.4g} x its design "
               "actions")  # fmt: skip
    else:
        how = f"finds no equilibrium past {chk.ratio:.4g} x its design actions (a limit point)"
    return f"its J2 load path {how}: r_R < gamma_M1 = {GAMMA_M1:g}"


def str_verdicts(
    act: Actions,
    cases: list[Case],
    results: tuple[CaseResult, ...],
    count: int | None,
    fixed: Index,
    size: float,
) -> tuple[CaseResult, ...]:
    """``results`` with their STR cases' verdicts: a case whose linear elastic
    stresses stay below the yield stress stands (no plastic strain at all);
    of the others ``count`` (None: all) are checked by their J2 load path
    (:func:`strength_check`): the permanent one (``G`` alone) first, then
    those of the largest elastic peak (the linear screen); any other does
    not stand, its reason saying it was not checked (no verdict is guessed)."""
    by_name = {c.name: c for c in cases}
    yielding = [r for r in results if r.kind == "STR" and r.utilisation > 1.0]
    ranked = sorted(yielding, key=lambda r: (set(by_name[r.name].factor) != {"G"}, -r.utilisation))
    chosen = {r.name for r in (ranked if count is None else ranked[:count])}
    out = []
    for r in results:
        if r.kind != "STR" or r.utilisation <= 1.0:
            out.append(r)
        elif r.name in chosen:
            chk = strength_check(act, by_name[r.name], fixed, size)
            out.append(replace(r, stands=chk.stands, reason=_reason(chk), strength=chk))
        else:
            why = (f"not checked by a J2 load path (peak elastic stress {r.utilisation:.3g} x f_y; "
                   "--strength-cases all checks it)")  # fmt: skip
            out.append(replace(r, stands=False, reason=why))
    return tuple(out)
