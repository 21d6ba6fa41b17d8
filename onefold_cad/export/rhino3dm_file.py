"""NAME.3dm: the folded form and its flat pattern for Rhino (a rhino3dm adapter).

One Rhino 8 file, model units from the design (mm, m, in, ft), holding:

- ``Folded::Sheet``: the folded form as one Brep per side (``upper side``,
  ``lower side``), each a single NURBS face on the exact cone whose natural
  boundary is the part's edge, C0 at the sheet's corners, with a render mesh
  (:mod:`.rhino_sides`, fitted to the STEP's tolerance: :data:`TOLERANCE` x
  the sheet's size);
- ``Folded::Crease UP`` / ``Folded::Crease DOWN``: each crease half as a line
  from the apex to the sheet's edge, on the layer of its bend;
  ``Folded::Apex``: the apex point; ``Folded::Ground contacts``: where the
  form touches the ground (resting placement only);
- the flat pattern (:mod:`onefold_cad.fabrication.flat_pattern`) on layers
  named and coloured like the DXF's (:data:`onefold_cad.export.dxf.LAYERS`)
  under ``Flat::``: the cut outline and relief hole (``Flat::CUT``), the bend
  lines (``Flat::BEND_UP`` / ``Flat::BEND_DOWN``), bend zones, rulings, the
  apex and the notes (as text dots), on the ground plane z = 0 beside the
  form (+x of it, a tenth of the sheet's size apart);
- user strings (:mod:`.rhino_strings`): the design's parameters (as in its
  template: ``frame.alpha``, ...) and the report's key numbers
  (``report.fold_angles_deg.plus_x``, ``report.resting.height``, ...) on the
  document and on each side's Brep (its attributes and its geometry), with
  the crease halves' angles and the faces' fit on the document.

Two writes of the same design give the same bytes: the layers' and objects'
ids are derived from the design (:func:`onefold_cad.export.dxf.design_seed`
with the placement and body), the file is written from memory (openNURBS
records no file name) and with its revision set before writing, so that
openNURBS stamps no time (the file's created / last edited times are unset;
rhino3dm 8's ``File3dm.Created`` cannot convert an unset time and raises).

The form stands as it rests (:func:`onefold_cad.fabrication.rules.resting_placement`,
as the STEP's and the GLB's) or in the fold frame (``placement='frame'``).
"""

from __future__ import annotations

import base64
import os
import uuid
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import rhino3dm
from ezdxf.colors import aci2rgb

from onefold_cad.choices import Body, Compensation, Placement, Units
from onefold_cad.design import Design
from onefold_cad.errors import ExportError
from onefold_cad.export.atomic import atomic_output
from onefold_cad.export.colour_scale import STEEL_GREY
from onefold_cad.export.dxf import LAYERS as DXF_LAYERS
from onefold_cad.export.dxf import design_seed
from onefold_cad.export.dxf_notes import flat_pattern_notes
from onefold_cad.export.rhino_sides import TOLERANCE, FoldSides, fold_sides, placement_of
from onefold_cad.fabrication.flat_pattern import FlatPattern, flat_pattern_once
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import Array

__all__ = [
    "FLAT_LAYERS",
    "FOLDED_LAYERS",
    "TOLERANCE",
    "RhinoModel",
    "build_3dm",
    "file_bytes",
    "layer_colour",
    "write_3dm",
]

#: Rhino 8's archive version.
VERSION = 8
_UNITS = {
    Units.MM: rhino3dm.UnitSystem.Millimeters,
    Units.M: rhino3dm.UnitSystem.Meters,
    Units.IN: rhino3dm.UnitSystem.Inches,
    Units.FT: rhino3dm.UnitSystem.Feet,
}
#: The namespace of the file's ids (uuid5 of the design's seed and the component).
_ID_NAMESPACE = uuid.uuid5(uuid.NAMESPACE_DNS, "3dm.onefold_cad")


def layer_colour(aci: int) -> tuple[int, int, int]:
    """The RGB of an AutoCAD colour index as Rhino shows it: ezdxf's table,
    with ACI 7 (white on black, black on white) as black for Rhino's white
    viewports."""
    return (0, 0, 0) if aci == 7 else tuple(aci2rgb(aci))  # type: ignore[return-value]


#: Flat:: layer name -> RGB, the DXF's layers and colours.
FLAT_LAYERS: dict[str, tuple[int, int, int]] = {
    name: layer_colour(aci) for name, (aci, _) in DXF_LAYERS.items()
}
#: Folded:: layer name -> RGB: the sheet steel grey, the creases as the DXF's
#: bend lines, the apex as its APEX layer.
FOLDED_LAYERS: dict[str, tuple[int, int, int]] = {
    "Sheet": tuple(round(255 * c) for c in STEEL_GREY),  # type: ignore[dict-item]
    "Crease UP": FLAT_LAYERS["BEND_UP"],
    "Crease DOWN": FLAT_LAYERS["BEND_DOWN"],
    "Apex": FLAT_LAYERS["APEX"],
    "Ground contacts": layer_colour(6),
}


