"""Triangles to pixels as Agg fills them without antialiasing.

The expectations: exact areas (the shoelace formula, a pixel's area) and
matplotlib's own Agg canvas filling the same triangles."""

from __future__ import annotations

import numpy as np
import pytest

from onefold_cad.export.pictures.raster import fill_triangles, pixel_coverage


def _shoelace(tri: np.ndarray) -> np.ndarray:
    d1, d2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    return 0.5 * (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])


def test_a_triangle_covering_a_pixel_covers_all_of_it_with_its_winding_sign():
    big = np.array([[[-5.0, -5.0], [10.0, -5.0], [-5.0, 10.0]]])  # counter-clockwise
    corner = np.array([[1.0, 2.0]])
    assert pixel_coverage(big, corner) == pytest.approx([1.0], abs=1e-12)
    assert pixel_coverage(big[:, ::-1], corner) == pytest.approx([-1.0], abs=1e-12)
    # the pixel's lower-left half: the diagonal cuts it in two
    half = np.array([[[1.0, 2.0], [2.0, 2.0], [1.0, 3.0]]])
    assert pixel_coverage(half, corner) == pytest.approx([0.5], abs=1e-12)
    assert pixel_coverage(half, np.array([[0.0, 2.0]])) == pytest.approx([0.0], abs=1e-12)


def test_the_coverages_of_every_pixel_add_up_to_the_triangles_area():
    rng = np.random.default_rng(7)
    tri = rng.uniform(0.0, 6.0, (40, 3, 2))
    xs, ys = np.meshgrid(np.arange(-1, 7), np.arange(-1, 7))
    corners = np.column_stack([xs.ravel(), ys.ravel()]).astype(float)
    for t, area in zip(tri, _shoelace(tri), strict=True):
        cover = pixel_coverage(np.repeat(t[None], len(corners), axis=0), corners)
        assert cover.sum() == pytest.approx(area, abs=1e-9)
        assert np.all(np.abs(cover) <= 1.0 + 1e-12)
        assert np.all(np.sign(cover[np.abs(cover) > 1e-12]) == np.sign(area))


def test_later_triangles_paint_over_earlier_ones_in_their_colour():
    square = np.array([[[0.0, 0.0], [4.0, 0.0], [4.0, 4.0]], [[0.0, 0.0], [4.0, 4.0], [0.0, 4.0]]])
    red, blue = [1.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0]
    over = np.array([[[0.0, 0.0], [8.0, 0.0], [0.0, 8.0]]])  # covers the square's pixels
    image, painted = fill_triangles(
        np.concatenate([square, over]), np.array([red, red, blue]), (6, 6)
    )
    assert painted[2:, :4].all()  # rows from the top: the square is the bottom-left 4 x 4
    assert (image[2:, :4] == [0, 0, 255, 255]).all()
    image, _ = fill_triangles(np.concatenate([over, square]), np.array([blue, red, red]), (6, 6))
    assert (image[2:, :4] == [255, 0, 0, 255]).all()
    # a pixel no triangle reaches is transparent; colours round to 8 bits
    assert not painted[0, 5] and (image[0, 5] == 0).all()
    grey, _ = fill_triangles(square[:1], np.array([[0.5, 0.25, 0.0, 1.0]]), (6, 6))
    assert tuple(grey[5, 3]) == (128, 64, 0, 255)


def _agg(tri: np.ndarray, rgba: np.ndarray, size: tuple[int, int]) -> np.ndarray:
    """matplotlib's Agg canvas filling the triangles, antialiasing off."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.collections import PolyCollection
    from matplotlib.figure import Figure
    from matplotlib.transforms import IdentityTransform

    fig = Figure(figsize=(size[0] / 100, size[1] / 100), dpi=100)
    FigureCanvasAgg(fig)
    fig.patch.set_alpha(0.0)
    fig.add_artist(
        PolyCollection(
            tri,
            facecolors=rgba,
            edgecolors="none",
            antialiased=False,
            transform=IdentityTransform(),
        )
    )
    fig.canvas.draw()
    return np.asarray(fig.canvas.buffer_rgba()).copy()


@pytest.mark.parametrize("scale", [0.5, 2.0, 8.0])
def test_the_pixels_are_aggs_own(scale):
    """Random triangles of about ``scale`` pixels, overlapping, either
    winding: the pixels Agg paints, in its colours, but for a few where
    Agg's integer cell arithmetic and the exact area part ways (a pixel
    touched by a sliver)."""
    rng = np.random.default_rng(int(scale * 10))
    size = (80, 60)
    tri = rng.uniform([-3, -3], [83, 63], (400, 1, 2)) + rng.normal(0.0, scale, (400, 3, 2))
    rgba = np.column_stack([rng.uniform(0.0, 1.0, (400, 3)), np.ones(400)])
    expected = _agg(tri, rgba, size)
    image, painted = fill_triangles(tri, rgba, size)
    assert (painted == (expected[..., 3] > 0)).mean() > 0.997
    differ = np.any(image != expected, axis=-1) & painted
    assert differ.sum() <= 0.01 * painted.sum()
    assert painted.sum() > 0.1 * size[0] * size[1]
