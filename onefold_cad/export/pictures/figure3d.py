"""The pieces the 3D pictures share: light, camera, shading, axes, the PNG file.

The preview (:mod:`onefold_cad.export.pictures.preview`) and the simulation's pictures
(:mod:`onefold_cad.export.simulation.pictures`) draw a form standing on the
ground the same way: a matplotlib 3D axes on the non-interactive Agg canvas,
seen from ``elev``/``azim``, lit from :data:`LIGHT`, axes sized to the form
with few ticks, written atomically as PNG. matplotlib is imported inside the
functions only (importing this module costs nothing).
"""

from __future__ import annotations

import os
import textwrap
from pathlib import Path
from typing import Any

import numpy as np

from onefold_cad.errors import ExportError
from onefold_cad.export.atomic import atomic_output
from onefold_cad.geometry.numeric import Array, Mask

__all__ = [
    "HEADING_WIDTH",
    "LIGHT",
    "agg_figure",
    "fit_axes",
    "heading",
    "label_axes",
    "lambert",
    "legend_below",
    "save_png",
    "shaded_surface",
    "view_direction",
]

#: The direction the light comes from (unit vector, z up).
LIGHT = np.array([-0.4, -0.6, 0.7]) / np.linalg.norm([-0.4, -0.6, 0.7])


def view_direction(elev: float, azim: float) -> Array:
    """``(3,)`` the unit vector towards the camera of matplotlib's ``elev``,
    ``azim`` (deg)."""
    e, a = np.radians(elev), np.radians(azim)
    return np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])


def lambert(tri: Array, view: Array) -> tuple[Mask, Array]:
    """Which side of each triangle ``(m, 3, 3)`` faces the camera and how
    bright it is lit.

    Returns:
        ``(facing_top (m,) bool, shade (m,))``: the triangle's own normal (by
        its vertex order) points towards ``view``; the brightness 0.45..1 of
        the side that faces the camera under :data:`LIGHT`.
    """
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    facing_top = (n @ view) > 0.0
    n = np.where(facing_top[:, None], n, -n)
    return facing_top, 0.45 + 0.55 * np.clip(n @ LIGHT, 0.0, 1.0)


def shaded_surface(ax: Any, tri: Array, rgb: Array, view: Array, zorder: float = 3.0) -> None:
    """Add ``(m, 3, 3)`` triangles to the 3D axes ``ax`` in colours ``rgb (m, 3)``,
    lightly shaded as seen along ``view`` (the colour stays readable against
    a colour bar). matplotlib is imported here only."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    _, shade = lambert(tri, view)
    light = 0.7 + 0.3 * (shade - 0.45) / 0.55
    rgba = np.concatenate([np.clip(rgb * light[:, None], 0, 1), np.ones((len(tri), 1))], axis=1)
    surface = Poly3DCollection(tri, facecolors=rgba, edgecolors="none", antialiased=False)
    surface.set_zorder(zorder)
    ax.add_collection3d(surface)


#: Characters of a picture's heading per line: a design named by its flags
#: (``patkau-one-fold-alpha56.4-beta9.705-...``) wraps instead of running
#: off the picture or across its legend.
HEADING_WIDTH = 90


def heading(fig: Any, text: str, fontsize: float = 11) -> Any:
    """``text`` as the figure's heading, centred at the top, wrapped at
    :data:`HEADING_WIDTH` characters; returns its matplotlib ``Text``."""
    return fig.suptitle(textwrap.fill(text, HEADING_WIDTH), fontsize=fontsize, y=0.985, va="top")


def legend_below(fig: Any, handles: list[Any], head: Any | None, fontsize: float = 8) -> None:
    """The legend of ``handles`` at the figure's top right, below the heading
    ``head`` (:func:`heading`) however many lines it has (None: at the top)."""
    top = 0.995
    if head is not None:
        box = head.get_window_extent(fig.canvas.get_renderer())
        top = box.y0 / fig.bbox.height - 0.006
    fig.legend(handles=handles, loc="upper right", bbox_to_anchor=(0.995, top),
               fontsize=fontsize, frameon=False)  # fmt: skip


def agg_figure(size_px: tuple[int, int], dpi: int = 100) -> Any:
    """A matplotlib figure of ``size_px`` (width, height) pixels on an Agg canvas."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(size_px[0] / dpi, size_px[1] / dpi), dpi=dpi)
    FigureCanvasAgg(fig)
    return fig


def fit_axes(
    ax: Any,
    verts: Array,
    *,
    ground: bool,
    elev: float,
    azim: float,
    zoom: float,
) -> None:
    """Size the 3D axes ``ax`` to ``verts (k, 3)`` at true proportions and turn
    the camera to ``elev``, ``azim`` (deg); with ``ground`` the z axis starts
    at the ground (z = 0)."""
    lo, hi = verts.min(axis=0), verts.max(axis=0)
    span = np.maximum(hi - lo, 1e-9 * float(np.max(hi - lo)))
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(0.0 if ground else lo[2], hi[2])
    ax.set_box_aspect(tuple(span), zoom=zoom)
    ax.view_init(elev=elev, azim=azim)


def label_axes(ax: Any, units: str) -> None:
    """Name the axes x, y, z in ``units`` with small labels and few ticks
    (tick labels cost most of a 3D figure's drawing time)."""
    from matplotlib.ticker import MaxNLocator

    unit = f" ({units})" if units else ""
    ax.set_xlabel(f"x{unit}", fontsize=8)
    ax.set_ylabel(f"y{unit}", fontsize=8)
    ax.set_zlabel(f"z{unit}", fontsize=8)
    ax.tick_params(labelsize=7, pad=0)
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(nbins=4))


def save_png(fig: Any, path: str | os.PathLike[str], what: str = "preview") -> Path:
    """Write ``fig`` to the PNG file ``path`` atomically (its folder made when
    missing) and return the path.

    Raises:
        ExportError: the image could not be written (names ``what`` and the file).
    """
    out = Path(path)
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ExportError(f"cannot write {what} {str(out)!r}: {exc.strerror or exc}") from exc
    with atomic_output(out) as tmp:
        # zlib level 1: a third of the encoding time, a slightly larger file
        fig.savefig(tmp, format="png", dpi=fig.dpi, pil_kwargs={"compress_level": 1})
    return out
