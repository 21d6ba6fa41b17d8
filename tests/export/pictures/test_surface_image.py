"""The shaded surface drawn as one image looks as matplotlib's own
``Poly3DCollection`` of the same triangles does (what the pictures were
drawn with before), pixel for pixel but for a few at shared edges."""

from __future__ import annotations

import io

import numpy as np
import pytest

from onefold_cad import Design, FrameCurve, Sheet, fold_design
from onefold_cad.export.pictures import preview
from onefold_cad.export.pictures.preview import thumbnail_png
from onefold_cad.export.pictures.surface_image import painter_order, project_triangles
from onefold_cad.fabrication.rules import resting_placement


def _collection(ax, tri, rgba, zorder):
    """The surface as the pictures drew it before: one triangle a path."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    surface = Poly3DCollection(tri, facecolors=rgba, edgecolors="none", antialiased=False)
    surface.set_zorder(zorder)
    ax.add_collection3d(surface)
    return surface


def _pixels(png: bytes) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(png)).convert("RGBA")).astype(int)


DESIGNS = {
    "rectangle": Design("p", FrameCurve(40, 40), Sheet.rectangle(300, 200, 0.5)),
    "steep": Design("q", FrameCurve(70, 25, 20.0), Sheet.rectangle(260, 300, 0.4)),
}


@pytest.mark.parametrize("name", sorted(DESIGNS))
@pytest.mark.parametrize("size", [(240, 180), (600, 450)])
def test_the_surface_looks_as_the_collection_drew_it(monkeypatch, name, size):
    """At most 0.1 % of the pixels differ, and at most 5 by more than 16 of
    255 levels: Agg rounds each corner to 1/256 pixel and sums a pixel's
    area in integers; the exact area disagrees with it only for a pixel a
    triangle grazes, where the neighbouring triangle (the next ruling, a
    shade of nearly the same colour) or the other side wins instead."""
    design = DESIGNS[name]
    folded = fold_design(design)
    rest = resting_placement(design, folded)
    ours = _pixels(thumbnail_png(folded, rest, size_px=size))
    monkeypatch.setattr(preview, "add_surface", _collection)
    before = _pixels(thumbnail_png(folded, rest, size_px=size))
    diff = np.abs(ours - before).max(axis=-1)
    surface = np.abs(before[..., 0] - before[..., 2]) > 20  # warm or cool: the sheet
    assert surface.sum() > 0.05 * diff.size
    assert (diff > 0).sum() <= 0.001 * diff.size
    assert (diff > 16).sum() <= 5


def test_projection_and_order_are_the_collections():
    """The corners projected by mplot3d's own transform, the triangles in
    the order a Poly3DCollection (zsort 'average') sorts them."""
    from matplotlib.figure import Figure
    from mpl_toolkits.mplot3d import proj3d

    fig = Figure()
    ax = fig.add_subplot(projection="3d")
    ax.view_init(elev=20, azim=-110)
    ax.M = ax.get_proj()
    rng = np.random.default_rng(3)
    tri = rng.uniform(-1.0, 1.0, (50, 3, 3))
    got = project_triangles(tri, ax.M)
    xs, ys, zs = proj3d.proj_transform(*tri.reshape(-1, 3).T, ax.M)
    np.testing.assert_allclose(got.reshape(-1, 3), np.column_stack([xs, ys, zs]), atol=1e-12)
    depth = got[..., 2].mean(axis=1)
    order = painter_order(got)
    assert sorted(order) == list(range(50))
    assert np.all(np.diff(depth[order]) <= 0.0)  # the farthest (largest depth) first
