"""Would a coarser preview mesh bring J2's coarse preview to the CPU bar?

The coarse level grades its triangles ``model.MESH_GRADING`` times faster
away from the relief hole than the normal mesh (1.5). This runs
``onefold simulate TEMPLATE --mesh coarse --json`` in-process (J2, its
reserve check) at the shipped grading and at each ``--gradings`` value,
today's moment law at the shipped grading beside them, and each law's normal
mesh without its check (the reference its previews are read against), and prints
per run the nodes, the CPU of the command's call, the springback and
standing maxima, their change from the normal mesh, the Newton iterations
and the verdict on "stands". Asserts nothing; the shipped grading is put
back after each run.

Run from the repository root::

    .venv/bin/python benchmarks/bench_coarse_grading.py [--gradings 2.0]
        [--templates patkau-one-fold broken-vault ...]
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import os
import time

from onefold_cad.choices import MeshLevel
from onefold_cad.cli.main import main as onefold
from onefold_cad.mechanics import model as mechanics_model

#: The steel the paper's templates run as (they carry none of their own).
STEEL = "--youngs-modulus 193 --poisson 0.29 --yield-stress 215 --density 8000 --thickness 1"
CASES = {
    "patkau-one-fold": "",
    "broken-vault": "",
    "patkau-one-fold --thickness 3": "",
    "paper-square": STEEL + " --relief-hole 4",
    "star-polygon": STEEL,
    "table1-row3": STEEL + " --model exact",
    "table1-row4": STEEL + " --model exact",
}


def run(args: list[str], grading: float | None) -> tuple[dict, float]:
    """``onefold simulate ARGS --json``'s simulation report and its CPU (s),
    the coarse level graded at ``grading`` (None: as shipped)."""
    shipped = mechanics_model.MESH_GRADING[MeshLevel.COARSE]
    if grading is not None:
        mechanics_model.MESH_GRADING[MeshLevel.COARSE] = grading
    out = io.StringIO()
    t = time.process_time()
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
            onefold(["simulate", *args, "--json"])
    except SystemExit:
        pass
    finally:
        mechanics_model.MESH_GRADING[MeshLevel.COARSE] = shipped
    return json.loads(out.getvalue())["simulation"], time.process_time() - t


def change(value: float | None, reference: float | None) -> str:
    if value is None or reference is None:
        return "-"
    return f"{100 * (value / reference - 1):+.1f} %"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--gradings", type=float, nargs="+", default=[2.0])
    ap.add_argument("--templates", nargs="+", default=list(CASES))
    args = ap.parse_args()
    shipped = mechanics_model.MESH_GRADING[MeshLevel.COARSE]
    print("| template | run | nodes | CPU s | springback max | vs normal | standing max "
          "| vs normal | iterations | stands |")  # fmt: skip
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name in args.templates:
        flags = (name + " " + CASES.get(name, "")).split()
        refs = {law: run([*flags, "--no-check", "--law", law], None)[0] for law in ("moment", "j2")}
        rows = [(f"normal, {law}, no check", law, sim, None) for law, sim in refs.items()]
        for law, grading in [("moment", None), ("j2", None)] + [("j2", g) for g in args.gradings]:
            sim, cpu = run([*flags, "--mesh", "coarse", "--law", law], grading)
            rows.append((f"coarse, {law}, grading {grading or shipped:g}", law, sim, cpu))
        for label, law, sim, cpu in rows:
            r, s, ref = sim["released"], sim["standing"], refs[law]
            stood = s.get("verdict") or ("stands" if s["stands"] else "does not stand")
            print(f"| {name} | {label} | {sim['mesh']['nodes']} | "
                  f"{'-' if cpu is None else f'{cpu:.2f}'} | {r['max_deviation']:.4g} | "
                  f"{change(r['max_deviation'], ref['released']['max_deviation'])} | "
                  f"{s['max_deviation'] or 0:.4g} | "
                  f"{change(s['max_deviation'], ref['standing']['max_deviation'])} | "
                  f"{r['iterations']} + {s['iterations']} | {stood} |", flush=True)  # fmt: skip
    print(f"\nload average {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
