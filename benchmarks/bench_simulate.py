"""The structural check against the peer FE program, each at its 1 % mesh.

``onefold simulate --reference designed --supports anchored`` with a yield
stress never reached (the designed form taken as stress-free, loaded by its
own weight on its three resting contacts) and the same problem in
KratosMultiphysics (``kratos_shell.py``: ``ShellThinElementCorotational3D3N``,
one nonlinear load step, the same three anchored contacts), in one run:

1. each program on a sequence of meshes (ours: ``run(h_max=h)``; Kratos:
   ``kratos_shell.py --h h`` in its own interpreter, ``--kratos-python``);
2. each program's converged largest movement by Richardson extrapolation on
   its three finest meshes (the observed order, the mesh size taken as
   triangles^-1/2);
3. each program's 1 % mesh: the coarsest of its meshes within 1 % of its own
   converged value; the ratio of the CPU times there (Kratos / ours).

Times are CPU seconds (user + system of the process for Kratos, whose own
timing covers its mesh, model build and solve; ``time.process_time`` around
``run`` for ours: meshing, model, the solves, after one untimed warm-up
run), each the median of ``--repeat`` runs; the design's solve and resting
placement are excluded from both. Kratos is no dependency: without ``--kratos-python`` (or
``$KRATOS_PYTHON``) only our side runs. Prints only; ``--write-docs`` pastes
the table into docs/mechanics.md (block ``bench-simulate``).

Run from the repository root::

    .venv/bin/python benchmarks/bench_simulate.py [--ours-h 0.2 0.14 0.1 0.07]
        [--kratos-python /work/kratos-venv/bin/python] [--kratos-h 0.05 0.035 0.025]
        [--repeat 1] [--json] [--write-docs]
    .venv/bin/python benchmarks/bench_simulate.py --commands [--repeat 3] [--write-docs]

``--commands`` times the whole ``onefold simulate`` processes instead (the
normal mesh with its convergence check, and the coarse preview; each with
the default law, J2, and with the moment law, in one run): CPU, wall
and peak memory against the issue's bounds (60 s, 5 s, 2 GB), block
``simulate-commands``.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from dataclasses import asdict, dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from docs_block import ROOT, machine_line, write_block  # noqa: E402
from interleave import run_process  # noqa: E402

from onefold_cad.design import fold_design  # noqa: E402
from onefold_cad.mechanics.simulate import run  # noqa: E402
from onefold_cad.templates import find_template, load_template  # noqa: E402

#: The accuracy both programs are timed at: within this of their converged value.
WITHIN = 0.01


@dataclass(frozen=True)
class Point:
    """One program on one mesh: size (m), nodes, triangles, largest movement
    (mm), CPU time (s, median of the runs)."""

    h: float
    nodes: int
    triangles: int
    movement_mm: float
    cpu_s: float


def richardson(points: list[Point]) -> tuple[float, float]:
    """``(converged value, observed order)`` from the three finest points, the
    mesh size taken as triangles^-1/2 (so a graded mesh counts its triangles)."""
    a, b, c = sorted(points, key=lambda p: p.triangles)[-3:]
    h = [p.triangles**-0.5 for p in (a, b, c)]
    f = [p.movement_mm for p in (a, b, c)]
    # f_i = f* + C h_i^p: solve for p by bisection on the ratio of differences
    ratio = (f[1] - f[0]) / (f[2] - f[1])

    def gap(p: float) -> float:
        return (h[0] ** p - h[1] ** p) / (h[1] ** p - h[2] ** p) - ratio

    lo, hi = 0.05, 8.0
    if gap(lo) * gap(hi) > 0:
        raise SystemExit(
            f"Richardson: no order in (0.05, 8) fits {f} (not in the asymptotic range)"
        )
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if gap(lo) * gap(mid) > 0 else (lo, mid)
    p = 0.5 * (lo + hi)
    converged = f[2] + (f[2] - f[1]) * h[2] ** p / (h[1] ** p - h[2] ** p)
    return converged, p


def one_percent_mesh(points: list[Point], converged: float) -> Point | None:
    """The coarsest point within :data:`WITHIN` of ``converged``."""
    ok = [p for p in points if abs(p.movement_mm / converged - 1) <= WITHIN]
    return min(ok, key=lambda p: p.triangles) if ok else None


def ours(template: str, hs: list[float], repeat: int) -> list[Point]:
    design = load_template(find_template(template))
    folded = fold_design(design)
    unreachable = design.material.youngs_modulus * 1e3  # MPa: the yield stress never reached
    # one untimed run on the coarsest mesh first: imports and one-time set-up are
    # not the check's cost (Kratos's own timing excludes its imports too)
    run(design, folded, reference="designed", h_max=max(hs), yield_stress_MPa=unreachable)
    out = []
    for h in hs:
        times, sim = [], None
        for _ in range(repeat):
            t0 = time.process_time()
            sim = run(
                design,
                folded,
                reference="designed",
                supports="anchored",
                h_max=h,
                yield_stress_MPa=unreachable,
            )
            times.append(time.process_time() - t0)
        assert sim is not None and sim.designed is not None
        scale = {"mm": 1.0, "in": 25.4, "ft": 304.8}[sim.unit]
        point = Point(
            h,
            sim.nodes,
            sim.triangles,
            sim.designed.max_displacement * scale,
            statistics.median(times),
        )
        print(f"  ours   h {h:6.3f} m  {point.nodes:6d} nodes  {point.movement_mm:8.3f} mm  "
              f"{point.cpu_s:8.2f} s CPU", file=sys.stderr, flush=True)  # fmt: skip
        out.append(point)
    return out


def kratos(python: str, template: str, hs: list[float], repeat: int) -> list[Point]:
    out = []
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    script = str(ROOT / "benchmarks" / "kratos_shell.py")
    for h in hs:
        argv = [python, script, template, "--h", str(h), "--json", "--repeat", str(repeat)]
        proc = subprocess.run(argv, capture_output=True, text=True, env=env, check=False)
        if proc.returncode:
            raise SystemExit(f"kratos_shell.py --h {h} failed:\n{proc.stderr[-2000:]}")
        res = json.loads(proc.stdout)
        point = Point(
            h,
            int(res["nodes"]),
            int(res["elements"]),
            float(res["max_displacement_mm"]),
            float(res["timings"]["total_cpu_s"]),
        )
        print(f"  Kratos h {h:6.3f} m  {point.nodes:6d} nodes  {point.movement_mm:8.3f} mm  "
              f"{point.cpu_s:8.2f} s CPU", file=sys.stderr, flush=True)  # fmt: skip
        out.append(point)
    return out


def table(results: dict[str, list[Point]]) -> tuple[str, dict[str, object]]:
    rows = [
        "| program | h (m) | nodes | triangles | largest movement (mm) | vs converged | CPU (s) |",
        "|---|---|---|---|---|---|---|",
    ]
    summary: dict[str, object] = {}
    for name, points in results.items():
        converged, order = richardson(points)
        best = one_percent_mesh(points, converged)
        summary[name] = {
            "converged_mm": converged,
            "order": order,
            "one_percent_mesh": None if best is None else asdict(best),
            "points": [asdict(p) for p in points],
        }
        for p in points:
            mark = " **(1 % mesh)**" if p == best else ""
            rows.append(
                f"| {name} | {p.h:g} | {p.nodes} | {p.triangles} | {p.movement_mm:.3f} | "
                f"{100 * (p.movement_mm / converged - 1):+.2f} %{mark} | {p.cpu_s:.2f} |"
            )
        rows.append(f"| {name}, converged | | | | **{converged:.2f}** (order {order:.2f}) | | |")
    lines = ["\n".join(rows), ""]
    o, k = summary.get("ours"), summary.get("Kratos")
    if o and k and o["one_percent_mesh"] and k["one_percent_mesh"]:
        t_o = o["one_percent_mesh"]["cpu_s"]
        t_k = k["one_percent_mesh"]["cpu_s"]
        summary["speedup"] = t_k / t_o
        summary["agreement"] = o["converged_mm"] / k["converged_mm"] - 1
        lines.append(
            f"At each program's 1 % mesh: Kratos {t_k:.1f} s CPU, ours {t_o:.2f} s CPU: ours "
            f"**{t_k / t_o:.0f}x faster** (target at least 2x: "
            f"{'PASS' if t_k / t_o >= 2 else 'FAIL'}). Converged largest movements: ours "
            f"{o['converged_mm']:.2f} mm, Kratos {k['converged_mm']:.2f} mm "
            f"({100 * summary['agreement']:+.1f} %; the issue's bound 10 %)."
        )
    lines.append("")
    lines.append(machine_line())
    return "\n".join(lines), summary


#: The commands the issue times, with its bounds: (label, argv tail, CPU s bound);
#: the moment law's beside the default (J2), timed in the same run.
COMMANDS = (
    ("normal, convergence check", ["--json"], 60.0),
    ("coarse preview", ["--mesh", "coarse", "--json"], 5.0),
    ("normal, moment law", ["--law", "moment", "--json"], 60.0),
    ("coarse preview, moment law", ["--mesh", "coarse", "--law", "moment", "--json"], 5.0),
)
MEMORY_BOUND = 2 * 1024**3


def commands(template: str, repeat: int) -> str:
    """``onefold simulate TEMPLATE ...`` as whole processes (imports included):
    median wall and CPU (user + system) and the largest peak memory, against
    the issue's bounds (printed as PASS or FAIL, never asserted)."""
    exe = str(Path(sys.executable).parent / "onefold")
    rows = [
        "| command | CPU (s) | wall (s) | peak memory (MB) | bound |",
        "|---|---|---|---|---|",
    ]
    argvs = [[exe, "simulate", template, *tail, "-q"] for _, tail, _ in COMMANDS]
    timed: list[list] = [[] for _ in COMMANDS]
    for _ in range(repeat):  # interleaved: a change of load falls on every command
        for argv, runs in zip(argvs, timed, strict=True):
            runs.append(run_process(argv))
            if runs[-1].returncode:
                raise SystemExit(f"{' '.join(argv)} failed")
    cpus = {}
    for (label, tail, bound), runs in zip(COMMANDS, timed, strict=True):
        cpu = cpus[label] = statistics.median(r.cpu for r in runs)
        wall = statistics.median(r.wall for r in runs)
        peak = max(r.peak_rss for r in runs)
        ok = cpu < bound and peak < MEMORY_BOUND
        rows.append(
            f"| `onefold simulate {template} {' '.join(tail)}` ({label}) | {cpu:.1f} | "
            f"{wall:.1f} | {peak / 2**20:.0f} | CPU < {bound:g} s, memory < 2 GB: "
            f"{'PASS' if ok else 'FAIL'} |"
        )
        print(rows[-1], file=sys.stderr, flush=True)
    load = os.getloadavg()[0]
    ratios = (
        f"J2 against the moment law, CPU: "
        f"{cpus['normal, convergence check'] / cpus['normal, moment law']:.2f} times on the "
        f"normal mesh, {cpus['coarse preview'] / cpus['coarse preview, moment law']:.2f} "
        f"times on the coarse."
    )
    return "\n".join(rows) + (
        f"\n\n{ratios} Medians of {repeat} interleaved runs; load average {load:.1f} at "
        f"the end. " + machine_line()
    )


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--template", default="patkau-one-fold")
    ap.add_argument("--ours-h", type=float, nargs="+", default=[0.2, 0.14, 0.1, 0.07])
    ap.add_argument("--kratos-python", default=os.environ.get("KRATOS_PYTHON"))
    ap.add_argument("--kratos-h", type=float, nargs="+", default=[0.05, 0.035, 0.025])
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--write-docs", action="store_true")
    ap.add_argument(
        "--commands",
        action="store_true",
        help="time the whole `onefold simulate` commands instead (normal and coarse)",
    )
    args = ap.parse_args(argv)
    if args.commands:
        text = commands(args.template, args.repeat)
        print(text)
        if args.write_docs:
            command = "benchmarks/bench_simulate.py " + " ".join(argv or sys.argv[1:])
            write_block("simulate-commands", text, command.strip(), ROOT / "docs" / "mechanics.md")
        return 0
    if len(args.ours_h) < 3 or (args.kratos_python and len(args.kratos_h) < 3):
        ap.error("Richardson needs at least three meshes per program")
    results = {"ours": ours(args.template, args.ours_h, args.repeat)}
    if args.kratos_python:
        results["Kratos"] = kratos(args.kratos_python, args.template, args.kratos_h, args.repeat)
    text, summary = table(results)
    print(json.dumps(summary, indent=1) if args.json else text)
    if args.write_docs:
        command = "benchmarks/bench_simulate.py " + " ".join(argv or sys.argv[1:])
        write_block("bench-simulate", text, command.strip(), ROOT / "docs" / "mechanics.md")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
