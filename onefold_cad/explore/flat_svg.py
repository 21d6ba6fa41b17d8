"""The flat pattern as an SVG fragment for the page (drawing only, no geometry).

Everything drawn comes from :class:`onefold_cad.fabrication.flat_pattern.FlatPattern`
(the same object the DXF is drawn from): the part's outline, the relief hole,
the apex mark, each fold half with its bend direction and angle
(:attr:`FoldHalf.label`), the bend zones and the rulings. SVG's y axis points
down, so a point (x, y) of the pattern is drawn at (x, -y); strokes do not
scale with the drawing, so they read at any sheet size.
"""

from __future__ import annotations

import math
from xml.sax.saxutils import escape, quoteattr

import numpy as np
from numpy.typing import NDArray

from onefold_cad.fabrication.flat_pattern import FlatPattern

__all__ = ["flat_pattern_svg"]

_STROKE = 'vector-effect="non-scaling-stroke"'


def _xy(p: NDArray[np.float64]) -> tuple[float, float]:
    return float(p[0]), float(-p[1])


def _num(x: float) -> str:
    return f"{x:.6g}"


def _line(a: NDArray[np.float64], b: NDArray[np.float64], cls: str, extra: str = "") -> str:
    (x1, y1), (x2, y2) = _xy(a), _xy(b)
    return (
        f'<line class="{cls}" x1="{_num(x1)}" y1="{_num(y1)}" x2="{_num(x2)}" '
        f'y2="{_num(y2)}" {_STROKE}{extra}/>'
    )


def flat_pattern_svg(pattern: FlatPattern) -> str:
    """An ``<svg>`` element of ``pattern`` in its own units (the viewBox is the
    part's bounding box with a margin); classes ``outline``, ``hole``,
    ``apex``, ``fold up|down`` (with ``data-half``, ``data-bend`` and
    ``data-angle-deg``), ``fold-label``, ``bend-zone`` and ``ruling``."""
    outline = pattern.outline
    lo, hi = outline.min(axis=0), outline.max(axis=0)
    scale = float(max(hi - lo))
    margin = 0.08 * scale
    x0, y0 = float(lo[0] - margin), float(-hi[1] - margin)
    w, h = float(hi[0] - lo[0] + 2 * margin), float(hi[1] - lo[1] + 2 * margin)
    text_h = scale / 32.0
    parts = [
        f'<svg xmlns="http://www.w3.org/2000/svg" class="flat-pattern" '
        f'viewBox="{_num(x0)} {_num(y0)} {_num(w)} {_num(h)}" '
        f'preserveAspectRatio="xMidYMid meet" role="img" '
        f"aria-label={quoteattr(f'flat pattern of {pattern.name}')}>"
    ]
    d = " ".join(
        ("M" if i == 0 else "L") + f"{_num(x)} {_num(y)}"
        for i, (x, y) in enumerate(_xy(p) for p in outline)
    )
    parts.append(f'<path class="outline" d="{d} Z" {_STROKE}/>')
    for a, b in pattern.rulings:
        parts.append(_line(a, b, "ruling"))
    for half in pattern.halves:
        for a, b in half.zone:
            parts.append(_line(a, b, "bend-zone"))
    ax, ay = _xy(pattern.apex)
    if pattern.hole_diameter > 0.0:
        r = pattern.hole_diameter / 2.0
        parts.append(
            f'<circle class="hole" cx="{_num(ax)}" cy="{_num(ay)}" r="{_num(r)}" {_STROKE}/>'
        )
    f = pattern.fold_direction
    n = np.array([-f[1], f[0]])
    m = scale / 50.0
    for arm in ((f + n) / math.sqrt(2.0), (f - n) / math.sqrt(2.0)):
        parts.append(_line(pattern.apex - m * arm, pattern.apex + m * arm, "apex"))
    fold_deg = -math.degrees(math.atan2(f[1], f[0]))  # SVG rotates clockwise (y down)
    if fold_deg > 90.0:
        fold_deg -= 180.0
    elif fold_deg <= -90.0:
        fold_deg += 180.0
    for half in pattern.halves:
        bend = half.bend.lower()
        parts.append(
            _line(
                half.start,
                half.end,
                f"fold {bend}",
                f' data-half="{half.name}" data-bend="{half.bend}" '
                f'data-angle-deg="{half.angle_deg!r}"',
            )
        )
        zone_w = max((abs(float((z[0] - pattern.apex) @ n)) for z in half.zone), default=0.0)
        pos = (half.start + half.end) / 2.0 + n * max(0.8 * text_h, 1.5 * zone_w)
        px, py = _xy(pos)
        parts.append(
            f'<text class="fold-label {bend}" x="{_num(px)}" y="{_num(py)}" '
            f'font-size="{_num(text_h)}" text-anchor="middle" '
            f'transform="rotate({_num(fold_deg)} {_num(px)} {_num(py)})">'
            f"{escape(half.label)}</text>"
        )
    parts.append("</svg>")
    return "".join(parts)
