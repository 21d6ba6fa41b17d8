"""SITE.png: a shaded picture of every sheet of a site as it stands.

Each sheet's surface (its fold's mesh, :func:`onefold_cad.export.pictures.preview.resting_mesh`
in the placement its STEP holds) moved onto the site
(:class:`onefold_cad.site.placement.SitePlacement`), its outline on the
ground and its name; the sheets are drawn as one collection so that their
triangles are depth-sorted together. The smallest distance between two
sheets is written under the view. matplotlib on the Agg canvas, as the
design's preview (:mod:`onefold_cad.export.pictures.preview`).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np

from onefold_cad.export.pictures.figure3d import (
    agg_figure,
    fit_axes,
    heading,
    label_axes,
    lambert,
    legend_below,
    save_png,
    view_direction,
)
from onefold_cad.export.pictures.preview import resting_mesh
from onefold_cad.export.site.context import SiteContext

__all__ = ["render_site_picture"]

#: Sheet colours (top face; the bottom face is drawn darker), one per sheet in turn.
SHEET_COLOURS = ((0.86, 0.62, 0.30), (0.40, 0.62, 0.80), (0.55, 0.72, 0.42), (0.80, 0.50, 0.60))
_GROUND = "#8a8a8a"


def render_site_picture(
    ctx: SiteContext,
    path: str | os.PathLike[str],
    size_px: tuple[int, int] = (1200, 800),
    elev: float = 28.0,
    azim: float = -120.0,
) -> Path:
    """Draw the site's sheets as they stand to a PNG file (atomically).

    Args:
        ctx: the site (its sheets, their placements and clearance).
        path: the PNG file.
        size_px: width and height in pixels.
        elev, azim: the camera (deg, matplotlib's).

    Returns:
        The path written.
    """
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    view = view_direction(elev, azim)
    fig = agg_figure(size_px)
    ax = fig.add_axes((0.03, 0.06, 0.8, 0.88), projection="3d", computed_zorder=False)
    tris, colours, everything = [], [], []
    handles: list[Any] = []  # matplotlib artists for the legend
    for i, s in enumerate(ctx.sheets):
        verts, faces = resting_mesh(s.folded, angular=90, radial=6, placement=s.resting)
        verts = s.site.apply(verts)
        tri = verts[faces]
        top, shade = lambert(tri, view)
        base = np.asarray(SHEET_COLOURS[i % len(SHEET_COLOURS)])
        rgb = np.where(top[:, None], base, base * 0.6) * shade[:, None]
        tris.append(tri)
        colours.append(np.clip(rgb, 0.0, 1.0))
        everything.append(verts)
        edge = s.site.apply(s.resting.apply(s.folded.boundary_3d))
        edge = np.vstack([edge, edge[:1]])
        ax.plot(edge[:, 0], edge[:, 1], np.zeros(len(edge)), color=_GROUND, lw=0.8, zorder=1)
        top_point = verts[np.argmax(verts[:, 2])]
        ax.text(*top_point, f" {s.name}", fontsize=10, zorder=6)
        handles.append(Patch(color=tuple(base), label=s.name))
    surface = Poly3DCollection(
        np.concatenate(tris), facecolors=np.concatenate(colours), edgecolors="none"
    )
    surface.set_zorder(3)
    ax.add_collection3d(surface)
    fit_axes(ax, np.concatenate(everything), ground=True, elev=elev, azim=azim, zoom=1.12)
    label_axes(ax, ctx.units)
    head = heading(fig, f"site {ctx.name}: {len(ctx.sheets)} sheets as they stand", fontsize=12)
    handles.append(Line2D([], [], color=_GROUND, lw=0.8, label="outline on the ground"))
    legend_below(fig, handles, head, fontsize=9)
    c = ctx.clearance
    p = None if c is None else c.smallest
    if p is not None:
        fig.text(
            0.015,
            0.015,
            f"smallest distance between two sheets: {p.distance:.0f} {ctx.units} ({p.a} - {p.b})",
            fontsize=9,
            va="bottom",
        )
    return save_png(fig, path, "site picture")
