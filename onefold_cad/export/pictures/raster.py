"""Opaque triangles to pixels, as Agg fills them without antialiasing.

The shaded surface of a preview is some 9 000 small triangles. matplotlib
draws each as its own path (a Python ``Path`` per triangle, an Agg
rasterisation per path): most of a sweep's thumbnail time went there.
:func:`fill_triangles` paints them all at once with numpy and gives the
pixels Agg gives (matplotlib's ``antialiased=False`` fill):

- a triangle paints every pixel it covers by a positive area, its corners
  first rounded to 1/256 pixel (Agg's sub-pixel grid); Agg's coverage of a
  pixel is an integer count of 1/256 of the pixel's area, truncated towards
  minus infinity, so a triangle wound clockwise on the screen (y up) paints
  a pixel it touches by any area, a counter-clockwise one only from 1/256
  of the pixel on (the sign of the shoelace sum decides which way the
  truncation goes);
- later triangles paint over earlier ones (the painter's order the caller
  gives), each with its colour rounded to 8 bits.

How: the candidate pixels of a triangle are its bounding box, handled in
blocks of triangles whose boxes pad to one size; whether a triangle touches
a pixel, and whether it covers it whole, are separating-axis tests at the
pixel's corners (exact on the 1/256 grid). The area itself is needed only
where a counter-clockwise triangle merely touches a pixel no later triangle
surely paints, latest painter first: Green's theorem with the field
``(0, clamp(x, 0, 1) * [0 <= y <= 1])`` (curl: the pixel's indicator), an
exact integral per edge (:func:`pixel_coverage`).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from onefold_cad.geometry.numeric import Array, Mask

__all__ = ["SUBPIXEL", "fill_triangles", "pixel_coverage"]

#: Agg's sub-pixel grid: corners are rounded to 1 / SUBPIXEL of a pixel.
SUBPIXEL = 256
#: Pixels measured at once (bounds the memory: some 20 arrays of 3 x _CHUNK).
_CHUNK = 100_000
#: Block sizes (pixels) a triangle's bounding box is padded to: few blocks,
#: little padding.
_SIZES = np.unique(np.outer(1 << np.arange(31), [2, 3]) // 2)  # 1, 2, 3, 4, 6, 8, 12, ...
#: Below this area (pixel areas) a coverage is zero (round-off of the
#: integral; Agg's smallest area is 1 / (2 * 256^2) = 7.6e-6).
_ZERO = 1e-9


def _edges(tri: Array) -> tuple[Array, Array, Array, Array, Array]:
    """Per triangle and edge ``(m, 3)``: the edge's lowest and highest y, the
    sign of its dy (0 for a level edge), dx/dy and the x where its line
    crosses y = 0."""
    p, q = tri, np.roll(tri, -1, axis=1)
    dy = q[..., 1] - p[..., 1]
    slope = (q[..., 0] - p[..., 0]) / np.where(dy != 0.0, dy, 1.0)
    return (
        np.minimum(p[..., 1], q[..., 1]),
        np.maximum(p[..., 1], q[..., 1]),
        np.sign(dy),
        slope,
        p[..., 0] - slope * p[..., 1],
    )


def _half_planes(tri: Array, ccw: Mask) -> Array:
    """``(m, 3, 4)``: for each triangle and edge ``(a, b, c, r)`` with
    ``a x + b y + c`` positive inside the triangle (exact for corners on the
    1/256 grid) and ``r = (|a| + |b|) / 2`` its largest change from a
    pixel's centre to a corner."""
    p, q = tri, np.roll(tri, -1, axis=1)
    dx, dy = q[..., 0] - p[..., 0], q[..., 1] - p[..., 1]
    sign = np.where(ccw, 1.0, -1.0)[:, None]
    a, b = -dy * sign, dx * sign
    c = (dy * p[..., 0] - dx * p[..., 1]) * sign
    return np.stack([a, b, c, 0.5 * (np.abs(a) + np.abs(b))], axis=-1)


