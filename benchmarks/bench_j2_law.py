"""``onefold simulate``'s laws side by side, in one process: the J2 law
(plasticity through the thickness), today's moment law and the moment law of
an earlier commit (``--baseline``, main before the J2 work, extracted from git
by ``git_baseline.py``), each on the same design and mesh level, interleaved
round by round (CPU seconds of ``simulate``, the design's solve excluded),
with the numbers each reports (formed plastic share, springback, standing
deviation, largest stress, Newton iterations). ``--before COMMIT`` adds that
commit's J2 and moment laws (say, main before a speed-up) to the same rounds;
``--digits`` the significant digits of the numbers.

Run from the repository root::

    .venv/bin/python benchmarks/bench_j2_law.py [TEMPLATE] [--levels coarse normal]
        [--rounds 1] [--baseline 8921478] [--before main] [--digits 4]
        [--check-mesh finer|coarser]

The normal level runs with its convergence check (``simulate``'s default;
``--check-mesh coarser``: today's runs check against the coarse level's mesh),
the coarse preview without. Prints only.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from git_baseline import load  # noqa: E402

from onefold_cad.choices import MeshLevel  # noqa: E402
from onefold_cad.design import fold_design  # noqa: E402
from onefold_cad.mechanics.simulate import simulate  # noqa: E402
from onefold_cad.templates import find_template, load_template  # noqa: E402

#: Template keys newer than the baseline (its loader refuses them).
NEW_KEYS = ("hardening_modulus", "kinematic_hardening")


def _row(sim) -> dict[str, float | None]:
    f, r, s = sim.formed, sim.released, sim.standing
    return {
        "plastic share": f.plastic_area_share,
        "springback max": r.max_deviation,
        "standing max": s.max_deviation,
        "largest stress MPa": s.max_stress_MPa,
        "iterations": (r.iterations or 0) + (s.iterations or 0),
        "mesh change %": _change(sim),
    }


def _change(sim) -> float | None:
    """The convergence check's relative change in percent (None without one)."""
    conv = getattr(sim, "convergence", None) or {}
    change = conv.get("max_deviation_change")
    return None if change is None else 100 * change


def _before_runs(commit: str, template: str) -> dict:
    """``commit``'s J2 and moment laws, its own package on its own template."""
    pkg, why = load(commit)
    if pkg is None:
        print(f"no {commit}: {why}")
        return {}
    import importlib

    osim = importlib.import_module(pkg.__name__ + ".mechanics.simulate")
    odes = importlib.import_module(pkg.__name__ + ".design")
    otpl = importlib.import_module(pkg.__name__ + ".templates")
    od = otpl.load_template(str(find_template(template)))  # the file as this tree has it
    of = odes.fold_design(od)

    def law(name: str):
        return lambda d, f, lvl, chk: osim.simulate(od, of, level=lvl, convergence=chk, law=name)

    return {f"J2 ({commit})": law("j2"), f"moment ({commit})": law("moment")}


def baseline_simulate(commit: str, template: str):
    """``commit``'s ``simulate`` (its default law) on ``template`` as a function
    ``(level, convergence) -> Simulation``, the design loaded and folded on the
    first call from the template's file without the keys the commit did not
    know yet (:data:`NEW_KEYS`); None (the reason printed) when git or the
    commit is not there."""
    old, why = load(commit)
    if old is None:
        print(f"no baseline: {why}")
        return None
    import importlib

    osim = importlib.import_module(old.__name__ + ".mechanics.simulate")
    odes = importlib.import_module(old.__name__ + ".design")
    otpl = importlib.import_module(old.__name__ + ".templates")
    cache: dict[str, object] = {}

    def run(level: str, convergence: bool):
        if "pair" not in cache:
            text = find_template(template).read_text(encoding="utf-8")
            keep = [ln for ln in text.splitlines() if not ln.startswith(NEW_KEYS)]
            tmp = Path(tempfile.mkdtemp()) / f"{template}.toml"
            tmp.write_text("\n".join(keep) + "\n", encoding="utf-8")
            od = otpl.load_template(str(tmp))
            fold = getattr(odes, "fold_design", None) or odes.build_design  # its old name
            cache["pair"] = (od, fold(od))
        od, of = cache["pair"]  # type: ignore[misc]
        return osim.simulate(od, of, level=level, convergence=convergence)

    return run


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--levels", nargs="*", default=["coarse", "normal"])
    ap.add_argument("--rounds", type=int, default=1)
    ap.add_argument("--baseline", default="8921478")
    ap.add_argument("--before", default=None)
    ap.add_argument("--digits", type=int, default=4)
    ap.add_argument(
        "--check-mesh", default="finer", choices=["finer", "coarser"],
        help="today's convergence check's mesh (the baseline's and --before's: finer)",
    )  # fmt: skip
    args = ap.parse_args(argv)
    mesh = args.check_mesh
    baseline = baseline_simulate(args.baseline, args.template)
    today = "today" if mesh == "finer" else "today, checked on the coarser mesh"
    runs = {
        f"J2 ({today})": lambda d, f, lvl, chk: simulate(
            d, f, level=lvl, convergence=chk, law="j2", check_mesh=mesh if chk else "finer"
        ),
        f"moment ({today})": lambda d, f, lvl, chk: simulate(
            d, f, level=lvl, convergence=chk, law="moment", check_mesh=mesh if chk else "finer"
        ),
    }
    if baseline is not None:
        runs[f"moment ({args.baseline})"] = lambda d, f, lvl, chk: baseline(lvl, chk)
    if args.before:
        runs = {**_before_runs(args.before, args.template), **runs}
    design = load_template(args.template)
    folded = fold_design(design)
    print(f"{args.template}: CPU s of simulate (median of {args.rounds}), interleaved")
    heads = ["plastic share", "springback max", "standing max", "largest stress MPa", "iterations",
             "mesh change %"]  # fmt: skip
    print("| level | law | CPU s | x baseline | " + " | ".join(heads) + " |")
    print("|---" * (4 + len(heads)) + "|")
    for level in args.levels:
        check = MeshLevel.parse(level).checked
        times: dict[str, list[float]] = {k: [] for k in runs}
        rows: dict[str, dict] = {}
        for _ in range(args.rounds):
            for name, fn in runs.items():
                t = time.process_time()
                sim = fn(design, folded, level, check)
                times[name].append(time.process_time() - t)
                rows[name] = _row(sim)
        base = statistics.median(times[list(runs)[-1]])
        for name in runs:
            med = statistics.median(times[name])
            vals = " | ".join(
                "-" if v is None else f"{v:.{args.digits}g}" for v in rows[name].values()
            )
            print(f"| {level} | {name} | {med:.2f} | {med / base:.2f} | {vals} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
