"""Would a looser Newton tolerance for the load steps short of a path's end
make ``simulate --law j2`` cheaper?

Runs ``simulate(..., law="j2", convergence=False, reserve=False)`` on
patkau-one-fold with every ``solve_path`` step short of ``s = 1`` solved
to ``TOL`` times the sheet's weight (the path's end keeps
``stages.RTOL``; Abaqus's default residual tolerance, for comparison, is
5e-3 of the average force at every increment), for each ``--tolerances``
value (``base``: the package as it is), and prints the Newton iterations
of the release and the stand, the CPU time, the springback and standing
deviations and whether it stands. Asserts nothing.

Run from the repository root::

    .venv/bin/python benchmarks/bench_path_tolerance.py [--levels coarse normal]
        [--tolerances base 1e-5 1e-4 1e-3]
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from typing import Any

from onefold_cad.design import fold_design
from onefold_cad.mechanics import equilibrium
from onefold_cad.mechanics import stages as moment_stages
from onefold_cad.mechanics.j2 import stages as j2_stages
from onefold_cad.mechanics.simulate import simulate
from onefold_cad.templates import find_template, load_template

_SOLVE_PATH = equilibrium.solve_path
_SOLVE = equilibrium.solve_equilibrium


def loose_path(tol: float) -> Callable[..., Any]:
    """``solve_path`` whose steps short of the end are solved to ``tol``."""

    def path(shell_at: Callable[[float], Any], q0: Any, **options: Any) -> Any:
        final = {"at_end": False}

        def at(s: float) -> Any:
            final["at_end"] = s >= 1.0
            return shell_at(s)

        def solve(shell: Any, start: Any, **opts: Any) -> Any:
            if not final["at_end"]:
                opts["rtol"] = max(float(opts.get("rtol", 0.0)), tol)
            return _SOLVE(shell, start, **opts)

        equilibrium.solve_equilibrium = solve  # type: ignore[assignment]
        try:
            return _SOLVE_PATH(at, q0, **options)
        finally:
            equilibrium.solve_equilibrium = _SOLVE

    return path


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--levels", nargs="+", default=["coarse", "normal"])
    ap.add_argument("--tolerances", nargs="+", default=["base", "1e-5", "1e-4", "1e-3"])
    args = ap.parse_args()
    design = load_template(find_template("patkau-one-fold"))
    folded = fold_design(design)
    print(
        "| mesh | steps short of the end to | release + stand iterations | CPU s | "
        "springback max | standing max (or the load carried) |"
    )
    print("|---|---|---|---|---|---|")
    for level in args.levels:
        for tol in args.tolerances:
            path = _SOLVE_PATH if tol == "base" else loose_path(float(tol))
            j2_stages.solve_path = path  # type: ignore[assignment]
            moment_stages.solve_path = path  # type: ignore[assignment]
            t = time.process_time()
            sim = simulate(design, folded, level=level, convergence=False, law="j2",
                           reserve=False)  # fmt: skip
            cpu = time.process_time() - t
            r, s = sim.released, sim.standing
            assert r is not None
            stood = (
                f"{s.max_deviation:.4f} mm" if s.max_deviation is not None
                else f"does not stand: {s.load_factor:.3g} of the weight"
            )  # fmt: skip
            what = f"{stages_rtol()} (as the end)" if tol == "base" else f"{tol} x weight"
            print(f"| {level} | {what} | {r.iterations} + {s.iterations} | {cpu:.2f} | "
                  f"{r.max_deviation:.4f} mm | {stood} |")  # fmt: skip
    j2_stages.solve_path = _SOLVE_PATH  # type: ignore[assignment]
    moment_stages.solve_path = _SOLVE_PATH  # type: ignore[assignment]


def stages_rtol() -> str:
    return f"{moment_stages.RTOL:g} x weight"


if __name__ == "__main__":
    main()
