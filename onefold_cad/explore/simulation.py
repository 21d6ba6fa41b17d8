"""The page's Simulate button: a coarse simulation of the current design.

:func:`simulation_state` runs :func:`onefold_cad.mechanics.simulate.simulate`
on the coarse mesh without its convergence check (seconds, not minutes), with
the law it is given (the Simulate button: :data:`SIMULATE_LAW`, ``onefold
simulate``'s J2; the Steel view: :data:`LAW`, the faster moment law), and
returns what the page draws: the standing form (or, without a standing
equilibrium, the released form) and the designed form on the simulation's
own mesh, both in its resting frame (z up, ground z = 0, design units), each
vertex's colour on the deviation scale of
:mod:`onefold_cad.export.simulation.colour_scale` (the colours of NAME-deviation.png
and the simulation's GLB), the scale's legend, and the numbers. The page
computes nothing.

One simulation runs at a time (the machine's cores are the solver's); the
server answers each request on its own thread, so the page's other requests
are answered meanwhile. A request may say when its answer is no longer
wanted (``cancelled``, the steel view's :mod:`onefold_cad.explore.steel`): it
is then given up before it starts and at the simulation's next Newton step.
A design that cannot be simulated (the paper model, no thickness, no elastic
data, ...) answers ``ok: false`` with the one-line
message ``onefold simulate`` would print.

The Steel view asks for the form first (``check_later``): the coarse
preview's reserve check (:mod:`onefold_cad.mechanics.reserve`, about a third
of the coarse simulation) is left for :func:`check_state`, which the page asks
for once the form is drawn; until then the numbers say ``checking: true`` and
the page says "checking…", never a plain "stands".
"""

from __future__ import annotations

import base64
import threading
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from onefold_cad.choices import SIMULATION_DEFAULTS, Law
from onefold_cad.design import Design, fold_design
from onefold_cad.errors import OneFoldError
from onefold_cad.export.simulation.colour_scale import (
    DEVIATION_STOPS,
    deviation_label,
    deviation_range,
    ramp,
    to_uint8,
)
from onefold_cad.mechanics.results import Simulation

__all__ = [
    "LAW",
    "LEVEL",
    "SIMULATE_LAW",
    "SUPERSEDED",
    "check_state",
    "simulation_numbers",
    "simulation_state",
    "steel_law",
]

#: The mesh level the page simulates on.
LEVEL = "coarse"

#: The bending law of the Steel view and the page's Compensate preview: the
#: moment law, a preview within the view's second (J2's springback is a
#: third to two fifths larger; the page says which law), but for cones
#: formed past their springback (:func:`steel_law`).
LAW = "moment"

#: The bending law of the Simulate button: ``onefold simulate``'s own (J2
#: through the thickness), so a press gives ``onefold simulate --mesh
#: coarse``'s numbers, its stresses within the flow stress.
SIMULATE_LAW = SIMULATION_DEFAULTS["law"].value


def steel_law(design: Design) -> str:
    """The Steel view's and the page Compensate's law for ``design``: :data:`LAW`,
    or J2 (:data:`SIMULATE_LAW`) where its cones are formed past their
    springback, which the moment law cannot form (``onefold simulate --law
    moment`` refuses them)."""
    return Law.J2.value if design.material.cones_compensated else LAW


#: The answer's ``error`` for a request given up for a newer one.
SUPERSEDED = "superseded: a newer design was asked for"

_ONE_AT_A_TIME = threading.Lock()


class _GivenUp(Exception):
    """Raised at a Newton step of a simulation whose answer is no longer wanted."""


def _b64(a: np.ndarray, dtype: str) -> str:
    return base64.b64encode(np.ascontiguousarray(a, dtype=dtype).tobytes()).decode("ascii")


def _line(text: object) -> str:
    return " ".join(str(text).split())


def simulation_numbers(sim: Simulation) -> dict[str, Any]:
    """The numbers the page prints (design unit, MPa, shares 0..1; ``law``: the
    bending law, 'moment' or 'j2'; ``cone_forming``: 'design' or
    'compensated', the cones formed past their springback); None where the
    simulation has none (no standing equilibrium, reference 'designed');
    ``checking``: its reserve check is still to come (:func:`check_state`)."""
    s = sim.standing
    return {
        "checking": sim.pending_reserve is not None,
        "stands": bool(s.stands),
        "uncertain": s.uncertain,
        "reason": s.reason,
        "max_deviation": s.max_deviation,
        "rms_deviation": s.rms_deviation,
        "height": s.height,
        "span": s.span,
        "tipping_margin_deg": s.tipping_margin_deg,
        "springback_max_deviation": None if sim.released is None else sim.released.max_deviation,
        "plastic_area_share": None if sim.formed is None else sim.formed.plastic_area_share,
        "max_stress_MPa": s.max_stress_MPa,
        "yield_stress_MPa": sim.yield_stress_MPa,
        "utilisation": s.utilisation,
        "law": sim.law,
        "cone_forming": sim.cone_forming,
        "weight_N": sim.weight_N,
        "nodes": sim.nodes,
        "triangles": sim.triangles,
    }


def _mesh(sim: Simulation) -> dict[str, Any]:
    """The forms and their colours for the page (float32, uint16/uint32, uint8)."""
    if sim.standing_positions is not None:
        kind, shown = "standing", sim.standing_positions
    elif sim.released_positions is not None:
        kind, shown = "released", sim.released_positions
    else:
        kind, shown = None, None
    if sim.faces is None or sim.designed_positions is None:
        raise OneFoldError("the simulation carries no mesh to show")
    faces = np.asarray(sim.faces)
    small = len(sim.designed_positions) < 2**16
    out: dict[str, Any] = {
        "form": kind,
        "designed": _b64(sim.designed_positions, "<f4"),
        "positions": None if shown is None else _b64(shown, "<f4"),
        "indices": _b64(faces, "<u2" if small else "<u4"),
        "index_type": "uint16" if small else "uint32",
        "vertex_count": int(len(sim.designed_positions)),
        "triangle_count": int(len(faces)),
        "colours": None,
    }
    if kind == "standing" and sim.deviation is not None:
        out["colours"] = _b64(to_uint8(ramp(sim.deviation, *deviation_range(sim.deviation))), "u1")
    return out


