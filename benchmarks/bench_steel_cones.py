"""The explorer's Steel view for cones formed past their springback (J2, the
moment law cannot form them) beside the view as it is for cones formed to the
design (the moment law), in one run, interleaved.

Each case is ``explore.simulation.simulation_state`` as the Steel view calls
it (``steel_law``, the reserve check left for after the form), on the
template's coarse mesh; the rows give its wall time (median and quartiles:
the server's time for a release's steel) and, from one further call of
each, the form's deviation, the law and the CPU of the reserve check left
for later (``check_state``).

    .venv/bin/python benchmarks/bench_steel_cones.py [TEMPLATE] [--rounds 5]
"""

from __future__ import annotations

import argparse
import os

from interleave import interleave

from onefold_cad.explore.controls import design_from_params
from onefold_cad.explore.server import load_templates
from onefold_cad.explore.simulation import check_state, simulation_state, steel_law


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--rounds", type=int, default=5, help="interleaved rounds per case")
    args = ap.parse_args()
    data, key = load_templates(args.template)
    designs = {
        forming: design_from_params({"cone_forming": forming}, data, key)
        for forming in ("design", "compensated")
    }

    def case(forming: str):
        d = designs[forming]
        return lambda: simulation_state(d, law=steel_law(d), check_later=True)

    stats = interleave(
        {f: case(f) for f in designs}, rounds=args.rounds, batch_time=0.0, clock="wall"
    )
    print(f"{args.template}, coarse mesh, {args.rounds} interleaved rounds; "
          f"load average {os.getloadavg()[0]:.1f}")  # fmt: skip
    print("| cones | law | ms: median [q1, q3] | max deviation | check CPU (s) |")
    print("|---|---|---|---|---|")
    for forming, d in designs.items():
        kept = []
        state = simulation_state(d, law=steel_law(d), check_later=True, keep=kept.append)
        check = check_state(kept[0], None) if kept[0].pending_reserve is not None else None
        s = stats[forming]
        n = state["numbers"]
        after = "-" if check is None else f"{check['cpu_ms'] / 1e3:.2f}"
        print(
            f"| {forming} | {n['law']} | {s.fmt(1e3, digits=4)} | "
            f"{n['max_deviation']:.4g} {state['units']} | {after} |"
        )


if __name__ == "__main__":
    main()
