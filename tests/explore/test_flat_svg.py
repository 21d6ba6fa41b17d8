"""The flat pattern's SVG: the outline, hole, fold halves and labels where they belong."""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from onefold_cad import Design, FrameCurve, Material, Sheet, fold_design
from onefold_cad.explore.flat_svg import flat_pattern_svg
from onefold_cad.fabrication.flat_pattern import flat_pattern

SVG = "{http://www.w3.org/2000/svg}"
W, H, F = 1200.0, 2600.0, 0.35


def _svg(design: Design):
    folded = fold_design(design)
    return ET.fromstring(flat_pattern_svg(flat_pattern(design, folded))), folded


def _rectangle(thickness: float = 2.0) -> Design:
    return Design(
        "rect",
        FrameCurve(alpha=35, beta=40),
        Sheet.rectangle(W, H, F),
        material=Material(
            thickness=thickness, bend_radius=3.0, relief_hole=12.0 if thickness else None
        ),
    )


def test_the_outline_is_the_sheet_drawn_with_y_down():
    """t = 0: the outline is the rectangle itself; SVG puts the sheet's (x, y) at (x, -y)."""
    root, _ = _svg(_rectangle(thickness=0.0))
    d = root.find(f"{SVG}path[@class='outline']").get("d")
    pts = np.array([[float(a), float(b)] for a, b in re.findall(r"[ML]([-\d.e+]+) ([-\d.e+]+)", d)])
    corners = {(0.0, 0.0), (W, 0.0), (W, -H), (0.0, -H)}
    assert len(pts) == 4
    for p in pts:
        assert min(math.dist(p, c) for c in corners) <= 1e-6 * H


def test_the_fold_halves_run_from_the_apex_to_the_diagonals_ends():
    """H sits at F of the diagonal from (0, 0) to (W, H); the +x half ends at (W, H)."""
    root, folded = _svg(_rectangle(thickness=0.0))
    folds = {e.get("data-half"): e for e in root.iter(f"{SVG}line") if "fold" in e.get("class")}
    apex = (F * W, -F * H)
    for name, end in (("plus_x", (W, -H)), ("minus_x", (0.0, 0.0))):
        e = folds[name]
        a = (float(e.get("x1")), float(e.get("y1")))
        b = (float(e.get("x2")), float(e.get("y2")))
        assert math.dist(a, apex) <= 1e-6 * H and math.dist(b, end) <= 1e-6 * H
    for c in folded.crease:
        e = folds[c.name]
        assert float(e.get("data-angle-deg")) == c.fold_angle_deg
        assert e.get("data-bend") == c.bend and c.bend.lower() in e.get("class").split()


def test_each_half_is_labelled_with_its_bend_and_angle():
    root, folded = _svg(_rectangle())
    labels = sorted(t.text for t in root.iter(f"{SVG}text"))
    assert labels == sorted(f"{c.bend} {c.fold_angle_deg:.2f} deg" for c in folded.crease)


def test_the_relief_hole_and_bend_zones_are_drawn_when_there_is_thickness():
    root, _ = _svg(_rectangle(thickness=2.0))
    hole = root.find(f"{SVG}circle[@class='hole']")
    assert float(hole.get("r")) == pytest.approx(6.0, rel=1e-6)
    assert (float(hole.get("cx")), float(hole.get("cy"))) == pytest.approx(
        (F * W, -F * H), rel=1e-6
    )
    zones = [e for e in root.iter(f"{SVG}line") if e.get("class") == "bend-zone"]
    assert len(zones) == 4  # two limit lines per crease half
    flat, _ = _svg(_rectangle(thickness=0.0))
    assert flat.find(f"{SVG}circle[@class='hole']") is None
    assert not [e for e in flat.iter(f"{SVG}line") if e.get("class") == "bend-zone"]
