"""The shaded surface drawn in one call looks as matplotlib's own
``Poly3DCollection`` of the same triangles does (what the pictures were
drawn with before), pixel for pixel but for the smoothing of outlines."""

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


def _outline(image: np.ndarray) -> np.ndarray:
    """Pixels within one of a step of more than 8 levels to a neighbour: an
    outline (a smoothed outline differs from an aliased one by at most the
    step it smooths)."""
    rgb = image[..., :3]
    edge = np.zeros(rgb.shape[:2], dtype=bool)
    for axis in (0, 1):
        step = np.abs(np.diff(rgb, axis=axis)).max(axis=-1) > 8
        if axis == 0:
            edge[1:] |= step
            edge[:-1] |= step
        else:
            edge[:, 1:] |= step
            edge[:, :-1] |= step
    grown = edge.copy()
    grown[1:] |= edge[:-1]
    grown[:-1] |= edge[1:]
    grown[:, 1:] |= edge[:, :-1]
    grown[:, :-1] |= edge[:, 1:]
    return grown


@pytest.mark.parametrize("name", sorted(DESIGNS))
@pytest.mark.parametrize("size", [(240, 180), (600, 450)])
def test_the_surface_looks_as_the_collection_drew_it(monkeypatch, name, size):
    """The same picture but for the smoothing of outlines: inside the
    surface every pixel is the collection's to 8 of 255 levels (so no seam
    at the triangles' shared edges, where an antialiased collection lets the
    background through), and a pixel that differs by more than that lies on
    an outline of the collection's picture (Agg smooths the surface's outer
    edges; the collection drew them aliased)."""
    design = DESIGNS[name]
    folded = fold_design(design)
    rest = resting_placement(design, folded)
    ours = _pixels(thumbnail_png(folded, rest, size_px=size))
    monkeypatch.setattr(preview, "add_surface", _collection)
    before = _pixels(thumbnail_png(folded, rest, size_px=size))
    diff = np.abs(ours - before).max(axis=-1)
    surface = np.abs(before[..., 0] - before[..., 2]) > 20  # warm or cool: the sheet
    assert surface.sum() > 0.05 * diff.size
    assert not np.any((diff > 8) & ~_outline(before))
    assert np.abs(ours - before).mean() < 1.0
    assert (diff > 8).sum() < 0.02 * diff.size


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
