#!/usr/bin/env python3
"""STEP for every valid design, or a clear reason: a seeded corpus, rerunnable.

Without options: the thick solids of Table 1's square (alpha 50, beta 45,
300 mm) at t = 3 mm, one per sheet surface, with validity, faces, the volume
against area x t and against the volume integrated from the geometry
(``slab_volume``), and the build time.

``--corpus N --seed S``: N random designs, extremes favoured (alpha and beta
near 0 and 90 deg, H near an end of the f-line, slivers, thin and thick
sheets from 1e-4 to 5e-2 of the sheet size, sheets from 0.1 to 10 000 units,
both models, 3 to 1000 divisions), each solved, then written as STEP (the
default body: the solid for an exact design with thickness, else the
shell; resting on the ground) and read back with build123d. Every design
lands in one class:

* ``no design``: the inputs are refused before STEP (not a STEP matter);
* ``written``: the STEP was written and reads back valid;
* ``refused``: the STEP writer refused with a message (counted per message
  pattern, each printed once with an example);
* ``invalid``: a STEP was written that does not read back valid (a bug);
* ``crash``: any other exception (a bug).

Run: ``.venv/bin/python scripts/solid_check.py --corpus 200 --seed 1``
(about 0.3 s per design). Exit status 1 if any design is invalid or crashed.
"""

from __future__ import annotations

import argparse
import math
import re
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

import numpy as np

from onefold_cad import Design, FrameCurve, Material, Sheet, SheetSurface, fold_design
from onefold_cad.errors import InvalidParameterError, NoSolutionError, OneFoldError
from onefold_cad.export.measure import measure
from onefold_cad.export.part import build_shell, build_solid
from onefold_cad.export.step import export_design_step, read_step
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.fabrication.rules import default_body
from onefold_cad.geometry.slab_volume import slab_volume


def check(design: Design) -> str:
    """One line of numbers about the solid of ``design`` (Table 1's square)."""
    folded = fold_design(design)
    hole = relief_hole_diameter(design, folded)
    m = design.material.with_changes(relief_hole=hole)
    t0 = time.process_time()
    solid = build_solid(folded, m)
    dt = time.process_time() - t0
    area = measure(build_shell(folded, relief_hole=hole))
    vol = measure(solid, "volume")
    return (
        f"{m.sheet_surface.value:7s} hole {hole:g}: valid {solid.is_valid}, "
        f"faces {len(solid.faces())}, V/(A t) - 1 = {vol / (area * m.thickness) - 1:+.1e}, "
        f"V/slab_volume - 1 = {vol / slab_volume(folded, m, hole) - 1:+.1e}, {dt:.2f} s CPU"
    )


def _angle(rng: np.random.Generator) -> float:
    """An angle in (0, 90) deg: a third near 0, a third near 90, a third uniform."""
    k = rng.integers(3)
    if k == 0:
        return float(10.0 ** rng.uniform(-3.0, 1.0))
    if k == 1:
        return float(90.0 - 10.0 ** rng.uniform(-3.0, 1.0))
    return float(rng.uniform(0.5, 89.5))


def random_design(rng: np.random.Generator, i: int) -> Design:
    """Design ``i`` of the corpus (raises for inadmissible draws)."""
    alpha, beta = _angle(rng), _angle(rng)
    frac = rng.choice(
        [rng.uniform(-0.6, 0.6), rng.choice([-1, 1]) * (1 - 10 ** rng.uniform(-4, -1))]
    )
    size = float(10.0 ** rng.uniform(-1.0, 4.0))
    kind = i % 3
    if kind == 0:  # the paper's quadrilateral, slivers included
        sides = size * 10.0 ** rng.uniform(-1.5, 0.0, 4)
        sheet = Sheet.quadrilateral(*sides)
    elif kind == 1:
        aspect = 10.0 ** rng.uniform(-1.5, 1.5)
        sheet = Sheet.rectangle(size, size * aspect, float(rng.uniform(0.02, 0.98)))
    else:
        k = int(rng.integers(5, 14))
        ang = np.sort(rng.uniform(0.0, 2.0 * math.pi, k))
        rad = size * rng.uniform(0.3, 1.0, k)
        sheet = Sheet.polygon(np.stack([rad * np.cos(ang), rad * np.sin(ang)], 1))
    exact = rng.random() < 0.6
    divisions = int(round(10.0 ** rng.uniform(math.log10(3), 3.0)))
    frame = FrameCurve(alpha, beta, frac * 100.0 * math.cos(math.radians(alpha)), 100.0, divisions)
    t = (
        0.0
        if rng.random() < 0.25
        else float(10.0 ** rng.uniform(-4.0, math.log10(0.05)) * sheet.size)
    )
    material = Material(
        thickness=t,
        bend_radius=float(rng.uniform(0.0, 2.0)) * t,
        sheet_surface=list(SheetSurface)[int(rng.integers(3))],
    )
    return Design(f"c{i}", frame, sheet, model="exact" if exact else "paper", material=material)


def _pattern(message: str) -> str:
    """A refusal message with its numbers blanked, to count alike ones together."""
    return re.sub(r"-?\d[\d.e+-]*", "#", message)[:160]


def corpus(n: int, seed: int) -> int:
    rng = np.random.default_rng(seed)
    counts: Counter[str] = Counter()
    refusals: Counter[str] = Counter()
    examples: dict[str, str] = {}
    times = []
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(n):
            try:
                design = random_design(rng, i)
                folded = fold_design(design)
            except (InvalidParameterError, NoSolutionError) as err:
                counts["no design"] += 1
                print(f"{i}: no design ({err.__class__.__name__}: {err})"[:200])
                continue
            body = default_body(design)
            path = Path(tmp) / f"{design.name}.step"
            t0 = time.perf_counter()
            try:
                export_design_step(design, path, folded)
            except OneFoldError as err:
                counts["refused"] += 1
                key = f"{err.__class__.__name__}: {_pattern(str(err))}"
                refusals[key] += 1
                examples.setdefault(key, f"{design!r}: {err}")
                print(f"{i}: {body} refused: {err}"[:240])
                continue
            except Exception as err:
                counts["crash"] += 1
                print(f"{i}: {body} CRASH {err.__class__.__name__}: {err} -- {design}")
                continue
            times.append(time.perf_counter() - t0)
            shape = read_step(path)
            ok = shape.is_valid and len(shape.faces()) > 0
            counts["written" if ok else "invalid"] += 1
            print(f"{i}: {body} {'ok' if ok else 'INVALID'} {times[-1]:.2f} s {design.frame}"[:200])
    print()
    print(
        f"corpus of {n} designs, seed {seed}: " + ", ".join(f"{k} {v}" for k, v in counts.items())
    )
    for key, c in refusals.most_common():
        print(f"  {c} x {key}\n      e.g. {examples[key]}"[:600])
    if times:
        print(f"write time median {np.median(times):.2f} s, max {np.max(times):.2f} s (wall)")
    return 1 if counts["invalid"] or counts["crash"] else 0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--corpus", type=int, default=0, help="random designs to write as STEP")
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    if args.corpus:
        return corpus(args.corpus, args.seed)
    square = Design("sq", FrameCurve(50, 45), Sheet.quadrilateral(300, 300, 300, 300))
    for surface in SheetSurface:
        print(check(square.with_changes(material=Material(thickness=3.0, sheet_surface=surface))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
