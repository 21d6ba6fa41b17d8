"""The loads picture's colour scale: a percentile by area, so a few small
faces at a stress singularity do not set it."""

from __future__ import annotations

import numpy as np
import pytest

from onefold_cad.export.loads.picture import area_percentile


def test_many_small_faces_do_not_set_the_scale():
    # 98 large faces at 1..98 and 1000 tiny ones at 5000 (a fine mesh at H)
    values = np.concatenate([np.arange(1.0, 99.0), np.full(1000, 5000.0)])
    areas = np.concatenate([np.ones(98), np.full(1000, 1e-4)])
    assert np.percentile(values, 98.0) == 5000.0  # by count: the singular faces
    # 98 % of the area (total 98.1) is 96.14: covered by the faces up to 97
    assert area_percentile(values, areas, 98.0) == 97.0


@pytest.mark.parametrize("q", [0.0, 10.0, 50.0, 90.0, 100.0])
def test_equal_areas_give_the_plain_percentile(q):
    values = np.random.default_rng(1).permutation(np.arange(1.0, 101.0))
    got = area_percentile(values, np.ones(100), q)
    assert got == max(1.0, np.ceil(q))  # the smallest value covering q % of 100
