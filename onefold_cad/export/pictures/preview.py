"""A shaded 3D preview (PNG) of the folded form standing on the ground.

What the picture shows, each item named in its legend: the sheet's top face
(the flat sheet's +z side) warm and its bottom face cool, whichever faces the
camera; the crease dark, with each half's fold angle written beside it; the
apex (H) as a dot; the form's outline on the ground (its shadow from above);
the support polygon (the hull of the points that touch the ground) and the
centre of mass with a plumb line to its ground point. Under the view: the fold
angles and bend directions, the height and footprint, and whether it stands.
:func:`thumbnail_png` draws the same view small, without the words (a
sweep's picture of each design).
With ``frame=True`` (``build --placement frame``, like the STEP and GLB) the
form is drawn in the fold frame instead (apex above H), without the ground,
support polygon and centre of mass; the caption still gives how it stands.

matplotlib is imported only inside :func:`render_folded_preview` (and only
when a preview is drawn), on the non-interactive Agg canvas, so the rest of
the package never pays for it; the figure work is kept small (no layout
engine; the shaded surface's ~9 000 triangles painted in numpy as one image,
:mod:`~onefold_cad.export.pictures.surface_image`, the pixels matplotlib's
own collection gives) because ``onefold build`` draws one per design; a
sweep's thumbnails reuse one emptied figure per thread
(:mod:`~onefold_cad.export.pictures.reuse`).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from onefold_cad.design import rest_once
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
from onefold_cad.export.pictures.reuse import empty_axes3d
from onefold_cad.export.pictures.surface_image import add_surface
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import Array
from onefold_cad.geometry.resting.placement import RestingPlacement

__all__ = ["render_folded_preview", "resting_mesh", "support_and_centre", "thumbnail_png"]

_TOP_RGB = (0.86, 0.62, 0.30)  # the flat sheet's top (+z) face
_BOTTOM_RGB = (0.55, 0.63, 0.72)
_TOP, _BOTTOM = np.array(_TOP_RGB), np.array(_BOTTOM_RGB)
_CREASE, _APEX, _GROUND = "#222222", "#c0392b", "#8a8a8a"
_SUPPORT, _COM = "#2e8b57", "#6a1b9a"
#: Mesh density: rays of each side, points along each ray. The surface is
#: straight along a ray, but matplotlib paints triangles in the order of their
#: mean depth, and where the two sides overlap in the view a long triangle of
#: the far side's top face sorts in front of the near underside: orange
#: speckles on the underside (patkau-one-fold at 900 x 700 px: 185 such pixels
#: with 6 points a ray, 10 with 24; a 360 x 60 mesh is the reference).
_ANGULAR, _RADIAL = 90, 24


def resting_mesh(
    folded: FoldedSheet,
    angular: int = 120,
    radial: int = 16,
    placement: RestingPlacement | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """The form's triangle mesh moved into its resting placement.

    Args:
        folded: the folded sheet.
        angular, radial: the mesh density (see :meth:`FoldedSheet.mesh`).
        placement: how the form stands (default ``rest_once(folded)``, the bare
            surface; :func:`onefold_cad.fabrication.rules.resting_placement` for the
            body the STEP holds).

    Returns:
        ``(vertices (k, 3), faces (m, 3))``: vertices in the design unit, the
        ground at z = 0; faces oriented so their normal is the top side's.
    """
    rest = rest_once(folded) if placement is None else placement
    verts, faces = folded.mesh(angular=angular, radial=radial)
    return rest.apply(verts), faces


def support_and_centre(placement: RestingPlacement) -> tuple[Array, Array]:
    """The support polygon and the centre of mass of a resting form, in 3D.

    Returns:
        ``(polygon (k, 3), centre (3,))``: the placement's support polygon on
        the ground (z = 0), counter-clockwise (one or two points when the
        form rests on a point or rocks on an edge), and its centre of mass
        (the sheet with its thickness), in the resting frame (design unit).
    """
    poly = np.asarray(placement.support_polygon, dtype=float).reshape(-1, 2)
    return np.column_stack([poly, np.zeros(len(poly))]), np.asarray(placement.centre_of_mass)


def _face_colours(tri: NDArray[np.float64], view: NDArray[np.float64]) -> NDArray[np.float64]:
    """Lambert-shaded RGBA per triangle ``(m, 3, 3)``: the side facing the
    viewer decides whether the top or the bottom colour shows."""
    facing_top, shade = lambert(tri, view)
    base = np.where(facing_top[:, None], _TOP, _BOTTOM)
    rgb = np.clip(base * shade[:, None], 0.0, 1.0)
    return np.concatenate([rgb, np.ones((len(rgb), 1))], axis=1)


def _caption(folded: FoldedSheet, rest: RestingPlacement, units: str, frame: bool = False) -> str:
    """The lines written under the view: fold angles, size, stability, read
    from the placement (the report's ``resting`` section says the same); with
    ``frame``, that the view is the fold frame."""
    u = f" {units}" if units else ""
    folds = ", ".join(
        f"{c.name.replace('_', ' ')} {c.fold_angle_deg:.1f}\N{DEGREE SIGN} {c.bend}"
        for c in folded.crease
    )
    margin = rest.tipping_margin_deg
    stands = (
        f"stands with a tipping margin of {margin:.1f}\N{DEGREE SIGN}"
        if rest.stable
        else "does NOT stand stably (no tipping margin)"
    )
    where = "shown in the fold frame (apex above H); standing, " if frame else ""
    return (
        f"fold angles: {folds} (UP: the top faces end inside)\n"
        f"{where}height {rest.height:.4g}{u}, footprint {rest.width:.4g} x {rest.depth:.4g}{u} "
        "(x by y)\n"
        f"the {rest.body} {stands}; tilted {rest.tilt_deg:.1f}\N{DEGREE SIGN} from the fold frame"
    )


def render_folded_preview(
    folded: FoldedSheet,
    path: str | os.PathLike[str],
    *,
    placement: RestingPlacement | None = None,
    frame: bool = False,
    title: str = "",
    units: str = "",
    size_px: tuple[int, int] = (900, 700),
    elev: float = 20.0,
    azim: float = -110.0,
) -> Path:
    """Draw the folded form, standing on the ground, to a PNG file.

    Written to a temporary name in the same folder and renamed into place,
    so ``path`` never holds a partial image.

    Args:
        folded: the folded sheet.
        path: the PNG file to write.
        placement: how the form stands (default ``rest_once(folded)``;
            ``build`` passes :func:`onefold_cad.fabrication.rules.resting_placement`,
            the placement of the STEP's body).
        frame: draw the form in the fold frame (apex above H) instead of
            standing, without ground, support polygon and centre of mass;
            the caption still says how it stands (``placement``).
        title: a caption (e.g. the design name).
        units: the length unit for the axis labels and the caption.
        size_px: image width and height in pixels.
        elev, azim: the camera's elevation and azimuth (deg, matplotlib's).

    Returns:
        The path written.

    Raises:
        ExportError: the image could not be written.
    """
    fig = _figure(folded, placement, frame, title, units, size_px, elev, azim, annotate=True)
    return save_png(fig, path, "preview")


def thumbnail_png(
    folded: FoldedSheet,
    placement: RestingPlacement | None = None,
    size_px: tuple[int, int] = (240, 180),
    elev: float = 20.0,
    azim: float = -110.0,
) -> bytes:
    """A small picture of the form as it stands (PNG bytes): the shaded
    surface, the crease, the apex, the outline on the ground, the support
    polygon and the centre of mass, as :func:`render_folded_preview` draws
    them, without legend, caption, labels or axes (a sweep's thumbnail).
    ``size_px`` is width and height in pixels."""
    import io

    fig = _figure(folded, placement, False, "", "", size_px, elev, azim, annotate=False)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=fig.dpi, pil_kwargs={"compress_level": 6})
    return buf.getvalue()


def _figure(
    folded: FoldedSheet,
    placement: RestingPlacement | None,
    frame: bool,
    title: str,
    units: str,
    size_px: tuple[int, int],
    elev: float,
    azim: float,
    annotate: bool,
) -> Any:
    """The preview's figure (on an Agg canvas); ``annotate``: with legend,
    caption, fold-angle labels and axes."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    rest = rest_once(folded) if placement is None else placement
    move = (lambda p: np.asarray(p, dtype=float)) if frame else rest.apply
    verts, faces = folded.mesh(angular=_ANGULAR, radial=_RADIAL)
    verts = move(verts)
    tri = verts[faces]
    view = view_direction(elev, azim)
    apex = move(folded.apex[None, :])[0]
    support, centre = support_and_centre(rest)

    # explicit drawing order (ground, surface, crease, labels, dots): the dots
    # and labels stay visible where the surface would hide them
    bottom = 60.0 / size_px[1] if annotate else 0.0  # room for the three caption lines
    box = (0.0, bottom, 0.8, 0.99 - bottom) if annotate else (0.0, 0.0, 1.0, 1.0)
    if annotate:
        fig = agg_figure(size_px)
        ax = fig.add_axes(box, projection="3d", computed_zorder=False)
    else:  # a thumbnail: the thread's figure of this size, emptied
        fig, ax = empty_axes3d(size_px, box)
    edge = move(folded.boundary_3d)
    edge = np.vstack([edge, edge[:1]])
    if not frame:
        ax.plot(edge[:, 0], edge[:, 1], np.zeros(len(edge)), color=_GROUND, lw=0.9, zorder=1)
        if len(support) >= 3:
            poly = Poly3DCollection([support], facecolors=_SUPPORT, alpha=0.35, zorder=2)
            poly.set_edgecolor(_SUPPORT)
            ax.add_collection3d(poly)
        else:
            ax.plot(*support.T, color=_SUPPORT, linewidth=1.5, zorder=2)
        com_line = np.stack([centre, centre * [1.0, 1.0, 0.0]]).T
        ax.plot(*com_line, color=_COM, lw=1.0, ls=":", zorder=2)
    add_surface(ax, tri, _face_colours(tri, view), zorder=3)
    ax.plot(edge[:, 0], edge[:, 1], edge[:, 2], color="#333333", linewidth=0.7, zorder=4)
    crease = move(np.array([[folded.apex, c.end_3d] for c in folded.crease]).reshape(-1, 3))
    crease = crease.reshape(-1, 2, 3)
    ax.add_collection3d(Line3DCollection(crease, colors=_CREASE, linewidths=1.8, zorder=4))
    for (p, q), half in zip(crease, folded.crease, strict=True) if annotate else ():
        label = f"{half.fold_angle_deg:.1f}\N{DEGREE SIGN}"
        ax.text(
            *(0.5 * (p + q)),
            label,
            fontsize=8.5,
            color=_CREASE,
            zorder=5,
            bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.75},
        )
    dot = 30 if annotate else 10
    if not frame:
        ax.scatter(*centre, color=_COM, s=dot, depthshade=False, zorder=6)
    ax.scatter(*apex, color=_APEX, s=dot, depthshade=False, zorder=6)

    fit_axes(ax, verts, ground=not frame, elev=elev, azim=azim, zoom=0.95 if annotate else 1.2)
    if not annotate:
        ax.set_axis_off()
        return fig
    label_axes(ax, units)
    head = heading(fig, title) if title else None
    handles = [
        Patch(color=_TOP_RGB, label="top face (+z of the flat sheet)"),
        Patch(color=_BOTTOM_RGB, label="bottom face"),
        Line2D([], [], color=_CREASE, lw=1.8, label="crease, fold angle"),
        Line2D([], [], color=_APEX, marker="o", ls="", label="apex (H)"),
    ]
    if not frame:
        handles += [
            Line2D([], [], color=_GROUND, lw=0.9, label="outline on the ground"),
            Patch(facecolor=_SUPPORT, alpha=0.5, edgecolor=_SUPPORT, label="support polygon"),
            Line2D([], [], color=_COM, marker="o", ls=":", label="centre of mass"),
        ]
    legend_below(fig, handles, head)
    fig.text(0.015, 0.015, _caption(folded, rest, units, frame), fontsize=8.5, va="bottom")

    return fig
