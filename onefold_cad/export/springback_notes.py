"""Springback lines added to a written DXF's notes and bend sheet: the angle
to fold each crease half to and the angle it stands at after springback
(``onefold compensate``'s files).

:func:`add_dxf_notes` appends TEXT lines on layer NOTES under the notes
already there (same column and height), audits and rewrites the file
atomically; :func:`add_bend_columns` adds the column ``after_springback_deg``
to ``NAME-bends.csv`` (which has the angle to fold to, ``fold_to_deg``), by
crease half.
"""

from __future__ import annotations

import csv
import io
import os
from collections.abc import Mapping, Sequence
from pathlib import Path

from onefold_cad.errors import ExportError
from onefold_cad.export.atomic import atomic_output

__all__ = ["add_bend_columns", "add_dxf_notes"]


def add_dxf_notes(path: str | os.PathLike[str], lines: Sequence[str]) -> Path:
    """Append ``lines`` to the DXF's NOTES, under the last note.

    Raises:
        ExportError: the file has no notes to continue, or fails its audit.
    """
    import ezdxf

    doc = ezdxf.readfile(path)
    msp = doc.modelspace()
    notes = [e for e in msp.query("TEXT") if e.dxf.layer == "NOTES"]
    if not notes:
        raise ExportError(f"{Path(path).name}: no NOTES to continue")
    last = min(notes, key=lambda e: e.dxf.insert[1])
    x, y = last.dxf.insert[0], last.dxf.insert[1]
    h = last.dxf.height
    for i, text in enumerate(lines, 1):
        msp.add_text(text, height=h, dxfattribs={"layer": "NOTES", "insert": (x, y - 1.6 * i * h)})
    auditor = doc.audit()
    if auditor.has_errors:
        raise ExportError(f"{Path(path).name}: the DXF failed its audit: {auditor.errors}")
    with atomic_output(path) as tmp:
        doc.saveas(tmp)
    return Path(path)


def add_bend_columns(path: str | os.PathLike[str], angles: Mapping[str, float]) -> Path:
    """Add ``after_springback_deg`` to the bend sheet: ``angles`` maps a
    crease half's name (the ``half`` column) to it."""
    rows = list(csv.reader(Path(path).read_text(encoding="utf-8").splitlines()))
    head = rows[0]
    if "half" not in head:
        raise ExportError(f"{Path(path).name}: no 'half' column")
    key = head.index("half")
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow([*head, "after_springback_deg"])
    for r in rows[1:]:
        if r[key] not in angles:
            raise ExportError(f"{Path(path).name}: no springback for crease half {r[key]!r}")
        writer.writerow([*r, f"{angles[r[key]]:.4f}"])
    with atomic_output(path) as tmp:
        tmp.write_text(out.getvalue(), encoding="utf-8")
    return Path(path)
