"""A load case solved again with the full model: Newton on the shell with the
case's loads as its external forces (``Shell.load``) and its weight factor
in its gravity, the load ramped from the standing equilibrium
(``equilibrium.solve_path``): the check of the linear superposition where a
thin sheet softens (or snaps through: the path stalls and says how much of
the case it carried)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from onefold_cad.errors import ConvergenceError
from onefold_cad.geometry.numeric import Array, Index
from onefold_cad.mechanics.equilibrium import PathStalled, solve_path
from onefold_cad.mechanics.loads.cases import Actions
from onefold_cad.mechanics.loads.combinations import Case
from onefold_cad.mechanics.model import GRAVITY
from onefold_cad.mechanics.stress import face_stress

__all__ = ["NonlinearCheck", "solve_case"]

#: Newton's tolerance relative to the weight, the smallest load step, the
#: most movement per step (share of the sheet's size) and the most solves.
RTOL, MIN_STEP, MAX_MOVE, MAX_SOLVES = 1e-7, 1 / 64, 0.05, 32


@dataclass(frozen=True)
class NonlinearCheck:
    """One case solved with the full model.

    Attributes:
        case: its name.
        reached: the share of the case's variable loads carried (1: all).
        max_deflection: the largest movement from the standing form (design
            unit), at ``reached``; ``linear_deflection`` the same measure of the
            linear superposition (the weight's factor included), at ``reached``.
        utilisation: the largest stress over the yield stress, at ``reached``.
        reactions_N: ``(k, 3)`` the feet's reactions (N), at ``reached``.
    """

    case: str
    reached: float
    max_deflection: float | None
    linear_deflection: float | None
    utilisation: float | None
    reactions_N: Array | None

    def to_data(self) -> dict[str, Any]:
        """The JSON data."""
        return {
            "case": self.case,
            "reached": float(self.reached),
            "max_deflection": self.max_deflection,
            "linear_deflection": self.linear_deflection,
            "utilisation": self.utilisation,
            "reactions_N": None if self.reactions_N is None else self.reactions_N.tolist(),
        }


def solve_case(act: Actions, case: Case, fixed: Index, size: float) -> NonlinearCheck:
    """``case`` solved from the standing equilibrium with ``fixed`` held;
    ``size`` the sheet's size (m) bounds a step's movement."""
    fac = case.factor
    g = fac.get("G", 0.0)
    n = act.x.shape[0]
    load = act.variable_load(case)
    weight = float(-act.weight_load[:, 2].sum())

    def shell_at(s: float):
        grav = np.array([0.0, 0.0, -GRAVITY * (1.0 + s * (g - 1.0))])
        return act.shell.with_changes(gravity=grav, load=s * load)

    try:
        eq = solve_path(shell_at, act.q_standing, fixed=fixed, force_scale=weight, rtol=RTOL,
                        first_step=1.0, min_step=MIN_STEP, max_move=MAX_MOVE * size,
                        max_solves=MAX_SOLVES)  # fmt: skip
        reached = 1.0
    except PathStalled as err:
        if err.last is None:
            return NonlinearCheck(case.name, err.reached, None, None, None, None)
        eq, reached = err.last, err.reached
    except ConvergenceError:
        return NonlinearCheck(case.name, 0.0, None, None, None, None)
    moved = (eq.q - act.q_standing)[: 3 * n].reshape(n, 3)
    util = face_stress(shell_at(reached), eq.q) / act.yield_Pa
    var = act.combined(case)[1]
    lin = reached * (var + (g - 1.0) * (act.q_standing - act.q_placed))
    lin_moved = lin[: 3 * n].reshape(n, 3)
    feet_r = np.array([eq.reactions[f].sum(axis=0) for f in act.feet])
    return NonlinearCheck(
        case.name,
        reached,
        float(np.linalg.norm(moved, axis=1).max()) / act.scale,
        float(np.linalg.norm(lin_moved, axis=1).max()) / act.scale,
        float(util.max()),
        feet_r,
    )
