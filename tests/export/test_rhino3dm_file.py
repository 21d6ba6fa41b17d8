"""NAME.3dm read back with rhino3dm: Rhino 8, the design's units, the DXF's
layers and colours under Flat:: and Folded::, the flat outline the blank's,
every folded face on the exact cone (measured against rays of the fold,
independently of the writer's own fit), the faces' areas the sheet's."""

from __future__ import annotations

import math

import numpy as np
import pytest
import rhino3dm
from ezdxf.colors import aci2rgb
from scipy.interpolate import BSpline

from onefold_cad import Design, FrameCurve, Material, Sheet, build_design
from onefold_cad.export.dxf import LAYERS as DXF_LAYERS
from onefold_cad.export.rhino3dm_file import write_3dm
from onefold_cad.fabrication.flat_pattern import flat_pattern_once
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.fabrication.rules import resting_placement

FLOAT32 = float(np.finfo(np.float32).eps)
#: The issue's bound on a face point's distance from the exact cone (x sheet size).
ON_CONE = 1e-6


def _read(path) -> rhino3dm.File3dm:
    doc = rhino3dm.File3dm.Read(str(path))
    assert doc is not None
    return doc


def _on(doc, layer: str) -> list:
    """The objects of ``doc`` on the layer with the full path ``layer``."""
    index = {lay.FullPath: lay.Index for lay in doc.Layers}[layer]
    return [o for o in doc.Objects if o.Attributes.LayerIndex == index]


@pytest.fixture(scope="module")
def shell(tmp_path_factory):
    """A zero-thickness design in inches (no relief hole), in the fold frame."""
    design = Design("shell", FrameCurve(40, 40), Sheet.quadrilateral(30, 30, 20, 20), units="in")
    folded = build_design(design)
    path = tmp_path_factory.mktemp("3dm") / "shell.3dm"
    write_3dm(design, folded, path, placement="frame")
    return design, folded, _read(path)


@pytest.fixture(scope="module")
def holed(tmp_path_factory):
    """A 2 mm sheet with its default relief hole, an uneven polygon, standing as it rests."""
    sheet = Sheet.polygon([[100, 0], [70, 90], [-40, 110], [-120, 0], [-60, -80], [80, -70]])
    design = Design("holed", FrameCurve(45, 35, h_c=5.0), sheet, material=Material(thickness=2.0))
    folded = build_design(design)
    path = tmp_path_factory.mktemp("3dm") / "holed.3dm"
    write_3dm(design, folded, path)
    return design, folded, _read(path)


@pytest.fixture(scope="module")
def paper(tmp_path_factory):
    """The paper model (a fan of 12 planar triangles a side) in feet, in the fold frame."""
    frame = FrameCurve(35, 40, divisions=12)
    design = Design("fan", frame, Sheet.rectangle(8, 5, 0.4), model="paper", units="ft")
    folded = build_design(design)
    path = tmp_path_factory.mktemp("3dm") / "fan.3dm"
    write_3dm(design, folded, path, placement="frame")
    return design, folded, _read(path)


def _grid(surface, nu: int = 13, nv: int = 5) -> np.ndarray:
    u, v = surface.Domain(0), surface.Domain(1)
    return np.array(
        [
            [(p := surface.PointAt(a, b)).X, p.Y, p.Z]
            for a in np.linspace(u.T0, u.T1, nu)
            for b in np.linspace(v.T0, v.T1, nv)
        ]
    )


def _faces(doc) -> list:
    return [o.Geometry.Surfaces[0] for o in _on(doc, "Folded::Sheet")]


def _cone_distances(folded, p: np.ndarray) -> np.ndarray:
    """Distances ``(k,)`` from points ``p`` ``(k, 3)`` (fold frame) to the exact
    cone: the closest of the rays A + t U(psi) of both sides, U(psi) the fold
    of the unit flat direction at polar angle psi (map_points), found on a
    dense grid of psi and refined by golden-section search, all points at once."""
    apex = folded.apex
    w = p - apex

    def gap(psi: np.ndarray) -> np.ndarray:
        u = folded.map_points(np.stack([np.cos(psi), np.sin(psi)], axis=1)) - apex
        t = np.maximum(np.einsum("ij,ij->i", w, u), 0.0)
        return np.linalg.norm(w - t[:, None] * u, axis=1)

    grid = np.linspace(-math.pi, math.pi, 1441)
    table = np.array([gap(np.full(len(p), x)) for x in grid])  # (grid, k)
    i = np.argmin(table, axis=0)
    lo, hi = grid[np.maximum(i - 1, 0)], grid[np.minimum(i + 1, len(grid) - 1)]
    g = (math.sqrt(5.0) - 1.0) / 2.0
    for _ in range(80):
        a, b = hi - g * (hi - lo), lo + g * (hi - lo)
        left = gap(a) < gap(b)
        hi, lo = np.where(left, b, hi), np.where(left, lo, a)
    return np.minimum(gap(0.5 * (lo + hi)), table.min(axis=0))


