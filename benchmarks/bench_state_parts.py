"""Where the explorer's state of one slider move goes, part by part, in one process.

For ``--moves`` designs of the default template (alpha stepped by 0.01 deg
from the template's value: each a new design, nothing cached from the one
before), the parts of :func:`onefold_cad.explore.state.design_state` are
timed in the order it runs them: solve and fold, the view's mesh, the
resting placement, the relief hole's refusal check, the flat pattern, the
report's warnings, the numbers, the SVG; then the whole state and its JSON on
further fresh designs. Prints the median and spread (ms) of each; asserts
nothing.

Run from the repository root::

    .venv/bin/python benchmarks/bench_state_parts.py [--moves 60]
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from interleave import stats_of  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    from onefold_cad.design import fold_design
    from onefold_cad.explore.controls import design_from_params
    from onefold_cad.explore.flat_svg import flat_pattern_svg
    from onefold_cad.explore.server import load_templates
    from onefold_cad.explore.state import MESH_ANGULAR, MESH_RADIAL, design_state
    from onefold_cad.fabrication.flat_pattern import flat_pattern
    from onefold_cad.fabrication.relief_hole import relief_hole_diameter, relief_hole_problem
    from onefold_cad.fabrication.report import report_warnings, resting_numbers
    from onefold_cad.fabrication.rules import resting_placement

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--moves", type=int, default=60, help="designs timed")
    args = ap.parse_args(argv)
    templates, key = load_templates(None)
    alpha = float(design_from_params({}, templates, key).frame.alpha)

    def design(i: int) -> Any:
        return design_from_params({"alpha": f"{alpha + 0.01 * (i + 1):.4f}"}, templates, key)

    design_state(design(-1))  # imports warmed
    times: dict[str, list[float]] = {}

    def timed(name: str, fn: Callable[[], Any]) -> Any:
        t0 = time.perf_counter()
        out = fn()
        times.setdefault(name, []).append(1e3 * (time.perf_counter() - t0))
        return out

    for i in range(args.moves):
        d = design(i)
        folded = timed("solve + fold", lambda d=d: fold_design(d))
        timed("mesh", lambda f=folded: f.mesh(MESH_ANGULAR, MESH_RADIAL))
        timed("resting placement", lambda d=d, f=folded: resting_placement(d, f))
        timed("relief hole check", lambda d=d: relief_hole_problem(d))
        pattern = timed("flat pattern", lambda d=d, f=folded: flat_pattern(d, f))
        timed("report warnings", lambda d=d, f=folded, p=pattern: report_warnings(d, f, p))
        timed(
            "numbers",
            lambda d=d, f=folded: (resting_numbers(d, f), relief_hole_diameter(d, f)),
        )
        timed("SVG", lambda p=pattern: flat_pattern_svg(p))
    for i in range(args.moves, 2 * args.moves):
        fresh = design(i)
        state = timed("whole state", lambda d=fresh: design_state(d))
        timed("JSON", lambda s=state: json.dumps(s, allow_nan=False, separators=(",", ":")))
    print(f"The default template's state, {args.moves} moves (ms):\n")
    print("| part | median [q1, q3] |\n|---|---|")
    for name, ms in times.items():
        print(f"| {name} | {stats_of(ms).fmt(unit=' ms')} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
