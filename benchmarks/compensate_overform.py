"""Would cones formed tighter than the design's reach what the family cannot?

``onefold compensate`` moves the fold (alpha, beta, h_c) and the crease's
set angle; its standing steel stays about three times closer to the design
than uncompensated, not the five times asked (docs/compensate.md, "How far
the family reaches"). The die compensation of sheet-metal programs changes
the tool's shape instead: here, the cones are formed to ``F`` times the
designed curvature at every face (a curvature the One-Fold construction
does not give), and the sheet is released and stood as ``onefold simulate``
does. The J2 forming is imposed (membrane-free, proportional), so the
scaled curvature needs no compatible form; the release starts from the
designed form with that plastic state, as if the tool had first brought
the sheet back to the design's shape: elastically where the curvature's
change (F - 1) k stays below twice the yield curvature (the reverse
yielding of the rest, near H, is left out), and the release ramps the
forces that hold it there down.

Nelder-Mead on the largest distance from the design (the command's measure,
``standing_measures``) from the same start over (alpha, beta, overbend) with
``F = 1`` (the family) and over (F, alpha, beta, overbend), the same number
of simulations each, on the coarse mesh. An experiment, not a knob of the
package: ``F`` is applied by replacing ``j2.stages.cartesian_curvatures``
(what ``form_to`` forms each face to) in this process. Run from the repository root::

    .venv/bin/python benchmarks/compensate_overform.py [TEMPLATE] [--mesh coarse]
        [--start F,ALPHA,BETA,OVERBEND] [--evaluations 70]
"""

from __future__ import annotations

import argparse
import math
import time
from collections.abc import Callable

import numpy as np

import onefold_cad.mechanics.j2.stages as j2_stages
from onefold_cad.compensate.evaluate import node_weights, simulate_standing, standing_measures
from onefold_cad.compensate.optimise import fold_knobs, formed_to
from onefold_cad.errors import OneFoldError
from onefold_cad.mechanics.shell import Shell
from onefold_cad.templates import find_template, load_template

_CURVATURES = j2_stages.cartesian_curvatures


def scaled_curvatures(factor: float) -> Callable[[Shell, np.ndarray], np.ndarray]:
    """``j2.stages.cartesian_curvatures`` times ``factor``: what ``form_to``,
    its one caller, forms each face to (the release and the stand take their
    curvatures from the energy, not from it)."""

    def curvatures(shell: Shell, q: np.ndarray) -> np.ndarray:
        return factor * _CURVATURES(shell, q)

    return curvatures


def deviation(name: str, mesh: str, factor: float, alpha: float, beta: float,
              overbend: float) -> tuple[float, float, float] | None:  # fmt: skip
    """(max, rms distance from the design, CPU s) of the template formed to
    ``alpha``, ``beta`` with its cones at ``factor`` times their curvature and
    the crease ``overbend`` deg past the fold; None if it does not stand."""
    base = load_template(find_template(name))
    design = formed_to(base, fold_knobs(base) | {"alpha": alpha, "beta": beta,
                                                 "overbend": overbend})  # fmt: skip
    j2_stages.cartesian_curvatures = scaled_curvatures(factor)  # type: ignore[assignment]
    try:
        s = simulate_standing(design, mesh, law="j2")
    except OneFoldError:
        return None
    finally:
        j2_stages.cartesian_curvatures = _CURVATURES
    if not s.stands:
        return None
    m = standing_measures(base, s.flat, node_weights(s.flat, s.faces), s)
    return m.max_deviation, m.rms_deviation, s.cpu_s


def floor(name: str, mesh: str, start: list[float], evaluations: int,
          with_factor: bool) -> tuple[list[float], float, float, float]:  # fmt: skip
    """Nelder-Mead's smallest largest distance from ``start`` (F, alpha, beta,
    overbend; F held at 1 unless ``with_factor``): (knobs, max, rms, CPU s)."""
    from scipy.optimize import minimize

    seen: dict[tuple[float, ...], tuple[float, float, float] | None] = {}

    def knobs(y: np.ndarray) -> list[float]:
        v = [float(a) for a in y]
        return v if with_factor else [1.0, *v]

    def cost(y: np.ndarray) -> float:
        k = tuple(knobs(y))
        if k not in seen:
            seen[k] = deviation(name, mesh, *k)
            got = "falls" if seen[k] is None else f"max {seen[k][0]:.4g} rms {seen[k][1]:.4g}"
            print(f"  F {k[0]:.3f} alpha {k[1]:.2f} beta {k[2]:.2f} overbend {k[3]:+.2f}: {got}",
                  flush=True)  # fmt: skip
        r = seen[k]
        return math.inf if r is None else r[0]

    x0 = np.array(start if with_factor else start[1:])
    steps = ([0.3] if with_factor else []) + [4.0, 4.0, 4.0]
    simplex = np.vstack([x0] + [x0 + np.eye(len(x0))[i] * s for i, s in enumerate(steps)])
    minimize(cost, x0, method="Nelder-Mead",
             options={"maxfev": evaluations, "initial_simplex": simplex})  # fmt: skip
    best = min((k for k, r in seen.items() if r is not None), key=lambda k: seen[k][0])  # type: ignore[index]
    r = seen[best]
    assert r is not None
    return list(best), r[0], r[1], sum(v[2] for v in seen.values() if v is not None)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--mesh", default="coarse", choices=("coarse", "normal"))
    ap.add_argument("--start", default="1.4,33,33,0", help="F,ALPHA,BETA,OVERBEND")
    ap.add_argument("--evaluations", type=int, default=70)
    ns = ap.parse_args()
    start = [float(v) for v in ns.start.split(",")]
    base = load_template(find_template(ns.template))
    k = fold_knobs(base)
    t0 = time.monotonic()
    own = deviation(ns.template, ns.mesh, 1.0, k["alpha"], k["beta"], k["overbend"])
    if own is None:
        raise SystemExit(f"{ns.template} does not stand on the {ns.mesh} mesh")
    unit = base.units.value
    print(f"uncompensated: max {own[0]:.4g} rms {own[1]:.4g} {unit}; a fifth {own[0] / 5:.4g}")
    rows = []
    for with_factor in (False, True):
        print("the family (F = 1):" if not with_factor else "cones formed F times tighter:")
        rows.append((with_factor, *floor(ns.template, ns.mesh, start, ns.evaluations, with_factor)))
    head = f"| knobs ({ns.template}, {ns.mesh} mesh, J2) | smallest max / rms ({unit}) | "
    print(f"\n{head}at F, alpha, beta, overbend | x uncompensated | CPU s |\n|---|---|---|---|---|")
    for with_factor, best, mx, rms, cpu in rows:
        what = "alpha, beta, overbend, F" if with_factor else "alpha, beta, overbend"
        at = ", ".join(f"{v:.3g}" for v in best)
        print(f"| {what} | {mx:.4g} / {rms:.4g} | {at} | {mx / own[0]:.2f} | {cpu:.0f} |")
    print(f"\nwall {time.monotonic() - t0:.0f} s")


if __name__ == "__main__":
    main()
