"""One load case evaluated: the combination of the actions' responses about
the standing form, its feet's reactions, its rigid-body, strength and
deflection checks and the ballast it asks of each foot."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from onefold_cad.geometry.numeric import Array, Index
from onefold_cad.mechanics.loads.combinations import GAMMA, Case
from onefold_cad.mechanics.loads.feet import resultant, rigid_check
from onefold_cad.mechanics.loads.linear_stress import von_mises_faces
from onefold_cad.mechanics.loads.results import CaseResult
from onefold_cad.mechanics.model import GRAVITY
from onefold_cad.mechanics.shell import Shell

__all__ = ["Actions", "evaluate_case"]


@dataclass(frozen=True, eq=False)
class Actions:
    """The actions' loads and responses about the standing form (SI units).

    Attributes:
        shell: the standing shell (for the stresses).
        q_placed: the designed form set on the ground (stress-free state).
        q_standing: the standing equilibrium under the weight.
        x: ``(n, 3)`` the standing nodes (m).
        weight_load: ``(n, 3)`` the weight's nodal forces (N).
        weight_reactions: ``(n, 3)`` the supports' forces under the weight (N).
        loads: action name -> ``(n, 3)`` nodal forces (N).
        moves: action name -> ``(N,)`` its linear response.
        reactions: action name -> ``(n, 3)`` its supports' forces (N).
        strains: action name (and ``G``: the standing state's) -> its faces'
            membrane strains and curvature changes (``linear_stress``).
        feet: the feet's node ids; ``feet_xy`` ``(k, 2)`` where they are (m).
        yield_Pa: the yield stress over gamma_M0 (Pa).
        friction: ``mu``; ``supports``: the support mode.
        scale: metres per design unit.
    """

    shell: Shell
    q_placed: Array
    q_standing: Array
    x: Array
    weight_load: Array
    weight_reactions: Array
    loads: dict[str, Array]
    moves: dict[str, Array]
    reactions: dict[str, Array]
    strains: dict[str, tuple[Array, Array]]
    feet: list[Index]
    feet_xy: Array
    yield_Pa: float
    friction: float
    supports: str
    scale: float

    def variable_load(self, case: Case) -> Array:
        """``case``'s variable actions (all but ``G``) times their factors, as a
        shell's external load ``(N,)`` (N on the coordinates, none on the
        director angles): what a full-model load path ramps."""
        n = self.x.shape[0]
        load = np.zeros_like(self.q_standing)
        for name, f in case.factor.items():
            if name != "G":
                load[: 3 * n] += f * self.loads[name].ravel()
        return load

    def combined(self, case: Case) -> tuple[Array, Array, Array, Array]:
        """``case``'s faces' stresses ``(m,)`` (Pa), variable movement ``(N,)``,
        nodal loads and supports' forces ``(n, 3)``."""
        fac = case.factor
        g = fac.get("G", 0.0)
        var = np.zeros_like(self.q_standing)
        load = g * self.weight_load
        react = g * self.weight_reactions
        e, k = (g * v for v in self.strains["G"])
        for name, f in fac.items():
            if name == "G":
                continue
            var = var + f * self.moves[name]
            load = load + f * self.loads[name]
            react = react + f * self.reactions[name]
            e = e + f * self.strains[name][0]
            k = k + f * self.strains[name][1]
        return von_mises_faces(self.shell, e, k), var, load, react


def _ballast(feet_react: Array, mu: float) -> Array:
    """``(k,)`` the ballast (kg) each foot needs in an EQU case: enough that the
    ground pushes on it by at least its horizontal force over ``mu`` (so it
    neither lifts nor slips; ballast is a favourable permanent action: it
    counts 0.9 times, EN 1990 Table A1.2(A))."""
    favourable = GAMMA["EQU"]["G_inf"] * GRAVITY
    h = np.hypot(feet_react[:, 0], feet_react[:, 1])
    return np.maximum(h / mu - feet_react[:, 2], 0.0) / favourable


def _face_at(act: Actions, face: int) -> Array:
    """``(2,)`` the centroid of ``face`` on the flat sheet (design unit)."""
    mesh = act.shell.mesh
    return mesh.nodes[mesh.triangles[face]].mean(axis=0) / act.scale


def evaluate_case(act: Actions, case: Case) -> tuple[CaseResult, Array, Array]:
    """``case`` checked; with its movement ``(n, 3)`` (m) and its faces'
    utilisation ``(m,)`` for the picture."""
    stress, var, load, react = act.combined(case)
    n = act.x.shape[0]
    util = stress / act.yield_Pa
    feet_r = np.array([react[f].sum(axis=0) for f in act.feet])
    force, moment = resultant(act.x, load)
    rigid = rigid_check(act.feet_xy, force, moment, act.friction)
    moved = var[: 3 * n].reshape(n, 3)
    deflection = float(np.linalg.norm(moved, axis=1).max()) / act.scale
    weight = float(-act.weight_load[:, 2].sum())
    pulls = [i for i, r in enumerate(feet_r) if r[2] < -1e-9 * weight]
    reason = ""  # STR: the J2 load path's verdict (``strength``), set by the caller
    if case.kind == "EQU" and act.supports == "friction":
        if rigid.lifts_off:
            reason = f"the wind lifts it off (a net {-rigid.vertical_N / 1e3:.3g} kN up)"
        elif rigid.tips:
            assert rigid.tip_margin is not None
            reason = (f"it tips: the loads' resultant meets the ground {-rigid.tip_margin:.3g} m "
                      "outside its feet")  # fmt: skip
        elif pulls:
            names = ", ".join(f"foot {i + 1} ({-feet_r[i][2] / 1e3:.3g} kN)" for i in pulls)
            reason = f"a foot lifts: {names} would have to pull"
        elif rigid.slides:
            reason = (f"it slides: {rigid.horizontal_N / 1e3:.3g} kN sideways against "
                      f"mu V = {act.friction * rigid.vertical_N / 1e3:.3g} kN")  # fmt: skip
        else:
            h = np.hypot(feet_r[:, 0], feet_r[:, 1])
            slip = [i for i in range(len(h)) if h[i] > act.friction * feet_r[i, 2]]
            if slip:
                i = max(slip, key=lambda j: h[j] / max(feet_r[j, 2], 1e-300))
                reason = (f"foot {i + 1} slips (the feet spread): {h[i] / 1e3:.3g} kN sideways "
                          f"against mu N = {act.friction * feet_r[i, 2] / 1e3:.3g} kN")  # fmt: skip
    res = CaseResult(
        name=case.name,
        kind=case.kind,
        stands=reason == "",
        reason=reason,
        reactions_N=feet_r,
        vertical_N=rigid.vertical_N,
        horizontal_N=rigid.horizontal_N,
        slide_ratio=rigid.slide_ratio,
        tip_margin=None if rigid.tip_margin is None else rigid.tip_margin / act.scale,
        max_deflection=deflection,
        utilisation=float(util.max()),
        ballast_kg=np.zeros(len(act.feet)),
        utilisation_at=_face_at(act, int(np.argmax(util))),
    )
    if case.kind == "EQU":
        res = replace(res, ballast_kg=_ballast(feet_r, act.friction))
    return res, moved, util
