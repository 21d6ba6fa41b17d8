"""PNG/SVG preview of a DXF flat pattern, rendered by ezdxf's drawing add-on.

SVG uses ezdxf's own SVG back-end (no matplotlib); PNG uses the matplotlib
back-end, imported only here and only when a PNG is asked for. The file is
written atomically (temporary file in the same directory, then replaced).

Size and units. The SVG is drawn at the sheet's true size in the drawing's
own unit (the DXF's ``$INSUNITS``): ``width="3054mm"`` for a 3 m sheet in
millimetres, ``width="185in"`` for a 5 x 12 ft sheet in inches. SVG has no
foot, so a foot drawing says its size in inches (12 per foot). A DXF without
units (R12, or ``$INSUNITS`` 0) is drawn at one unit per millimetre.

Strokes. SVG lines are drawn relative to the drawing, not in millimetres, so
they read at any size: the outline to cut (layer CUT) :data:`CUT_STROKE` of
the drawing's larger side, everything else :data:`STROKE` of it (about 3 px
and 1 px when the drawing is shown 1000 px tall); a millimetre stroke is
invisible on a 7 m sheet shown on a screen. A PNG is an image of a given
width: its CUT lines are 2 pt wide at its dpi (about 3 px at 100 dpi), the
others one pixel.

Notes. The drawing's NOTES block (the TEXT lines of the NOTES layer written
left-aligned under the blank: material, bends, the bend table) is drawn up
to :data:`MAX_NOTE_LINES` lines, then one line saying how many more the DXF
holds: a paper fan of 10 000 divisions lists its 19 978 ruling folds there,
and every glyph of them became an SVG path (3.9 GB and 16 minutes for a
500 MB picture). The DXF and the bend sheet keep every line.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import ezdxf
from ezdxf import bbox
from ezdxf import units as dxf_units
from ezdxf.addons.drawing import Frontend, RenderContext
from ezdxf.addons.drawing.config import BackgroundPolicy, Configuration, LineweightPolicy
from ezdxf.document import Drawing

from onefold_cad.errors import InvalidParameterError
from onefold_cad.export.atomic import atomic_output

__all__ = ["CUT_STROKE", "MAX_NOTE_LINES", "STROKE", "render_preview"]

#: Stroke width of the CUT layer, relative to the drawing's larger side.
CUT_STROKE = 0.003
#: Stroke width of every other line, relative to the drawing's larger side.
STROKE = 0.001
#: The most lines of the drawing's NOTES block a preview draws (every shipped
#: design's block is shorter: 194 lines at most, table1-row1; the rest is
#: counted in one more line).
MAX_NOTE_LINES = 200
#: Blank margin around the drawing, relative to its larger side.
_MARGIN = 0.02
#: DXF's largest lineweight (mm); the CUT layer is drawn with it.
_HEAVY = 2.11
_CONFIG = Configuration(
    background_policy=BackgroundPolicy.WHITE, lineweight_policy=LineweightPolicy.RELATIVE
)
#: The SVG length unit and how many of it make a millimetre, per DXF unit.
_SVG_UNIT = {
    dxf_units.MM: ("mm", 1.0),
    dxf_units.M: ("mm", 1.0),
    dxf_units.IN: ("in", 1 / 25.4),
    dxf_units.FT: ("in", 1 / 25.4),
}


def _units(doc: Drawing) -> int:
    """The drawing's ``$INSUNITS`` code (0, unitless, for R12)."""
    return doc.units if doc.dxfversion > "AC1009" else 0


def _mm_per_unit(doc: Drawing) -> float:
    """Millimetres per drawing unit (1 when the DXF states none)."""
    code = _units(doc)
    if not code:
        return 1.0
    return dxf_units.conversion_factor(
        dxf_units.InsertUnits(code), dxf_units.InsertUnits.Millimeters
    )


def _weights(entity: Any, properties: Any) -> None:
    """SVG property override: the CUT layer heavy, every other line light
    (mapped to :data:`CUT_STROKE` and :data:`STROKE`)."""
    properties.lineweight = _HEAVY if properties.layer.upper() == "CUT" else 0.05


def _png_weights(entity: Any, properties: Any) -> None:
    """PNG property override (ezdxf's matplotlib back-end draws a lineweight
    as that many points, at least one pixel): the CUT layer 2 pt, every other
    line one pixel."""
    properties.lineweight = 2.0 if properties.layer.upper() == "CUT" else 0.0


def _is_note_line(entity: Any) -> bool:
    """A line of the NOTES block: left-aligned TEXT on the NOTES layer (the
    fold halves' labels on that layer are centred)."""
    return (
        entity.dxftype() == "TEXT"
        and entity.dxf.layer.upper() == "NOTES"
        and entity.dxf.get("halign", 0) == 0
        and entity.dxf.get("valign", 0) == 0
    )


