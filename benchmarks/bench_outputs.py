"""What the pictures and the FOLD / GLB files cost, next to a bare ``import build123d``.

    .venv/bin/python benchmarks/bench_outputs.py [--template NAME] [--rounds 5]

Two measurements, both interleaved (A B C, B C A, ...) so a burst of load on
a shared machine hits every case alike; medians with the 25th-75th percentile:

1. Whole processes (wall and CPU time, by the OS): ``import build123d``
   alone; the same plus solving the template; the same plus drawing its
   3D preview (matplotlib imported) and its flat SVG (from its DXF). The
   previews' share of ``onefold build`` is the difference of the last two,
   quoted as a fraction of the bare import.
2. In one process (CPU time per call): each writer on the solved template
   (the GLB from a part built beforehand, as ``build`` passes the STEP's).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from interleave import interleave, run_process, stats_of  # noqa: E402

from onefold_cad.geometry.placement import rest_form

_SOLVE = (
    "from onefold_cad import fold_design; from onefold_cad.templates import load_template; "
    "d = load_template({t!r}); f = fold_design(d); f.resting; "
)
_PREVIEWS = (
    "import tempfile, pathlib; o = pathlib.Path(tempfile.mkdtemp()); "
    "from onefold_cad.export.preview import render_folded_preview; "
    "from onefold_cad.export.dxf import export_design_dxf; "
    "from onefold_cad.export.dxf_preview import render_preview; "
    "render_folded_preview(f, o / 'a.png', title=d.name, units=d.units.value); "
    "render_preview(export_design_dxf(d, o / 'a.dxf', folded=f), o / 'a.svg')"
)


def processes(template: str, rounds: int) -> None:
    py = sys.executable
    cases = {
        "import build123d": [py, "-c", "import build123d"],
        "+ solve": [py, "-c", "import build123d; " + _SOLVE.format(t=template)],
        "+ solve + previews": [
            py,
            "-c",
            "import build123d; " + _SOLVE.format(t=template) + _PREVIEWS,
        ],
    }
    names = list(cases)
    wall: dict[str, list[float]] = {k: [] for k in names}
    cpu: dict[str, list[float]] = {k: [] for k in names}
    for i in range(rounds):
        for k in names[i % 3 :] + names[: i % 3]:
            run = run_process(cases[k])
            if run.returncode:
                raise SystemExit(f"{k!r} failed with exit status {run.returncode}")
            wall[k].append(run.wall)
            cpu[k].append(run.cpu)
    print(f"whole processes, {template}, {rounds} rounds (median [q1, q3] s)")
    for k in names:
        print(f"  {k:22s} wall {stats_of(wall[k]).fmt()}  cpu {stats_of(cpu[k]).fmt()}")
    base = names[0]
    for clock, data in (("wall", wall), ("cpu", cpu)):
        extra = [c - b for c, b in zip(data[names[2]], data[names[1]], strict=True)]
        share = [e / a for e, a in zip(extra, data[base], strict=True)]
        print(
            f"  previews ({clock}): {stats_of(extra).fmt(unit=' s')}, "
            f"{stats_of(share).fmt(100, ' % of a bare import build123d')}"
        )


def writers(template: str, rounds: int) -> None:
    from onefold_cad import fold, fold_design, solve
    from onefold_cad.export.dxf import export_design_dxf
    from onefold_cad.export.dxf_preview import render_preview
    from onefold_cad.export.fold_file import write_fold
    from onefold_cad.export.glb import write_glb
    from onefold_cad.export.part import build_part
    from onefold_cad.export.preview import render_folded_preview
    from onefold_cad.templates import load_template

    design = load_template(template)
    folded = fold_design(design)
    part = build_part(design, folded)
    out = Path(tempfile.mkdtemp())
    dxf = export_design_dxf(design, out / "a.dxf", folded=folded)
    cases = {
        # a fresh fold each call (fold_design keeps one per design object)
        "solve + fold": lambda: rest_form(fold(solve(design.frame, design.model), design.sheet)),
        "3D preview PNG": lambda: render_folded_preview(
            folded, out / "a.png", title=design.name, units=design.units.value
        ),
        "flat SVG (from the DXF)": lambda: render_preview(dxf, out / "a.svg"),
        "FOLD": lambda: write_fold(design, folded, out / "a.fold"),
        f"GLB ({type(part).__name__.lower()} given)": lambda: write_glb(
            design, folded, out / "a.glb", part=part
        ),
    }
    res = interleave(cases, rounds=rounds, batch_time=0.2)
    print(f"in one process, {template}, per call (CPU, median [q1, q3] s)")
    for k, st in res.items():
        print(f"  {k:26s} {st.fmt()}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--template", default="patkau-one-fold")
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    processes(args.template, args.rounds)
    writers(args.template, max(args.rounds, 5))


if __name__ == "__main__":
    main()