@dataclass
class RhinoModel:
    """A built .3dm document and what the report says of it.

    Attributes:
        file: the rhino3dm document.
        faces: the number of NURBS faces of the folded form (one per side).
        fit_deviation: the faces' largest measured distance from the exact
            cone (length).
        fit_tolerance: the distance allowed (length).
        flat_offset: ``(2,)`` where the flat pattern's sheet frame origin lies
            on the ground plane (length).
    """

    file: Any
    faces: int
    fit_deviation: float
    fit_tolerance: float
    flat_offset: Array


class _Ids:
    """Ids derived from a seed: the n-th id asked for a kind is always the same."""

    def __init__(self, seed: str) -> None:
        self.seed = seed
        self.count: dict[str, int] = {}

    def __call__(self, kind: str) -> str:
        n = self.count.get(kind, 0)
        self.count[kind] = n + 1
        return str(uuid.uuid5(_ID_NAMESPACE, f"{kind}:{n}:{self.seed}"))


def _p3(p: Array) -> Any:
    x, y, *z = (float(c) for c in p)
    return rhino3dm.Point3d(x, y, z[0] if z else 0.0)


def _layers(doc: Any, ids: _Ids) -> dict[str, int]:
    """Add the parents and their layers; return 'Folded::Sheet' -> index, ..."""
    index = {}
    for parent, layers in (("Folded", FOLDED_LAYERS), ("Flat", FLAT_LAYERS)):
        top = rhino3dm.Layer()
        top.Name = parent
        top.Color = (0, 0, 0, 255)
        top.Id = ids("layer")
        parent_id = doc.Layers[doc.Layers.Add(top)].Id
        for name, (r, g, b) in layers.items():
            layer = rhino3dm.Layer()
            layer.Name = name
            layer.Color = (r, g, b, 255)
            layer.ParentLayerId = parent_id
            layer.Id = ids("layer")
            index[f"{parent}::{name}"] = doc.Layers.Add(layer)
    return index


class _Adder:
    """Attributes for the objects of one document: layer, name, user strings
    and an id from the document's seed."""

    def __init__(self, layers: dict[str, int], ids: _Ids) -> None:
        self.layers, self.ids = layers, ids

    def __call__(self, layer: str, label: str = "", **strings: object) -> Any:
        a = rhino3dm.ObjectAttributes()
        a.LayerIndex = self.layers[layer]
        a.Id = self.ids("object")
        if label:
            a.Name = label
        for key, value in strings.items():
            a.SetUserString(key, str(value))
        return a


def _folded(doc: Any, attrs: _Adder, folded: FoldedSheet, sides: FoldSides, place: Any) -> Array:
    """The side Breps, creases and apex; returns the form's bounds (2, 3)."""
    corners = []
    for (name, brep), net in zip(sides.breps, sides.nets, strict=True):
        a = attrs("Folded::Sheet", f"{name} side")
        for key, value in brep.GetUserStrings():
            a.SetUserString(key, value)
        doc.Objects.AddBrep(brep, a)
        corners.append(place(np.concatenate([net.inner, net.outer])))
    apex = place(folded.apex[None, :])[0]
    for half in folded.crease:
        a = attrs(
            f"Folded::Crease {half.bend}",
            f"crease {half.name}",
            name=half.name,
            bend=half.bend,
            fold_angle_deg=f"{half.fold_angle_deg:.6f}",
            length=f"{half.length:.9g}",
        )
        doc.Objects.AddLine(_p3(apex), _p3(place(half.end_3d[None, :])[0]), a)
    doc.Objects.AddPoint(_p3(apex), attrs("Folded::Apex", "apex"))
    pts = np.concatenate(corners)
    return np.stack([pts.min(axis=0), pts.max(axis=0)])


