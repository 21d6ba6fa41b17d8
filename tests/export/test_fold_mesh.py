"""The FOLD file's mesh: bounds on its angles and edges, every face in one planar
wedge of the fan, the folded vertices the fan's own fold of the flat ones; on
every template and on property-drawn designs."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings

from onefold_cad import Design, FrameCurve, NoSolutionError, Sheet, fold_design
from onefold_cad.export.fold_file import fold_data, fold_fan
from onefold_cad.export.fold_mesh import (
    MAX_STEINER,
    MIN_EDGE,
    MIN_FACE_ANGLE_DEG,
    QUALITY_CAP_DEG,
    face_angles_deg,
    fold_mesh,
    mesh_limits,
)
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.templates import load_template
from tests.export.fold_designs import fold_designs
from tests.shipped import DESIGN_TEMPLATES

TEMPLATES = DESIGN_TEMPLATES


def test_face_angles_of_a_3_4_5_triangle_worked_by_hand():
    """Right angle at the origin, atan(4/3) and atan(3/4) at the others, in
    2D and the same triangle standing in 3D."""
    pts = np.array([[0.0, 0.0], [3.0, 0.0], [0.0, 4.0]])
    want = [90.0, math.degrees(math.atan2(4, 3)), math.degrees(math.atan2(3, 4))]
    np.testing.assert_allclose(face_angles_deg(pts, np.array([[0, 1, 2]]))[0], want)
    pts3 = np.array([[1.0, 1.0, 1.0], [1.0, 4.0, 1.0], [1.0, 1.0, 5.0]])
    np.testing.assert_allclose(face_angles_deg(pts3, np.array([[0, 1, 2]]))[0], want)


def _wedges(mesh) -> tuple[np.ndarray, np.ndarray]:
    """Per face, the wedge (index of its first ray) its flat centroid lies in,
    and per vertex its flat polar angle in [0, 2 pi)."""
    phi = np.arctan2(mesh.flat[:, 1], mesh.flat[:, 0]) % (2.0 * math.pi)
    c = mesh.flat[mesh.faces].mean(axis=1)
    centre = np.arctan2(c[:, 1], c[:, 0]) % (2.0 * math.pi)
    wedge = np.searchsorted(mesh.ray_theta, centre, side="right") - 1
    return wedge, phi


def _check_mesh(design: Design) -> tuple[float, float]:
    """The mesh of ``design``'s FOLD file: faces inside one wedge each (their
    vertices' flat angles between the wedge's rays), each face in its wedge's
    plane through the apex when folded, every vertex folded by the fan's map
    (distance from the apex = flat distance from H, within the wedge), the
    ray edges on their rays; returns the smallest face angle (deg) and the
    shortest edge (fraction of the sheet's size)."""
    folded = fold_design(design)
    fan = fold_fan(design, folded)
    radius = relief_hole_diameter(design, folded) / 2.0
    mesh = fold_mesh(fan, radius)
    size = design.sheet.size
    wedge, phi = _wedges(mesh)
    n = len(mesh.ray_theta)
    lo = mesh.ray_theta[wedge]
    hi = np.append(mesh.ray_theta, 2.0 * math.pi)[wedge + 1]
    at_h = np.linalg.norm(mesh.flat, axis=1) <= 1e-12 * size
    for k in range(3):
        v = mesh.faces[:, k]
        a = np.where((phi[v] < lo - 1e-9) & (wedge == n - 1), phi[v] + 2 * math.pi, phi[v])
        a = np.where((hi >= 2 * math.pi - 1e-9) & (phi[v] < 1e-9), 2 * math.pi, a)
        inside = (a >= lo - 1e-9) & (a <= hi + 1e-9)
        assert np.all(inside | at_h[v]), "a face crosses a division ray"
    # folded: each face in the plane of its wedge (apex, its two rays' folded directions)
    ray_dir = np.array([[math.cos(t), math.sin(t)] for t in mesh.ray_theta])
    d3 = fan.map_points(ray_dir) - fan.apex
    normal = np.cross(d3, np.roll(d3, -1, axis=0))
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    off = np.einsum("fkj,fj->fk", mesh.folded[mesh.faces] - fan.apex, normal[wedge])
    assert np.abs(off).max() <= 1e-12 * size * 64
    r2 = np.linalg.norm(mesh.flat, axis=1)
    r3 = np.linalg.norm(mesh.folded - fan.apex, axis=1)
    np.testing.assert_allclose(r3, r2, rtol=0, atol=1e-12 * size * 16)
    # ray edges: both ends on their ray
    on = mesh.edge_ray >= 0
    for end in (0, 1):
        p = mesh.flat[mesh.edges[on, end]]
        d = ray_dir[mesh.edge_ray[on]]
        assert np.abs(p[:, 0] * d[:, 1] - p[:, 1] * d[:, 0]).max() <= 1e-12 * size * 16
    angle = float(face_angles_deg(mesh.flat, mesh.faces).min())
    e = mesh.edges
    edge = float(np.linalg.norm(mesh.flat[e[:, 1]] - mesh.flat[e[:, 0]], axis=1).min()) / size
    return angle, edge


@pytest.mark.parametrize("name", TEMPLATES)
def test_every_template_meshes_within_the_bounds(name):
    """Every shipped template: no face angle under MIN_FACE_ANGLE_DEG, no edge
    under MIN_EDGE of the sheet's size, and the file says so."""
    design = load_template(name)
    angle, edge = _check_mesh(design)
    assert angle >= MIN_FACE_ANGLE_DEG
    assert edge >= MIN_EDGE
    doc = fold_data(design, fold_design(design))
    assert doc["onefold:mesh"]["within_bounds"] is True
    assert doc["onefold:mesh"]["min_face_angle_deg"] == pytest.approx(angle, rel=1e-12)


def test_a_ruling_through_a_sheet_corner_cuts_no_sliver():
    """star-polygon: a division ray passes within 0.5 mm of a star corner,
    which the old fan (a ray through every corner) cut into 0.059 deg slivers;
    the mesh keeps the corner as an outline vertex and its smallest angle is
    the fan's own smallest wedge angle (the graded fan's beside the crease,
    just above the bound), to Triangle's 10 %."""
    design = load_template("star-polygon")
    fan = fold_fan(design, fold_design(design))
    gamma = math.degrees(float(np.diff(fold_mesh(fan).ray_theta).min()))
    angle, _ = _check_mesh(design)
    assert angle >= MIN_FACE_ANGLE_DEG and angle >= 0.9 * min(gamma, 20.0)


def test_limits_of_a_square_about_its_centre_worked_by_hand():
    """A 200 x 200 square about H, paper model with 4 divisions per side (8
    rays): the design's smallest angle is the smallest of the wedges' apex
    angles, the square's corners (90 deg) and the angles at which the rays
    meet the sides (a ray to (x, 100) meets the side at atan2(100, |x|)); its
    shortest edge is the shortest piece of the outline between ray ends and
    corners."""
    square = Sheet.polygon([(100.0, 100.0), (-100.0, 100.0), (-100.0, -100.0), (100.0, -100.0)])
    design = Design("sq", FrameCurve(40, 40, 0.0, 100.0, 4), square, "paper")
    fan = fold_fan(design, fold_design(design))
    mesh = fold_mesh(fan)
    assert len(mesh.ray_theta) == 8
    gamma = np.degrees(np.diff(np.append(mesh.ray_theta, 2 * math.pi)))
    ends = np.stack([np.cos(mesh.ray_theta), np.sin(mesh.ray_theta)], axis=1)
    ends *= 100.0 / np.abs(ends).max(axis=1, keepdims=True)  # on the square's sides
    meet = np.degrees(np.arctan2(100.0, np.abs(ends).min(axis=1)))
    angle, edge = mesh_limits(fan, 0.0)
    assert angle == pytest.approx(min(gamma.min(), meet.min(), 90.0), rel=1e-9)
    corners = np.array([[100.0, 100.0], [-100.0, 100.0], [-100.0, -100.0], [100.0, -100.0]])
    pts = np.vstack([ends, corners])
    phi = np.arctan2(pts[:, 1], pts[:, 0])
    ring = pts[np.argsort(phi)]
    pieces = np.linalg.norm(np.roll(ring, -1, axis=0) - ring, axis=1)
    assert edge == pytest.approx(pieces[pieces > 1e-9].min(), rel=1e-9)
    # and the mesh keeps them (to Triangle's 10 %), up to the quality asked for
    assert float(face_angles_deg(mesh.flat, mesh.faces).min()) >= 0.9 * min(angle, QUALITY_CAP_DEG)


@settings(max_examples=25, deadline=None)
@given(design=fold_designs())
def test_property_drawn_designs_mesh_within_the_bounds_their_geometry_allows(design: Design):
    """A drawn frame, division count, quadrilateral sheet and relief hole (a
    fraction of twice H's distance to the nearest edge): the mesh is planar
    and isometric wedge by wedge (:func:`_check_mesh`); its smallest angle is
    at least the bound or, where the design itself has a smaller one (a
    wedge's apex angle, a corner, a ray meeting the outline), that one, to
    Triangle's rounding; likewise its shortest edge."""
    try:
        folded = fold_design(design)
        fan = fold_fan(design, folded)
    except (NoSolutionError, ValueError):  # no fold, or no fan for the exact model: no file
        return
    angle, edge = _check_mesh(design)
    own_angle, own_edge = mesh_limits(fan, relief_hole_diameter(design, folded) / 2.0)
    assert angle >= min(MIN_FACE_ANGLE_DEG, own_angle) * (1.0 - 1e-9)
    assert edge >= min(MIN_EDGE, own_edge / design.sheet.size) * (1.0 - 1e-9)


def test_the_docs_table_of_the_templates_meshes_is_the_files():
    """docs/formats.md lists each template's smallest face angle and shortest
    edge: they are its FOLD file's ``onefold:mesh``, to the digits shown."""
    docs = (Path(__file__).parents[2] / "docs" / "formats.md").read_text(encoding="utf-8")
    rows = {}
    for line in docs.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 4 and cells[0] in TEMPLATES:
            rows[cells[0]] = (float(cells[1]), float(cells[2]))
    assert sorted(rows) == TEMPLATES
    for name, (angle, edge) in rows.items():
        design = load_template(name)
        mesh = fold_data(design, fold_design(design))["onefold:mesh"]
        assert mesh["min_face_angle_deg"] == pytest.approx(angle, abs=0.005)
        assert float(f"{mesh['min_edge_relative']:.1e}") == edge


def test_a_sliver_s_mesh_stops_at_the_point_budget():
    """A sheet 1.4e-6 wide and 125 long (a fuzzed sliver): a 1 deg face angle
    needs about length / width / tan(1 deg) = 5e9 triangles, which Triangle
    tried to make (4.9 GB after two minutes). It stops at MAX_STEINER added
    points, and the file says that the bounds are not kept."""
    sliver = Sheet.polygon([[99.375, 0.0], [0.0, 6.87e-7], [-25.67, 0.0], [0.0, -6.87e-7]])
    design = Design("sliver", FrameCurve(66, 49, 0.0, 0.0363, 90), sliver)
    fan = fold_fan(design, fold_design(design))
    mesh = fold_mesh(fan)
    given = len(fan.boundary_flat) + 1  # the outline's points and H
    assert given < len(mesh.flat) <= given + MAX_STEINER
    quality = fold_data(design, fold_design(design))["onefold:mesh"]
    assert quality["within_bounds"] is False
    assert quality["min_face_angle_deg"] < MIN_FACE_ANGLE_DEG
