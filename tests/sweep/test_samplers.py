"""The design points: grid counts and order, Latin hypercube and Sobol' samples
in their ranges and stratified, lists crossed with the samples."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from onefold_cad.sweep.samplers import count_of, grid_points, sample_points, unit_samples
from onefold_cad.sweep.spec import parse_vary


@given(st.lists(st.integers(1, 4), min_size=1, max_size=4))
def test_a_grid_is_every_combination_the_first_vary_slowest(counts):
    names = ["alpha", "beta", "hc", "radius"][: len(counts)]
    specs = [
        parse_vary(f"{n}={','.join(str(10 + i) for i in range(c))}")
        for n, c in zip(names, counts, strict=True)
    ]
    pts = grid_points(specs)
    assert len(pts) == int(np.prod(counts)) == count_of(specs, "grid", None)
    assert len({tuple(p.values()) for p in pts}) == len(pts)
    assert [list(p) for p in pts[:1]] == [names]
    if len(pts) > 1 and counts[-1] > 1:  # the last vary changes first
        assert pts[0][names[-1]] != pts[1][names[-1]]


@pytest.mark.parametrize("method", ["lhs", "sobol"])
@pytest.mark.parametrize("n", [8, 32])
def test_samples_lie_in_their_ranges_one_in_each_slice(method, n):
    specs = [parse_vary("alpha=10:80"), parse_vary("beta=5:85"), parse_vary("hc=-40:40")]
    pts = sample_points(specs, method, n, seed=3)
    assert len(pts) == n
    for s in specs:
        v = np.array([p[s.dest] for p in pts])
        assert np.all((v >= s.low) & (v <= s.high))
        # stratified: each of the n equal slices of the range holds one sample
        # (a Latin hypercube by construction, a Sobol' net of 2^m points too)
        slices = np.floor((v - s.low) / (s.high - s.low) * n).astype(int)
        assert sorted(slices) == list(range(n))


def test_samples_repeat_with_their_seed_and_change_with_another():
    a = unit_samples("lhs", 16, 3, seed=7)
    assert np.array_equal(a, unit_samples("lhs", 16, 3, seed=7))
    assert not np.array_equal(a, unit_samples("lhs", 16, 3, seed=8))
    assert np.array_equal(unit_samples("sobol", 8, 2, 1), unit_samples("sobol", 8, 2, 1))


def test_lists_are_crossed_with_the_samples_and_whole_numbers_rounded():
    specs = [
        parse_vary("alpha=10:80"),
        parse_vary("model=exact,paper"),
        parse_vary("divisions=10:90"),
    ]
    pts = sample_points(specs, "lhs", 5, seed=0)
    assert len(pts) == 10 == count_of(specs, "lhs", 5)
    assert [list(p) for p in pts[:1]] == [["alpha", "model", "divisions"]]
    assert {p["model"] for p in pts} == {"exact", "paper"}
    assert all(isinstance(p["divisions"], int) for p in pts)