def _ramp_integral(u: Array) -> Array:
    """The antiderivative of ``clamp(u, 0, 1)`` that is 0 at u <= 0."""
    u = np.maximum(u, 0.0)
    return np.where(u <= 1.0, 0.5 * u * u, u - 0.5)


def _coverage(edges: tuple[Array, ...], which: NDArray[np.int64], x: Array, y: Array) -> Array:
    """Signed area of triangle ``which`` in pixel ``(x, y)`` (lower-left
    corners, ``(n,)`` each) from its :func:`_edges`: for each edge, the
    integral over its y span inside the pixel of clamp(u, 0, 1), u its x
    from the pixel's left side (linear in y): the span's length times the
    ramp's mean between u's end values (the ramp's middle value where these
    are within 1e-6 of each other: no small difference divided by another)."""
    ylo, yhi, sign, slope, cross = (e[which] for e in edges)
    lo = np.clip(ylo - y[:, None], 0.0, 1.0)
    hi = np.clip(yhi - y[:, None], 0.0, 1.0)
    c = cross + slope * y[:, None] - x[:, None]  # u at the pixel's bottom
    u0, u1 = c + slope * lo, c + slope * hi
    du = u1 - u0
    near = np.abs(du) < 1e-6
    ramp = (_ramp_integral(u1) - _ramp_integral(u0)) / np.where(near, 1.0, du)
    mean = np.where(near, np.clip(0.5 * (u0 + u1), 0.0, 1.0), ramp)
    return np.sum(sign * (hi - lo) * mean, axis=1)


def pixel_coverage(tri: Array, corner: Array) -> Array:
    """Signed area of each triangle inside its pixel.

    Args:
        tri: ``(n, 3, 2)`` triangle corners (pixels, y up).
        corner: ``(n, 2)`` the lower-left corner of the pixel
            ``[x, x + 1] x [y, y + 1]`` each triangle is measured in.

    Returns:
        ``(n,)`` the area (pixel areas, 0..1) of triangle ∩ pixel, positive
        for a counter-clockwise triangle, negative for a clockwise one.
    """
    corner = np.asarray(corner, dtype=float)
    return _coverage(
        _edges(np.asarray(tri, float)), np.arange(len(tri)), corner[:, 0], corner[:, 1]
    )


