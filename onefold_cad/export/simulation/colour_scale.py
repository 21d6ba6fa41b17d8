"""The one colour scale of a simulation's deviation, shared by every view of it.

The deviation picture (NAME-deviation.png), the simulation's GLB and the
explorer colour the standing form by each node's distance from the designed
form with the same scale: :data:`DEVIATION_STOPS` (viridis, dark purple for
no deviation to yellow for the largest) stretched from 0 to the largest
deviation, so the three agree colour for colour. numpy only.
"""

from __future__ import annotations

import numpy as np

from onefold_cad.geometry.numeric import Array

__all__ = [
    "DEVIATION_STOPS",
    "STEEL_GREY",
    "deviation_label",
    "deviation_range",
    "ramp",
    "srgb_to_linear",
    "to_uint8",
]

#: The scale's colours (sRGB hex), evenly spaced from its low end to its high end.
DEVIATION_STOPS: tuple[str, ...] = (
    "#440154",
    "#472d7b",
    "#3b528b",
    "#2c728e",
    "#21918c",
    "#28ae80",
    "#5ec962",
    "#addc30",
    "#fde725",
)


#: A form drawn without a scale (sRGB 0..1): the steel grey of NAME.glb.
STEEL_GREY = (0.72, 0.74, 0.78)


def deviation_label(unit: str) -> str:
    """The scale's legend: what it measures, in the design's unit."""
    return f"deviation from the design ({unit})" if unit else "deviation from the design"


def deviation_range(values: Array) -> tuple[float, float]:
    """The scale's ends for per-node deviations ``values`` (design unit): 0 and
    the largest (a tiny positive span when every value is 0)."""
    hi = float(np.max(values)) if len(values) else 0.0
    return 0.0, hi if hi > 0.0 else 1e-12


def _rgb(stops: tuple[str, ...]) -> Array:
    return np.array([[int(s[i : i + 2], 16) / 255.0 for i in (1, 3, 5)] for s in stops])


def ramp(values: Array, lo: float, hi: float, stops: tuple[str, ...] = DEVIATION_STOPS) -> Array:
    """``(n, 3)`` sRGB colours (0..1) of ``values`` on the scale from ``lo`` to
    ``hi`` (clipped to its ends), interpolated linearly between ``stops``."""
    rgb = _rgb(stops)
    t = np.clip((np.asarray(values, dtype=float) - lo) / max(hi - lo, 1e-300), 0.0, 1.0)
    x = np.linspace(0.0, 1.0, len(rgb))
    return np.stack([np.interp(t, x, rgb[:, k]) for k in range(3)], axis=-1)


def srgb_to_linear(rgb: Array) -> Array:
    """sRGB components (0..1) to linear light (glTF's vertex colours are linear)."""
    c = np.asarray(rgb, dtype=float)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def to_uint8(rgb: Array) -> Array:
    """Components 0..1 as bytes 0..255 (rounded)."""
    return np.round(np.clip(rgb, 0.0, 1.0) * 255.0).astype(np.uint8)
