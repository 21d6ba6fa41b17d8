"""Hypothesis strategies for admissible designs."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import strategies as st

from onefold_cad import FrameCurve, Sheet


@st.composite
def frames(draw: st.DrawFn, divisions: int | None = None) -> FrameCurve:
    """Admissible frame curves: alpha, beta in [5, 85] deg, H anywhere inside the f-line."""
    alpha = draw(st.floats(5.0, 85.0))
    beta = draw(st.floats(5.0, 85.0))
    radius = draw(st.floats(10.0, 1000.0))
    frac = draw(st.floats(-0.999, 0.999))
    n = divisions if divisions is not None else draw(st.integers(12, 400))
    return FrameCurve(alpha, beta, frac * radius * math.cos(math.radians(alpha)), radius, n)


@st.composite
def star_polygons(draw: st.DrawFn) -> Sheet:
    """Random polygons strictly star-shaped about H (every angular gap < 170 deg)."""
    n = draw(st.integers(3, 14))
    weights = np.array(draw(st.lists(st.floats(0.05, 1.0), min_size=n, max_size=n)))
    gaps = weights / weights.sum() * 2 * math.pi
    if np.any(gaps >= math.radians(170.0)):
        gaps = np.full(n, 2 * math.pi / n) if n >= 3 else gaps
    start = draw(st.floats(0.0, 2 * math.pi))
    angles = start + np.concatenate([[0.0], np.cumsum(gaps)[:-1]])
    radii = np.array(draw(st.lists(st.floats(20.0, 400.0), min_size=n, max_size=n)))
    pts = np.stack([radii * np.cos(angles), radii * np.sin(angles)], axis=-1)
    return Sheet.polygon(pts)


@st.composite
def rectangles(draw: st.DrawFn) -> Sheet:
    """Random rectangles folded along a diagonal with a random apex fraction."""
    w = draw(st.floats(10.0, 1000.0))
    h = draw(st.floats(10.0, 1000.0))
    f = draw(st.floats(0.05, 0.95))
    return Sheet.rectangle(w, h, f)


sheets = st.one_of(star_polygons(), rectangles())
