"""``onefold loads``'s STR strength check: the CPU of the J2 load paths per
case against the linear check, per mesh level, and what each path says
(``r_R``, what ended it, the plastic strain at the case and where), so the
cost of ``--strength-cases`` can be chosen.

Run from the repository root::

    .venv/bin/python benchmarks/bench_loads_strength.py [TEMPLATE]
        [--levels coarse normal] [--cases 3|all] [--wind-speed 25] [--snow 1]

Prints only (CPU seconds: ``time.process_time``; the machine's other jobs
slow the wall clock, not these).
"""

from __future__ import annotations

import argparse
import time

from onefold_cad.design import fold_design
from onefold_cad.mechanics.loads.outdoors import outdoors
from onefold_cad.mechanics.loads.spec import LoadSpec
from onefold_cad.templates import load_template


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--levels", nargs="*", default=["coarse", "normal"])
    ap.add_argument("--cases", default="3", help="a number, or all")
    ap.add_argument("--wind-speed", type=float, default=25.0)
    ap.add_argument("--snow", type=float, default=1.0)
    args = ap.parse_args(argv)
    count = None if args.cases == "all" else int(args.cases)
    design = load_template(args.template)
    folded = fold_design(design)
    spec = LoadSpec(wind_speed=args.wind_speed, snow_kPa=args.snow)
    for level in args.levels:
        t0 = time.process_time()
        o = outdoors(design, folded, spec, level=level, strength_cases=count)
        total = time.process_time() - t0
        j2 = o.strength["cpu_s"]
        print(f"{args.template} {level}: {o.mesh['nodes']} nodes, {len(o.cases)} cases; "
              f"CPU {total:.1f} s in all, {j2:.1f} s in {len(o.strength['cases_checked'])} "
              f"J2 paths, {total - j2:.1f} s else")  # fmt: skip
        for c in o.cases:
            s = c.strength
            if s is None:
                continue
            at = (
                ""
                if s.max_plastic_strain_at is None
                else (f" at ({s.max_plastic_strain_at[0]:.4g}, {s.max_plastic_strain_at[1]:.4g})")
            )
            print(f"  {c.name:<32} r_R {s.ratio:6.3g} ({s.limit:8}) plastic strain "
                  f"{100 * s.max_plastic_strain:.3g} %{at}, elastic peak {c.utilisation:.3g} "
                  f"x f_y, {s.cpu_s:.1f} s")  # fmt: skip
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
