"""Draw the README's two pictures with the package's own exporters.

    .venv/bin/python scripts/readme_images.py

writes docs/images/readme-folded.png (the default template folded, standing on
the ground, with its legend) and docs/images/readme-flat.png (its flat
pattern), both :data:`WIDTH_PX` pixels wide.

The flat picture is the DXF as ``onefold build`` writes it, drawn by the flat
preview's renderer, with its notes set beside the sheet instead of under it:
the notes' long lines would otherwise set the picture's width and shrink the
sheet and every letter (a 3 x 7 m sheet with one-line notes is unreadable
below about 1500 px). The notes are the flat pattern's own lines
(:attr:`FlatPattern.notes`, the DXF's NOTES), wrapped.
"""

from __future__ import annotations

import tempfile
import textwrap
from pathlib import Path

from onefold_cad import fold_design
from onefold_cad.export.dxf import draw_flat_pattern
from onefold_cad.export.dxf_preview import render_preview
from onefold_cad.export.preview import render_folded_preview
from onefold_cad.fabrication.flat_pattern import flat_pattern
from onefold_cad.fabrication.rules import resting_placement
from onefold_cad.templates import DEFAULT_TEMPLATE, load_template

IMAGES = Path(__file__).resolve().parent.parent / "docs" / "images"
#: Width of both pictures (pixels): readable on a README page.
WIDTH_PX = 1000
#: The flat picture: height (px), the drawing's share of the width, the
#: notes' font size (pt at 100 dpi: 11 pt is 15 px, 12 px when shown 800 px wide).
FLAT_HEIGHT_PX = 1000
DRAWING_SHARE = 0.4
NOTES_PT = 11
NOTES_WRAP = 62


def flat_picture(design, folded, path: Path) -> Path:
    """The flat pattern's DXF drawing (without its notes block) beside its
    notes, wrapped, at a size that reads on a README page."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.image as mpimg
    import matplotlib.pyplot as plt

    pattern = flat_pattern(design, folded)
    doc = draw_flat_pattern(pattern)
    labels = {half.label for half in pattern.halves}  # the fold labels stay on the sheet
    msp = doc.modelspace()
    for text in msp.query('TEXT[layer=="NOTES"]'):
        if text.dxf.text not in labels:
            msp.delete_entity(text)
    dpi = 100
    with tempfile.TemporaryDirectory() as tmp:
        drawing = render_preview(
            doc, Path(tmp) / "drawing.png", dpi=dpi, width_px=int(WIDTH_PX * DRAWING_SHARE)
        )
        image = mpimg.imread(drawing)
    fig = plt.figure(figsize=(WIDTH_PX / dpi, FLAT_HEIGHT_PX / dpi), dpi=dpi)
    try:
        left = fig.add_axes((0.0, 0.0, DRAWING_SHARE, 1.0))
        left.imshow(image)
        left.set_anchor("N")
        left.axis("off")
        right = fig.add_axes((DRAWING_SHARE + 0.02, 0.0, 0.98 - DRAWING_SHARE, 1.0))
        right.axis("off")
        lines = [
            textwrap.fill(line, NOTES_WRAP, subsequent_indent="    ", break_on_hyphens=False)
            for line in pattern.notes
        ]
        right.text(0.0, 0.985, "\n".join(lines), va="top", ha="left", fontsize=NOTES_PT,
                   linespacing=1.35, family="DejaVu Sans")  # fmt: skip
        fig.savefig(path, dpi=dpi, format="png")
    finally:
        plt.close(fig)
    return path


def main() -> None:
    design = load_template(DEFAULT_TEMPLATE)
    folded = fold_design(design)
    IMAGES.mkdir(parents=True, exist_ok=True)
    render_folded_preview(  # as `onefold build` draws it: the STEP's body as it rests
        folded,
        IMAGES / "readme-folded.png",
        placement=resting_placement(design, folded),
        title=f"{design.name} (folded, resting on the ground)",
        units=design.units.value,
        size_px=(WIDTH_PX, 760),
    )
    flat_picture(design, folded, IMAGES / "readme-flat.png")
    print(f"wrote {IMAGES / 'readme-folded.png'} and {IMAGES / 'readme-flat.png'}")


if __name__ == "__main__":
    main()
