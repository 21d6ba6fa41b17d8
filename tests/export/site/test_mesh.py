"""The parts' meshes for the site: every node on the B-rep, the area near it."""

from __future__ import annotations

import math

import build123d as bd
import numpy as np
import pytest

from onefold_cad.export.site.mesh import mesh_area, mesh_shape


def test_a_box_s_mesh_has_its_exact_area_and_outward_triangles():
    box = bd.Box(10.0, 20.0, 30.0)
    v, t = mesh_shape(box, 0.01, 0.1)
    assert mesh_area(v, t) == pytest.approx(2 * (10 * 20 + 20 * 30 + 30 * 10), rel=1e-12)
    normals = np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]])
    centres = v[t].mean(axis=1)
    assert (np.einsum("ij,ij->i", normals, centres) > 0).all()  # box centred at the origin


def test_a_cylinder_s_nodes_lie_on_it_and_its_area_is_within_the_chords():
    r, h, d = 5.0, 10.0, 0.01
    cyl = bd.Cylinder(r, h)
    v, t = mesh_shape(cyl, d, 0.05)
    side = np.abs(np.hypot(v[:, 0], v[:, 1]) - r) < 1e-9
    assert side.any() and (np.hypot(v[:, 0], v[:, 1]) <= r + 1e-9).all()
    exact = 2 * math.pi * r * h + 2 * math.pi * r * r
    # chords of a circle cut within deflection d: the area falls short by at most ~ 2 d / r
    assert 0.0 < exact - mesh_area(v, t) <= exact * 2 * d / r


def test_a_moved_part_s_mesh_is_moved():
    box = bd.Box(1.0, 1.0, 1.0)
    moved = box.moved(bd.Location((100.0, 0.0, 0.0)))
    v, _ = mesh_shape(moved, 0.01, 0.1)
    assert v[:, 0].min() == pytest.approx(99.5) and v[:, 0].max() == pytest.approx(100.5)
