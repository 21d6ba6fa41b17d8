"""NAME.3dm: the folded form and its flat pattern for Rhino (a rhino3dm adapter).

One Rhino 8 file, model units from the design (mm, in, ft), holding:

- ``Folded::Sheet``: the folded form as NURBS faces on the exact cone, one
  Brep per face (per side, one face per sector between the sheet's corners;
  rhino3dm joins no Breps), each with a render mesh and grouped per side
  (groups ``upper side`` / ``lower side``): :mod:`.rhino_faces`, fitted to
  the STEP's tolerance (:data:`TOLERANCE` x the sheet's size);
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
- the design's parameters (as in its template: ``frame.alpha``, ...), the
  crease halves' angles and the faces' fit as document user strings.

openNURBS stamps the file with the time it was written and fresh ids for
its layers and objects, so two writes differ in those bytes; the file name
it records is the file's own (not the temporary one it is written under).

The form stands as it rests (:func:`onefold_cad.fabrication.rules.resting_placement`,
as the STEP's and the GLB's) or in the fold frame (``placement='frame'``).
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import rhino3dm
from ezdxf.colors import aci2rgb

from onefold_cad.choices import Compensation, Units
from onefold_cad.design import Design
from onefold_cad.errors import ExportError
from onefold_cad.export.atomic import atomic_output
from onefold_cad.export.colour_scale import STEEL_GREY
from onefold_cad.export.dxf import LAYERS as DXF_LAYERS
from onefold_cad.export.dxf_notes import flat_pattern_notes
from onefold_cad.export.rhino_faces import Place, face_brep, face_nets
from onefold_cad.export.step_checks import BOUNDARY_TOLERANCE
from onefold_cad.fabrication.flat_pattern import FlatPattern, flat_pattern_once
from onefold_cad.fabrication.relief_hole import relief_hole_diameter, relief_hole_problem
from onefold_cad.fabrication.rules import resting_placement
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import Array

__all__ = [
    "FLAT_LAYERS",
    "FOLDED_LAYERS",
    "TOLERANCE",
    "RhinoModel",
    "build_3dm",
    "layer_colour",
    "write_3dm",
]

#: The faces' largest distance from the exact cone, relative to the sheet's size
#: (the STEP's boundary tolerance).
TOLERANCE = BOUNDARY_TOLERANCE
#: Rhino 8's archive version.
VERSION = 8
_UNITS = {
    Units.MM: rhino3dm.UnitSystem.Millimeters,
    Units.IN: rhino3dm.UnitSystem.Inches,
    Units.FT: rhino3dm.UnitSystem.Feet,
}


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
        faces: the number of NURBS faces of the folded form.
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


def _p3(p: Array) -> Any:
    x, y, *z = (float(c) for c in p)
    return rhino3dm.Point3d(x, y, z[0] if z else 0.0)


def _layers(doc: Any) -> dict[str, int]:
    """Add the parents and their layers; return 'Folded::Sheet' -> index, ..."""
    index = {}
    for parent, layers in (("Folded", FOLDED_LAYERS), ("Flat", FLAT_LAYERS)):
        top = rhino3dm.Layer()
        top.Name = parent
        top.Color = (0, 0, 0, 255)
        parent_id = doc.Layers[doc.Layers.Add(top)].Id
        for name, (r, g, b) in layers.items():
            layer = rhino3dm.Layer()
            layer.Name = name
            layer.Color = (r, g, b, 255)
            layer.ParentLayerId = parent_id
            index[f"{parent}::{name}"] = doc.Layers.Add(layer)
    return index


def _attributes(layer: int, label: str = "", **strings: object) -> Any:
    a = rhino3dm.ObjectAttributes()
    a.LayerIndex = layer
    if label:
        a.Name = label
    for key, value in strings.items():
        a.SetUserString(key, str(value))
    return a


def _flatten(data: Mapping[str, Any], prefix: str = "") -> dict[str, str]:
    out: dict[str, str] = {}
    for key, value in data.items():
        if isinstance(value, Mapping):
            out.update(_flatten(value, f"{prefix}{key}."))
        else:
            out[f"{prefix}{key}"] = str(value)
    return out


def _folded(
    doc: Any, layers: dict[str, int], folded: FoldedSheet, hole: float, place: Place, tol: float
) -> tuple[int, float, Array]:
    """The faces, creases and apex; returns (faces, deviation, bounds (2, 3))."""
    nets = face_nets(folded, hole, tol)
    groups = []
    for side in ("upper side", "lower side"):
        group = rhino3dm.Group()
        group.Name = side
        doc.Groups.Add(group)
        groups.append(doc.Groups.FindName(side).Index)
    corners = []
    for net in nets:
        side = ("upper", "lower")[net.side]
        a = _attributes(
            layers["Folded::Sheet"],
            f"{side} face {net.sector}",
            side=side,
            sector=net.sector,
            fit_deviation=f"{net.deviation:.6g}",
        )
        a.AddToGroup(groups[net.side])
        doc.Objects.AddBrep(face_brep(folded, net, hole, place), a)
        corners.append(place(np.concatenate([net.inner, net.outer])))
    apex = place(folded.apex[None, :])[0]
    for half in folded.crease:
        a = _attributes(
            layers[f"Folded::Crease {half.bend}"],
            f"crease {half.name}",
            name=half.name,
            bend=half.bend,
            fold_angle_deg=f"{half.fold_angle_deg:.6f}",
            length=f"{half.length:.9g}",
        )
        doc.Objects.AddLine(_p3(apex), _p3(place(half.end_3d[None, :])[0]), a)
    doc.Objects.AddPoint(_p3(apex), _attributes(layers["Folded::Apex"], "apex"))
    pts = np.concatenate(corners)
    deviation = max(net.deviation for net in nets)
    return len(nets), deviation, np.stack([pts.min(axis=0), pts.max(axis=0)])


def _flat(doc: Any, layers: dict[str, int], pattern: FlatPattern, offset: Array) -> None:
    """The flat pattern on the ground plane, moved by ``offset`` ``(2,)``."""

    def line(layer: str, a: Array, b: Array, label: str = "", **strings: object) -> None:
        attrs = _attributes(layers[f"Flat::{layer}"], label, **strings)
        doc.Objects.AddLine(_p3(a + offset), _p3(b + offset), attrs)

    outline = [_p3(p + offset) for p in pattern.cut_outline]
    curve = rhino3dm.PolylineCurve([*outline, outline[0]])
    doc.Objects.AddCurve(curve, _attributes(layers["Flat::CUT"], "outline"))
    apex = pattern.apex + offset
    if pattern.cut_hole_diameter > 0.0:
        circle = rhino3dm.Circle(_p3(apex), pattern.cut_hole_diameter / 2.0)
        doc.Objects.AddCircle(circle, _attributes(layers["Flat::CUT"], "relief hole"))
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
    doc.Objects.AddPoint(_p3(apex), _attributes(layers["Flat::APEX"], "H"))
    h = pattern.scale / 60.0
    x0, y0 = pattern.outline.min(axis=0) + offset
    for i, text in enumerate(flat_pattern_notes(pattern)):
        at = np.array([x0, y0 - (2 + 1.6 * i) * h])
        doc.Objects.AddTextDot(text, _p3(at), _attributes(layers["Flat::NOTES"]))


def build_3dm(
    design: Design,
    folded: FoldedSheet,
    *,
    pattern: FlatPattern | None = None,
    placement: str = "rest",
    body: str | None = None,
    compensation: Compensation | str = Compensation.SHARP,
) -> RhinoModel:
    """The .3dm document of ``design`` (see the module docstring).

    Args:
        design: the design (its unit, material and parameters).
        folded: ``build_design(design)``.
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
    problem = relief_hole_problem(design, folded)
    if problem is not None:
        raise problem
    if pattern is None:
        pattern = flat_pattern_once(design, folded, compensation)
    rest = resting_placement(design, folded, body) if placement == "rest" else None

    def place(p: Array) -> Array:
        return np.asarray(p, dtype=float) if rest is None else rest.apply(p)

    doc = rhino3dm.File3dm()
    doc.Settings.ModelUnitSystem = _UNITS[design.units]
    size = folded.sheet.size
    tol = TOLERANCE * size
    doc.Settings.ModelAbsoluteTolerance = tol
    layers = _layers(doc)
    hole = relief_hole_diameter(design, folded) / 2.0
    faces, deviation, bounds = _folded(doc, layers, folded, hole, place, tol)
    if rest is not None:
        for i, p in enumerate(rest.contacts):
            doc.Objects.AddPoint(_p3(p), _attributes(layers["Folded::Ground contacts"], f"c{i}"))
    lo = pattern.outline.min(axis=0)
    offset = np.array([bounds[1, 0] + 0.1 * size - lo[0], bounds[0, 1] - lo[1]])
    _flat(doc, layers, pattern, offset)
    from onefold_cad.templates import design_to_data

    strings = _flatten(design_to_data(design))
    for half in folded.crease:
        strings[f"crease.{half.name}.fold_angle_deg"] = f"{half.fold_angle_deg:.6f}"
        strings[f"crease.{half.name}.bend"] = half.bend
    strings.update(
        {
            "rhino.placement": placement,
            "rhino.faces": str(faces),
            "rhino.fit_deviation": f"{deviation:.6g}",
            "rhino.fit_tolerance": f"{tol:.6g}",
            "flat.compensation": pattern.compensation,
        }
    )
    for key, value in strings.items():
        doc.Strings[key] = value
    return RhinoModel(doc, faces, deviation, tol, offset)


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
    out = Path(path)
    # openNURBS records the name it writes to in the file: write under the
    # file's own name (in a private folder), then move it into place
    with atomic_output(out) as tmp, tempfile.TemporaryDirectory(dir=out.parent) as folder:
        named = Path(folder) / out.name
        if not model.file.Write(str(named), VERSION):
            raise ExportError(f"rhino3dm could not write {out}")
        os.replace(named, tmp)
    return model
