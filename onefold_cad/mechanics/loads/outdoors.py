"""``onefold loads``'s computation: the designed sheet standing outdoors.

The designed form is taken as stress-free (as an engineer checks a built
shell), set on its resting contacts and stood under its weight with its
contacts held (:func:`~onefold_cad.mechanics.stages.stand`, Newton on the
full model); that equilibrium is the reference. Every other action (wind
per direction and sign, snow, the person) is a load vector whose response
is linear about it (:mod:`.response`, one factorisation), and the cases
(:mod:`.combinations`) superpose them with EN 1990's factors.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import asdict
from typing import Any

import numpy as np

from onefold_cad.design import Design
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.mechanics.loads.cases import Actions, evaluate_case
from onefold_cad.mechanics.loads.combinations import GAMMA, Case, combinations
from onefold_cad.mechanics.loads.feet import feet_of
from onefold_cad.mechanics.loads.linear_stress import first_order, strains
from onefold_cad.mechanics.loads.nonlinear import NonlinearCheck, solve_case
from onefold_cad.mechanics.loads.point import grid_points, point_load
from onefold_cad.mechanics.loads.response import linear_response, node_dofs
from onefold_cad.mechanics.loads.results import CaseResult, Foot, Outdoors
from onefold_cad.mechanics.loads.snow import snow_load
from onefold_cad.mechanics.loads.spec import LoadSpec
from onefold_cad.mechanics.loads.strength import STRENGTH_METHOD, str_verdicts
from onefold_cad.mechanics.loads.wind import peak_velocity_pressure, terrain, wind_load
from onefold_cad.mechanics.model import GRAVITY, SheetModel, sheet_model
from onefold_cad.mechanics.shell import director_angles, pack
from onefold_cad.mechanics.stages import place, stand

__all__ = ["ASSUMPTIONS", "outdoors"]

#: What the check assumes, each with its source (the report repeats them).
ASSUMPTIONS = (
    "wind: EN 1991-1-4 peak velocity pressure q_p(z_e) (Eq. 4.8, c_o = 1, c_dir = c_season = 1, "
    "rho = 1.25 kg/m^3) at z_e = the standing form's height unless given",
    "wind: the sheet taken as a canopy roof (EN 1991-1-4 7.3), its net pressure c_f q_p normal "
    "to the surface with Table 7.6's overall coefficients (pitch 0, empty: +0.2 down, -0.5 up; "
    "blocked underneath: -1.3) unless given, centred a quarter of the plan depth from the "
    "windward edge (7.3(6), Figure 7.16): 3 (1 - s)^2 times the mean along the wind",
    "snow: EN 1991-1-3 s = mu_1 C_e C_t s_k on the plan, mu_1 by each face's slope (Table 5.2), "
    "undrifted",
    "person: EN 1991-1-1 Table 6.10, roof category H, Q_k = 1 kN at a point, not combined with "
    "snow or wind (3.3.2(1))",
    "combinations: EN 1990 Annex A1 (EQU Table A1.2(A), STR Eq. 6.10 Table A1.2(B), SLS Eq. "
    "6.14b; psi_0 wind 0.6, snow 0.5)",
    STRENGTH_METHOD,
    "response: the designed form stress-free, standing under its weight on its held contacts "
    "(Newton); the other loads linear about it and superposed, their directions fixed",
)

Progress = Callable[[str, int, float], None]


def _standing(model: SheetModel, progress: Progress | None):
    q0 = pack(model.designed, director_angles(model.shell, model.designed, model.normals))
    placed = place(model, q0)
    cb = None if progress is None else (lambda it, res, energy: progress("standing", it, res))
    stage = stand(model, placed, model.shell.rest_curvature, None, "anchored", cb)
    return placed, stage.equilibrium


def _person(spec: LoadSpec, model: SheetModel, unit_scale: float):
    """The person's candidate loads: name -> (n, 3), and where each stands."""
    flat = model.mesh.nodes / unit_scale
    tri = model.mesh.triangles
    f = spec.person_kN * 1e3
    points = (
        np.array([spec.person_at], dtype=float)
        if spec.person_at is not None
        else grid_points(flat, tri, spec.person_grid)
    )
    return {f"P@{i}": point_load(flat, tri, p, f) for i, p in enumerate(points)}, points


