"""Regenerate every figure and generated text block of docs/.

Run from the repository root::

    .venv/bin/python docs/make_figures.py            # figures + generated blocks
    .venv/bin/python docs/make_figures.py --no-text  # figures only

Figures go to docs/images/ (PNG, matplotlib Agg); every number in them is
computed by onefold_cad. The generated text blocks (CLI reference, template
catalogue, bend worked example) are written by docs/make_reference.py, which
this script runs at the end.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from collections.abc import Callable
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

from onefold_cad import FrameCurve, Model, Sheet, fold, solve  # noqa: E402
from onefold_cad.geometry.arc import arc_points, arc_range
from onefold_cad.geometry.resting.placement import rest_form
from onefold_cad.geometry.solver import make_direction_surface  # noqa: E402

DOCS = Path(__file__).resolve().parent
IMAGES = DOCS / "images"
SQUARE = dict(x_plus=300.0, x_minus=300.0, y_plus=300.0, y_minus=300.0)
TOP, BOTTOM = np.array([0.86, 0.62, 0.30]), np.array([0.55, 0.63, 0.72])
LIGHT = np.array([-0.4, -0.6, 0.7]) / np.linalg.norm([-0.4, -0.6, 0.7])
MIRROR = np.array([1.0, -1.0, 1.0])


def save(fig: plt.Figure, name: str) -> Path:
    """Write ``fig`` to docs/images/<name> atomically and close it."""
    IMAGES.mkdir(parents=True, exist_ok=True)
    out = IMAGES / name
    tmp = out.with_name(f".{out.name}.tmp")
    fig.savefig(tmp, format="png", dpi=100)
    plt.close(fig)
    os.replace(tmp, out)
    return out


def shade(tri: np.ndarray, elev: float, azim: float) -> np.ndarray:
    """Lambert colours for triangles ``(m, 3, 3)``: warm top side, cool bottom side."""
    e, a = math.radians(elev), math.radians(azim)
    view = np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    top = (n @ view) > 0.0
    n = np.where(top[:, None], n, -n)
    s = 0.45 + 0.55 * np.clip(n @ LIGHT, 0.0, 1.0)
    return np.clip(np.where(top[:, None], TOP, BOTTOM) * s[:, None], 0, 1)


def axes3d(
    fig: plt.Figure,
    pos: int | tuple,
    pts: np.ndarray,
    title: str,
    elev: float = 22.0,
    azim: float = -60.0,
) -> plt.Axes:
    """A 3D axes with equal scale fitted to ``pts`` ``(k, 3)``."""
    ax = (
        fig.add_subplot(*pos, projection="3d")
        if isinstance(pos, tuple)
        else fig.add_subplot(pos, projection="3d")
    )
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(tuple(np.maximum(hi - lo, 1e-6 * float(np.max(hi - lo)))))
    ax.view_init(elev=elev, azim=azim)
    ax.set_title(title, fontsize=9)
    ax.tick_params(labelsize=6)
    return ax


def draw_mesh(
    ax: plt.Axes,
    verts: np.ndarray,
    faces: np.ndarray,
    elev: float = 22.0,
    azim: float = -60.0,
    alpha: float = 1.0,
) -> None:
    tri = verts[faces]
    ax.add_collection3d(
        Poly3DCollection(tri, facecolors=shade(tri, elev, azim), edgecolors="none", alpha=alpha)
    )


def cone_mesh(frame: FrameCurve, h: float, n: int = 90) -> tuple[np.ndarray, np.ndarray]:
    """The direction-surface (both sides): the cone from A = (0, 0, h) over the arcs."""
    p0, p1 = arc_range(frame)
    arc = arc_points(frame, np.linspace(p0, p1, n + 1))
    apex = np.array([0.0, 0.0, h])
    verts = np.vstack([apex, arc, arc * MIRROR])
    i = np.arange(n)
    up = np.stack([np.zeros(n, int), 1 + i, 2 + i], axis=1)
    lo = np.stack([np.zeros(n, int), n + 3 + i, n + 2 + i], axis=1)
    return verts, np.vstack([up, lo])


def draw_frame(ax: plt.Axes, frame: FrameCurve, h: float | None, color: str = "k") -> None:
    """The two frame curves, the f-line, H and (if given) the apex."""
    p0, p1 = arc_range(frame)
    arc = arc_points(frame, np.linspace(p0, p1, 200))
    for a in (arc, arc * MIRROR):
        ax.plot(a[:, 0], a[:, 1], a[:, 2], color=color, lw=1.2)
    ax.plot([arc[0, 0], arc[-1, 0]], [0, 0], [0, 0], color="#444444", lw=1.0)
    ax.scatter([0], [0], [0], color="k", s=8)
    if h is not None:
        ax.scatter([0], [0], [h], color="#b22222", s=14)
        ax.plot([0, 0], [0, 0], [0, h], color="#b22222", lw=0.6, ls=":")


def fig_alpha() -> Path:
    """Figure 10: the frame curve for several alpha, and two folded forms."""
    fig = plt.figure(figsize=(12, 4.2))
    ax = fig.add_subplot(1, 3, 1)
    for alpha, c in zip(
        (10, 30, 50, 70), ("#1f77b4", "#2ca02c", "#ff7f0e", "#d62728"), strict=True
    ):
        fr = FrameCurve(alpha, 45.0)
        p0, p1 = arc_range(fr)
        phi = np.linspace(p0, p1, 200)
        x = fr.radius * np.cos(phi)
        d = fr.radius * math.sin(math.radians(alpha)) + fr.radius * np.sin(phi)
        ax.plot(x, d, color=c, label=f"alpha = {alpha} deg, f-line {2 * fr.half_chord:.0f}")
        ax.plot([-fr.half_chord, fr.half_chord], [0, 0], color=c, lw=2.5, alpha=0.6)
    ax.set_aspect("equal")
    ax.set_title("frame curve: arc of 180 + 2 alpha on the f-line (R = 100)", fontsize=9)
    ax.legend(fontsize=7, loc="upper right")
    ax.set_xlabel("x")
    ax.set_ylabel("distance from the f-line")
    for k, alpha in enumerate((30, 50)):
        folded = fold(solve(FrameCurve(alpha, 45.0), Model.EXACT), Sheet.quadrilateral(**SQUARE))
        v, f = folded.mesh(angular=90, radial=10)
        ax3 = axes3d(
            fig,
            (1, 3, 2 + k),
            v,
            f"alpha = {alpha} deg, beta = 45 deg: h = {folded.solution.apex_height:.1f}",
        )
        draw_mesh(ax3, v, f)
    fig.tight_layout()
    return save(fig, "theory_alpha.png")


def fig_beta() -> Path:
    """Figure 12: beta tilts the frame curves and the direction-surface."""
    fig = plt.figure(figsize=(12, 4.2))
    for k, beta in enumerate((25.0, 45.0, 65.0)):
        fr = FrameCurve(40.0, beta)
        s = solve(fr, Model.EXACT)
        v, f = cone_mesh(fr, s.apex_height)
        ax = axes3d(
            fig, (1, 3, k + 1), v, f"alpha = 40, beta = {beta:g} deg: apex h = {s.apex_height:.1f}"
        )
        draw_mesh(ax, v, f, alpha=0.85)
        draw_frame(ax, fr, s.apex_height)
    fig.tight_layout()
    return save(fig, "theory_beta.png")


def fig_hc() -> Path:
    """Figure 9: where H sits on the f-line shifts the fold angles."""
    fig = plt.figure(figsize=(12, 4.2))
    for k, hc in enumerate((-50.0, 0.0, 50.0)):
        fr = FrameCurve(40.0, 45.0, h_c=hc)
        s = solve(fr, Model.EXACT)
        v, f = cone_mesh(fr, s.apex_height)
        ax = axes3d(fig, (1, 3, k + 1), v, f"h_c = {hc:g}: apex h = {s.apex_height:.1f}", azim=-80)
        draw_mesh(ax, v, f, azim=-80, alpha=0.85)
        draw_frame(ax, fr, s.apex_height)
    fig.tight_layout()
    return save(fig, "theory_hc.png")


def flat_panel(ax: plt.Axes, folded, title: str, rulings: bool = True) -> None:
    """The flat sheet with its rulings, crease and H."""
    b = folded.boundary_flat
    b = np.vstack([b, b[:1]])
    ax.fill(b[:, 0], b[:, 1], color=TOP, alpha=0.35)
    ax.plot(b[:, 0], b[:, 1], color="k", lw=1)
    if rulings:
        for r in folded.rulings_flat:
            ax.plot(r[:, 0], r[:, 1], color="#777777", lw=0.4)
    for c in folded.crease:
        ax.plot(
            [0, c.end_flat[0]],
            [0, c.end_flat[1]],
            color="#d62728" if c.bend == "UP" else "#1f77b4",
            lw=1.8,
        )
    ax.plot([0], [0], "ko", ms=3)
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=9)
    ax.tick_params(labelsize=6)


def fig_direction_vs_final() -> Path:
    """Figures 4 and 17: direction-surface against final surface."""
    cases = [
        (FrameCurve(50, 45), dict(SQUARE), "alpha 50, beta 45, square"),
        (FrameCurve(32, 34), dict(SQUARE), "alpha 32, beta 34, square"),
        (
            FrameCurve(32, 34, h_c=68),
            dict(x_plus=103.0, x_minus=201.0, y_plus=300.0, y_minus=96.0),
            "alpha 32, beta 34, h_c 68, Table 1 row 4",
        ),
    ]
    fig = plt.figure(figsize=(12, 11))
    for row, (fr, quad, label) in enumerate(cases):
        folded = fold(solve(fr, Model.PAPER), Sheet.quadrilateral(**quad))
        flat_panel(fig.add_subplot(3, 3, 3 * row + 1), folded, f"(a) flat: {label}")
        h = folded.solution.apex_height
        v, f = cone_mesh(fr, h)
        ax = axes3d(fig, (3, 3, 3 * row + 2), v, "(b) direction-surface (paper fan)")
        draw_mesh(ax, v, f, alpha=0.85)
        draw_frame(ax, fr, h)
        vm, fm = folded.mesh(angular=90, radial=10)
        ax = axes3d(fig, (3, 3, 3 * row + 3), np.vstack([vm, v]), "(c) final surface")
        draw_mesh(ax, vm, fm)
        for r in folded.rulings_3d[:: max(1, len(folded.rulings_3d) // 30)]:
            ax.plot(r[:, 0], r[:, 1], r[:, 2], color="#555555", lw=0.3)
        draw_frame(ax, fr, h, color="#444444")
    fig.tight_layout()
    return save(fig, "theory_direction_vs_final.png")


def star_sheet(points: int = 5, outer: float = 300.0, inner: float = 150.0) -> Sheet:
    """A star-shaped polygon about H with a tip on the +x axis."""
    k = np.arange(2 * points)
    rad = np.where(k % 2 == 0, outer, inner)
    ang = math.pi * k / points
    return Sheet.polygon(np.stack([rad * np.cos(ang), rad * np.sin(ang)], axis=1))


def fig_star() -> Path:
    """Figure 18: a star-shaped sheet, flat and folded from two sides."""
    folded = fold(solve(FrameCurve(40, 50), Model.EXACT), star_sheet(6))
    fig = plt.figure(figsize=(12, 4.2))
    flat_panel(fig.add_subplot(1, 3, 1), folded, "(a) flat star, rulings through its vertices")
    v, f = folded.mesh(angular=180, radial=12)
    v = rest_form(folded).apply(v)
    for k, azim in enumerate((-60.0, 30.0)):
        ax = axes3d(fig, (1, 3, 2 + k), v, f"({'bc'[k]}) folded, resting on the ground", azim=azim)
        draw_mesh(ax, v, f, azim=azim)
    fig.tight_layout()
    return save(fig, "theory_star.png")


def fig_angle_condition() -> Path:
    """Figure 13: S(h) against h, the root and the paper's bracket [l, 2R]."""
    fig, axs = plt.subplots(1, 2, figsize=(12, 4.2))
    for ax, (a, b) in zip(axs, ((50.0, 45.0), (85.0, 85.0)), strict=True):
        fr = FrameCurve(a, b)
        surf = make_direction_surface(fr, Model.EXACT)
        h = np.linspace(0.5, 320.0, 500)
        s = np.degrees([surf.angle_sum(x) for x in h])
        root = solve(fr, Model.EXACT).apex_height
        lo, hi = fr.paper_lower_bound, 2.0 * fr.radius
        ax.axvspan(
            lo,
            hi,
            color="#ffdd99",
            alpha=0.6,
            label=f"paper's bracket [l, 2R] = [{lo:.1f}, {hi:.0f}]",
        )
        ax.plot(h, s, color="#1f77b4", label="S(h), exact cone")
        ax.axhline(180.0, color="k", lw=0.8)
        ax.plot(
            [root],
            [180.0],
            "o",
            color="#d62728",
            label=f"root h = {root:.2f}" + (" (outside!)" if not lo <= root <= hi else ""),
        )
        ax.set_xlabel("apex height h (R = 100)")
        ax.set_ylabel("sum of one side's apex angles S(h) (deg)")
        ax.set_title(f"alpha = {a:g} deg, beta = {b:g} deg", fontsize=10)
        ax.legend(fontsize=8)
    fig.tight_layout()
    return save(fig, "theory_angle_condition.png")


