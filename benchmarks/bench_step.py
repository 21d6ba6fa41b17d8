"""Benchmark: build and write the STEP of every template (or the Table 1 designs).

Prints times as ratios against solving the same design (measured in the same
run); asserts nothing about timings. Run: ``python benchmarks/bench_step.py``.
"""

from __future__ import annotations

import glob
import os
import tempfile
import time
from pathlib import Path

from onefold_cad import Design, FrameCurve, Sheet, build_design
from onefold_cad.export.step import build_part, export_design_step

TABLE1 = [
    (0, 50, 45, 90, 300, 300, 300, 300),
    (0, 50, 45, 20, 300, 300, 300, 300),
    (0, 32, 34, 90, 300, 300, 300, 300),
    (68, 32, 34, 90, 300, 96, 103, 201),
]


def designs() -> list[Design]:
    """The templates in templates/*.toml when the loader exists, else Table 1."""
    root = Path(__file__).resolve().parents[1]
    paths = sorted(glob.glob(str(root / "templates" / "*.toml")))
    try:
        from onefold_cad.templates import load_template  # type: ignore[attr-defined]
    except ImportError:
        load_template = None
    if paths and load_template is not None:
        return [load_template(p) for p in paths]
    return [
        Design(f"table1-{i}", FrameCurve(a, b, hc, 100, n), Sheet.quadrilateral(xp, xm, yp, ym))
        for i, (hc, a, b, n, yp, ym, xp, xm) in enumerate(TABLE1)
    ]


def _best(fn, repeat: int = 3) -> float:
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def main() -> None:
    print(f"{'design':24s} {'solve s':>9s} {'build/solve':>12s} {'write/solve':>12s} {'KiB':>8s}")
    with tempfile.TemporaryDirectory() as tmp:
        for d in designs():
            folded = build_design(d)
            t_solve = _best(lambda d=d: build_design(d))
            path = Path(tmp) / f"{d.name}.step"
            try:
                t_build = _best(lambda d=d, f=folded: build_part(d, f))
                t_write = _best(lambda d=d, f=folded, p=path: export_design_step(d, p, f))
                size = os.path.getsize(path) / 1024
                print(
                    f"{d.name:24s} {t_solve:9.4f} {t_build / t_solve:12.1f} "
                    f"{t_write / t_solve:12.1f} {size:8.1f}"
                )
            except Exception as err:  # report and go on (e.g. thickness not supported yet)
                print(f"{d.name:24s} {t_solve:9.4f} failed: {err}")


if __name__ == "__main__":
    main()
