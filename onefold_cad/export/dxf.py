"""DXF flat pattern for laser and plasma cutting (an ezdxf adapter).

Layers (exact names, so a CAM setup maps them once):

- ``CUT``: the outline as one closed LWPOLYLINE (POLYLINE in R12) and the
  relief hole as a CIRCLE, both offset by kerf/2 when a kerf is given.
- ``BEND_UP`` / ``BEND_DOWN``: each fold half as a LINE from H to the outline
  with the DASHED linetype (the layer's and the entity's own), on the layer
  of its bend direction seen from the drawing's (top) side; XDATA
  (application ``ONEFOLD``) holds the direction and angle.
- ``APEX``: a cross and a small circle at H (always drawn); with a relief
  hole, a leader from the hole's edge and its label ("relief hole, diameter 19.14
  mm"), so the hole shows at full-sheet scale.
- ``BEND_ZONE``: for t > 0, each half's limit lines at +-BA/2.
- the paper model's ruling folds (:attr:`FlatPattern.fold_rulings`: its fan's
  triangles meet at an angle along them) on ``BEND_UP`` / ``BEND_DOWN`` like
  the crease halves (DASHED, XDATA with their name, direction and angle).
- ``RULINGS`` (optional): the rulings that are no folds as light etch lines
  (the exact model's: the sheet curves smoothly along them).
- ``NOTES``: design name, units, material, what UP and DOWN mean, the
  compensation used, the bend sheet (:mod:`onefold_cad.fabrication.bend_table`),
  size, area, mass, and each half's direction and angle next to it.

Everything is in modelspace, in the sheet's own frame; ``$INSUNITS`` and
``$MEASUREMENT`` follow the design's units (R12 has no ``$INSUNITS``).
The geometry comes from :mod:`onefold_cad.fabrication.flat_pattern`.

Deterministic files: two writes of one drawing are byte-identical.
:func:`write_dxf_atomic` fixes every time stamp ezdxf writes ($TDCREATE,
$TDUCREATE, $TDUPDATE, $TDUUPDATE, $TDINDWG, $TDUSRTIMER and ezdxf's own
CREATED_BY/WRITTEN_BY metadata) and derives $FINGERPRINTGUID and
$VERSIONGUID from a seed (the design's data for :func:`export_design_dxf`).
"""

from __future__ import annotations

import hashlib
import io
import math
import os
import uuid
from collections.abc import Iterator
from contextlib import contextmanager
from datetime import datetime
from pathlib import Path

import ezdxf
import numpy as np
from ezdxf import units as dxf_units
from ezdxf.document import Drawing

from onefold_cad.choices import Compensation, Units
from onefold_cad.design import Design, fold_design
from onefold_cad.errors import ExportError, InvalidParameterError
from onefold_cad.export.atomic import atomic_output
from onefold_cad.export.dxf_notes import flat_pattern_notes
from onefold_cad.fabrication.flat_pattern import FlatPattern, flat_pattern_once
from onefold_cad.geometry.folding import FoldedSheet

__all__ = [
    "LAYERS",
    "atomic_output",
    "design_seed",
    "draw_flat_pattern",
    "export_design_dxf",
    "new_document",
    "write_dxf_atomic",
]

#: layer name -> (ACI colour, linetype)
LAYERS: dict[str, tuple[int, str]] = {
    "CUT": (7, "Continuous"),
    "BEND_UP": (1, "DASHED"),
    "BEND_DOWN": (5, "DASHED"),
    "APEX": (3, "Continuous"),
    "BEND_ZONE": (8, "Continuous"),
    "RULINGS": (9, "Continuous"),
    "NOTES": (7, "Continuous"),
}
_VERSIONS = ("R12", "R2000", "R2004", "R2007", "R2010", "R2013", "R2018")
_INSUNITS = {
    Units.MM: dxf_units.MM,
    Units.M: dxf_units.M,
    Units.IN: dxf_units.IN,
    Units.FT: dxf_units.FT,
}
_APPID = "ONEFOLD"
#: the fixed date of every time stamp in the files (2000-01-01, as ezdxf's own tests)
_FIXED_DATE = datetime(2000, 1, 1)
_GUID_NAMESPACE = uuid.uuid5(uuid.NAMESPACE_DNS, "dxf.onefold_cad")