def test_units_are_the_designs(tmp_path):
    for units, want in (
        ("mm", rhino3dm.UnitSystem.Millimeters),
        ("in", rhino3dm.UnitSystem.Inches),
        ("ft", rhino3dm.UnitSystem.Feet),
    ):
        design = Design("u", FrameCurve(40, 40), Sheet.rectangle(10, 6), units=units)
        write_3dm(design, build_design(design), tmp_path / f"{units}.3dm")
        doc = _read(tmp_path / f"{units}.3dm")
        assert doc.Settings.ModelUnitSystem == want
        assert rhino3dm.File3dm.ReadArchiveVersion(str(tmp_path / f"{units}.3dm")) == 80


def test_layers_are_named_and_coloured_like_the_dxfs(shell):
    layers = {lay.FullPath: lay.Color[:3] for lay in shell[2].Layers}
    for name, (aci, _) in DXF_LAYERS.items():
        want = (0, 0, 0) if aci == 7 else tuple(aci2rgb(aci))
        assert layers[f"Flat::{name}"] == want, name
    for name in ("Sheet", "Crease UP", "Crease DOWN", "Apex", "Ground contacts"):
        assert f"Folded::{name}" in layers
    assert layers["Folded::Crease UP"] == layers["Flat::BEND_UP"]
    assert layers["Folded::Crease DOWN"] == layers["Flat::BEND_DOWN"]


def _polyline(curve) -> np.ndarray:
    return np.array([[(p := curve.Point(i)).X, p.Y, p.Z] for i in range(curve.PointCount)])


