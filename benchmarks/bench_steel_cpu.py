"""The explorer's Steel view's simulation alone, this tree against an earlier
commit in one process: ``simulate(design, folded, level="coarse",
convergence=False, reserve=False)`` as the Steel view calls it (its reserve
check left for later), this tree's and ``--before COMMIT``'s package
(``git_baseline.py``) interleaved round by round in rotated order
(``interleave.interleave``: CPU medians with quartiles, and the paired ratio
before / today), one BLAS thread as ``simulate`` runs it, the load average
at the start and the end. Beside the times, each side's reported numbers
(springback and standing deviation, Newton iterations) and, from one
untimed run each, how many energy evaluations (by order) and
factorisations its simulation made.

Run from the repository root::

    .venv/bin/python benchmarks/bench_steel_cpu.py [TEMPLATE] [--before main]
        [--rounds 9] [--law moment|j2]

Prints only.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
from collections import Counter
from pathlib import Path
from types import ModuleType

sys.path.insert(0, str(Path(__file__).resolve().parent))

from git_baseline import load  # noqa: E402
from interleave import interleave, paired_ratio  # noqa: E402


def _package(prefix: str) -> tuple[ModuleType, ModuleType, ModuleType]:
    """``simulate``'s, ``design``'s and ``templates``' modules of a package."""
    return tuple(  # type: ignore[return-value]
        importlib.import_module(f"{prefix}.{name}")
        for name in ("mechanics.simulate", "design", "templates")
    )


def _counted(prefix: str, call) -> Counter:
    """Energy evaluations by order and factorisations of one ``call()`` of
    the package ``prefix`` (its functions wrapped for the run, then restored)."""
    counts: Counter = Counter()
    eq = importlib.import_module(f"{prefix}.mechanics.equilibrium")
    newton = importlib.import_module(f"{prefix}.mechanics.newton")
    evaluate, factor = eq.evaluate, newton.SymmetricFactor.factor

    def counted_evaluate(shell, q, order=2):
        counts[f"evaluate order {order}"] += 1
        return evaluate(shell, q, order)

    def counted_factor(self, a, shift=None):
        counts["factorisations"] += 1
        return factor(self, a, shift)

    eq.evaluate, newton.SymmetricFactor.factor = counted_evaluate, counted_factor
    try:
        call()
    finally:
        eq.evaluate, newton.SymmetricFactor.factor = evaluate, factor
    return counts


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--before", default="main")
    ap.add_argument("--rounds", type=int, default=9)
    ap.add_argument("--law", default="moment", choices=["moment", "j2"])
    args = ap.parse_args(argv)
    old, why = load(args.before)
    if old is None:
        print(f"no {args.before}: {why}")
        return 1
    from onefold_cad.templates import find_template

    path = str(find_template(args.template))  # the file as this tree has it, for both
    calls = {}
    for label, prefix in (("today", "onefold_cad"), (args.before, old.__name__)):
        sim, des, tpl = _package(prefix)
        design = tpl.load_template(path)
        folded = des.fold_design(design)

        def call(sim=sim, design=design, folded=folded):
            return sim.simulate(
                design, folded, level="coarse", convergence=False, reserve=False, law=args.law
            )

        calls[label] = (prefix, call)
    print(f"{args.template}, coarse, law {args.law}: the Steel view's simulate")
    print("| package | springback max | standing max | Newton iterations | counts |")
    print("|---|---|---|---|---|")
    for label, (prefix, call) in calls.items():
        s = call()
        its = f"{s.released.iterations} + {s.standing.iterations}"
        counts = ", ".join(f"{k} {v}" for k, v in sorted(_counted(prefix, call).items()))
        print(
            f"| {label} | {s.released.max_deviation:.7g} | {s.standing.max_deviation:.7g} "
            f"| {its} | {counts} |"
        )
    load_start = os.getloadavg()[0]
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1, user_api="blas"):
        stats = interleave({k: v[1] for k, v in calls.items()}, rounds=args.rounds)
    load_end = os.getloadavg()[0]
    for label, st in stats.items():
        print(f"{label}: CPU {st.fmt(unit=' s')}")
    ratio = paired_ratio(stats, args.before, "today")
    print(f"paired ratio {args.before} / today: {ratio.fmt()}")
    print(f"load average (1 min): {load_start:.2f} at the start, {load_end:.2f} at the end")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
