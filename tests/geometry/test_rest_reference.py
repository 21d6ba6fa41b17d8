"""The resting placement against the one issue 24 replaced, which it must
reproduce: the same contacts and margins, to rounding.

``data/rest_main.json`` holds the placements of commit 9567d0a (written by
``scripts/rest_reference.py`` from that commit's own code) for every shipped
template as each body it can be written as, the default template over a grid
of alpha and beta, and seeded rectangles of its material.

What "to rounding" means depends on how well a placement is determined:

* the shipped templates (what ``onefold build`` writes): every number within
  1e-12 of the sheet's size (lengths) or 1e-12 (rotation, degrees);
* every design: the centre of mass within 1e-13 of the size (its rule is
  the same, the angles at its nodes now from the cone's node table); the
  rotation, translation and bounds within 1e-10 (of the size); the contacts
  within 1e-9 of the size and the margin within 1e-6 deg. A contact where a
  curved edge touches the ground is known along the edge only to about the
  square root of the rounding (the height is flat at a tangency: both
  algorithms stop their zooms once the parabola predicts the height, about
  1e-8 of the size along the edge), and the plane through three such
  contacts, or the balance of a form rocking on two, inherits 1e-12 of it;
* the same number of support corners and the same ``settled``.
"""

from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest

from onefold_cad import fold, solve
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.geometry.placement import rest_form

DATA = Path(__file__).resolve().parent / "data" / "rest_main.json"
SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "rest_reference.py"
CASES = json.loads(DATA.read_text())["cases"]


def _name(case: dict[str, Any]) -> str:
    spec = case["spec"]
    frame = spec.get("frame", {})
    tail = "-".join(f"{v:.4g}" for v in frame.values())
    return f"{spec['template']}{'-' + tail if tail else ''}-{spec['body']}"


@pytest.fixture(scope="module")
def reference() -> ModuleType:
    spec = importlib.util.spec_from_file_location("onefold_rest_reference", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("case", CASES, ids=_name)
def test_rests_where_the_placement_of_main_rested(case: dict[str, Any], reference) -> None:
    spec = case["spec"]
    design = reference.design_of(spec)
    folded = fold(solve(design.frame, design.model), design.sheet)
    material = design.material.with_changes(relief_hole=relief_hole_diameter(design, folded))
    rest = rest_form(folded, material, spec["body"])
    size = case["size"]
    shipped = "frame" not in spec and "rectangle" not in spec
    tight = 1e-12 if shipped else 1e-10

    def off(ours: Any, theirs: Any) -> float:
        return float(np.max(np.abs(np.asarray(ours) - np.asarray(theirs))))

    assert off(rest.centre_of_mass, case["centre_of_mass"]) <= 1e-13 * size
    assert off(rest.rotation, case["rotation"]) <= tight
    assert off(rest.translation, case["translation"]) <= tight * size
    assert off(rest.bounds, case["bounds"]) <= tight * size
    assert rest.settled == case["settled"]
    assert len(rest.support_polygon) == len(case["support_polygon"])
    # each of main's contacts is one of ours, ours none it did not have
    theirs = np.array(case["contacts"]).reshape(-1, 3)
    assert len(rest.contacts) == len(theirs)
    near = max(float(np.linalg.norm(rest.contacts - p, axis=1).min()) for p in theirs)
    assert near <= (tight if shipped else 1e-9) * size
    assert abs(rest.tipping_margin_deg - case["tipping_margin_deg"]) <= (tight if shipped else 1e-6)
    footprint = abs(rest.footprint_area - case["footprint_area"])
    assert footprint <= (tight if shipped else 1e-10) * case["footprint_area"]
