"""The flat preview draws a bounded NOTES block: a paper fan lists every
ruling fold in the DXF's notes, and every glyph of them became an SVG path
(once 3.9 GB and 16 minutes for a 500 MB SVG at 10 000 divisions)."""

from __future__ import annotations

from pathlib import Path

from onefold_cad import fold_design
from onefold_cad.export.dxf import export_design_dxf
from onefold_cad.export.dxf_notes import flat_pattern_notes
from onefold_cad.export.dxf_preview import MAX_NOTE_LINES, _notes_cut, render_preview
from onefold_cad.fabrication.flat_pattern import flat_pattern
from onefold_cad.templates import find_template, load_template


def paper(divisions: int):
    d = load_template(find_template("patkau-one-fold"))
    return d.with_changes(model="paper", frame=d.frame.with_changes(divisions=divisions))


def svg_size(tmp_path: Path, divisions: int) -> tuple[int, int]:
    """The flat SVG's bytes and the number of NOTES lines of the design."""
    d = paper(divisions)
    folded = fold_design(d)
    dxf = export_design_dxf(d, tmp_path / f"p{divisions}.dxf", folded)
    svg = render_preview(dxf, tmp_path / f"p{divisions}-flat.svg")
    return svg.stat().st_size, len(flat_pattern_notes(flat_pattern(d, folded)))


def test_the_notes_past_the_limit_are_one_line_that_counts_them(tmp_path):
    import ezdxf

    d = paper(300)
    folded = fold_design(d)
    notes = flat_pattern_notes(flat_pattern(d, folded))
    assert len(notes) > MAX_NOTE_LINES
    doc = ezdxf.readfile(export_design_dxf(d, tmp_path / "p.dxf", folded))
    skipped, (more,) = _notes_cut(doc)
    assert len(skipped) == len(notes) - MAX_NOTE_LINES
    assert more.dxf.text.startswith(f"... {len(notes) - MAX_NOTE_LINES} more lines")
    assert more.dxf.layer == "NOTES"


def test_the_svg_grows_with_the_drawing_not_with_the_notes(tmp_path):
    """Twice the divisions add the fan's fold lines (a short path each, under
    300 bytes) but no notes: before, every note line added its glyphs (about
    25 KB a line)."""
    small, n_small = svg_size(tmp_path, 200)
    large, n_large = svg_size(tmp_path, 400)
    assert n_large - n_small >= 390  # a note line per ruling fold
    assert large - small < 2 * 200 * 300, (small, large)