def outdoors(
    design: Design,
    folded: FoldedSheet,
    spec: LoadSpec,
    *,
    level: str = "normal",
    h_max: float | None = None,
    nonlinear: bool = False,
    strength_cases: int | None = 0,
    progress: Progress | None = None,
) -> Outdoors:
    """The outdoors check of ``design`` under ``spec``'s loads on its supports;
    with ``nonlinear`` the governing cases solved again with the full model
    (``nonlinear.solve_case``: seconds to minutes more). The STR cases past
    first yield are checked by their J2 load path (``strength.str_verdicts``):
    ``strength_cases`` of them (None: all), the permanent one first, then
    those of the largest elastic peak; the others say they were not checked.

    Raises:
        InvalidParameterError: the design cannot be simulated, or a load is
            outside its range (named).
        ConvergenceError: no standing equilibrium under its weight.
    """
    model = sheet_model(design, folded, h_max=h_max, level=level)
    s = model.scale
    tri = model.mesh.triangles
    if spec.person_at is not None:  # before the minutes of the standing
        point_load(model.mesh.nodes / s, tri, np.asarray(spec.person_at), 1.0)
    placed, eq = _standing(model, progress)
    x = eq.positions
    shell = placed.shell.with_changes(gravity=np.array([0.0, 0.0, -GRAVITY]))
    z_e = spec.height if spec.height is not None else float(x[:, 2].max())
    if spec.velocity_pressure_kPa is not None:
        q_p = spec.velocity_pressure_kPa * 1e3
    else:
        assert spec.wind_speed is not None
        q_p = peak_velocity_pressure(float(spec.wind_speed), z_e, terrain(spec.terrain))
    loads: dict[str, np.ndarray] = {}
    for d in spec.direction_list:
        loads[f"W+{d:g}"] = wind_load(x, tri, q_p, spec.cf_down, d)
        loads[f"W-{d:g}"] = wind_load(x, tri, q_p, spec.cf_up, d)
    snow = spec.snow_kPa > 0.0
    if snow:
        loads["S"] = snow_load(x, tri, spec.snow_kPa * 1e3, spec.exposure, spec.thermal)
    person, points = ({}, np.zeros((0, 2)))
    if spec.person_kN > 0.0:
        person, points = _person(spec, model, s)
        loads.update(person)
    contacts = np.flatnonzero(eq.contacts)
    names = list(loads)
    resp = linear_response(shell, eq.q, node_dofs(contacts), np.array([loads[k] for k in names]))
    feet = feet_of(contacts, model.mesh.edges)
    act = Actions(
        shell=shell,
        q_placed=placed.q,
        q_standing=eq.q,
        x=x,
        weight_load=np.outer(shell.node_mass, [0.0, 0.0, -GRAVITY]),
        weight_reactions=eq.reactions,
        loads=loads,
        moves=dict(zip(names, resp.moves, strict=True)),
        reactions=dict(zip(names, resp.reactions, strict=True)),
        strains={"G": strains(shell, eq.q)}
        | {k: first_order(shell, eq.q, u) for k, u in zip(names, resp.moves, strict=True)},
        feet=feet,
        feet_xy=np.array([x[f, :2].mean(axis=0) for f in feet]),
        yield_Pa=model.material.yield_stress / 1.0,
        friction=spec.friction,
        supports=spec.supports,
        scale=s,
    )
    person_at = None
    if person:
        person_at = _worst_person(act, person, points)
        act.loads["P"] = act.loads[person_at[0]]
        act.moves["P"] = act.moves[person_at[0]]
        act.reactions["P"] = act.reactions[person_at[0]]
        act.strains["P"] = act.strains[person_at[0]]
    cases = combinations(spec.direction_list, snow, bool(person))
    evaluated = [evaluate_case(act, c) for c in cases]
    start = time.process_time()
    results = str_verdicts(act, cases, tuple(e[0] for e in evaluated), strength_cases,
                           node_dofs(contacts), model.size)  # fmt: skip
    strength_cpu = time.process_time() - start
    governing = _governing(results, spec.supports)
    strength = _governing_strength(results)
    g_index = [r.name for r in results].index(governing)
    checks = tuple(
        solve_case(act, next(c for c in cases if c.name == name), node_dofs(contacts), model.size)
        for name in dict.fromkeys([governing, strength])
        if nonlinear
    )
    return Outdoors(
        unit=design.units.value,
        inputs=_inputs(spec),
        assumptions=ASSUMPTIONS,
        weight_N=model.weight_N,
        reference_height_m=z_e,
        peak_velocity_pressure_kPa=q_p / 1e3,
        mesh={"nodes": model.mesh.n_nodes, "triangles": model.mesh.n_faces},
        feet=_feet(act, results),
        cases=results,
        governing=governing,
        governing_strength=strength,
        stands=all(r.stands for r in results),
        person_at=None if person_at is None else person_at[1],
        nonlinear=checks,
        strength={
            "screened_by": "the permanent case first, then the largest linear elastic peak",
            "cases_checked": [r.name for r in results if r.strength is not None],
            "cases_not_checked": [
                r.name
                for r in results
                if r.kind == "STR" and r.strength is None and r.utilisation > 1
            ],
            "cpu_s": strength_cpu,
        },  # fmt: skip
        warnings=tuple(_warnings(act, checks, design.units.value) + _unchecked(results)),
        faces=tri,
        positions=x,
        moves=evaluated[g_index][1],
        face_utilisation=evaluated[g_index][2],
    )


