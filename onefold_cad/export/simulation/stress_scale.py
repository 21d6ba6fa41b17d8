"""The stress picture's colour scale: the bulk of the sheet readable, yield marked.

A formed sheet's stresses span orders of magnitude (a few faces by the relief
hole carry many times what the rest does), so a scale from 0 to the largest
stress would paint nearly the whole sheet one colour. :func:`stress_scale`
picks the scale's ends from the stresses themselves:

- 'yield': some faces pass the yield stress and the 99th percentile by area
  does too: cool colours from 0 to yield, warm ones from yield to that
  percentile (each half of the colour bar), a distinct colour above it;
- 'capped': some pass yield but the 99th percentile by area does not: cool
  colours from 0 to yield, one warm colour above yield;
- 'below': nothing reaches yield: cool colours from 0 to the largest stress.

Below yield the scale is linear, or a square-root scale when 99 % of the
area lies in its lower half (the low stresses of a sheet far from yield
spread over the colours).

numpy only: the picture builds its matplotlib colour map from the stops here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from onefold_cad.geometry.numeric import Array

__all__ = ["ABOVE_CAP", "BELOW_YIELD", "OVER_YIELD", "PERCENTILE", "StressScale", "stress_scale"]

#: The share of the sheet's area (percent) below the warm colours' top end.
PERCENTILE = 99.0
#: Colours below yield (sRGB hex, low to high): pale to deep blue.
BELOW_YIELD: tuple[str, ...] = ("#c6dbef", "#6baed6", "#2171b5", "#08306b")
#: Colours from yield to the scale's top: yellow to dark red.
OVER_YIELD: tuple[str, ...] = ("#fed976", "#fd8d3c", "#e31a1c", "#800026")
#: The colour of faces above the scale's top.
ABOVE_CAP = "#ff33cc"


@dataclass(frozen=True)
class StressScale:
    """The stress picture's scale (MPa).

    Attributes:
        kind: 'yield', 'capped' or 'below' (see the module docstring).
        top: the colours' top end (the percentile, the yield stress, or the
            largest stress).
        yield_MPa: the yield stress.
        over: some faces lie above ``top`` (drawn in the over colour).
        over_colour: that colour (hex), None without ``over``.
        note: the scale in words, for the legend.
        gamma: the cool colours' scale: 1 linear, 0.5 square root (of the
            stress over ``top``).
    """

    kind: str
    top: float
    yield_MPa: float
    over: bool
    over_colour: str | None
    note: str
    gamma: float = 1.0


def weighted_percentile(values: Array, weights: Array, percent: float) -> float:
    """The value below which ``percent`` % of the ``weights`` lie."""
    order = np.argsort(values)
    cum = np.cumsum(np.asarray(weights, dtype=float)[order])
    k = int(np.searchsorted(cum, percent / 100.0 * cum[-1]))
    return float(np.asarray(values, dtype=float)[order][min(k, len(order) - 1)])


def stress_scale(stress: Array, areas: Array, yield_MPa: float) -> StressScale:
    """The scale for per-face stresses ``stress`` (MPa) on faces of ``areas``."""
    largest = float(np.max(stress))
    cap = weighted_percentile(stress, areas, PERCENTILE)
    share = float(np.sum(areas[stress > yield_MPa]) / np.sum(areas))
    if largest <= yield_MPa:
        top = max(largest, 1e-9 * yield_MPa)
        gamma = 0.5 if cap < 0.5 * top else 1.0
        note = f"all below the yield stress ({yield_MPa:.4g} MPa)" + _root(gamma)
        return StressScale("below", top, yield_MPa, False, None, note, gamma)
    if cap > yield_MPa:
        over = largest > cap
        note = (
            f"above yield ({100 * share:.3g} % of the area): warm colours; "
            f"scale capped at {cap:.4g} MPa ({PERCENTILE:.0f}th percentile by area)"
            + ("; above it: pink" if over else "")
        )
        return StressScale("yield", cap, yield_MPa, over, ABOVE_CAP if over else None, note)
    gamma = 0.5 if cap < 0.5 * yield_MPa else 1.0
    note = (
        f"above yield ({100 * share:.3g} % of the area): red; scale capped at the yield stress"
        + _root(gamma)
    )
    return StressScale("capped", yield_MPa, yield_MPa, True, OVER_YIELD[2], note, gamma)


def _root(gamma: float) -> str:
    return "; square-root scale (99 % of the area in its lower half)" if gamma != 1.0 else ""
