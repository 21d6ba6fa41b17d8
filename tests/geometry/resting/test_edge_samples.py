"""The sheet edges' samples a body is laid out on (once per sheet)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onefold_cad.geometry.resting.edge_samples import edge_samples
from onefold_cad.geometry.sheet import Sheet

STEP = math.pi / 180


@pytest.mark.parametrize(
    "sheet",
    [
        Sheet.rectangle(3048.0, 7315.2, 0.5),
        Sheet.rectangle(100.0, 40.0, 0.1),
        Sheet.polygon([(5.0, 0.0), (1.0, 0.01), (-3.0, 0.0), (0.0, -2.0)]),
    ],
)
def test_every_edge_is_sampled_along_its_length_and_its_flat_angle(sheet: Sheet) -> None:
    edges = edge_samples(sheet, 1200, STEP)
    v = sheet.vertices
    assert len(edges) == len(v)
    total = 0
    for k, e in enumerate(edges):
        a, b = v[k], v[(k + 1) % len(v)]
        np.testing.assert_array_equal(e.a, a)
        np.testing.assert_array_equal(e.b, b)
        length = math.hypot(*(b - a))
        # the samples' points on the edge, from its flat angles: each ray at
        # theta (on the edge's own side) meets the edge's line
        side = -1.0 if a[1] + b[1] < 0.0 else 1.0
        d = np.column_stack([np.cos(e.theta), side * np.sin(e.theta)])
        e_dir = (b - a) / length
        # r with a + t e = r d: r = (a x e) / (d x e)
        r = (a[0] * e_dir[1] - a[1] * e_dir[0]) / (d[:, 0] * e_dir[1] - d[:, 1] * e_dir[0])
        t = ((r[:, None] * d - a) @ e_dir) / length
        assert t[0] == pytest.approx(0.0, abs=1e-9) and t[-1] == pytest.approx(1.0, abs=1e-9)
        assert np.all(np.diff(t) > 0.0)  # in order, no two alike
        n = max(16, math.ceil(1200 * length / sheet.perimeter))
        assert len(t) >= n
        assert e.step <= length / (n - 1) * (1 + 1e-12)
        assert np.max(np.diff(t)) * length == pytest.approx(e.step, rel=1e-9)
        # and no step in flat angle wider than asked
        assert np.max(np.abs(np.diff(e.theta))) <= STEP * (1 + 1e-9)
        total += len(t)
    assert total >= 1200


def test_the_samples_are_made_once_per_sheet_and_read_only() -> None:
    sheet = Sheet.rectangle(300.0, 700.0, 0.4)
    first = edge_samples(sheet, 1200, STEP)
    assert edge_samples(sheet, 1200, STEP) is first
    assert edge_samples(sheet, 600, STEP) is not first
    with pytest.raises(ValueError):
        first[0].theta[0] = 1.0
