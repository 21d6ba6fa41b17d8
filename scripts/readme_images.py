"""Draw the README's two pictures with the package's own exporters.

    .venv/bin/python scripts/readme_images.py

writes docs/images/readme-folded.png (the default template folded, standing on
the ground, with its legend) and docs/images/readme-flat.png (its flat
pattern, from its DXF), both :data:`WIDTH_PX` pixels wide.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from onefold_cad import build_design
from onefold_cad.export.dxf import export_design_dxf
from onefold_cad.export.dxf_preview import render_preview
from onefold_cad.export.preview import render_folded_preview
from onefold_cad.templates import DEFAULT_TEMPLATE, load_template

IMAGES = Path(__file__).resolve().parent.parent / "docs" / "images"
#: Width of both pictures (pixels): readable on a README page.
WIDTH_PX = 1000


def main() -> None:
    design = load_template(DEFAULT_TEMPLATE)
    folded = build_design(design)
    IMAGES.mkdir(parents=True, exist_ok=True)
    render_folded_preview(
        folded,
        IMAGES / "readme-folded.png",
        title=f"{design.name} (folded, resting on the ground)",
        units=design.units.value,
        size_px=(WIDTH_PX, 760),
    )
    with tempfile.TemporaryDirectory() as tmp:
        dxf = export_design_dxf(design, Path(tmp) / f"{design.name}.dxf", folded=folded)
        render_preview(dxf, IMAGES / "readme-flat.png", dpi=100, width_px=WIDTH_PX)
    print(f"wrote {IMAGES / 'readme-folded.png'} and {IMAGES / 'readme-flat.png'}")


if __name__ == "__main__":
    main()
