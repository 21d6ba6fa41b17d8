#!/usr/bin/env python3
"""Write the resting placements of the placement issue 24 replaced, for the
test that holds the new one to them (tests/geometry/resting/test_rest_reference.py).

The designs: every shipped template as each body it can be written as, the
default template over a grid of alpha and beta, and seeded rectangles of
Patkau's material (thicknesses 1 to 10, each reference surface). The placement
is that of commit ``--commit`` (9567d0a, before issue 24), extracted from git
beside today's package (benchmarks/git_baseline.py), which builds the designs
and folds too (the same code as today's). Run from the repository root::

    .venv/bin/python scripts/rest_reference.py [--commit 9567d0a]
"""

from __future__ import annotations

import argparse
import importlib
import json
import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benchmarks"))

import git_baseline  # noqa: E402

from onefold_cad import Sheet  # noqa: E402
from onefold_cad.design import Design  # noqa: E402
from onefold_cad.templates import find_template, list_templates, load_template  # noqa: E402

OUT = ROOT / "tests" / "geometry" / "data" / "rest_main.json"


def cases() -> list[dict[str, Any]]:
    """The designs, as specs (see :func:`design_of`), and the bodies of each."""
    out: list[dict[str, Any]] = []
    for t in list_templates():
        d = load_template(t.name)
        m = d.material
        exact = d.model.value == "exact"
        solid = exact and m.thickness > 0.0 and m.relief_hole_diameter > 0.0
        for body in ("shell", "solid") if solid else ("shell",):
            out.append({"template": t.name, "body": body})
    for a in (10.0, 30.0, 50.0, 70.0, 85.0):
        for b in (10.0, 45.0, 80.0):
            out.append(
                {"template": "patkau-one-fold", "frame": {"alpha": a, "beta": b}, "body": "solid"}
            )
    rng = np.random.default_rng(3)
    for _ in range(16):
        a, b = float(rng.uniform(5, 85)), float(rng.uniform(5, 85))
        hc = float(rng.uniform(-0.8, 0.8)) * 100.0 * math.cos(math.radians(a))
        sheet = [
            float(rng.uniform(500, 4000)),
            float(rng.uniform(500, 8000)),
            float(rng.uniform(0.1, 0.9)),
        ]
        material = {
            "thickness": float(rng.choice([1.0, 3.57, 10.0])),
            "sheet_surface": str(rng.choice(["MID", "INSIDE", "OUTSIDE"])),
        }
        for body in ("shell", "solid"):
            out.append(
                {
                    "template": "patkau-one-fold",
                    "frame": {"alpha": a, "beta": b, "h_c": hc},
                    "rectangle": sheet,
                    "material": material,
                    "body": body,
                }
            )
    return out


def design_of(spec: dict[str, Any], pkg: Any = None) -> Design:
    """The design a spec names: a template, with frame, rectangle and material
    changes (built by ``pkg``, a package like ``onefold_cad``; default it)."""
    if pkg is None:
        d, rectangle = load_template(spec["template"]), Sheet.rectangle
    else:
        templates = importlib.import_module(f"{pkg.__name__}.templates")
        d = templates.load_template(str(find_template(spec["template"])))
        rectangle = importlib.import_module(f"{pkg.__name__}.geometry.sheet").Sheet.rectangle
    changes: dict[str, Any] = {}
    if "frame" in spec:
        changes["frame"] = d.frame.with_changes(**spec["frame"])
    if "rectangle" in spec:
        changes["sheet"] = rectangle(*spec["rectangle"])
    if "material" in spec:
        changes["material"] = d.material.with_changes(**spec["material"])
    return d.with_changes(**changes) if changes else d


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--commit", default="9567d0a")
    args = ap.parse_args(argv)
    old, why = git_baseline.load(args.commit)
    if old is None:
        raise SystemExit(why)

    def mod(sub: str) -> Any:
        return importlib.import_module(f"{old.__name__}.{sub}")

    rest = mod("geometry.placement").rest_form
    hole = mod("fabrication.relief_hole").relief_hole_diameter
    fold, solve = mod("geometry.folding").fold, mod("geometry.solver").solve
    rows = []
    for spec in cases():
        d = design_of(spec, old)
        folded = fold(solve(d.frame, d.model), d.sheet)
        m = d.material.with_changes(relief_hole=hole(d, folded))
        r = rest(folded, m, spec["body"])
        rows.append(
            {
                "spec": spec,
                "size": float(folded.sheet.size),
                "rotation": r.rotation.tolist(),
                "translation": r.translation.tolist(),
                "centre_of_mass": r.centre_of_mass.tolist(),
                "contacts": r.contacts.tolist(),
                "support_polygon": r.support_polygon.tolist(),
                "tipping_margin_deg": r.tipping_margin_deg,
                "bounds": r.bounds.tolist(),
                "footprint_area": r.footprint_area,
                "settled": r.settled,
            }
        )
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text(json.dumps({"commit": args.commit, "cases": rows}, indent=1) + "\n")
    print(f"{OUT.relative_to(ROOT)}: {len(rows)} placements of {args.commit}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
