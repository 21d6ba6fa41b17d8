"""The kerf offset against ezdxf's offset_vertices_2d (an independent implementation)."""

from __future__ import annotations

import math

import numpy as np
from ezdxf.math import offset_vertices_2d
from hypothesis import given, settings
from hypothesis import strategies as st

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
