"""The shaded surface of a 3D picture, drawn in one call.

A matplotlib ``Poly3DCollection`` of the preview's ~9 000 triangles makes a
``Path`` per triangle twice per picture and has Agg fill each one: most of a
sweep's time. :func:`add_surface` puts one artist in the 3D axes instead
that, when the figure is drawn, does what the collection does with the same
numbers: projects the corners with the axes' projection matrix, orders the
triangles by their mean depth (the far ones first, ``np.argsort`` of the
same values, so ties fall the same way), maps them to pixels with the axes'
``transData`` and has Agg paint them all in one call
(``RendererBase.draw_gouraud_triangles``, each triangle's three corners of
its one colour), clipped to the axes like the collection. Agg antialiases
these triangles' outer edges (the collection drew them aliased) and leaves
no seam at shared ones: the picture differs from the collection's only
along the surface's outline, by its smoothing.

matplotlib is imported inside :func:`add_surface` only.
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np
from numpy.typing import NDArray

from onefold_cad.geometry.numeric import Array

__all__ = ["add_surface", "painter_order", "project_triangles"]


def project_triangles(tri: Array, proj: Array) -> Array:
    """``(m, 3, 3)`` triangles through a 4 x 4 projection matrix ``proj``
    (mplot3d's ``axes.M``): the projected x, y and depth, as
    ``mpl_toolkits.mplot3d.proj3d`` computes them."""
    pts = tri.reshape(-1, 3).T
    vec = np.vstack([pts, np.ones(pts.shape[1])])
    product = np.dot(proj, vec)
    return (product[:3] / product[3]).T.reshape(tri.shape)


def painter_order(projected: Array) -> NDArray[np.int64]:
    """The order a ``Poly3DCollection`` (zsort 'average') paints ``(m, 3, 3)``
    projected triangles in: by mean depth, the largest first."""
    return np.argsort(np.average(projected[..., 2], axis=-1), axis=-1)[::-1]


@functools.cache
def _surface_class() -> Any:
    """The artist class (made once: matplotlib is imported when it is)."""
    from matplotlib.artist import Artist
    from matplotlib.transforms import IdentityTransform

    class Surface(Artist):
        """Opaque triangles of an ``Axes3D``, painted by Agg in one call."""

        def __init__(self, tri: Array, rgba: Array) -> None:
            super().__init__()
            self.tri, self.rgba = tri, rgba

        def draw(self, renderer: Any) -> None:
            if not self.get_visible():
                return
            ax: Any = self.axes
            projected = project_triangles(self.tri, ax.M)
            order = painter_order(projected)
            flat = projected[order, :, :2].reshape(-1, 2)
            pixels = ax.transData.transform(flat).reshape(-1, 3, 2)
            colors = np.repeat(self.rgba[order, None, :], 3, axis=1)
            gc = renderer.new_gc()
            if self.get_clip_on():  # the axes' patch, as for a collection
                gc.set_clip_rectangle(self.get_clip_box())
                gc.set_clip_path(self.get_clip_path())
            renderer.draw_gouraud_triangles(gc, pixels, colors, IdentityTransform())
            gc.restore()
            self.stale = False

    return Surface


def add_surface(ax: Any, tri: Array, rgba: Array, zorder: float) -> Any:
    """Add opaque triangles to the mplot3d axes ``ax`` as one image artist.

    Args:
        ax: an ``Axes3D``.
        tri: ``(m, 3, 3)`` the triangles' corners (data coordinates).
        rgba: ``(m, 4)`` their colours, 0..1.
        zorder: the artist's place in the drawing order.

    Returns:
        The artist (drawn with the figure).
    """
    artist = _surface_class()(np.asarray(tri, dtype=float), np.asarray(rgba, dtype=float))
    artist.set_zorder(zorder)
    ax.add_artist(artist)  # clipped to the axes' patch, as a collection is
    return artist
