"""NAME-loads.png: the governing case of an outdoors check.

The sheet standing, moved by the governing case's loads (the movement drawn
to scale, the standing form's outline thin and dashed), each face coloured
by its linear elastic von Mises stress over the yield stress (in %, the
scale up to the 98th percentile by area or 100 %, faces above it in its
top colour; information: the STR
verdict is the J2 load path's), and each foot's reaction drawn as
an arrow from the foot (its length proportional to the force, the largest
labelled in kN). Written atomically; matplotlib is imported only here.
"""

from __future__ import annotations

import os
import textwrap
from pathlib import Path
from typing import Any

import numpy as np

from onefold_cad.export.pictures.figure3d import (
    agg_figure,
    fit_axes,
    heading,
    label_axes,
    save_png,
    shaded_surface,
    view_direction,
)

__all__ = ["area_percentile", "render_governing"]

_ARROW = "#1d4ed8"


def _areas(tri: Any) -> Any:
    """``(m,)`` the areas of ``(m, 3, 3)`` triangles."""
    return 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)


def area_percentile(values: Any, areas: Any, q: float) -> float:
    """The value below which ``q`` % of the area lies (faces' ``values`` with
    their ``areas``; the smallest value whose faces and those below it cover
    at least ``q`` % of the total)."""
    order = np.argsort(values)
    covered = np.cumsum(np.asarray(areas, dtype=float)[order])
    i = int(np.searchsorted(covered, q / 100.0 * covered[-1]))
    return float(np.asarray(values, dtype=float)[order][min(i, len(order) - 1)])


def render_governing(result: Any, path: str | os.PathLike[str], title: str = "") -> Path:
    """Draw ``result`` (:class:`~onefold_cad.mechanics.loads.results.Outdoors`)'s
    governing case into the PNG ``path``."""
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    scale = {"mm": 1000.0, "in": 1 / 0.0254, "ft": 1 / 0.3048}.get(result.unit, 1.0)
    x0 = np.asarray(result.positions) * scale
    moved = x0 + np.asarray(result.moves) * scale
    faces = np.asarray(result.faces)
    util = np.asarray(result.face_utilisation)
    case = result.case(result.governing)
    fig = agg_figure((960, 720))
    ax = fig.add_axes((0.0, 0.1, 0.8, 0.82), projection="3d", computed_zorder=False)
    elev, azim = 24.0, -60.0
    view = view_direction(elev, azim)
    import matplotlib as mpl

    cmap = mpl.colormaps["viridis"]
    # the scale to the 98th percentile by area (the mesh is fine and the
    # elastic stress singular next to H and the relief hole: by count, those
    # few small faces set the scale and wash the sheet out)
    top = max(area_percentile(util * 100.0, _areas(x0[faces]), 98.0), 100.0)
    norm = mpl.colors.Normalize(vmin=0.0, vmax=top)
    rgb = cmap(norm(np.clip(util * 100.0, 0.0, None)))[:, :3]
    shaded_surface(ax, moved[faces], rgb, view)
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    uniq, count = np.unique(edges, axis=0, return_counts=True)
    rim = uniq[count == 1]
    outline = Line3DCollection(x0[rim], colors="#333333", linewidths=0.6, linestyles=(0, (3, 2)))
    outline.set_zorder(4)
    ax.add_collection3d(outline)
    reactions = np.asarray(case.reactions_N, dtype=float)
    feet = np.array([np.append(f.at, 0.0) for f in result.feet])
    size = float(np.ptp(x0, axis=0).max())
    largest = max(float(np.linalg.norm(reactions, axis=1).max()), 1e-9)
    for foot, r in zip(feet, reactions, strict=True):
        d = 0.25 * size * r / largest
        ax.quiver(*foot, *d, color=_ARROW, linewidth=1.6, arrow_length_ratio=0.15, zorder=6)
        ax.text(*(foot + d), f"{np.linalg.norm(r) / 1e3:.3g} kN", fontsize=8, color=_ARROW,
                zorder=7)  # fmt: skip
    fit_axes(ax, np.vstack([x0, moved, feet]), ground=True, elev=elev, azim=azim, zoom=1.05)
    label_axes(ax, result.unit)
    head = f"governing case {case.name}"
    heading(fig, f"{title}: {head}" if title else head)
    bar = fig.add_axes((0.86, 0.2, 0.025, 0.6))
    over = bool(np.any(util * 100.0 > top))
    fig.colorbar(mpl.cm.ScalarMappable(norm=norm, cmap=cmap), cax=bar,
                 extend="max" if over else "neither",
                 label="linear elastic stress (% of f_y; information)")  # fmt: skip
    verdict = "stands" if case.stands else f"does NOT stand: {case.reason}"
    caption = (
        f"{verdict}; largest movement {case.max_deflection:.4g} {result.unit} (drawn to scale), "
        f"peak elastic stress {case.utilisation:.3g} x f_y (information); arrows: the feet's "
        "reactions on the sheet"
    )
    fig.text(0.02, 0.02, "\n".join(textwrap.wrap(caption, 130)), fontsize=8)
    return save_png(fig, path, "the loads picture")