def _shoelace(xy: np.ndarray) -> float:
    x, y = xy[:, 0], xy[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


@pytest.mark.parametrize("case", ["shell", "holed"])
def test_flat_outline_area_is_the_blanks_on_the_ground_beside_the_form(case, request):
    design, folded, doc = request.getfixturevalue(case)
    (outline,) = [o.Geometry for o in _on(doc, "Flat::CUT") if o.Attributes.Name == "outline"]
    pts = _polyline(outline)
    assert outline.IsClosed and np.all(pts[:, 2] == 0.0)
    blank = flat_pattern_once(design, folded, "sharp").outline
    assert _shoelace(pts[:-1, :2]) == pytest.approx(_shoelace(blank), rel=1e-12)
    if design.material.thickness == 0.0:
        assert _shoelace(pts[:-1, :2]) == pytest.approx(design.sheet.area, rel=1e-12)
    form = np.concatenate([_grid(s) for s in _faces(doc)])
    assert pts[:, 0].min() > form[:, 0].max()  # beside the form, not under it


def test_relief_hole_is_a_circle_of_its_diameter(holed):
    design, folded, doc = holed
    (hole,) = [o.Geometry for o in _on(doc, "Flat::CUT") if o.Attributes.Name == "relief hole"]
    circle = hole.TryGetCircle()
    assert hole.IsCircle() and circle.Radius == pytest.approx(
        relief_hole_diameter(design, folded) / 2.0
    )


@pytest.mark.parametrize("case", ["shell", "holed", "paper"])
def test_every_face_lies_on_the_exact_cone(case, request):
    """(The paper model's surface is its fan: the rays of map_points all the same.)"""
    design, folded, doc = request.getfixturevalue(case)
    faces = _faces(doc)
    sides = [len(a) - 1 for a in folded.ruling_angles]
    assert len(faces) == sum(sides)  # one per sector between the sheet's corners
    rest = resting_placement(design, folded) if case == "holed" else None
    size = design.sheet.size
    worst = 0.0
    for s in faces:
        p = _grid(s)
        if rest is not None:
            p = (p - rest.translation) @ rest.rotation  # inverse of R p + t
        worst = max(worst, float(_cone_distances(folded, p).max()))
    assert worst <= ON_CONE * size


@pytest.mark.parametrize("case", ["shell", "holed", "paper"])
def test_faces_areas_add_up_to_the_sheets(case, request):
    """Integrated from the file's control nets (Gauss-Legendre on each knot
    span): the folded sheet keeps the flat area, less the relief hole."""
    design, folded, doc = request.getfixturevalue(case)
    gu, wu = np.polynomial.legendre.leggauss(8)
    total = 0.0
    for s in _faces(doc):
        n = s.ToNurbsSurface()
        assert (n.OrderU, n.OrderV) == (4, 2) and not n.IsRational
        knots = np.array([n.KnotsU[i] for i in range(len(n.KnotsU))])
        knots = np.concatenate([knots[:1], knots, knots[-1:]])
        count = n.Points.CountU
        net = np.array(
            [[[(q := n.Points[i, j]).X, q.Y, q.Z] for j in range(2)] for i in range(count)]
        )
        inner, outer = BSpline(knots, net[:, 0], 3), BSpline(knots, net[:, 1], 3)
        d_in, d_out = inner.derivative(), outer.derivative()
        spans = np.unique(knots)
        for a, b in zip(spans[:-1], spans[1:], strict=True):
            u = 0.5 * (a + b) + 0.5 * (b - a) * gu
            for v, wv in zip(0.5 + 0.5 * gu, 0.5 * wu, strict=True):
                su = (1 - v) * d_in(u) + v * d_out(u)
                sv = outer(u) - inner(u)
                total += float(
                    np.sum(0.5 * (b - a) * wu * wv * np.linalg.norm(np.cross(su, sv), axis=1))
                )
    hole = relief_hole_diameter(design, folded)
    assert total == pytest.approx(design.sheet.area - math.pi * hole**2 / 4.0, rel=1e-6)


@pytest.mark.parametrize("case", ["shell", "holed"])
def test_each_face_has_a_render_mesh_on_the_cone_facing_the_top(case, request):
    design, folded, doc = request.getfixturevalue(case)
    rest = resting_placement(design, folded) if case == "holed" else None
    for o in _on(doc, "Folded::Sheet"):
        face = o.Geometry.Faces[0]
        mesh = face.GetMesh(rhino3dm.MeshType.Render)
        assert mesh is not None and len(mesh.Faces) > 0
        v = np.array([[(q := mesh.Vertices[i]).X, q.Y, q.Z] for i in range(len(mesh.Vertices))])
        s = o.Geometry.Surfaces[0]
        u, w = s.Domain(0), s.Domain(1)
        um, wm = 0.5 * (u.T0 + u.T1), 0.5 * (w.T0 + w.T1)
        mid, nrm = s.PointAt(um, wm), s.NormalAt(um, wm)
        p, n = np.array([[mid.X, mid.Y, mid.Z]]), np.array([nrm.X, nrm.Y, nrm.Z])
        scale = float(np.abs(v).max())  # the mesh's vertices are float32 in the file
        if rest is not None:
            v = (v - rest.translation) @ rest.rotation
            p, n = (p - rest.translation) @ rest.rotation, n @ rest.rotation
        _, off = folded.unfold(v)
        assert off.max() <= 8 * FLOAT32 * scale
        flat, _ = folded.unfold(p)
        assert float(n @ folded.normals(flat)[0]) > 0.999  # the face's normal is the top side's


def test_creases_and_apex_are_the_folds(shell):
    design, folded, doc = shell
    (apex,) = [o.Geometry.Location for o in _on(doc, "Folded::Apex")]
    assert np.allclose([apex.X, apex.Y, apex.Z], folded.apex, rtol=0, atol=1e-12 * 40)
    lines = _on(doc, "Folded::Crease UP") + _on(doc, "Folded::Crease DOWN")
    assert len(lines) == 2
    for o in lines:
        half = next(h for h in folded.crease if h.name == o.Attributes.GetUserString("name"))
        assert o.Attributes.GetUserString("bend") == half.bend
        layer = {lay.Index: lay.FullPath for lay in doc.Layers}[o.Attributes.LayerIndex]
        assert layer == f"Folded::Crease {half.bend}"
        assert float(o.Attributes.GetUserString("fold_angle_deg")) == pytest.approx(
            half.fold_angle_deg, abs=1e-6
        )
        end = o.Geometry.PointAtEnd
        want = folded.map_points(half.end_flat[None, :])[0]
        assert np.allclose([end.X, end.Y, end.Z], want, rtol=0, atol=1e-9 * design.sheet.size)


def test_the_resting_form_stands_on_the_ground(holed):
    design, folded, doc = holed
    z = np.concatenate([_grid(s)[:, 2] for s in _faces(doc)])
    size = design.sheet.size
    assert z.min() >= -ON_CONE * size
    contacts = [o.Geometry.Location for o in _on(doc, "Folded::Ground contacts")]
    assert len(contacts) >= 3 and all(abs(c.Z) <= 1e-9 * size for c in contacts)


def test_design_parameters_are_document_user_strings(holed):
    design, folded, doc = holed
    s = doc.Strings
    assert float(s["frame.alpha"]) == design.frame.alpha
    assert float(s["frame.h_c"]) == design.frame.h_c
    assert float(s["material.thickness"]) == design.material.thickness
    assert s["units"] == "mm"
    assert float(s["rhino.fit_deviation"]) <= float(s["rhino.fit_tolerance"])
    for half in folded.crease:
        assert float(s[f"crease.{half.name}.fold_angle_deg"]) == pytest.approx(
            half.fold_angle_deg, abs=1e-6
        )
