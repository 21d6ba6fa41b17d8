"""A simulation's two pictures: NAME-deviation.png and NAME-stress.png.

Both show the sheet as steel standing on the ground under its weight
(:func:`onefold_cad.mechanics.simulate.simulate`), drawn like the 3D preview
(:mod:`onefold_cad.export.pictures.figure3d`: the same camera, light and axes), with
the designed form's outline drawn thin and dashed for comparison:

- :func:`render_deviation`: each face coloured by its nodes' mean distance
  from the designed form as it stands (the scale of
  :mod:`onefold_cad.export.simulation.colour_scale`, in the design's unit); the caption
  gives the largest and rms deviation, the height and span and whether it
  stands;
- :func:`render_stress`: each face coloured by its von Mises stress at the
  sheet's faces (MPa) on the scale of :mod:`onefold_cad.export.simulation.stress_scale`
  (the yield stress marked on the colour bar), the largest stress marked.

A simulation without a standing equilibrium draws its released form (or,
without one, the designed form) uncoloured and says so in the picture.
Both files are written atomically; matplotlib is imported only when drawing.
"""

from __future__ import annotations

import os
import textwrap
from pathlib import Path
from typing import Any

import numpy as np

from onefold_cad.errors import ExportError
from onefold_cad.export.pictures.figure3d import (
    agg_figure,
    fit_axes,
    heading,
    label_axes,
    legend_below,
    save_png,
    shaded_surface,
    view_direction,
)
from onefold_cad.export.simulation.colour_scale import (
    DEVIATION_STOPS,
    STEEL_GREY,
    deviation_label,
    deviation_range,
    ramp,
)
from onefold_cad.export.simulation.stress_scale import (
    BELOW_YIELD,
    OVER_YIELD,
    StressScale,
    stress_scale,
)
from onefold_cad.geometry.numeric import Array
from onefold_cad.mechanics.results import Simulation

__all__ = ["render_deviation", "render_stress"]

_OUTLINE = "#333333"  # the designed form's outline
_NEUTRAL = np.array(STEEL_GREY)  # an uncoloured form
_MARK = "#111111"  # the largest stress
_NOTICE = "#b91c1c"
_NO_STAND = "it does NOT stand: no equilibrium under its weight (the note on the right says why)"


def _form(sim: Simulation) -> tuple[str, Array]:
    """The form to draw: ('standing', its nodes), else ('released', ...), else
    ('designed', ...) (design unit, resting frame)."""
    if sim.faces is None or sim.designed_positions is None:
        raise ExportError("the simulation carries no mesh to draw")
    if sim.standing_positions is not None:
        return "standing", np.asarray(sim.standing_positions, dtype=float)
    if sim.released_positions is not None:
        return "released", np.asarray(sim.released_positions, dtype=float)
    return "designed", np.asarray(sim.designed_positions, dtype=float)


def _faces(sim: Simulation) -> Array:
    """``(m, 3)`` the simulation's mesh triangles (node indices).

    Raises:
        ExportError: the simulation carries no mesh.
    """
    if sim.faces is None:
        raise ExportError("the simulation carries no mesh to draw")
    return np.asarray(sim.faces)


def _outline(faces: Array, points: Array) -> Array:
    """``(k, 2, 3)`` the mesh's boundary edges (used by one triangle) on ``points``."""
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    uniq, count = np.unique(edges, axis=0, return_counts=True)
    return points[uniq[count == 1]]


def _flat_areas(sim: Simulation) -> Array:
    """``(m,)`` the triangles' areas on the flat sheet (design unit squared)."""
    tri = np.asarray(sim.flat, dtype=float)[_faces(sim)]
    a, b = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    return 0.5 * np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])


def _length(x: float | None, unit: str) -> str:
    return "-" if x is None else f"{x:.4g} {unit}"


def _new_figure(
    sim: Simulation, subject: str, title: str, size_px: tuple[int, int], elev: float, azim: float
) -> tuple[Any, Any, Array, str, Array, Any]:
    """The figure with its 3D axes (room right for the colour bar, below for the
    caption), the designed outline drawn and the heading (wrapped):
    ``(fig, ax, view, kind, points, head)``."""
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    kind, points = _form(sim)
    fig = agg_figure(size_px)
    bottom = 64.0 / size_px[1]
    ax = fig.add_axes((0.0, bottom, 0.8, 0.95 - bottom), projection="3d", computed_zorder=False)
    designed = np.asarray(sim.designed_positions, dtype=float)
    if kind != "designed":
        outline = Line3DCollection(
            _outline(_faces(sim), designed), colors=_OUTLINE, linewidths=0.6, linestyles=(0, (3, 2))
        )
        outline.set_zorder(4)
        ax.add_collection3d(outline)
    fit_axes(ax, np.vstack([points, designed]), ground=True, elev=elev, azim=azim, zoom=1.1)
    label_axes(ax, sim.unit)
    head = heading(fig, f"{title}: {subject}" if title else subject)
    return fig, ax, view_direction(elev, azim), kind, points, head


