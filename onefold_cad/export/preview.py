"""A shaded 3D preview (PNG) of the folded form standing on the ground.

matplotlib is imported only inside this module (and only when a preview is
drawn), on the non-interactive Agg canvas, so the rest of the package never
pays for it.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from onefold_cad.errors import ExportError
from onefold_cad.export.atomic import atomic_output
from onefold_cad.geometry.folding import FoldedSheet

__all__ = ["render_folded_preview", "resting_mesh"]

_TOP = np.array([0.86, 0.62, 0.30])  # the flat sheet's top (+z) face
_BOTTOM = np.array([0.55, 0.63, 0.72])
_LIGHT = np.array([-0.4, -0.6, 0.7]) / np.linalg.norm([-0.4, -0.6, 0.7])


def resting_mesh(
    folded: FoldedSheet, angular: int = 120, radial: int = 16
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """The form's triangle mesh moved into its resting placement.

    Returns:
        ``(vertices (k, 3), faces (m, 3))``: vertices in the design unit, the
        ground at z = 0; faces oriented so their normal is the top side's.
    """
    verts, faces = folded.mesh(angular=angular, radial=radial)
    return folded.resting.apply(verts), faces


def _face_colours(tri: NDArray[np.float64], view: NDArray[np.float64]) -> NDArray[np.float64]:
    """Lambert-shaded RGBA per triangle ``(m, 3, 3)``: the side facing the
    viewer decides whether the top or the bottom colour shows."""
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    facing_top = (n @ view) > 0.0
    n = np.where(facing_top[:, None], n, -n)
    shade = 0.45 + 0.55 * np.clip(n @ _LIGHT, 0.0, 1.0)
    base = np.where(facing_top[:, None], _TOP, _BOTTOM)
    rgb = np.clip(base * shade[:, None], 0.0, 1.0)
    return np.concatenate([rgb, np.ones((len(rgb), 1))], axis=1)


def render_folded_preview(
    folded: FoldedSheet,
    path: str | os.PathLike[str],
    *,
    title: str = "",
    units: str = "",
    size_px: tuple[int, int] = (900, 700),
    elev: float = 20.0,
    azim: float = -110.0,
) -> Path:
    """Draw the folded form, standing on the ground, to a PNG file.

    The crease halves are drawn dark, the sheet's top face warm and its
    bottom face cool. Written to a temporary name in the same folder and
    renamed into place, so ``path`` never holds a partial image.

    Args:
        folded: the folded sheet.
        path: the PNG file to write.
        title: a caption (e.g. the design name).
        units: the length unit for the axis labels.
        size_px: image width and height in pixels.
        elev, azim: the camera's elevation and azimuth (deg, matplotlib's).

    Returns:
        The path written.

    Raises:
        ExportError: the image could not be written.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    out = Path(path)
    verts, faces = resting_mesh(folded)
    tri = verts[faces]
    e, a = np.radians(elev), np.radians(azim)
    view = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])

    dpi = 100
    fig = Figure(figsize=(size_px[0] / dpi, size_px[1] / dpi), dpi=dpi)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(projection="3d")
    ax.add_collection3d(
        Poly3DCollection(tri, facecolors=_face_colours(tri, view), edgecolors="none")
    )
    crease = np.array([[folded.apex, c.end_3d] for c in folded.crease])
    ax.add_collection3d(
        Line3DCollection(
            folded.resting.apply(crease.reshape(-1, 3)).reshape(-1, 2, 3),
            colors="#222222",
            linewidths=1.6,
        )
    )
    edge = folded.resting.apply(folded.boundary_3d)
    edge = np.vstack([edge, edge[:1]])
    ax.plot(edge[:, 0], edge[:, 1], edge[:, 2], color="#333333", linewidth=0.7)
    ax.plot(edge[:, 0], edge[:, 1], np.zeros(len(edge)), color="#999999", linewidth=0.5)

    lo, hi = verts.min(axis=0), verts.max(axis=0)
    span = np.maximum(hi - lo, 1e-9 * float(np.max(hi - lo)))
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(0.0, hi[2])
    ax.set_box_aspect(tuple(span))
    ax.view_init(elev=elev, azim=azim)
    unit = f" ({units})" if units else ""
    ax.set_xlabel(f"x{unit}", fontsize=8)
    ax.set_ylabel(f"y{unit}", fontsize=8)
    ax.set_zlabel(f"z{unit}", fontsize=8)
    ax.tick_params(labelsize=7)
    if title:
        ax.set_title(title, fontsize=10)
    fig.subplots_adjust(left=0.0, right=1.0, bottom=0.02, top=0.95)

    try:
        out.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ExportError(f"cannot write preview {str(out)!r}: {exc.strerror or exc}") from exc
    with atomic_output(out) as tmp:
        fig.savefig(tmp, format="png", dpi=dpi)
    return out