def _notes_cut(doc: Drawing) -> tuple[set[int], list[Any]]:
    """The NOTES lines past :data:`MAX_NOTE_LINES` (their ``id``) and the line
    that counts them (empty when none is cut; a new entity outside ``doc``:
    the document is the DXF writer's too)."""
    from ezdxf.entities import Text

    notes = [e for e in doc.modelspace() if _is_note_line(e)]
    if len(notes) <= MAX_NOTE_LINES:
        return set(), []
    last, after = notes[MAX_NOTE_LINES - 1], notes[MAX_NOTE_LINES]
    more = Text.new(dxfattribs=last.dxfattribs(drop={"handle", "owner"}))
    more.dxf.insert = after.dxf.insert
    cut = len(notes) - MAX_NOTE_LINES
    more.dxf.text = f"... {cut} more lines: the DXF's NOTES layer and the bend sheet hold them all"
    return {id(e) for e in notes[MAX_NOTE_LINES:]}, [more]


def _draw(frontend: Frontend, doc: Drawing) -> list[Any]:
    """Draw the modelspace with the NOTES block cut (:func:`_notes_cut`);
    return what was drawn."""
    skipped, extra = _notes_cut(doc)
    drawn = [e for e in doc.modelspace() if id(e) not in skipped]
    frontend.draw_layout(
        doc.modelspace(), finalize=False, filter_func=lambda e: id(e) not in skipped
    )
    frontend.draw_entities(extra)
    frontend.pipeline.finalize()
    return drawn + extra


def _svg(doc: Drawing, out: Path) -> None:
    from ezdxf.addons.drawing import layout, svg

    backend = svg.SVGBackend()
    frontend = Frontend(RenderContext(doc), backend, config=_CONFIG)
    frontend.push_property_override_function(_weights)
    drawn = _draw(frontend, doc)
    mm = _mm_per_unit(doc)
    box = bbox.extents(drawn)
    side = max(box.size.x, box.size.y) * mm if box.has_data else 0.0
    # a margin for the strokes (centred on the lines) and some air
    page = layout.Page(0, 0, layout.Units.mm, margins=layout.Margins.all(_MARGIN * side))
    # fit_page off: the content keeps the exact scale (ezdxf rounds the page
    # to 0.1 mm, and fitting would stretch the content to that rounding)
    settings = layout.Settings(
        scale=mm,
        fit_page=False,
        max_stroke_width=CUT_STROKE,
        min_stroke_width=STROKE / CUT_STROKE,
    )
    root = backend.get_xml_root_element(page, settings=settings)
    name, per_mm = _SVG_UNIT.get(_units(doc), ("mm", 1.0))
    for key in ("width", "height"):
        size_mm = float(root.get(key, "0mm").removesuffix("mm"))
        root.set(key, f"{size_mm * per_mm:.6g}{name}")
    import xml.etree.ElementTree as ET

    out.write_text(ET.tostring(root, encoding="unicode", xml_declaration=True), encoding="utf-8")


def _png(doc: Drawing, out: Path, dpi: int, width_px: int | None) -> None:
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from ezdxf.addons.drawing.matplotlib import MatplotlibBackend

    fig = plt.figure()
    try:
        ax = fig.add_axes((0, 0, 1, 1))
        config = Configuration(background_policy=BackgroundPolicy.WHITE)
        frontend = Frontend(
            RenderContext(doc), MatplotlibBackend(ax, adjust_figure=False), config=config
        )
        frontend.push_property_override_function(_png_weights)
        _draw(frontend, doc)
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        inches = 8.0 if width_px is None else width_px / dpi
        fig.set_size_inches(inches, inches * abs(y1 - y0) / max(abs(x1 - x0), 1e-300))
        fig.savefig(out, dpi=dpi, format="png")
    finally:
        plt.close(fig)


def render_preview(
    dxf: Drawing | str | os.PathLike[str],
    out_path: str | os.PathLike[str],
    *,
    dpi: int = 150,
    width_px: int | None = None,
) -> Path:
    """Render the modelspace of a DXF document or file to PNG or SVG.

    Args:
        dxf: an ezdxf document or the path of a DXF file.
        out_path: '.png' or '.svg' (chosen by the suffix).
        dpi: PNG resolution (dots per inch), 10..1200.
        width_px: PNG only: the image's width in pixels (its height follows
            the drawing's shape); default 8 inches at ``dpi``.

    Returns:
        The path written.
    """
    out = Path(out_path)
    kind = out.suffix.lower()
    if kind not in (".png", ".svg"):
        raise InvalidParameterError("out_path", f"must end in .png or .svg, got {out.name!r}")
    if not 10 <= int(dpi) <= 1200:
        raise InvalidParameterError("dpi", f"must be in [10, 1200], got {dpi}")
    if width_px is not None and not 16 <= int(width_px) <= 20000:
        raise InvalidParameterError("width_px", f"must be in [16, 20000], got {width_px}")
    doc = dxf if isinstance(dxf, Drawing) else ezdxf.readfile(dxf)
    with atomic_output(out) as tmp:
        if kind == ".svg":
            _svg(doc, tmp)
        else:
            _png(doc, tmp, int(dpi), None if width_px is None else int(width_px))
    return out
