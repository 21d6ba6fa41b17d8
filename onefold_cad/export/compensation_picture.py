"""The compensation picture: the design, the uncompensated steel and the
compensated steel side by side, the steel coloured by its distance from the
target (one colour scale for both, so the colours compare), each with its
max and rms deviation, height and span under it.

Forms are arrays (design unit, resting frame, z up): :class:`Panel`.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from onefold_cad.export.pictures.figure3d import (
    agg_figure,
    fit_axes,
    lambert,
    save_png,
    view_direction,
)
from onefold_cad.export.simulation.colour_scale import STEEL_GREY, deviation_label, ramp
from onefold_cad.geometry.numeric import Array

__all__ = ["Panel", "render_compensation"]


@dataclass(frozen=True)
class Panel:
    """One form of the picture.

    Attributes:
        title: its heading.
        points: ``(n, 3)`` nodes (design unit, standing frame).
        faces: ``(m, 3)`` triangles.
        deviation: ``(n,)`` distance from the target (design unit), or None
            (drawn steel grey: the target itself).
        caption: the line under it.
    """

    title: str
    points: Array
    faces: Array
    deviation: Array | None
    caption: str


def render_compensation(
    panels: list[Panel],
    unit: str,
    path: str | os.PathLike[str],
    *,
    title: str = "",
    elev: float = 20.0,
    azim: float = -110.0,
) -> Path:
    """Draw ``panels`` side by side with one deviation scale (PNG)."""
    from matplotlib import colormaps
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    devs = [p.deviation for p in panels if p.deviation is not None]
    hi = max([float(np.max(d)) for d in devs] + [1e-12])
    fig = agg_figure((420 * len(panels) + 120, 520))
    view = view_direction(elev, azim)
    every = np.concatenate([p.points for p in panels])
    width = 0.9 / len(panels)
    for i, p in enumerate(panels):
        ax = fig.add_axes((0.01 + i * width, 0.16, width, 0.74), projection="3d",
                          computed_zorder=False)  # fmt: skip
        tri = p.points[p.faces]
        _, shade = lambert(tri, view)
        if p.deviation is None:
            rgb = np.tile(np.array(STEEL_GREY), (len(tri), 1))
        else:
            rgb = ramp(np.asarray(p.deviation)[p.faces].mean(axis=1), 0.0, hi)
        light = 0.7 + 0.3 * (shade - 0.45) / 0.55
        rgba = np.concatenate([np.clip(rgb * light[:, None], 0, 1), np.ones((len(tri), 1))], 1)
        ax.add_collection3d(Poly3DCollection(tri, facecolors=rgba, edgecolors="none"))
        fit_axes(ax, every, ground=True, elev=elev, azim=azim, zoom=1.0)
        ax.set_axis_off()
        ax.set_title(p.title, fontsize=10)
        fig.text(0.01 + (i + 0.5) * width, 0.06, p.caption, fontsize=8, ha="center", va="bottom",
                 wrap=True)  # fmt: skip
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize

    bar = fig.add_axes((0.93, 0.2, 0.015, 0.6))
    mappable = ScalarMappable(Normalize(0.0, hi), colormaps["viridis"])
    fig.colorbar(mappable, cax=bar).set_label(deviation_label(unit).replace("design", "target"))
    if title:
        fig.suptitle(title, fontsize=11)
    return save_png(fig, path, "compensation picture")
