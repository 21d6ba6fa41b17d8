"""CalculiX's own formed state handed to its release (benchmarks/ccx_handover.py):
the Gauss levels of a composite section, the flat points of the 3-point
rule, the levels turned to the designed top normal, a field the handover
must carry exactly (linear in the plane and through the thickness), the
through-thickness stress taken out as a pressure, and the stresses scaled
back to the yield surface. No ccx needed; expected values by hand."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

import ccx_handover as ch  # noqa: E402
from ccx_deck import mises  # noqa: E402
from ccx_release import face_frames  # noqa: E402

T, LAYERS = 0.004, 4


def test_the_levels_are_two_gauss_points_of_each_layer_bottom_up():
    z = ch.level_heights(T, LAYERS)
    d = T / LAYERS
    g = d / (2 * math.sqrt(3))
    want = [-T / 2 + d / 2 - g, -T / 2 + d / 2 + g, -d / 2 - g, -d / 2 + g,
            d / 2 - g, d / 2 + g, T / 2 - d / 2 - g, T / 2 - d / 2 + g]  # fmt: skip
    assert z == pytest.approx(want, abs=1e-15)


def test_the_rule_s_points_lie_where_their_natural_coordinates_say():
    corners = np.array([[[0.0, 0.0], [3.0, 0.0], [0.0, 6.0]]])
    got = ch.point_flat(corners, np.array([(1 / 6, 1 / 6), (2 / 3, 1 / 6), (1 / 3, 1 / 3)]))
    assert got[0] == pytest.approx(np.array([[0.5, 1.0], [2.0, 1.0], [1.0, 2.0]]), abs=1e-15)


def _grid_forming(field, flip: np.ndarray | None = None) -> ch.Forming:
    """A flat 1 x 1 m sheet on both sides of the crease (y in -1..1), in S6
    triangles, 'formed' flat (normal +z), carrying ``field(x, y, z)`` (a
    (..., 6) stress) at its Gauss points; ``flip``: elements whose corners
    run clockwise (normal -z), their levels then stored top down."""
    xs = np.linspace(-1.0, 1.0, 9)
    gx, gy = np.meshgrid(xs, xs)
    pts = np.column_stack([gx.ravel(), gy.ravel()])
    # nodes moved a little off the grid, as a mesher's are (a regular grid's
    # cocircular points make Qhull's Delaunay slow), the crease kept straight
    inner = (np.abs(pts) < 1.0).all(axis=1) & (np.abs(pts[:, 1]) > 0)
    pts[inner] += np.random.default_rng(5).uniform(-0.02, 0.02, (int(inner.sum()), 2))
    k = len(xs)
    tris = []
    for i in range(k - 1):
        for j in range(k - 1):
            a, b, c, d = i * k + j, i * k + j + 1, (i + 1) * k + j, (i + 1) * k + j + 1
            tris += [[a, b, d], [a, d, c]]
    tri = np.array(tris)
    if flip is not None:
        tri[flip] = tri[flip][:, [0, 2, 1]]
    tri6 = np.concatenate([tri, tri], axis=1)  # the midpoints are not read
    natural = np.array([(1 / 6, 1 / 6), (2 / 3, 1 / 6), (1 / 6, 2 / 3)])
    at = ch.point_flat(pts[tri], natural)  # (m, 3, 2)
    z = ch.level_heights(T, LAYERS)
    normal_up = (
        np.ones(len(tri))
        if flip is None
        else np.where(np.isin(np.arange(len(tri)), flip), -1.0, 1.0)
    )
    zz = z[None, :, None] * normal_up[:, None, None]  # a level's height along +z
    stress = field(at[:, None, :, 0], at[:, None, :, 1], zz)
    return ch.Forming(
        flat=pts, tri6=tri6, formed=np.column_stack([pts, np.zeros(len(pts))]), layers=LAYERS,
        thickness=T, stress=stress, peeq=np.zeros(stress.shape[:-1]), perfectly_plastic=True,
        yield_stress=2e8,
    )  # fmt: skip


def _linear(x, y, z):
    x, y, z = np.broadcast_arrays(x, y, z)
    s = np.stack([1e6 * x + 4e10 * z, 2e6 * y - 3e10 * z, 0 * x, 5e5 * (x + y), 0 * x, 0 * x])
    return np.moveaxis(s, 0, -1)


@pytest.mark.parametrize("flipped", [False, True])
def test_a_field_linear_in_the_plane_and_the_thickness_is_carried_exactly(flipped):
    rng = np.random.default_rng(3)
    m = 2 * 8 * 8
    flip = rng.choice(m, m // 3, replace=False) if flipped else None
    forming = _grid_forming(_linear, flip)
    up = np.tile([0.0, 0.0, 1.0], (m, 1))
    dst = rng.uniform(-0.9, 0.9, (200, 2))
    dst[np.abs(dst[:, 1]) < 0.05, 1] += 0.1  # off the crease
    h = rng.uniform(-0.4 * T, 0.4 * T, 200)  # inside the outer levels
    got, _ = ch.handed_over(forming, up, dst, h)
    want = _linear(dst[:, 0], dst[:, 1], h)
    assert got == pytest.approx(want, rel=1e-9, abs=1e-3)


def test_the_sides_of_the_crease_are_never_mixed():
    # a field that jumps across y = 0: each side's points get their own side's
    def jump(x, y, z):
        x, y, z = np.broadcast_arrays(x, y, z)
        return _linear(x, y, z) + np.where(y > 0, 1e8, -1e8)[..., None] * [1, 0, 0, 0, 0, 0]

    forming = _grid_forming(jump)
    up = np.tile([0.0, 0.0, 1.0], (len(forming.tri6), 1))
    dst = np.array([[0.3, 0.01], [0.3, -0.01], [-0.7, 0.02], [-0.7, -0.02]])
    got, _ = ch.handed_over(forming, up, dst, np.zeros(4))
    # these points lie outside their side's Gauss points (the nearest is taken):
    # the linear part moves by less than 1e5 Pa there, the jump is 2e8
    side = got[:, 0] - _linear(dst[:, 0], dst[:, 1], np.zeros(4))[:, 0]
    assert side == pytest.approx([1e8, -1e8, 1e8, -1e8], abs=1e5)


def test_the_normal_stress_is_taken_out_as_a_pressure():
    frames = face_frames(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]]), np.array([[0, 1, 2]]))
    sig = np.array([[[120e6, -40e6, 900e6, 30e6, 5e6, -5e6]]])  # s33 large: a pressure
    plane, normal = ch.plane_stress(sig, frames)
    assert normal[0, 0] == pytest.approx(900e6)
    assert plane[0, 0] == pytest.approx([120e6 - 900e6, -40e6 - 900e6, 30e6])
    # the deviator in the plane is the one ccx had (transverse shears dropped)
    in_plane = np.array([[[120e6, -40e6, 900e6, 30e6, 0.0, 0.0]]])
    flat = np.array([[[plane[0, 0, 0], plane[0, 0, 1], 0.0, plane[0, 0, 2], 0.0, 0.0]]])
    assert mises(flat) == pytest.approx(mises(in_plane), rel=1e-12)


def test_points_past_yield_are_scaled_onto_it_and_counted():
    s = np.array([[300e6, 0, 0, 0, 0, 0], [100e6, 0, 0, 0, 0, 0.0]])
    out, n = ch.within_yield(s, 200e6)
    assert n == 1 and out[0, 0] == pytest.approx(200e6) and out[1, 0] == 100e6
