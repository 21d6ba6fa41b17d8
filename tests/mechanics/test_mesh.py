"""The triangulation (mechanics/mesh.py): conformity, quality, grading, topology."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onefold_cad.errors import InvalidParameterError
from onefold_cad.mechanics import BOUNDARY, CREASE, INTERIOR, build_mesh, mesh_sheet

OUTLINE = [[-3.0, -1.5], [3.0, -1.5], [3.0, 1.5], [-3.0, 1.5]]
HOLE = 0.1
CREASES = [[(HOLE, 0.0), (3.0, 0.0)], [(-HOLE, 0.0), (-3.0, 0.0)]]


@pytest.fixture(scope="module")
def sheet():
    return mesh_sheet(OUTLINE, size=(0.02, 0.1, 0.3), hole_radius=HOLE, creases=CREASES)


def _check_topology(mesh) -> None:
    p = mesh.nodes[mesh.triangles]
    area2 = np.cross(
        np.column_stack([p[:, 1] - p[:, 0], np.zeros(len(p))]),
        np.column_stack([p[:, 2] - p[:, 0], np.zeros(len(p))]),
    )[:, 2]
    assert np.all(area2 > 0), "triangles counter-clockwise"
    for e in range(0, mesh.n_edges, max(1, mesh.n_edges // 200)):
        a, b = mesh.edges[e]
        t0, t1 = mesh.edge_faces[e]
        tri = list(mesh.triangles[t0])
        i = tri.index(a)
        assert tri[(i + 1) % 3] == b, "an edge runs a -> b in T0"
        assert mesh.edge_opposite[e, 0] == tri[(i + 2) % 3]
        if t1 >= 0:
            tri1 = list(mesh.triangles[t1])
            j = tri1.index(b)
            assert tri1[(j + 1) % 3] == a, "and b -> a in T1"
        else:
            assert mesh.edge_kind[e] == BOUNDARY
    for f in range(0, mesh.n_faces, max(1, mesh.n_faces // 200)):
        for i in range(3):
            e = mesh.face_edges[f, i]
            assert set(mesh.edges[e]) == {
                mesh.triangles[f, (i + 1) % 3],
                mesh.triangles[f, (i + 2) % 3],
            }
            assert mesh.edge_faces[e, mesh.face_edge_side[f, i]] == f


def test_topology_and_quality(sheet):
    _check_topology(sheet)
    assert sheet.min_angle_deg() >= 27.5
    # Euler: a sheet with one hole has V - E + F = 0.
    assert sheet.n_nodes - sheet.n_edges + sheet.n_faces == 0
    assert sheet.n_sides == 2


def test_area_and_hole(sheet):
    polygon_area = 6.0 * 3.0 - 0.5 * len_hole_ring(sheet) * HOLE**2 * math.sin(
        2 * math.pi / len_hole_ring(sheet)
    )
    assert math.isclose(sheet.face_areas.sum(), polygon_area, rel_tol=1e-12)
    r = np.hypot(*sheet.nodes.T)
    assert r.min() >= HOLE * math.cos(math.pi / len_hole_ring(sheet)) * (1 - 1e-12), (
        "on the hole polygon"
    )
    centroids = sheet.nodes[sheet.triangles].mean(axis=1)
    assert np.hypot(*centroids.T).min() > HOLE * math.cos(math.pi / len_hole_ring(sheet))


def len_hole_ring(mesh) -> int:
    r = np.hypot(*mesh.nodes.T)
    return int(np.sum(np.abs(r - HOLE) < 1e-9))


def test_creases_are_edges_and_split_the_sheet(sheet):
    ce = sheet.crease_edges
    assert np.all(sheet.edge_kind[ce] == CREASE)
    ends = sheet.nodes[sheet.edges[ce]]
    assert np.all(np.abs(ends[:, :, 1]) < 1e-12), "crease edges lie on the fold line"
    length = np.sum(np.abs(ends[:, 1, 0] - ends[:, 0, 0]))
    assert math.isclose(length, 2 * (3.0 - HOLE), rel_tol=1e-12), "they cover it"
    # No triangle crosses the fold line: every triangle lies on one side of y = 0.
    y = sheet.nodes[sheet.triangles][:, :, 1]
    assert np.all((y.max(axis=1) <= 1e-12) | (y.min(axis=1) >= -1e-12))
    centroid_y = y.mean(axis=1)
    side_of_upper = sheet.face_side[centroid_y > 0]
    assert len(np.unique(side_of_upper)) == 1
    assert not np.isin(sheet.face_side[centroid_y < 0], side_of_upper).any()
    # Directors: a second angle per crease edge, used by its T1.
    fd = sheet.face_directors
    assert fd.max() == sheet.n_directors - 1
    on_t1 = (sheet.face_edge_side == 1) & (sheet.edge_kind[sheet.face_edges] == CREASE)
    assert np.all(fd[on_t1] >= sheet.n_edges) and np.all(fd[~on_t1] < sheet.n_edges)


def test_grading(sheet):
    lengths = sheet.edge_lengths
    mid = sheet.nodes[sheet.edges].mean(axis=1)
    r = np.hypot(*mid.T)
    near = lengths[r < 0.15]
    far = lengths[r > 2.5]
    assert 0.5 * 0.02 < np.median(near) < 1.5 * 0.02
    assert 0.5 * 0.3 < np.median(far) < 1.2 * 0.3
    target = np.clip(0.1 * r, 0.02, 0.3)
    assert np.percentile(lengths / target, 95) < 1.6


def test_rectangle_with_and_without_crease():
    plain = mesh_sheet([[0, 0], [1, 0], [1, 0.2], [0, 0.2]], size=(0.05, 0, 0.05))
    _check_topology(plain)
    assert len(plain.crease_edges) == 0 and plain.n_sides == 1
    assert plain.n_nodes - plain.n_edges + plain.n_faces == 1
    assert math.isclose(plain.face_areas.sum(), 0.2, rel_tol=1e-12)
    creased = mesh_sheet(
        [[0, 0], [1, 0], [1, 0.2], [0, 0.2]], size=(0.05, 0, 0.05), creases=[[(0.4, 0), (0.4, 0.2)]]
    )
    _check_topology(creased)
    assert creased.n_sides == 2
    xs = creased.nodes[creased.edges[creased.crease_edges]][:, :, 0]
    assert np.allclose(xs, 0.4, atol=1e-12)
    assert np.all(np.isin(creased.edge_kind, [INTERIOR, BOUNDARY, CREASE]))


def test_build_mesh_reorients_and_rejects():
    nodes = [[0, 0], [1, 0], [1, 1], [0, 1]]
    mesh = build_mesh(nodes, [[0, 2, 1], [0, 2, 3]])
    _check_topology(mesh)
    with pytest.raises(InvalidParameterError):
        build_mesh(nodes, [[0, 1, 1]])
    with pytest.raises(InvalidParameterError):
        build_mesh(nodes, [[0, 1, 2], [0, 2, 3]], crease_pairs=[[0, 1]])  # a boundary edge
    with pytest.raises(InvalidParameterError):
        mesh_sheet([[0, 0], [1, 0], [1, 1]], size=(0.5, 0, 0.1))


def test_an_outline_triangle_cannot_mesh_names_the_mesh():
    """Triangle's own refusal (a hole of 1e-320 m, which its arithmetic cannot
    place) is a named error, not the library's RuntimeError."""
    with pytest.raises(InvalidParameterError) as info:
        mesh_sheet(OUTLINE, size=(0.02, 0.1, 0.3), hole_radius=1e-320, creases=CREASES)
    assert info.value.parameter == "mesh"
