"""Draw the README's two pictures with the package's own exporters.

    .venv/bin/python scripts/readme_images.py

writes docs/images/readme-folded.png (the default template folded, standing on
the ground) and docs/images/readme-flat.png (its flat pattern, from its DXF).
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


def main() -> None:
    design = load_template(DEFAULT_TEMPLATE)
    folded = build_design(design)
    IMAGES.mkdir(parents=True, exist_ok=True)
    render_folded_preview(
        folded,
        IMAGES / "readme-folded.png",
        title=f"{design.name} (folded, resting on the ground)",
        units=design.units.value,
        size_px=(800, 560),
    )
    with tempfile.TemporaryDirectory() as tmp:
        dxf = export_design_dxf(design, Path(tmp) / f"{design.name}.dxf", folded=folded)
        render_preview(dxf, IMAGES / "readme-flat.png", dpi=60)
    print(f"wrote {IMAGES / 'readme-folded.png'} and {IMAGES / 'readme-flat.png'}")


if __name__ == "__main__":
    main()