def _scale(sim: Simulation) -> dict[str, Any] | None:
    if sim.standing_positions is None or sim.deviation is None:
        return None
    lo, hi = deviation_range(sim.deviation)
    return {"label": deviation_label(sim.unit), "min": lo, "max": hi, "stops": DEVIATION_STOPS}


def _stages_ms(sim: Simulation) -> dict[str, float]:
    return {stage: 1e3 * seconds for stage, seconds in sim.timings_s.items()}


def simulation_state(
    design: Design,
    cancelled: Callable[[], bool] | None = None,
    *,
    law: str,
    check_later: bool = False,
    keep: Callable[[Simulation], None] | None = None,
) -> dict[str, Any]:
    """Simulate ``design`` coarsely for the page.

    Args:
        design: the design.
        cancelled: asked before the simulation starts (after the one before it
            ended) and at each of its Newton steps; True gives it up (None:
            never given up).
        law: the bending law, :data:`SIMULATE_LAW` (the Simulate button) or
            :data:`LAW` (the Steel view).
        check_later: leave the reserve check for :func:`check_state` (the
            answer's ``numbers.checking`` says whether there is one).
        keep: called with the simulation when it is done (its check, if
            left for later, is ``Simulation.pending_reserve``).

    Returns:
        A JSON-ready dict: ``ok``; without it ``error`` (one line; a request
        given up also has ``superseded: true``); with it ``units``,
        ``level``, ``mesh`` (``form`` 'standing', 'released' or
        None, the ``designed`` and shown ``positions`` as base64 float32 on
        one triangle list ``indices``, ``colours`` as base64 sRGB bytes per
        vertex or None), ``scale`` (the deviation legend: ``label``, ``min``,
        ``max`` in the design unit, ``stops``) or None, ``numbers``
        (:func:`simulation_numbers`), ``warnings``, ``server_ms`` (ms from
        the call to the answer), ``queued_ms`` (of them, ms before the
        simulation started: the fold, and the wait for the one before it)
        and ``cpu_ms`` (the simulation's CPU time, ms: the server's work,
        whatever else the machine runs), ``stages_ms`` (CPU ms per stage:
        ``mesh``, ``formed``, ``released``, ``standing``).
    """
    from onefold_cad.mechanics.simulate import simulate

    def progress(stage: str, iteration: int, residual: float) -> None:
        if cancelled is not None and cancelled():
            raise _GivenUp

    t0 = time.perf_counter()
    try:
        folded = fold_design(design)
        with _ONE_AT_A_TIME:
            t1, cpu = time.perf_counter(), time.thread_time()
            if cancelled is not None and cancelled():
                raise _GivenUp
            sim = simulate(
                design,
                folded,
                level=LEVEL,
                law=law,
                convergence=False,
                progress=None if cancelled is None else progress,
                reserve=not check_later,
            )
            cpu = time.thread_time() - cpu
    except _GivenUp:
        return {"ok": False, "superseded": True, "error": SUPERSEDED}
    except OneFoldError as exc:
        return {"ok": False, "error": f"cannot simulate this design: {_line(exc)}"}
    if keep is not None:
        keep(sim)
    return {
        "ok": True,
        "units": sim.unit,
        "level": LEVEL,
        "mesh": _mesh(sim),
        "scale": _scale(sim),
        "numbers": simulation_numbers(sim),
        "warnings": [_line(w) for w in sim.warnings],
        "server_ms": 1e3 * (time.perf_counter() - t0),
        "queued_ms": 1e3 * (t1 - t0),
        "cpu_ms": 1e3 * cpu,
        "stages_ms": _stages_ms(sim),
    }


def check_state(sim: Simulation, cancelled: Callable[[], bool] | None = None) -> dict[str, Any]:
    """The reserve check ``sim`` left for later (``check_later``), for the page.

    Args:
        sim: the simulation, its ``pending_reserve`` set.
        cancelled: as :func:`simulation_state`'s.

    Returns:
        A JSON-ready dict: ``ok``; without it ``error`` (and ``superseded``);
        with it ``units``, ``numbers`` (:func:`simulation_numbers`: the
        verdict, ``checking`` false), ``warnings``, ``server_ms``,
        ``cpu_ms`` and ``stages_ms`` (with ``reserve``, the check's).
    """
    from onefold_cad.mechanics.verdicts import settle_reserve

    def progress(iteration: int, residual: float, energy: float) -> None:
        if cancelled is not None and cancelled():
            raise _GivenUp

    assert sim.pending_reserve is not None
    t0 = time.perf_counter()
    try:
        with _ONE_AT_A_TIME:
            cpu = time.thread_time()
            if cancelled is not None and cancelled():
                raise _GivenUp
            done = settle_reserve(sim, sim.pending_reserve, progress)
            cpu = time.thread_time() - cpu
    except _GivenUp:
        return {"ok": False, "superseded": True, "error": SUPERSEDED}
    return {
        "ok": True,
        "units": done.unit,
        "numbers": simulation_numbers(done),
        "warnings": [_line(w) for w in done.warnings],
        "server_ms": 1e3 * (time.perf_counter() - t0),
        "cpu_ms": 1e3 * cpu,
        "stages_ms": _stages_ms(done),
    }