def _flat(doc: Any, attrs: _Adder, pattern: FlatPattern, offset: Array) -> None:
    """The flat pattern on the ground plane, moved by ``offset`` ``(2,)``."""

    def line(layer: str, a: Array, b: Array, label: str = "", **strings: object) -> None:
        doc.Objects.AddLine(
            _p3(a + offset), _p3(b + offset), attrs(f"Flat::{layer}", label, **strings)
        )

    outline = [_p3(p + offset) for p in pattern.cut_outline]
    curve = rhino3dm.PolylineCurve([*outline, outline[0]])
    doc.Objects.AddCurve(curve, attrs("Flat::CUT", "outline"))
    apex = pattern.apex + offset
    if pattern.cut_hole_diameter > 0.0:
        circle = rhino3dm.Circle(_p3(apex), pattern.cut_hole_diameter / 2.0)
        doc.Objects.AddCircle(circle, attrs("Flat::CUT", "relief hole"))
    for half in pattern.halves:
        line(
            half.layer,
            half.start,
            half.end,
            f"bend {half.name}",
            name=half.name,
            bend=half.bend,
            angle_deg=f"{half.angle_deg:.6f}",
        )
        for a, b in half.zone:
            line("BEND_ZONE", a, b)
    for f in pattern.fold_rulings:
        line(f.layer, f.start, f.end, f.name, name=f.name, bend=f.bend, angle_deg=f.angle_deg)
    for a, b in pattern.rulings:
        line("RULINGS", a, b)
    doc.Objects.AddPoint(_p3(apex), attrs("Flat::APEX", "H"))
    h = pattern.scale / 60.0
    x0, y0 = pattern.outline.min(axis=0) + offset
    for i, text in enumerate(flat_pattern_notes(pattern)):
        at = np.array([x0, y0 - (2 + 1.6 * i) * h])
        doc.Objects.AddTextDot(text, _p3(at), attrs("Flat::NOTES"))


def build_3dm(
    design: Design,
    folded: FoldedSheet,
    *,
    pattern: FlatPattern | None = None,
    placement: Placement = Placement.REST,
    body: Body | None = None,
    compensation: Compensation | str = Compensation.SHARP,
) -> RhinoModel:
    """The .3dm document of ``design`` (see the module docstring).

    Args:
        design: the design (its unit, material and parameters).
        folded: ``fold_design(design)``.
        pattern: its flat pattern if already made (else made here with
            ``compensation``).
        placement: 'rest' (standing on the ground z = 0) or 'frame' (the
            fold frame).
        body: the body whose resting placement stands the form ('solid',
            'shell'; None for the default), as the STEP's.
        compensation: 'sharp' or 'none', for the flat pattern.

    Raises:
        FabricationError: the relief hole does not fit the sheet, or the flat
            pattern cannot be made.
        ExportError: a face cannot reach the tolerance.
    """
    sides = fold_sides(
        design, folded, placement=placement, body=body, pattern=pattern, compensation=compensation
    )
    if pattern is None:
        pattern = flat_pattern_once(design, folded, compensation)
    place, rest = placement_of(design, folded, placement, body)
    comp = Compensation.parse(compensation).value
    ids = _Ids(f"{design_seed(design, comp, '3dm')}:{placement}:{body}")
    doc = rhino3dm.File3dm()
    doc.Revision = 1  # a revision already: openNURBS then stamps no write time
    doc.Settings.ModelUnitSystem = _UNITS[design.units]
    size = folded.sheet.size
    doc.Settings.ModelAbsoluteTolerance = sides.tolerance
    attrs = _Adder(_layers(doc, ids), ids)
    bounds = _folded(doc, attrs, folded, sides, place)
    if rest is not None:
        for i, p in enumerate(rest.contacts):
            doc.Objects.AddPoint(_p3(p), attrs("Folded::Ground contacts", f"c{i}"))
    lo = pattern.outline.min(axis=0)
    offset = np.array([bounds[1, 0] + 0.1 * size - lo[0], bounds[0, 1] - lo[1]])
    _flat(doc, attrs, pattern, offset)
    strings = dict(sides.strings)
    for half in folded.crease:
        strings[f"crease.{half.name}.fold_angle_deg"] = f"{half.fold_angle_deg:.6f}"
        strings[f"crease.{half.name}.bend"] = half.bend
    strings["rhino.faces"] = str(len(sides.breps))
    strings["flat.compensation"] = pattern.compensation
    for key, value in strings.items():
        doc.Strings[key] = value
    return RhinoModel(doc, len(sides.breps), sides.deviation, sides.tolerance, offset)


def file_bytes(model: RhinoModel) -> bytes:
    """The bytes of the model's Rhino 8 file, written in memory (no file
    name recorded, no time stamped: the same model gives the same bytes).

    Raises:
        ExportError: rhino3dm cannot write it.
    """
    options = rhino3dm.File3dmWriteOptions()
    options.Version = VERSION
    data = base64.b64decode(model.file.Encode(options))
    if not data:
        raise ExportError("rhino3dm could not write the .3dm")
    return data


def write_3dm(
    design: Design,
    folded: FoldedSheet,
    path: str | os.PathLike[str],
    **options: Any,
) -> RhinoModel:
    """Write the .3dm of ``design`` at ``path`` (atomically, Rhino 8 format);
    ``options`` as :func:`build_3dm`. Returns the model written.

    Raises:
        FabricationError, ExportError: as :func:`build_3dm`; ExportError also
            when rhino3dm cannot write the file.
    """
    model = build_3dm(design, folded, **options)
    data = file_bytes(model)
    with atomic_output(Path(path)) as tmp:
        Path(tmp).write_bytes(data)
    return model