def fig_fan_vs_cone() -> Path:
    """How the paper's fan approaches the exact cone as divisions grow."""
    fr = FrameCurve(50, 45)
    exact = solve(fr, Model.EXACT).apex_height
    ns = np.unique(np.round(np.logspace(0.5, 4, 20)).astype(int))
    dh = [
        abs(solve(fr.with_changes(divisions=int(n)), Model.PAPER).apex_height - exact) for n in ns
    ]
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.loglog(ns, dh, "o-")
    ax.set_xlabel("divisions")
    ax.set_ylabel("|h(paper fan) - h(exact cone)|")
    ax.set_title("alpha 50, beta 45, R 100: the fan converges to the cone", fontsize=9)
    ax.grid(True, which="both", lw=0.3)
    fig.tight_layout()
    return save(fig, "theory_fan_vs_cone.png")


def fig_gallery() -> Path:
    """The index page's picture: the One-Fold square and the Patkau-like rectangle."""
    fig = plt.figure(figsize=(12, 5))
    designs = [
        (FrameCurve(50, 45), Sheet.quadrilateral(**SQUARE), "square 600 x 600 on its diagonal"),
        (
            FrameCurve(35, 40, radius=100.0),
            Sheet.rectangle(240.0, 100.0, 0.5),
            "rectangle 240 x 100 (10 x 24 proportions) on its diagonal",
        ),
    ]
    for k, (fr, sheet, title) in enumerate(designs):
        folded = fold(solve(fr, Model.EXACT), sheet)
        v, f = folded.mesh(angular=150, radial=14)
        v = rest_form(folded).apply(v)
        ax = axes3d(fig, (1, 2, k + 1), v, title, elev=18, azim=-50)
        draw_mesh(ax, v, f, elev=18, azim=-50)
    fig.tight_layout()
    return save(fig, "gallery.png")


FIGURES: list[Callable[[], Path]] = [
    fig_gallery,
    fig_alpha,
    fig_beta,
    fig_hc,
    fig_direction_vs_final,
    fig_star,
    fig_angle_condition,
    fig_fan_vs_cone,
]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description="regenerate docs/images and generated blocks")
    ap.add_argument("--no-text", action="store_true", help="skip the generated text blocks")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    for make in FIGURES:
        print(make())
    sys.path.insert(0, str(DOCS))
    import make_reference

    for p in make_reference.make_template_previews():
        print(p)
    print(make_reference.make_fabrication_figure())
    if not args.no_text:
        make_reference.main([])
    print(f"done in {time.perf_counter() - t0:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
