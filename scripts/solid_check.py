#!/usr/bin/env python3
"""Thick STEP solids of Table 1's square (alpha 50, beta 45, 300 mm) at t = 3 mm.

Prints, per sheet surface: validity, faces, the volume against area x t and
against the volume integrated from the geometry (``slab_volume``), and the
build time. With ``--sweep N`` it also builds N random designs (folds up to
170 deg, t from 0.5 to 2% of the sheet size, the default relief hole) and
counts failures. Run: ``.venv/bin/python scripts/solid_check.py [--sweep 36 --seed 1]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from onefold_cad import Design, FrameCurve, Material, Sheet, SheetSurface, build_design
from onefold_cad.design import relief_hole_diameter
from onefold_cad.export.measure import measure
from onefold_cad.export.step import build_shell, build_solid
from onefold_cad.geometry.thick_sheet import slab_volume


def check(design: Design) -> str:
    folded = build_design(design)
    hole = relief_hole_diameter(design, folded)
    m = design.material.with_changes(relief_hole=hole)
    t0 = time.perf_counter()
    solid = build_solid(folded, m)
    dt = time.perf_counter() - t0
    area = measure(build_shell(folded, relief_hole=hole))
    vol = measure(solid, "volume")
    return (
        f"{m.sheet_surface.value:7s} hole {hole:g}: valid {solid.is_valid}, "
        f"faces {len(solid.faces())}, V/(A t) - 1 = {vol / (area * m.thickness) - 1:+.1e}, "
        f"V/slab_volume - 1 = {vol / slab_volume(folded, m, hole) - 1:+.1e}, {dt:.1f} s"
    )


def random_design(rng: np.random.Generator, i: int) -> Design:
    a, b = rng.uniform(10, 80, 2)
    hc = rng.uniform(-0.6, 0.6) * 100.0 * np.cos(np.radians(a))
    kind = i % 3
    if kind == 0:
        sheet = Sheet.quadrilateral(*rng.uniform(80, 400, 4))
    elif kind == 1:
        sheet = Sheet.rectangle(rng.uniform(200, 800), rng.uniform(200, 800), rng.uniform(0.3, 0.7))
    else:
        k = int(rng.integers(8, 13))
        ang = np.sort(rng.uniform(0, 2 * np.pi, k))
        rad = rng.uniform(120, 300, k)
        sheet = Sheet.polygon(np.stack([rad * np.cos(ang), rad * np.sin(ang)], 1))
    surface = list(SheetSurface)[i % 3]
    t = float(rng.uniform(0.005, 0.02) * sheet.size)
    material = Material(thickness=t, sheet_surface=surface)
    return Design(f"r{i}", FrameCurve(a, b, hc), sheet, material=material)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sweep", type=int, default=0, help="random designs to build")
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    square = Design("sq", FrameCurve(50, 45), Sheet.quadrilateral(300, 300, 300, 300))
    for surface in SheetSurface:
        print(check(square.with_changes(material=Material(thickness=3.0, sheet_surface=surface))))
    rng = np.random.default_rng(args.seed)
    failures = 0
    for i in range(args.sweep):
        try:
            design = random_design(rng, i)
        except Exception as err:  # an inadmissible random draw: say so, go on
            print(f"{i}: design rejected ({err})")
            continue
        try:
            print(f"{i}: {check(design)}")
        except Exception as err:
            failures += 1
            print(f"{i}: FAIL {type(err).__name__}: {err}")
    if args.sweep:
        print(f"{failures} failures of {args.sweep}")
    return 1 if failures else 0


if __name__ == "__main__":
    raise SystemExit(main())
