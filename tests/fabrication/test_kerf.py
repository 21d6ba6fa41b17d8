"""The kerf offset against ezdxf's offset_vertices_2d (an independent implementation)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from ezdxf.math import offset_vertices_2d
from hypothesis import given, settings
from hypothesis import strategies as st

from onefold_cad.errors import InvalidParameterError
from onefold_cad.fabrication.kerf import offset_outline


def _ezdxf(outline: np.ndarray, distance: float) -> np.ndarray:
    return np.array([(p.x, p.y) for p in offset_vertices_2d(outline, -distance, True)])


def _star(radii: list[float]) -> np.ndarray:
    a = np.linspace(0.0, 2.0 * math.pi, len(radii), endpoint=False)
    return np.stack([np.cos(a), np.sin(a)], axis=-1) * np.asarray(radii)[:, None]


def test_a_square_grows_by_the_offset_at_every_edge() -> None:
    square = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])
    got = offset_outline(square, 0.25)
    assert np.allclose(got, [[-0.25, -0.25], [2.25, -0.25], [2.25, 2.25], [-0.25, 2.25]])


@settings(max_examples=200)
@given(
    st.lists(st.floats(0.2, 5.0), min_size=3, max_size=40),
    st.floats(1e-4, 0.05),
)
def test_star_polygons_match_ezdxf(radii: list[float], distance: float) -> None:
    outline = _star(radii)
    got = offset_outline(outline, distance)
    want = _ezdxf(outline, distance)
    assert got.shape == want.shape
    # the two mitre constructions round differently; both put each corner on
    # the two offset edges, so they agree to the rounding of the corner's lines,
    # which grows as the corner straightens (1 / sin of its turn)
    a = outline - np.roll(outline, 1, 0)
    b = np.roll(outline, -1, 0) - outline
    sin_turn = np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]) / (np.hypot(*a.T) * np.hypot(*b.T))
    scale = float(np.max(np.abs(outline)))
    assert np.all(np.hypot(*(got - want).T) <= 1e-12 * scale / np.maximum(sin_turn, 1e-6))


def test_every_edge_moves_exactly_the_offset() -> None:
    outline = _star([1.0, 0.4, 1.2, 0.5, 0.9, 0.3, 1.1])
    got = offset_outline(outline, 0.01)
    d = np.roll(outline, -1, 0) - outline
    n = np.stack([d[:, 1], -d[:, 0]], axis=-1) / np.hypot(*d.T)[:, None]
    # both ends of offset edge i lie at distance 0.01 outside edge i's line
    for end in (got, np.roll(got, -1, 0)):
        assert np.allclose(np.einsum("ij,ij->i", end - outline, n), 0.01, atol=1e-14)


def test_a_needle_corner_s_mitre_is_finite_and_exact() -> None:
    """The tip of a sliver (a fuzzed sheet 6.87e-7 wide, 99.375 long) turns by all
    but 2 phi, phi = atan(6.87e-7 / 99.375) = 6.9e-9 rad: 1 + m.n is then
    below the rounding of the 1 (it gave inf and NaN). The mitred tip moves
    along the axis by distance / sin(phi) (the corner of two lines offset by
    distance, meeting at angle 2 phi), worked by hand."""
    w, a, b = 6.87e-7, 99.375, 25.67
    outline = np.array([[a, 0.0], [0.0, w], [-b, 0.0], [0.0, -w]])
    got = offset_outline(outline, 5e-12)
    phi = math.atan2(w, a)
    assert np.all(np.isfinite(got))
    assert math.isclose(got[0, 0] - a, 5e-12 / math.sin(phi), rel_tol=1e-6)
    assert abs(got[0, 1]) <= 1e-12 * a
    psi = math.atan2(w, b)  # the other tip
    assert math.isclose(-b - got[2, 0], 5e-12 / math.sin(psi), rel_tol=1e-6)


def test_a_corner_that_turns_back_on_itself_is_refused() -> None:
    """Two edges along one line in opposite directions (a spike of angle 0):
    the offset lines never meet; a named error, not inf."""
    outline = np.array([[0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 1.0]])
    with pytest.raises(InvalidParameterError, match="kerf: the blank's corner at \\(2, 0\\)"):
        offset_outline(outline, 0.1)