def _outline_handle(kind: str) -> list[Any]:
    from matplotlib.lines import Line2D

    if kind == "designed":
        return []
    return [Line2D([], [], color=_OUTLINE, lw=0.8, ls=(0, (3, 2)), label="designed form's outline")]


def _no_equilibrium(fig: Any, ax: Any, sim: Simulation, kind: str, points: Array, view) -> None:
    """Draw ``points`` uncoloured and say in the picture why there are no colours."""
    faces = _faces(sim)
    shaded_surface(ax, points[faces], np.tile(_NEUTRAL, (len(faces), 1)), view)
    drawn = {
        "released": "drawn: the released form (after springback, without gravity), uncoloured",
        "designed": "drawn: the designed form, uncoloured",
    }[kind]
    reason = sim.standing.reason or "no equilibrium under its weight"
    text = "\n".join(
        ["NO STANDING EQUILIBRIUM", *textwrap.wrap(reason, 28)[:12], "", *textwrap.wrap(drawn, 28)]
    )
    fig.text(0.795, 0.86, text, fontsize=8, color=_NOTICE, va="top", ha="left")


def _stands_words(sim: Simulation) -> str:
    """The verdict in the caption's words (the report's warning says why a
    coarse preview's is uncertain)."""
    s = sim.standing
    if not s.stands:
        return "it does NOT stand: " + (s.reason or "no equilibrium")
    if s.uncertain:
        return "whether it stands is uncertain: run --mesh normal"
    margin = s.tipping_margin_deg
    return "it stands" + (f" (tipping margin {margin:.1f}\N{DEGREE SIGN})" if margin else "")


def _deviation_caption(sim: Simulation) -> str:
    s, u = sim.standing, sim.unit
    lines = []
    if s.max_deviation is not None:
        lines.append(
            f"standing on {sim.supports} supports under its weight ({sim.weight_N:.4g} N): "
            f"deviation max {_length(s.max_deviation, u)}, rms {_length(s.rms_deviation, u)}"
        )
        lines.append(
            f"height {_length(s.height, u)}, span {_length(s.span, u)}; {_stands_words(sim)}"
        )
    else:
        lines.append(_NO_STAND)
    extra = []
    if sim.released is not None:
        extra.append(f"springback alone: max deviation {_length(sim.released.max_deviation, u)}")
    if sim.formed is not None:
        extra.append(f"yielded in forming: {100 * sim.formed.plastic_area_share:.3g} % of the area")
    extra.append(f"mesh {sim.nodes} nodes, h_max {sim.h_max:.4g} {u}")
    lines.append("; ".join(extra))
    return "\n".join(lines)


def render_deviation(
    sim: Simulation,
    path: str | os.PathLike[str],
    *,
    title: str = "",
    size_px: tuple[int, int] = (900, 700),
    elev: float = 20.0,
    azim: float = -110.0,
) -> Path:
    """Draw the standing form coloured by its deviation from the design (PNG).

    Args:
        sim: the simulation (:func:`~onefold_cad.mechanics.simulate.simulate`).
        path: the PNG file (NAME-deviation.png), written atomically.
        title: the design's name for the heading.
        size_px: image width and height in pixels.
        elev, azim: the camera (deg, matplotlib's; the preview's by default).

    Returns:
        The path written.

    Raises:
        ExportError: the image could not be written, or ``sim`` has no mesh.
    """
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import LinearSegmentedColormap, Normalize

    subject = "the standing form's deviation from the design"
    fig, ax, view, kind, points, head = _new_figure(sim, subject, title, size_px, elev, azim)
    if kind == "standing" and sim.deviation is not None:
        dev = np.asarray(sim.deviation, dtype=float)
        lo, hi = deviation_range(dev)
        faces = _faces(sim)
        shaded_surface(ax, points[faces], ramp(dev[faces].mean(axis=1), lo, hi), view)
        cmap = LinearSegmentedColormap.from_list("deviation", DEVIATION_STOPS)
        cax = fig.add_axes((0.86, 0.2, 0.025, 0.55))
        bar = fig.colorbar(ScalarMappable(Normalize(lo, hi), cmap), cax=cax)
        bar.set_label(deviation_label(sim.unit) + ", mean of each face's nodes", fontsize=8)
        cax.tick_params(labelsize=7)
    else:
        _no_equilibrium(fig, ax, sim, kind, points, view)
    legend_below(fig, _outline_handle(kind), head)
    fig.text(0.015, 0.012, _deviation_caption(sim), fontsize=8.5, va="bottom")
    return save_png(fig, path, "deviation picture")


def _stress_colours(scale: StressScale) -> tuple[Any, Any]:
    """The colour map and norm of ``scale`` (matplotlib)."""
    from matplotlib.colors import (
        Colormap,
        LinearSegmentedColormap,
        ListedColormap,
        Normalize,
        PowerNorm,
        TwoSlopeNorm,
    )

    low = LinearSegmentedColormap.from_list("below", BELOW_YIELD)(np.linspace(0, 1, 128))
    if scale.kind == "yield":
        high = LinearSegmentedColormap.from_list("over", OVER_YIELD)(np.linspace(0, 1, 128))
        cmap: Colormap = ListedColormap(np.vstack([low, high]), name="stress")
        norm: Normalize = TwoSlopeNorm(vmin=0.0, vcenter=scale.yield_MPa, vmax=scale.top)
    else:
        cmap = ListedColormap(low, name="stress")
        linear = scale.gamma == 1.0
        norm = Normalize(0.0, scale.top) if linear else PowerNorm(scale.gamma, 0.0, scale.top)
    if scale.over_colour is not None:
        cmap = cmap.with_extremes(over=scale.over_colour)
    return cmap, norm


