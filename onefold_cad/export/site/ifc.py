"""SITE.ifc: the site for the architect's BIM, IFC4 written with IfcOpenShell.

What the file holds: an ``IfcProject`` (the site's name, its length unit;
areas in m^2, masses in kg) and an ``IfcSite`` it aggregates, holding one
``IfcPlate`` (PredefinedType SHEET) per sheet, named after it and placed
where it stands (an ``IfcLocalPlacement``: the site's turn about the
vertical and its move on the ground). Each plate has its material as an
``IfcMaterialLayerSetUsage`` (one layer of the sheet's thickness, the
material's name), the quantities ``Qto_PlateBaseQuantities`` (Width: the
thickness, NetArea: the blank's net area, NetWeight: the mass, all from the
sheet's report) and its body.

The body: an advanced B-rep needs IfcOpenShell to serialise the OCCT solid
(``ifcopenshell.geom.serialise``), which the installed IfcOpenShell may not
offer (0.9 has it commented out, and it takes pythonOCC shapes, not OCP's):
then the solid's OCCT tessellation (:func:`onefold_cad.export.site.mesh.mesh_shape`)
as an ``IfcTriangulatedFaceSet``, every
vertex on the solid's B-rep and every triangle within
:data:`~onefold_cad.export.site.context.MESH_DEFLECTION` of the sheet's size
of it (OCCT's linear deflection) and turning at most
:data:`~onefold_cad.export.site.context.MESH_ANGLE` rad from it; its area's
difference from the B-rep's is measured and reported (:class:`IfcResult`).
The tests validate the file with ``ifcopenshell.validate`` (20 s for the
shipped site: too slow for every write). Lengths in the site's unit.

Deterministic files: two writes of one site are byte-identical, so a BIM
program that reads the file again sees the same objects. FILE_NAME holds the
file's own name and :data:`~onefold_cad.export.brep.step.STEP_TIMESTAMP` (not the
clock), every relation lists its objects in file order, and every GlobalId
is derived (uuid5, in IFC's 22-character form) from the site's name, the
sheet an object belongs to (the project, the site and their relations:
none) and the object's class and rank among that sheet's objects of its
class: a plate keeps its GlobalId while its sheet keeps its name, and two
sites of different names share none.
"""

from __future__ import annotations

import os
import uuid
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from onefold_cad.export.atomic import atomic_output
from onefold_cad.export.brep.step import STEP_TIMESTAMP
from onefold_cad.export.site.context import MESH_ANGLE, MESH_DEFLECTION, SiteContext, SiteSheet
from onefold_cad.export.site.mesh import mesh_area

__all__ = ["IfcResult", "write_site_ifc"]

#: The namespace of the file's GlobalIds (uuid5 of the site, sheet, class, rank).
_ID_NAMESPACE = uuid.uuid5(uuid.NAMESPACE_DNS, "ifc.onefold_cad")

#: One site unit in metres.
_METRES = {"mm": 1e-3, "m": 1.0, "in": 0.0254, "ft": 0.3048}
_KG_PER_LB = 0.45359237


@dataclass(frozen=True)
class IfcResult:
    """What the IFC writer wrote.

    Attributes:
        path: the file.
        geometry: 'advanced_brep' or 'triangulated'.
        why: why the plates are not advanced B-reps ('' when they are).
        deviation: the largest distance of a triangle from its solid (length).
        angular_deflection: the largest turn of a triangle from its solid (rad).
        area_errors: per sheet, |mesh area / B-rep area - 1|.
        triangles: per sheet, the face set's triangles.
    """

    path: Path
    geometry: str
    why: str
    deviation: float
    angular_deflection: float
    area_errors: dict[str, float]
    triangles: dict[str, int]

    def to_data(self) -> dict[str, Any]:
        """The result as JSON data (the site report's ``ifc`` section)."""
        return {
            "geometry": self.geometry,
            "why": self.why,
            "deviation": self.deviation,
            "angular_deflection": self.angular_deflection,
            "area_errors": dict(self.area_errors),
            "max_area_error": max(self.area_errors.values(), default=0.0),
            "triangles": dict(self.triangles),
        }


def _units(f: Any, units: str) -> None:
    import ifcopenshell.api.unit as unit

    if units == "mm":
        length = unit.add_si_unit(f, unit_type="LENGTHUNIT", prefix="MILLI")
    elif units == "m":
        length = unit.add_si_unit(f, unit_type="LENGTHUNIT")
    else:
        length = unit.add_conversion_based_unit(f, name={"in": "inch", "ft": "foot"}[units])
    area = unit.add_si_unit(f, unit_type="AREAUNIT")
    mass = unit.add_si_unit(f, unit_type="MASSUNIT", prefix="KILO")
    assignment = unit.assign_unit(f, units=[length, area, mass])
    # IfcOpenShell's API gathers the units in a set: their order changed from
    # run to run, and with it the file's bytes.
    assignment.Units = (length, area, mass)


def _triangulated(f: Any, sheet: SiteSheet, context: Any) -> tuple[Any, float, int]:
    """The sheet's solid (resting frame) as an IfcTriangulatedFaceSet
    representation; the relative area error and the triangle count."""
    v, t = sheet.mesh
    error = abs(mesh_area(v, t) / float(sheet.part.area) - 1.0)
    points = f.createIfcCartesianPointList3D([tuple(map(float, p)) for p in v])
    faces = f.createIfcTriangulatedFaceSet(
        Coordinates=points, CoordIndex=[tuple(int(i) + 1 for i in tri) for tri in t]
    )
    rep = f.createIfcShapeRepresentation(context, "Body", "Tessellation", [faces])
    return rep, error, len(t)