def new_document(dxfversion: str, *, setup: bool = True) -> Drawing:
    """A new ezdxf document of ``dxfversion`` (one of R12 ... R2018)."""
    if dxfversion not in _VERSIONS:
        raise InvalidParameterError(
            "dxfversion", f"must be one of {', '.join(_VERSIONS)}, got {dxfversion!r}"
        )
    return ezdxf.new(dxfversion, setup=setup)


def set_units(doc: Drawing, units: Units) -> None:
    """$INSUNITS (not in R12) and $MEASUREMENT for the design's unit."""
    if doc.dxfversion > "AC1009":  # R12 has no $INSUNITS
        doc.units = _INSUNITS[units]
    doc.header["$MEASUREMENT"] = 1 if units in (Units.MM, Units.M) else 0


def _setup(doc: Drawing, pattern: FlatPattern) -> None:
    """Units, linetype scale, layers and the XDATA application id."""
    set_units(doc, pattern.units)
    dashed = doc.linetypes.get("DASHED") if "DASHED" in doc.linetypes else None
    if dashed is None:
        doc.linetypes.add("DASHED", [0.6, 0.5, -0.1], description="Dashed __ __ __")
        dashed = doc.linetypes.get("DASHED")
    period = float(sum(abs(x) for x in dashed.simplified_line_pattern())) or 1.0
    longest = max(float(np.hypot(*(h.end - h.start))) for h in pattern.halves)
    doc.header["$LTSCALE"] = max(longest / 25.0 / period, 1e-3)
    for name, (color, ltype) in LAYERS.items():
        if name not in doc.layers:
            doc.layers.add(name, color=color, linetype=ltype)
    if _APPID not in doc.appids:
        doc.appids.add(_APPID)


def _literal(text: str) -> str:
    """``text`` as DXF text that reads as written: powers of units plainly
    ('kg/m^3' as 'kg/m3', ASCII: R12 and R2000 files are in a code page, so a
    superscript would not be UTF-8), any other caret escaped ('^ ', the DXF
    form of a literal '^', which LibreCAD shows as is)."""
    return text.replace("^3", "3").replace("^2", "2").replace("^", "^ ")


def _text_height(pattern: FlatPattern) -> float:
    return pattern.scale / 60.0