def _stress_caption(sim: Simulation, scale: StressScale) -> str:
    s = sim.standing
    cause = (
        "what forming left in it and its weight"
        if sim.reference == "flat"
        else "its weight alone (the designed form taken stress-free)"
    )
    at = s.max_stress_at
    where = (
        "" if at is None else f" at ({at[0]:.4g}, {at[1]:.4g}) {sim.unit} from H on the flat sheet"
    )
    hardened = ""
    if sim.law == "j2" and sim.hardening_modulus_MPa > 0.0 and (s.utilisation or 0.0) > 1.0:
        # above the initial yield stress only as far as the steel has hardened
        hardened = (
            f"hardened: at most the flow stress, yield + {sim.hardening_modulus_MPa:.4g} MPa "
            "x plastic strain\n"
        )
    estimate = ""
    if sim.law == "moment" and (s.utilisation or 0.0) > 1.0:
        # the 1D law takes the membrane and the unloading elastic: past yield
        # its stress is an estimate no steel carries (docs/mechanics.md, Limits)
        estimate = (
            "past yield the moment law's elastic estimate, a stress the steel cannot be in "
            "(--law j2: the stress it can be in)\n"
        )
    return (
        f"von Mises stress at the sheet's faces as it stands: {cause}\n"
        f"largest {s.max_stress_MPa:.4g} MPa ({s.utilisation:.3g} x the yield stress "
        f"{sim.yield_stress_MPa:.4g} MPa){where}\n"
        f"{hardened}{estimate}colours: {scale.note}"
    )


def _stress_bar(fig: Any, scale: StressScale, cmap: Any, norm: Any) -> None:
    """The stress picture's colour bar: the yield stress a black line on it, the
    colour above the scale's top as its end triangle."""
    from matplotlib.cm import ScalarMappable

    cax = fig.add_axes((0.86, 0.2, 0.025, 0.55))
    bar = fig.colorbar(
        ScalarMappable(norm, cmap), cax=cax, extend="max" if scale.over else "neither"
    )
    bar.set_label("von Mises stress (MPa)", fontsize=8)
    cax.tick_params(labelsize=7)
    small = {"fontsize": 7, "va": "bottom", "ha": "center"}
    if scale.over:
        cax.text(0.5, 1.07, f"above {scale.top:.4g}", transform=cax.transAxes, **small)
    if scale.kind != "below":
        cax.axhline(scale.yield_MPa, color="black", lw=1.6)
        where = cax.get_yaxis_transform()
        label = f"yield\n{scale.yield_MPa:.4g}"
        cax.text(-0.6, scale.yield_MPa, label, transform=where, fontsize=7, ha="right", va="center")


def render_stress(
    sim: Simulation,
    path: str | os.PathLike[str],
    *,
    title: str = "",
    size_px: tuple[int, int] = (900, 700),
    elev: float = 20.0,
    azim: float = -110.0,
) -> Path:
    """Draw the standing form coloured by stress (MPa), yield marked (PNG).

    Arguments, return value and errors as :func:`render_deviation`'s
    (``path``: NAME-stress.png).
    """
    from matplotlib.lines import Line2D

    subject = "stress in the standing form"
    fig, ax, view, kind, points, head = _new_figure(sim, subject, title, size_px, elev, azim)
    handles = _outline_handle(kind)
    if kind == "standing" and sim.face_stress_MPa is not None and sim.standing.max_stress_MPa:
        stress = np.asarray(sim.face_stress_MPa, dtype=float)
        scale = stress_scale(stress, _flat_areas(sim), sim.yield_stress_MPa)
        cmap, norm = _stress_colours(scale)
        faces = _faces(sim)
        shaded_surface(ax, points[faces], cmap(norm(stress))[:, :3], view)
        k = int(np.argmax(stress))
        spot = points[faces[k]].mean(axis=0)
        ax.scatter(*spot, marker="X", s=70, color=_MARK, edgecolors="white", zorder=6)
        box = {"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.8}
        ax.text(*spot, f"  {stress[k]:.4g} MPa", fontsize=8, color=_MARK, zorder=6, bbox=box)
        handles.append(Line2D([], [], color=_MARK, marker="X", ls="", label="largest stress"))
        _stress_bar(fig, scale, cmap, norm)
        caption = _stress_caption(sim, scale)
    else:
        _no_equilibrium(fig, ax, sim, kind, points, view)
        caption = f"no stress to show: {_NO_STAND}"
    legend_below(fig, handles, head)
    fig.text(0.015, 0.012, caption, fontsize=8.5, va="bottom")
    return save_png(fig, path, "stress picture")
