"""Draw the design space of a template: height, span and tipping margin of the
form as it rests, over alpha and beta (h_c, sheet and material the template's).

    .venv/bin/python scripts/design_space.py [TEMPLATE] [--n 31] [--out PNG]

Each (alpha, beta) of an n x n grid over (0, 90) x (0, 90) deg (cell
centres) is solved, folded and stood on the ground as the STEP holds it
(:func:`onefold_cad.geometry.placement.rest_form`, the default template's
thickness and relief hole), and the resting height, footprint width (span,
along the resting frame's x axis) and tipping margin are drawn as three
colour maps. White cells have no non-trivial apex. The margin's map marks
the 5 deg warning line and the forms that rock on a curved edge (two
contacts: margin 0). Writes docs/images/design-space-TEMPLATE.png.
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np

from onefold_cad import fold_design
from onefold_cad.errors import OneFoldError
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.geometry.placement import TIPPING_WARNING_DEG, rest_form
from onefold_cad.templates import DEFAULT_TEMPLATE, load_template

IMAGES = Path(__file__).resolve().parent.parent / "docs" / "images"


def measure(name: str, n: int) -> tuple[np.ndarray, dict[str, np.ndarray], str]:
    """The grid's angles ``(n,)`` and height, span, margin and contact count
    ``(n, n)`` (NaN where the design has no apex; rows beta, columns alpha)."""
    design = load_template(name)
    angles = (np.arange(n) + 0.5) * 90.0 / n
    out = {k: np.full((n, n), np.nan) for k in ("height", "span", "margin", "contacts")}
    body = "shell"
    half = design.frame.radius * math.cos(math.radians(design.frame.alpha))
    frac = design.frame.h_c / half
    for i, beta in enumerate(angles):
        for j, alpha in enumerate(angles):
            h_c = frac * design.frame.radius * math.cos(math.radians(alpha))
            d = design.with_changes(
                frame=design.frame.with_changes(alpha=alpha, beta=beta, h_c=h_c)
            )
            try:
                folded = fold_design(d)
                m = d.material.with_changes(relief_hole=relief_hole_diameter(d, folded))
                solid = d.model.value == "exact" and m.thickness > 0 and m.relief_hole_diameter > 0
                body = "solid" if solid else "shell"
                rest = rest_form(folded, m, body)
            except OneFoldError:
                continue
            out["height"][i, j] = rest.height
            out["span"][i, j] = rest.width
            out["margin"][i, j] = rest.tipping_margin_deg
            out["contacts"][i, j] = len(rest.support_polygon)
    return angles, out, body


def draw(name: str, angles: np.ndarray, data: dict[str, np.ndarray], body: str, out: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    design = load_template(name)
    u = design.units.value
    fig, axes = plt.subplots(1, 3, figsize=(15.5, 5.0), constrained_layout=True)
    step = angles[1] - angles[0]
    extent = (angles[0] - step / 2, angles[-1] + step / 2) * 2
    panels = (
        ("height", f"resting height ({u})", "viridis", None),
        ("span", f"footprint width, span ({u})", "cividis", None),
        ("margin", "tipping margin (deg)", "RdYlGn", (0.0, 30.0)),
    )
    for ax, (key, title, cmap, lim) in zip(axes, panels, strict=True):
        z = data[key]
        vmin, vmax = lim if lim else (np.nanmin(z), np.nanmax(z))
        im = ax.imshow(
            z, origin="lower", extent=extent, cmap=cmap, vmin=vmin, vmax=vmax, aspect="equal"
        )
        fig.colorbar(im, ax=ax, shrink=0.85)
        if key in ("height", "span"):
            cs = ax.contour(angles, angles, z, levels=8, colors="k", linewidths=0.6)
            ax.clabel(cs, fmt="%.4g", fontsize=7)
        else:
            ax.contour(angles, angles, z, levels=[TIPPING_WARNING_DEG], colors="k", linewidths=1.0)
            rock = np.argwhere(data["contacts"] == 2)
            ax.plot(
                angles[rock[:, 1]], angles[rock[:, 0]], "x", color="k", ms=3, mew=0.6,
                label="rocks on a curved edge (margin 0)",
            )  # fmt: skip
            ax.legend(loc="upper left", fontsize=7, framealpha=0.8)
        mark = design.frame
        ax.plot([mark.alpha], [mark.beta], "o", mfc="none", mec="w", mew=1.5, ms=9)
        ax.set_title(title)
        ax.set_xlabel("alpha (deg)")
        ax.set_ylabel("beta (deg)")
    fig.suptitle(
        f"{name}: its {body} as it rests, over alpha and beta (h_c, sheet and material the "
        f"template's; circle: the template's alpha and beta; black line: "
        f"{TIPPING_WARNING_DEG:g} deg margin)"
    )
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=90)
    plt.close(fig)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("template", nargs="?", default=DEFAULT_TEMPLATE)
    parser.add_argument("--n", type=int, default=31, help="grid cells per axis")
    parser.add_argument("--out", type=Path, default=None)
    args = parser.parse_args()
    t0 = time.perf_counter()
    angles, data, body = measure(args.template, args.n)
    out = args.out or IMAGES / f"design-space-{args.template}.png"
    draw(args.template, angles, data, body, out)
    stood = int(np.sum(~np.isnan(data["height"])))
    print(f"wrote {out}: {stood} of {args.n**2} designs stood in {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