def draw_flat_pattern(
    pattern: FlatPattern,
    doc: Drawing | None = None,
    *,
    dxfversion: str = "R2000",
    rulings: bool = True,
) -> Drawing:
    """Draw ``pattern`` into the modelspace of ``doc`` (a new document if None).

    Args:
        pattern: from :func:`onefold_cad.fabrication.flat_pattern.flat_pattern`.
        doc: an existing ezdxf document to fill (its ``$INSUNITS``,
            ``$MEASUREMENT`` and ``$LTSCALE`` are set for the design), or None
            for a new one.
        dxfversion: 'R2000' (default), 'R12' for old CAM, or a later version;
            ignored when ``doc`` is given.
        rulings: draw the RULINGS layer (the etch lines; the paper model's
            ruling folds are bends and always drawn).

    Returns:
        The document (audited: no errors).
    """
    if doc is None:
        doc = new_document(dxfversion)
    _setup(doc, pattern)
    msp = doc.modelspace()
    outline = [tuple(p) for p in pattern.cut_outline.tolist()]
    if doc.dxfversion > "AC1009":
        msp.add_lwpolyline(outline, format="xy", close=True, dxfattribs={"layer": "CUT"})
    else:
        msp.add_polyline2d(outline, close=True, dxfattribs={"layer": "CUT"})
    apex = tuple(pattern.apex.tolist())
    if pattern.cut_hole_diameter > 0.0:
        msp.add_circle(apex, pattern.cut_hole_diameter / 2.0, dxfattribs={"layer": "CUT"})

    h = _text_height(pattern)
    fold_deg = math.degrees(math.atan2(pattern.fold_direction[1], pattern.fold_direction[0]))
    for half in pattern.halves:
        line = msp.add_line(
            tuple(half.start.tolist()),
            tuple(half.end.tolist()),
            dxfattribs={"layer": half.layer, "linetype": "DASHED"},
        )
        line.set_xdata(_APPID, [(1000, half.name), (1000, half.bend), (1040, half.angle_deg)])
        for a, b in half.zone:
            msp.add_line(tuple(a.tolist()), tuple(b.tolist()), dxfattribs={"layer": "BEND_ZONE"})
        mid = (half.start + half.end) / 2.0
        normal = np.array([-pattern.fold_direction[1], pattern.fold_direction[0]])
        zone_w = max((abs((z[0] - pattern.apex) @ normal) for z in half.zone), default=0.0)
        away = max(h, 1.5 * zone_w)
        pos = mid + normal * away
        label = msp.add_text(half.label, height=h, rotation=fold_deg, dxfattribs={"layer": "NOTES"})
        label.set_placement(
            tuple(pos.tolist()), align=ezdxf.enums.TextEntityAlignment.BOTTOM_CENTER
        )

    for f in pattern.fold_rulings:
        line = msp.add_line(
            tuple(f.start.tolist()),
            tuple(f.end.tolist()),
            dxfattribs={"layer": f.layer, "linetype": "DASHED"},
        )
        line.set_xdata(_APPID, [(1000, f.name), (1000, f.bend), (1040, f.angle_deg)])
    _apex_mark(msp, pattern)
    _hole_leader(msp, pattern, h)
    if rulings:
        for a, b in pattern.rulings:
            msp.add_line(tuple(a.tolist()), tuple(b.tolist()), dxfattribs={"layer": "RULINGS"})
    x0, y0 = pattern.outline.min(axis=0) - max(pattern.kerf, 0.0)
    for i, text in enumerate(flat_pattern_notes(pattern)):
        msp.add_text(
            _literal(text),
            height=h,
            dxfattribs={"layer": "NOTES", "insert": (x0, y0 - (2 + 1.6 * i) * h)},
        )
    auditor = doc.audit()
    if auditor.has_errors:
        raise ExportError(f"the DXF document failed its audit: {auditor.errors}")
    return doc


def _apex_mark(msp: object, pattern: FlatPattern) -> None:
    """A cross at +-45 deg to the fold line and a small circle at H."""
    m = pattern.scale / 50.0
    radius = m / 2.0
    for d in (pattern.hole_diameter, pattern.cut_hole_diameter):
        if abs(radius - d / 2.0) < 1e-3 * m:  # never on top of a CUT circle
            radius *= 1.5
    f = pattern.fold_direction
    n = np.array([-f[1], f[0]])
    for arm in ((f + n) / math.sqrt(2.0), (f - n) / math.sqrt(2.0)):
        a, b = pattern.apex - m * arm, pattern.apex + m * arm
        msp.add_line(tuple(a.tolist()), tuple(b.tolist()), dxfattribs={"layer": "APEX"})  # type: ignore[attr-defined]
    msp.add_circle(tuple(pattern.apex.tolist()), radius, dxfattribs={"layer": "APEX"})  # type: ignore[attr-defined]


def _hole_leader(msp: object, pattern: FlatPattern, height: float) -> None:
    """A leader (a LINE) from the relief hole's edge, square to the fold line,
    an eighth of the sheet long, and the hole's label at its end (APEX)."""
    d = pattern.hole_diameter
    if d <= 0.0:
        return
    f = pattern.fold_direction
    n = np.array([-f[1], f[0]])
    a = pattern.apex + n * d / 2.0
    b = pattern.apex + n * max(pattern.scale / 8.0, d)
    msp.add_line(tuple(a.tolist()), tuple(b.tolist()), dxfattribs={"layer": "APEX"})  # type: ignore[attr-defined]
    text = f"relief hole, diameter {d:.4g} {pattern.units.value}"
    label = msp.add_text(text, height=height, dxfattribs={"layer": "APEX"})  # type: ignore[attr-defined]
    label.set_placement(
        tuple((b + n * height / 2.0).tolist()), align=ezdxf.enums.TextEntityAlignment.BOTTOM_CENTER
    )


