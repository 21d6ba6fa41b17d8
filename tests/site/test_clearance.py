"""The clearance's maths: the smallest pair, what touches, the refusal."""

from __future__ import annotations

import numpy as np
import pytest

from onefold_cad.errors import InvalidParameterError
from onefold_cad.site.clearance import (
    TOUCH_TOLERANCE,
    PairDistance,
    clearance,
    convex_overlap,
    nearest_neighbours,
)


def pair(a: str, b: str, d: float, overlap: float = 0.0) -> PairDistance:
    """A pair at distance ``d`` whose footprints share ``overlap``."""
    return PairDistance(a, b, d, np.zeros(3), np.array([d, 0.0, 0.0]), overlap, 1000.0)


def test_the_smallest_pair_and_each_sheet_s_nearest_neighbour():
    c = clearance([pair("a", "b", 50.0), pair("a", "c", 10.0), pair("b", "c", 30.0)], 0.1)
    assert c.smallest is not None and (c.smallest.a, c.smallest.b) == ("a", "c")
    near = nearest_neighbours(c, ["a", "b", "c"])
    assert [(p.a, p.b) for p in near] == [("a", "c"), ("b", "c")]
    assert not c.touching
    c.check("mm")  # nothing touches: no error


def test_touching_is_within_the_tolerance_of_the_size():
    limit = TOUCH_TOLERANCE * 1000.0
    assert pair("a", "b", limit).touching and not pair("a", "b", 2 * limit).touching
    assert not pair("a", "b", 1.0, overlap=5.0).touching  # one may stand under the other's arch


def test_an_overlap_is_refused_naming_both_sheets_and_the_footprints_overlap():
    c = clearance([pair("a", "b", 50.0), pair("east", "west", 0.0, overlap=1234.5)], 0.1)
    with pytest.raises(InvalidParameterError) as err:
        c.check("mm")
    text = str(err.value)
    assert "'east' and 'west' touch or overlap" in text and "\n" not in text
    assert "footprints overlap by 1234.5 mm^2" in text
    c.check("mm", allow_touching=True)  # allowed: no error


def test_two_squares_overlap_by_their_shared_rectangle():
    sq = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])
    assert convex_overlap(sq, sq + [1.0, 0.5]) == pytest.approx(1.0 * 1.5, rel=1e-12)
    assert convex_overlap(sq, sq + [3.0, 0.0]) == 0.0
    # a square turned 45 deg about the other's centre: the regular octagon of side 2 (sqrt 2 - 1)
    t = np.radians(45.0)
    rot = (sq - 1.0) @ np.array([[np.cos(t), np.sin(t)], [-np.sin(t), np.cos(t)]]) + 1.0
    assert convex_overlap(sq, rot) == pytest.approx(8.0 * (np.sqrt(2.0) - 1.0), rel=1e-12)


def test_a_single_sheet_has_no_pair():
    c = clearance([], 0.0)
    assert c.smallest is None and nearest_neighbours(c, ["a"]) == []
