"""How much does a sheet formed past its springback depend on the yield
stress its forming radii were computed for?

``cone_forming = "compensated"`` forms each point of the cones to the
curvature whose springback, by the J2 section of the material as given,
leaves the design's (``mechanics/j2/springback.py``; the radii in
``NAME-cones.csv``). Far from H that curvature is just past first yield,
where the springback is steep in the yield stress. A mill certificate gives
the steel's own; here the radii are computed for ``f`` times the material's
yield stress while the sheet keeps its own (the forming table's law is
replaced in this process), and the standing steel is measured against the
target design as ``onefold compensate`` measures it (the best turn about the
vertical and shift along the ground).

    .venv/bin/python benchmarks/cones_yield.py COMPENSATED.toml --target TEMPLATE
        [--mesh normal] [--factors 0.9,0.95,1,1.05,1.1]

COMPENSATED.toml is what ``onefold compensate TEMPLATE -o DIR`` wrote
(``DIR/TEMPLATE-compensated.toml``); TEMPLATE the design it was compensated to.
"""

from __future__ import annotations

import argparse
import dataclasses
import time

import onefold_cad.mechanics.j2.stages as j2_stages
from onefold_cad.compensate.evaluate import node_weights, simulate_standing, standing_measures
from onefold_cad.mechanics.j2.springback import SpringbackTable
from onefold_cad.templates import find_template, load_template

_OF = SpringbackTable.of


def measured(toml: str, target: str, mesh: str, factor: float) -> tuple[float, float, float, float]:
    """(max, rms deviation from the target, height, span) of the compensated
    design's standing steel, its forming radii computed for ``factor`` times
    its yield stress."""

    def of(law, rule, steps):  # type: ignore[no-untyped-def]
        return _OF(dataclasses.replace(law, yield_stress=factor * law.yield_stress), rule, steps)

    j2_stages.SpringbackTable.of = of  # type: ignore[method-assign]
    try:
        s = simulate_standing(load_template(toml), mesh, law="j2")
    finally:
        j2_stages.SpringbackTable.of = _OF  # type: ignore[method-assign]
    if not s.stands:
        raise SystemExit(f"factor {factor}: the steel does not stand ({s.reason})")
    base = load_template(find_template(target))
    m = standing_measures(base, s.flat, node_weights(s.flat, s.faces), s)
    assert s.height is not None and s.span is not None
    return m.max_deviation, m.rms_deviation, s.height, s.span


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("toml")
    ap.add_argument("--target", required=True)
    ap.add_argument("--mesh", default="normal", choices=("coarse", "normal"))
    ap.add_argument("--factors", default="0.9,0.95,1,1.05,1.1")
    ns = ap.parse_args()
    unit = load_template(find_template(ns.target)).units.value
    t0 = time.process_time()
    print(f"| radii computed for sigma_y x | max / rms from {ns.target} ({unit}) | height | span |")
    print("|---|---|---|---|")
    for f in (float(v) for v in ns.factors.split(",")):
        mx, rms, h, s = measured(ns.toml, ns.target, ns.mesh, f)
        print(f"| {f:g} | {mx:.4g} / {rms:.4g} | {h:.5g} | {s:.5g} |", flush=True)
    print(f"\n{ns.mesh} mesh, J2; {time.process_time() - t0:.0f} s CPU")


if __name__ == "__main__":
    main()
