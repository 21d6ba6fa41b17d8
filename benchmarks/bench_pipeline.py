"""The whole pipeline per shipped template: solve + fold, STEP, DXF, previews.

Run from the repository root:

    .venv/bin/python benchmarks/bench_pipeline.py                # print the table
    .venv/bin/python benchmarks/bench_pipeline.py --write-docs   # also update docs/benchmarks.md

Each stage is timed with time.perf_counter (best of ``--repeat`` runs; the
file-writing stages write into a temporary folder) and shown with its ratio to
the template's own ``solve + fold`` measured in the same run. A stage whose
adapter is not installed is reported as missing, and a stage that raises a
OneFoldError as FAILED with its message, never skipped silently.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_solver import DOCS, best_of, machine_info, replace_block  # noqa: E402

from onefold_cad import Design, OneFoldError, build_design  # noqa: E402
from onefold_cad.templates import list_templates, load_template  # noqa: E402

Stage = Callable[[Design, Any, Path], Any]


def _step(design: Design, folded: Any, out: Path) -> Any:
    from onefold_cad.export.step import export_design_step

    return export_design_step(design, out / f"{design.name}.step", folded=folded)


def _dxf(design: Design, folded: Any, out: Path) -> Any:
    from onefold_cad.export.dxf import export_design_dxf

    return export_design_dxf(design, out / f"{design.name}.dxf", folded=folded)


def _preview_3d(design: Design, folded: Any, out: Path) -> Any:
    from onefold_cad.export.preview import render_folded_preview

    return render_folded_preview(folded, out / f"{design.name}.png", title=design.name)


def _preview_flat(design: Design, folded: Any, out: Path) -> Any:
    from onefold_cad.export.dxf import draw_flat_pattern
    from onefold_cad.export.dxf_preview import render_preview
    from onefold_cad.export.flat_pattern import flat_pattern

    doc = draw_flat_pattern(flat_pattern(design, folded))
    return render_preview(doc, out / f"{design.name}-flat.png")


STAGES: dict[str, Stage] = {
    "STEP": _step,
    "DXF": _dxf,
    "preview 3D": _preview_3d,
    "preview flat": _preview_flat,
}


def measure(design: Design, repeat: int, out: Path) -> dict[str, float | str]:
    """Seconds per stage (or the reason it could not run), for one design."""
    t_core, folded = best_of(lambda: build_design(design), repeat)
    res: dict[str, float | str] = {"solve + fold": t_core}
    for name, stage in STAGES.items():
        try:
            t, _ = best_of(lambda s=stage: s(design, folded, out), repeat)
        except (ImportError, AttributeError) as exc:
            res[name] = f"missing ({exc.__class__.__name__}: {exc})"
            continue
        except OneFoldError as exc:  # recorded, so a failing adapter shows in the table
            res[name] = f"FAILED: {str(exc).replace('|', '/')}"
            continue
        res[name] = t
    return res


def render(results: dict[str, dict[str, float | str]], repeat: int) -> str:
    info = machine_info()
    cols = ["solve + fold", *STAGES]
    lines = [
        f"Machine: {info['cpu']}, {info['cores']} cores, {info['os']}; Python "
        f"{info['python']}, numpy {info['numpy']}. Best of {repeat} runs. Each cell: "
        "seconds (ratio to the same template's solve + fold).",
        "",
        "| template | " + " | ".join(cols) + " | total |",
        "|---" * (len(cols) + 2) + "|",
    ]
    for name, res in results.items():
        base = res["solve + fold"]
        assert isinstance(base, float)
        cells, total = [], 0.0
        for c in cols:
            v = res[c]
            if isinstance(v, float):
                total += v
                cells.append(f"{v:.3g} ({v / base:.3g}x)")
            else:
                cells.append(v)
        lines.append(f"| {name} | " + " | ".join(cells) + f" | {total:.3g} |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=3, help="best of N runs (default 3)")
    ap.add_argument("--only", nargs="*", help="template names (default: all shipped)")
    ap.add_argument("--write-docs", action="store_true", help="update docs/benchmarks.md")
    args = ap.parse_args(argv)
    infos = [i for i in list_templates() if not args.only or i.name in args.only]
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        for info in infos:
            results[info.name] = measure(load_template(info.path), args.repeat, Path(tmp))
            print(f"{info.name}: done", file=sys.stderr)
    text = render(results, args.repeat)
    print(text)
    if args.write_docs:
        cmd = "python benchmarks/bench_pipeline.py --write-docs" + (
            f" --repeat {args.repeat}" if args.repeat != 3 else ""
        )
        replace_block(DOCS, "bench_pipeline", text, cmd)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