def _material(f: Any, plate: Any, sheet: SiteSheet) -> None:
    import ifcopenshell.api.attribute as attribute
    import ifcopenshell.api.material as material

    m = sheet.design.material
    name = m.name or "sheet material"
    mat = material.add_material(f, name=name, category="steel" if "steel" in name else None)
    layers = material.add_material_set(f, name=name, set_type="IfcMaterialLayerSet")
    layer = material.add_layer(f, layer_set=layers, material=mat)
    attribute.edit_attributes(f, product=layer, attributes={"LayerThickness": float(m.thickness)})
    material.assign_material(f, products=[plate], type="IfcMaterialLayerSetUsage", material=layers)


def _quantities(f: Any, plate: Any, sheet: SiteSheet, units: str) -> None:
    import ifcopenshell.api.pset as pset

    rep = sheet.report
    values: dict[str, Any] = {"Width": float(sheet.design.material.thickness)}
    if rep.get("flat_area") is not None:
        values["NetArea"] = float(rep["flat_area"]) * _METRES[units] ** 2
    mass = rep.get("mass")
    if mass is not None:
        values["NetWeight"] = float(mass["value"]) * (_KG_PER_LB if mass["unit"] == "lb" else 1.0)
    qto = pset.add_qto(f, product=plate, name="Qto_PlateBaseQuantities")
    pset.edit_qto(f, qto=qto, properties=values)


def _roots(f: Any) -> set[int]:
    """The ids of the file's rooted objects (those with a GlobalId)."""
    return {e.id() for e in f.by_type("IfcRoot")}


def _ordered_relations(f: Any) -> None:
    """Every relation's related objects in file order (IfcOpenShell's API keeps
    them as a set: their order changed from run to run)."""
    for rel in f.by_type("IfcRelationship"):
        for i in range(len(rel)):
            value = rel[i]
            if isinstance(value, tuple) and len(value) > 1 and all(hasattr(v, "id") for v in value):
                rel[i] = tuple(sorted(value, key=lambda v: v.id()))


def _fixed_ids(f: Any, site: str, owners: dict[int, str]) -> None:
    """Give every rooted object a GlobalId derived from ``site``, its owner
    (``owners``: object id -> sheet name; the others the site's) and its
    class and rank among its owner's objects of that class (file order)."""
    from ifcopenshell.guid import compress

    seen: dict[tuple[str, str], int] = {}
    for e in sorted(f.by_type("IfcRoot"), key=lambda e: e.id()):
        owner = owners.get(e.id(), "")
        rank = seen[(owner, e.is_a())] = seen.get((owner, e.is_a()), -1) + 1
        key = "\0".join((site, owner, e.is_a(), str(rank)))
        e.GlobalId = compress(uuid.uuid5(_ID_NAMESPACE, key).hex)


def write_site_ifc(ctx: SiteContext, path: str | os.PathLike[str]) -> IfcResult:
    """Write SITE.ifc (atomically, validated first).

    Returns:
        What was written (the plates' geometry kind and its deviation).
    """
    import ifcopenshell.api.aggregate as aggregate
    import ifcopenshell.api.context as context
    import ifcopenshell.api.geometry as geometry
    import ifcopenshell.api.project as project
    import ifcopenshell.api.root as root
    import ifcopenshell.api.spatial as spatial
    import ifcopenshell.geom

    f = project.create_file(version="IFC4")
    proj = root.create_entity(f, ifc_class="IfcProject", name=ctx.name)
    if ctx.description:
        proj.Description = ctx.description
    _units(f, ctx.units)
    model = context.add_context(f, context_type="Model")
    body = context.add_context(
        f, context_type="Model", context_identifier="Body", target_view="MODEL_VIEW", parent=model
    )
    site = root.create_entity(f, ifc_class="IfcSite", name=ctx.name)
    aggregate.assign_object(f, relating_object=proj, products=[site])
    geometry.edit_object_placement(f, product=site, matrix=np.eye(4), is_si=False)
    why = (
        "this IfcOpenShell has no geom.serialise"
        if not hasattr(ifcopenshell.geom, "serialise")
        else "IfcOpenShell serialises pythonOCC shapes, not OCP's"
    )
    errors, counts = {}, {}
    owners: dict[int, str] = {}
    for s in ctx.sheets:
        before = _roots(f)
        plate = root.create_entity(f, ifc_class="IfcPlate", predefined_type="SHEET", name=s.name)
        spatial.assign_container(f, relating_structure=site, products=[plate])
        geometry.edit_object_placement(f, product=plate, matrix=s.site.matrix, is_si=False)
        rep, errors[s.name], counts[s.name] = _triangulated(f, s, body)
        geometry.assign_representation(f, product=plate, representation=rep)
        _material(f, plate, s)
        _quantities(f, plate, s, ctx.units)
        owners.update(dict.fromkeys(_roots(f) - before, s.name))
    _fixed_ids(f, ctx.name, owners)
    _ordered_relations(f)
    out = Path(path)
    f.header.file_name.name = out.name
    f.header.file_name.time_stamp = STEP_TIMESTAMP
    with atomic_output(out) as tmp:
        f.write(str(tmp))
    deviation = MESH_DEFLECTION * ctx.size
    return IfcResult(out, "triangulated", why, deviation, MESH_ANGLE, errors, counts)