def fill_triangles(
    tri: Array, rgba: Array, size: tuple[int, int]
) -> tuple[NDArray[np.uint8], NDArray[np.bool_]]:
    """Paint opaque triangles in order, as Agg's non-antialiased fill does.

    Args:
        tri: ``(m, 3, 2)`` corners in display pixels (x right, y up, the
            canvas's lower-left corner at 0), in painting order.
        rgba: ``(m, 4)`` colours, 0..1 (the alpha is written as given).
        size: the canvas's ``(width, height)`` in pixels.

    Returns:
        ``(image (height, width, 4) uint8, painted (height, width) bool)``:
        the image's first row is the canvas's top; unpainted pixels are
        transparent black.
    """
    width, height = size
    tri = np.round(np.asarray(tri, dtype=float) * SUBPIXEL) / SUBPIXEL
    d1, d2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    ccw = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0] > 0.0
    # candidate pixels: those the bounding box overlaps by a positive area
    lo = np.maximum(np.floor(tri.min(axis=1)), 0).astype(np.int64)
    hi = np.minimum(np.ceil(tri.max(axis=1)) - 1, [width - 1, height - 1]).astype(np.int64)
    box = np.maximum(hi - lo + 1, 0)
    count = box[:, 0] * box[:, 1]
    planes = _half_planes(tri, ccw)
    edges = _edges(tri)
    pixels: list[NDArray[np.int64]] = []  # pixel numbers and painters, in turn
    doubts: list[NDArray[np.int64]] = []  # the same, to be measured
    # the triangles of one bounding-box size class at once: their candidate
    # pixels are a (k, rows, columns) block, no gathering per pixel (a box
    # padded to its class's size; the padding masked off)
    bucket = np.searchsorted(_SIZES, box)
    shape = bucket[:, 1] * len(_SIZES) + bucket[:, 0]
    for key in np.unique(shape[count > 0]):
        ids = np.flatnonzero(shape == key)
        rows, cols = (int(_SIZES[k]) for k in divmod(int(key), len(_SIZES)))
        plane, corner = planes[ids], lo[ids]
        # each edge's value at the centre of the block's first pixel (exact
        # on the 1/256 grid), then stepped along x and y; separating axes:
        # the pixel's corner deepest inside each edge's half-plane is inside
        # (touch), its shallowest too (full)
        first = plane[..., 2] + plane[..., 0] * (corner[:, 0, None] + 0.5)
        first += plane[..., 1] * (corner[:, 1, None] + 0.5)
        step_x = plane[..., 0, None] * np.arange(cols)  # (k, 3, cols)
        step_y = plane[..., 1, None] * np.arange(rows)  # (k, 3, rows)
        touch = (np.arange(rows)[:, None] < box[ids, 1, None, None]) & (
            np.arange(cols) < box[ids, 0, None, None]
        )
        full = np.ones_like(touch)
        for i in range(3):
            grid = step_y[:, i, :, None] + step_x[:, i, None, :]
            touch &= grid > -(first[:, i] + plane[:, i, 3])[:, None, None]
            full &= grid >= -(first[:, i] - plane[:, i, 3])[:, None, None]
        partial = touch & ~full & ccw[ids, None, None]
        # pixel numbers, row by row from the image's top
        first_pixel = (height - 1 - corner[:, 1]) * width + corner[:, 0]
        pixel = first_pixel[:, None, None] - width * np.arange(rows)[:, None] + np.arange(cols)
        sure = touch & ~partial
        pixels += [pixel[sure], ids[np.nonzero(sure)[0]]]
        doubts += [pixel[partial], ids[np.nonzero(partial)[0]]]
    winner = np.full(width * height, -1, dtype=np.int64)
    empty = np.empty(0, dtype=np.int64)
    np.maximum.at(
        winner, np.concatenate([empty, *pixels[::2]]), np.concatenate([empty, *pixels[1::2]])
    )
    # a counter-clockwise triangle needs 1/256 of a pixel it only touches:
    # measure it where no later triangle surely paints that pixel, the
    # latest-painted doubtful triangle of each pixel first (where it has its
    # 1/256, the earlier ones there need no measuring)
    pixel = np.concatenate([empty, *doubts[::2]])
    which = np.concatenate([empty, *doubts[1::2]])
    keep = which > winner[pixel]
    order = np.lexsort((-which[keep], pixel[keep]))
    which, pixel = which[keep][order], pixel[keep][order]
    x, y = pixel % width, height - 1 - pixel // width
    while len(which):
        head = np.flatnonzero(np.r_[True, pixel[1:] != pixel[:-1]])
        area = np.concatenate(
            [
                _coverage(edges, which[h], x[h] * 1.0, y[h] * 1.0)
                for h in np.array_split(head, -(-len(head) // _CHUNK))
            ]
        )
        enough = np.abs(area) > 1.0 / SUBPIXEL - _ZERO
        winner[pixel[head[enough]]] = which[head[enough]]
        rest = np.ones(len(which), dtype=bool)
        rest[head] = False
        rest &= ~np.isin(pixel, pixel[head[enough]])
        which, x, y, pixel = which[rest], x[rest], y[rest], pixel[rest]
    colours = np.floor(np.clip(np.asarray(rgba, dtype=float), 0.0, 1.0) * 255.0 + 0.5)
    painted = winner >= 0
    image = np.zeros((width * height, 4), dtype=np.uint8)
    image[painted] = colours.astype(np.uint8)[winner[painted]]
    return image.reshape(height, width, 4), painted.reshape(height, width)