def _worst_person(act: Actions, person: dict[str, np.ndarray], points: np.ndarray):
    """The candidate whose STR case (1.35 G + 1.5 P) stresses the sheet most."""
    g = GAMMA["STR"]
    best, worst = None, -math.inf
    for i, name in enumerate(person):
        r = evaluate_case(act, Case(name, "STR", (("G", g["G_sup"]), (name, g["Q"]))))[0]
        if r.utilisation > worst:
            best, worst = (name, points[i]), r.utilisation
    return best


def _governing_strength(results: tuple[CaseResult, ...]) -> str:
    """The STR case of the lowest J2 load ratio, or of the largest elastic peak
    when none was checked."""
    checked = [r for r in results if r.strength is not None]
    if checked:
        return min(checked, key=lambda r: r.strength.ratio if r.strength else 0.0).name
    return max((r for r in results if r.kind == "STR"), key=lambda r: r.utilisation).name


def _governing(results: tuple[CaseResult, ...], supports: str) -> str:
    uls = [r for r in results if r.kind in ("EQU", "STR")]
    equ = [r for r in results if r.kind == "EQU"] or uls
    if supports == "anchored":
        pull = max(uls, key=lambda r: float(-r.reactions_N[:, 2].min()))
        if float(-pull.reactions_N[:, 2].min()) > 0.0:
            return pull.name
        return max(uls, key=lambda r: r.utilisation).name
    if supports == "ballast":
        return max(equ, key=lambda r: float(r.ballast_kg.sum())).name
    failing = [r for r in equ if not r.stands]
    pool = failing or equ
    return max(pool, key=lambda r: r.slide_ratio).name


def _feet(act: Actions, results: tuple[CaseResult, ...]) -> tuple[Foot, ...]:
    uls = [r for r in results if r.kind in ("EQU", "STR")]
    out = []
    for i, nodes in enumerate(act.feet):
        z = np.array([r.reactions_N[i, 2] for r in uls])
        h = np.array([math.hypot(*r.reactions_N[i, :2]) for r in uls])
        ballast = max(float(r.ballast_kg[i]) for r in uls)
        out.append(Foot(act.feet_xy[i] / act.scale, len(nodes), float(max(-z.min(), 0.0)),
                        float(h.max()), float(max(z.max(), 0.0)), ballast))  # fmt: skip
    return tuple(out)


def _inputs(spec: LoadSpec) -> dict[str, Any]:
    data = asdict(spec)
    data["terrain"] = terrain(spec.terrain).name
    data["person_at"] = None if spec.person_at is None else list(spec.person_at)
    return data


def _unchecked(results: tuple[CaseResult, ...]) -> list[str]:
    """A line when STR cases past first yield were not checked by a J2 path."""
    left = [r for r in results if r.kind == "STR" and r.strength is None and r.utilisation > 1]
    if not left:
        return []
    return [f"{len(left)} STR case(s) past first yield were not checked by a J2 load path and "
            "do not count as standing (--strength-cases all checks them)"]  # fmt: skip


def _warnings(act: Actions, checks: tuple[NonlinearCheck, ...], u: str) -> list[str]:
    """The full model's disagreements with the linear cases, and too few feet."""
    out = []
    for c in checks:
        if c.reached < 1.0:
            out.append(
                f"{c.case}: the full model's load path stalls at {100 * c.reached:.3g} % of its "
                "loads (Newton finds no equilibrium in the steps tried: a limit point, where "
                "the sheet buckles or snaps through, or a path it could not follow): the linear "
                "answer is not to be trusted for it"
            )
        elif c.max_deflection is not None and c.linear_deflection:
            change = c.max_deflection / c.linear_deflection - 1.0
            if abs(change) > 0.1:
                out.append(
                    f"{c.case}: the full model moves the sheet by {c.max_deflection:.4g} {u} "
                    f"from its standing form, {100 * change:+.3g} % on the linear "
                    f"{c.linear_deflection:.4g} {u} "
                    f"(peak elastic stress {c.utilisation:.3g} x f_y): the linear cases are an "
                    "estimate"
                )
    if len(act.feet) < 3:
        out.append(f"it stands on {len(act.feet)} feet: no support polygon to resist tipping")
    return out
