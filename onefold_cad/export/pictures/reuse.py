"""One 3D figure per size and thread, emptied and drawn again.

A sweep draws a thumbnail per design, each on a new figure with a new 3D
axes: building the ``Axes3D`` (its three axes, their ticks, panes and
grids) cost a third of a thumbnail. :func:`empty_axes3d` keeps the figure
and axes of each size in the calling thread (a Dask worker may draw in
several threads at once) and hands them back with every artist of the last
picture removed; the caller sets the limits, the box and the view again
(:func:`~onefold_cad.export.pictures.figure3d.fit_axes`), so nothing of the
last picture shows in the next. Only pictures without axes use it (the
thumbnails): tick labels and legends would carry the last picture's text.
"""

from __future__ import annotations

import threading
from typing import Any

from onefold_cad.export.pictures.figure3d import agg_figure

__all__ = ["empty_axes3d"]

_KEPT = threading.local()


def empty_axes3d(size_px: tuple[int, int], box: tuple[float, float, float, float]) -> Any:
    """``(figure, axes)``: an Agg figure of ``size_px`` (width, height) with a
    3D axes at ``box`` (figure fraction: left, bottom, width, height),
    without axis lines, panes or ticks (``set_axis_off``), the painting
    order explicit (``computed_zorder=False``), holding no artist."""
    kept: dict[tuple[Any, ...], tuple[Any, Any]] = _KEPT.__dict__.setdefault("figures", {})
    key = (tuple(size_px), tuple(box))
    if key not in kept:
        fig = agg_figure(size_px)
        ax = fig.add_axes(box, projection="3d", computed_zorder=False)
        ax.set_axis_off()
        kept[key] = (fig, ax)
    fig, ax = kept[key]
    for artist in (*ax.lines, *ax.collections, *ax.artists, *ax.patches, *ax.texts, *ax.images):
        artist.remove()
    return fig, ax
