"""Where the J2 law's coarse preview goes, part by part, against the bar's
whole run, in one process.

``simulate(design, folded, level=..., convergence=False, law="j2")`` is run
``--rounds`` times, its CPU split by wrapping, for the run only:

- the factorisations and solves of Newton's steps
  (``newton.SymmetricFactor.factor`` and ``.solve``, QDLDL);
- the J2 law at the material points (``j2.section.update``: the return
  mappings, their tangents and energies);
- the rest: the shell's energy, gradient and Hessian (shared with the moment
  law), the mesh, forming, placement and the results;

and, across those parts, the coarse reserve check's (``ReserveCheck.carried``:
a solve at 2.5 times the weight, which the bar's commit did not have yet).

Interleaved with it, the bar: the moment law of ``--baseline`` (main before
the J2 work, ``git_baseline.py``) on the same design and level. Prints the
medians, J2's Newton iterations (every solve's: release, standing, the
reserve check, failed attempts) and what the rest alone
costs an iteration, and the iterations at that cost that fit into the bar's
whole run with the factorisations and the law taken as free: about the most
any release and stand could take to meet the bar with the shell's
evaluation as it is (generous where the rest exceeds the bar: the rest's
fixed part, the mesh and forming, is counted as the iterations'). Prints
only.

Run from the repository root::

    .venv/bin/python benchmarks/bench_j2_parts.py [TEMPLATE] [--level coarse]
        [--rounds 5] [--baseline 8921478] [--grading G]

``--grading`` grades the coarse level's J2 runs ``G`` times faster from the
relief hole than the normal mesh (``model.MESH_GRADING``, 1.5 as shipped;
the bar's runs keep their own commit's mesh), put back after each run.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_j2_law import baseline_simulate  # noqa: E402

from onefold_cad.choices import MeshLevel  # noqa: E402
from onefold_cad.design import fold_design  # noqa: E402
from onefold_cad.errors import ConvergenceError  # noqa: E402
from onefold_cad.mechanics import equilibrium, newton  # noqa: E402
from onefold_cad.mechanics import model as mechanics_model  # noqa: E402
from onefold_cad.mechanics.j2 import section  # noqa: E402
from onefold_cad.mechanics.reserve import ReserveCheck  # noqa: E402
from onefold_cad.mechanics.simulate import simulate  # noqa: E402
from onefold_cad.templates import load_template  # noqa: E402


class Clock:
    """CPU seconds spent inside wrapped callables (not nested)."""

    def __init__(self) -> None:
        self.spent = 0.0

    def wrap(self, fn: Callable) -> Callable:
        def timed(*args, **kwargs):
            t = time.process_time()
            try:
                return fn(*args, **kwargs)
            finally:
                self.spent += time.process_time() - t

        return timed


def j2_parts(design, folded, level: str, grading: float | None = None) -> dict[str, float]:
    """One J2 run's CPU: total, factorisations and solves, the law, the rest;
    and its Newton iterations (every solve's, the reserve check's and failed
    attempts' included)."""
    factor, law, reserve = Clock(), Clock(), Clock()
    carried = ReserveCheck.carried
    ReserveCheck.carried = reserve.wrap(carried)  # type: ignore[method-assign]
    saved = (newton.SymmetricFactor.factor, newton.SymmetricFactor.solve, section.update)
    newton.SymmetricFactor.factor = factor.wrap(saved[0])  # type: ignore[method-assign]
    newton.SymmetricFactor.solve = factor.wrap(saved[1])  # type: ignore[method-assign]
    section.update = law.wrap(saved[2])  # type: ignore[assignment]
    minimize = equilibrium.minimize
    count = [0]

    def counted(*args, **kwargs):
        try:
            result = minimize(*args, **kwargs)
        except ConvergenceError as err:
            count[0] += int(getattr(err, "iterations", 0) or 0)
            raise
        count[0] += result.iterations
        return result

    equilibrium.minimize = counted  # type: ignore[assignment]
    shipped = mechanics_model.MESH_GRADING[MeshLevel.COARSE]
    if grading is not None:
        mechanics_model.MESH_GRADING[MeshLevel.COARSE] = grading
    try:
        t = time.process_time()
        sim = simulate(design, folded, level=level, convergence=False, law="j2")
        total = time.process_time() - t
    finally:
        newton.SymmetricFactor.factor, newton.SymmetricFactor.solve = saved[0], saved[1]  # type: ignore[method-assign]
        section.update = saved[2]  # type: ignore[assignment]
        equilibrium.minimize = minimize  # type: ignore[assignment]
        ReserveCheck.carried = carried  # type: ignore[method-assign]
        mechanics_model.MESH_GRADING[MeshLevel.COARSE] = shipped
    iterations = count[0]
    return {
        "total": total,
        "factor": factor.spent,
        "law": law.spent,
        "rest": total - factor.spent - law.spent,
        "reserve": reserve.spent,
        "iterations": float(iterations),
        "nodes": float(sim.nodes),
        "springback": sim.released.max_deviation,
        "standing": sim.standing.max_deviation,
    }


def baseline_run(commit: str, template: str) -> Callable[[str], float] | None:
    """``commit``'s moment law on ``template``, as a function of the level
    giving its CPU seconds (``bench_j2_law.baseline_simulate``), or None."""
    simulate_old = baseline_simulate(commit, template)
    if simulate_old is None:
        return None

    def run(level: str) -> float:
        t = time.process_time()
        simulate_old(level, False)
        return time.process_time() - t

    return run


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--level", default="coarse")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--baseline", default="8921478")
    ap.add_argument("--grading", type=float, default=None)
    args = ap.parse_args(argv)
    design = load_template(args.template)
    folded = fold_design(design)
    bar = baseline_run(args.baseline, args.template)
    parts: list[dict[str, float]] = []
    bars: list[float] = []
    for _ in range(args.rounds):
        parts.append(j2_parts(design, folded, args.level, args.grading))
        if bar is not None:
            bars.append(bar(args.level))
    med = {k: statistics.median(p[k] for p in parts) for k in parts[0]}
    n = med["iterations"]
    print(f"{args.template}, {args.level} mesh ({med['nodes']:.0f} nodes; springback max "
          f"{med['springback']:.4g}, standing max {med['standing']:.4g} {design.units.value}), "
          "J2 without the convergence check: "
          f"CPU s, medians of {args.rounds}, interleaved with the bar")  # fmt: skip
    print("| part | CPU s | share | per Newton iteration (ms) |")
    print("|---|---|---|---|")
    for key, label in (
        ("total", "J2, whole run"),
        ("factor", "factorisations and solves (QDLDL)"),
        ("law", "the J2 law at the points"),
        ("rest", "the rest (shell terms, mesh, forming, results)"),
        ("reserve", "of the whole, the reserve check (each part; the bar has none)"),
    ):
        print(f"| {label} | {med[key]:.2f} | {med[key] / med['total']:.0%} | "
              f"{1e3 * med[key] / n:.1f} |")  # fmt: skip
    print(f"Newton iterations (every solve's, the reserve check's and failed attempts'): {n:.0f}")
    if bars:
        b = statistics.median(bars)
        print(f"the bar, moment law at {args.baseline}: {b:.2f} s; J2 {med['total'] / b:.2f} x it; "
              f"the rest alone {med['rest'] / b:.2f} x it; J2 without its reserve check "
            f"{(med['total'] - med['reserve']) / b:.2f} x it")  # fmt: skip
        print(
            f"iterations that fit into the bar at the rest's cost per iteration, "
            f"factorisations and law free: {b / (med['rest'] / n):.0f} (J2 takes {n:.0f})"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