def _guid(seed: str, kind: str) -> str:
    """A GUID in AutoCAD's form, derived from ``seed`` (uuid5)."""
    return "{" + str(uuid.uuid5(_GUID_NAMESPACE, f"{kind}:{seed}")).upper() + "}"


@contextmanager
def _fixed_metadata(doc: Drawing, seed: str) -> Iterator[None]:
    """While saving, every time stamp fixed and the GUIDs derived from ``seed``.

    ezdxf stamps a document when it writes it (``Drawing._update_metadata``:
    $TDUPDATE from the clock, a random $VERSIONGUID, WRITTEN_BY_EZDXF with the
    time); this wraps that step for ``doc`` alone and overrides what it set.
    """
    from ezdxf.document import CREATED_BY_EZDXF, WRITTEN_BY_EZDXF
    from ezdxf.tools.juliandate import juliandate

    stamp = getattr(doc, "_update_metadata", None)
    if stamp is None:  # the hook this relies on: a newer ezdxf would fail the tests
        raise ExportError("ezdxf's Drawing._update_metadata is gone: cannot fix the DXF's dates")

    def fixed() -> None:
        stamp()
        day = juliandate(_FIXED_DATE)
        for var in ("$TDCREATE", "$TDUCREATE", "$TDUPDATE", "$TDUUPDATE"):
            doc.header[var] = day
        doc.header["$TDINDWG"] = 0.0
        doc.header["$TDUSRTIMER"] = 0.0
        doc.header["$FINGERPRINTGUID"] = _guid(seed, "fingerprint")
        doc.header["$VERSIONGUID"] = _guid(seed, "version")
        meta = doc.ezdxf_metadata()
        marker = f"{ezdxf.__version__} @ {_FIXED_DATE.isoformat()}+00:00"
        meta[CREATED_BY_EZDXF] = marker
        meta[WRITTEN_BY_EZDXF] = marker

    doc._update_metadata = fixed  # type: ignore[method-assign]
    try:
        yield
    finally:
        del doc._update_metadata


def write_dxf_atomic(
    doc: Drawing, path: str | os.PathLike[str], *, seed: str | None = None
) -> Path:
    """Save ``doc`` to ``path`` via a temporary file in the same directory.

    The file is deterministic: fixed dates, and $FINGERPRINTGUID and
    $VERSIONGUID derived from ``seed`` (default: a hash of the drawing itself).
    """
    if seed is None:
        text = io.StringIO()
        with _fixed_metadata(doc, ""):
            doc.write(text)
        seed = hashlib.sha256(text.getvalue().encode("utf-8")).hexdigest()
    with atomic_output(path) as tmp, _fixed_metadata(doc, seed):
        doc.saveas(tmp)
    return Path(path)


def design_seed(design: Design, compensation: Compensation | str, kind: str) -> str:
    """The seed of a design's DXF GUIDs: its data (as in a template), the
    compensation and the kind of file."""
    import json

    from onefold_cad.templates import design_to_data

    data = json.dumps(design_to_data(design), sort_keys=True, default=str)
    return f"{kind}:{Compensation.parse(compensation).value}:{data}"


def export_design_dxf(
    design: Design,
    path: str | os.PathLike[str],
    folded: FoldedSheet | None = None,
    *,
    dxfversion: str = "R2000",
    rulings: bool = True,
    compensation: Compensation | str = Compensation.SHARP,
) -> Path:
    """Write the annotated flat pattern of ``design`` as a DXF file (atomically).

    Args:
        design: the design.
        path: the output file; nothing is written if anything fails.
        folded: ``fold_design(design)`` if already computed.
        dxfversion: 'R2000' (default) or 'R12' (or a later version).
        rulings: include the RULINGS layer.
        compensation: 'sharp' (default) or 'none', see
            :func:`~onefold_cad.fabrication.flat_pattern.flat_pattern`.

    Returns:
        The path written.

    Raises:
        FabricationError: the sharp-crease compensation's limits are passed.
    """
    folded = fold_design(design) if folded is None else folded
    pattern = flat_pattern_once(design, folded, compensation)
    doc = draw_flat_pattern(pattern, dxfversion=dxfversion, rulings=rulings)
    return write_dxf_atomic(doc, path, seed=design_seed(design, compensation, "annotated"))
