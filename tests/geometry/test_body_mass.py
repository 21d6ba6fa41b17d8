"""The centre of mass's rule: converged, and exact where a closed form exists.

A composite Gauss-Legendre rule is only as good as the smoothness of its
integrand within each panel. The references here do not share that premise:

* the paper model's sheet is planar polygons, so its area and centroid are
  those of the sheet's pieces between the division rays, each folded rigidly
  (polygon formulas on the flat sheet, mapped by the fold: closed form);
* for the exact model, the same integrand under a far finer rule (40
  points, 32 panels a sector, 40 halvings), whose error a kink the rule
  missed would leave at about 1e-10 of the size (the rule before the kinks
  were breaks: 16 points were off by up to 2e-8 of the size, 9e-7 on the
  paper model);
* the kinks themselves: tests/geometry/test_body_kinks.py.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import onefold_cad.geometry.body_mass as body_mass
from onefold_cad import Material, fold, solve
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.geometry.body import FoldedBody
from onefold_cad.geometry.body_mass import mass_properties
from onefold_cad.templates import load_template
from tests.geometry.folds import fold_or_none
from tests.shipped import DESIGN_TEMPLATES

from .conftest import frames, sheets

#: The finer rule: (points, panels, halvings) of each model.
FINE = {"EXACT": (40, 32, 40), "PAPER": (40, 32, 40)}


def _fine(folded, material: Material, kind: str) -> tuple[float, np.ndarray]:
    """``mass_properties`` of that body under the finer rule (the module's
    constants set for the call, then put back)."""
    names = [f"_{m}_{k}" for m in FINE for k in ("POINTS", "PANELS", "HALVINGS")]
    kept = {n: getattr(body_mass, n) for n in names}
    try:
        for m, values in FINE.items():
            for k, v in zip(("POINTS", "PANELS", "HALVINGS"), values, strict=True):
                setattr(body_mass, f"_{m}_{k}", v)
        return mass_properties(FoldedBody(folded, material, kind))
    finally:
        for n, v in kept.items():
            setattr(body_mass, n, v)


def _template_bodies() -> list[tuple[str, str]]:
    out = []
    for name in DESIGN_TEMPLATES:
        d = load_template(name)
        m = d.material
        solid = d.model.value == "exact" and m.thickness > 0.0 and m.relief_hole_diameter > 0.0
        out += [(name, "shell")] + ([(name, "solid")] if solid else [])
    return out


@pytest.mark.parametrize(("name", "kind"), _template_bodies())
def test_every_template_s_mass_is_the_finer_rule_s(name: str, kind: str) -> None:
    design = load_template(name)
    folded = fold(solve(design.frame, design.model), design.sheet)
    material = design.material.with_changes(relief_hole=relief_hole_diameter(design, folded))
    body = FoldedBody(folded, material, kind)
    measure, com = mass_properties(body)
    fine_measure, fine_com = _fine(folded, material, kind)
    assert abs(measure - fine_measure) <= 1e-12 * fine_measure
    assert float(np.abs(com - fine_com).max()) <= 1e-12 * body.size


@settings(max_examples=30)
@given(
    frame=frames(divisions=90),
    sheet=sheets,
    model=st.sampled_from(["exact", "paper"]),
    thickness=st.one_of(st.just(0.0), st.floats(1e-3, 2e-2)),
    surface=st.sampled_from(["INSIDE", "MID", "OUTSIDE"]),
    hole=st.floats(0.0, 0.5),
)
def test_drawn_designs_mass_is_the_finer_rule_s(frame, sheet, model, thickness, surface, hole):
    """Either model; thickness and hole as fractions of the sheet's size (a
    hole up to half the distance from H to the nearest edge). Within 1e-8
    over the whole range: most designs agree within 1e-12, paper sheets on
    a flat frame (alpha = beta = 5 deg) within about 2e-9. The rule before
    was off by 2e-8 of the size on thick exact sheets and 4e-7 on a thick
    paper needle (10 x 644 folded along its long diagonal); the template
    test above tells the rules apart at 1e-12."""
    folded = fold_or_none(frame, sheet, model)
    if folded is None:
        return
    size = float(np.max(np.hypot(*sheet.vertices.T)))
    near = float(np.min(sheet.ray_lengths(np.linspace(0.0, 2.0 * math.pi, 721))))
    material = Material(thickness=thickness * size, relief_hole=hole * near, sheet_surface=surface)
    body = FoldedBody(folded, material, "shell")
    measure, com = mass_properties(body)
    fine_measure, fine_com = _fine(folded, material, "shell")
    assert abs(measure - fine_measure) <= 1e-8 * fine_measure
    assert float(np.abs(com - fine_com).max()) <= 1e-8 * body.size


def _clip(poly: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """Sutherland-Hodgman: the part of polygon ``poly`` ``(m, 2)`` where
    ``normal . p >= 0`` (a half-plane through the origin)."""
    out = []
    for i in range(len(poly)):
        p, q = poly[i], poly[(i + 1) % len(poly)]
        dp, dq = float(normal @ p), float(normal @ q)
        if dp >= 0.0:
            out.append(p)
        if (dp >= 0.0) != (dq >= 0.0):
            out.append(p + (q - p) * (dp / (dp - dq)))
    return np.array(out)


def _area_centroid(poly: np.ndarray) -> tuple[float, np.ndarray]:
    x, y = poly[:, 0], poly[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    area = 0.5 * cross.sum()
    return area, np.array([((x + xn) * cross).sum(), ((y + yn) * cross).sum()]) / (6.0 * area)


@pytest.mark.parametrize("name", ["table1-row1", "table1-row2", "table1-row3", "table1-row4"])
def test_paper_sheet_s_centroid_is_its_folded_pieces(name: str) -> None:
    """The zero-thickness paper sheet: the centroid of each piece of the flat
    sheet between two neighbouring division rays, mapped by the fold (a rigid
    motion on the piece), weighted by the piece's area."""
    design = load_template(name)
    folded = fold(solve(design.frame, "paper"), design.sheet)
    body = FoldedBody(folded, Material(), "shell")
    area, com = mass_properties(body)
    rays = np.asarray(folded.solution.surface.thetas)
    flat = np.asarray(folded.sheet.vertices, dtype=float)
    total, moment = 0.0, np.zeros(3)
    for sign in (1.0, -1.0):  # the +y side's flat angles, the -y side's mirrored
        for a, b in zip(rays[:-1], rays[1:], strict=True):
            lo, hi = sign * a, sign * b
            if sign < 0:
                lo, hi = hi, lo
            piece = _clip(_clip(flat, np.array([-math.sin(lo), math.cos(lo)])),
                          np.array([math.sin(hi), -math.cos(hi)]))  # fmt: skip
            if len(piece) < 3:
                continue
            w, c = _area_centroid(piece)
            total += w
            moment += w * folded.map_points(c[None, :])[0]
    exact = moment / total - folded.apex
    assert abs(area - total) <= 1e-12 * total
    assert float(np.abs(com - exact).max()) <= 1e-12 * body.size
