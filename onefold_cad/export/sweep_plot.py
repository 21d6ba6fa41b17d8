"""A sweep's picture: parallel coordinates of its designs, the Pareto front marked.

One vertical axis per column (the varied inputs, then the outputs), each
scaled from its smallest to its largest value (written at its ends, with
the unit under the name); one line per design through its values, coloured
by one column (a colour bar says which), and the Pareto designs drawn on
top, thick and red. Reads plain arrays: the sweep
(:mod:`onefold_cad.sweep.outputs`) says what to draw.

matplotlib is imported inside :func:`draw_parallel_coordinates` only, on the
non-interactive Agg canvas.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from onefold_cad.export.atomic import atomic_output
from onefold_cad.geometry.numeric import Array

__all__ = ["draw_parallel_coordinates"]

_FRONT = "#d62728"


def _scaled(values: Array) -> tuple[Array, float, float]:
    v = np.asarray(values, dtype=float)
    finite = v[np.isfinite(v)]
    lo, hi = (float(finite.min()), float(finite.max())) if len(finite) else (0.0, 1.0)
    span = hi - lo if hi > lo else 1.0
    return (v - lo) / span if hi > lo else np.full_like(v, 0.5), lo, hi


def draw_parallel_coordinates(
    path: str | os.PathLike[str],
    axes: Sequence[tuple[str, str, Array]],
    *,
    front: Array | None = None,
    colour: tuple[str, Array] | None = None,
    title: str = "",
    size_px: tuple[int, int] = (1400, 700),
) -> Path:
    """Draw parallel coordinates to a PNG file (written atomically).

    Args:
        path: the PNG file.
        axes: ``(name, unit, values (n,))`` of each axis, left to right; a
            NaN value leaves that design's line out.
        front: ``(n,)`` the Pareto designs (drawn thick, red, on top).
        colour: ``(label, values (n,))`` colouring the lines (default: grey).
        title: written above.
        size_px: width and height in pixels.

    Returns:
        The path written.
    """
    from matplotlib import colormaps
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.collections import LineCollection
    from matplotlib.colors import Normalize
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D

    out = Path(path)
    dpi = 100
    fig = Figure(figsize=(size_px[0] / dpi, size_px[1] / dpi), dpi=dpi)
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0.05, 0.16, 0.84 if colour else 0.9, 0.74))
    k = len(axes)
    scaled = []
    for i, (name, unit, values) in enumerate(axes):
        s, lo, hi = _scaled(values)
        scaled.append(s)
        ax.axvline(i, color="#555555", lw=0.8, zorder=1)
        ax.text(i, -0.04, f"{lo:.4g}", ha="center", va="top", fontsize=8)
        ax.text(i, 1.02, f"{hi:.4g}", ha="center", va="bottom", fontsize=8)
        label = f"{name}\n({unit})" if unit else name
        ax.text(i, -0.11, label, ha="center", va="top", fontsize=9)
    y = np.column_stack(scaled) if scaled else np.zeros((0, 0))
    n = len(y)
    keep = np.all(np.isfinite(y), axis=1) if n else np.zeros(0, dtype=bool)
    on = np.zeros(n, dtype=bool) if front is None else np.asarray(front, dtype=bool)
    x = np.arange(k, dtype=float)
    segs = [np.column_stack([x, y[j]]) for j in np.flatnonzero(keep & ~on)]
    lines = LineCollection(segs, linewidths=0.6, alpha=0.35 if n < 2000 else 0.12, zorder=2)
    if colour is not None:
        c = np.asarray(colour[1], dtype=float)[keep & ~on]
        finite = c[np.isfinite(c)]
        norm = Normalize(*(finite.min(), finite.max()) if len(finite) else (0.0, 1.0))
        lines.set_array(c)
        lines.set_cmap(colormaps["viridis"])
        lines.set_norm(norm)
        bar = fig.colorbar(lines, ax=ax, fraction=0.03, pad=0.02)
        bar.set_label(colour[0], fontsize=9)
        if bar.solids is not None:  # drawn by colorbar() for a mappable with data
            bar.solids.set_alpha(1.0)
    else:
        lines.set_color("#7f7f7f")
    ax.add_collection(lines)
    front_segs = [np.column_stack([x, y[j]]) for j in np.flatnonzero(keep & on)]
    ax.add_collection(LineCollection(front_segs, colors=_FRONT, linewidths=2.0, zorder=3))
    ax.set_xlim(-0.3, k - 0.7 if k > 1 else 0.3)
    ax.set_ylim(-0.02, 1.02)
    ax.set_axis_off()
    handles = [Line2D([], [], color="#7f7f7f", lw=0.8, label=f"{int(keep.sum())} designs")]
    if front is not None:
        handles.append(
            Line2D([], [], color=_FRONT, lw=2.0, label=f"Pareto front ({int((keep & on).sum())})")
        )
    fig.legend(
        handles=handles, loc="lower right", bbox_to_anchor=(0.995, 0.005), fontsize=9, frameon=False
    )
    if title:
        fig.suptitle(title, fontsize=11, x=0.02, ha="left")
    out.parent.mkdir(parents=True, exist_ok=True)
    with atomic_output(out) as tmp:
        fig.savefig(tmp, format="png", dpi=dpi)
    return out
