"""The flat sheet: a simple polygon, star-shaped about H, in the fold frame.

Fold frame: the fold line is the x axis and H is the origin. Vertices are kept
counter-clockwise, start at the boundary's crossing of the +x axis, and every
crossing of the x axis is a vertex, so the upper (y >= 0) and lower (y <= 0)
boundaries are vertex runs of their own.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.errors import InvalidSheetError
from onefold_cad.geometry.validate import open_interval, positive

__all__ = ["Placement2D", "Sheet"]

_TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class Placement2D:
    """A rigid motion of the plane: ``sheet_xy = Rot(angle) @ fold_xy + (tx, ty)``.

    Attributes:
        angle: rotation in degrees (counter-clockwise).
        tx, ty: translation (length).
    """

    angle: float = 0.0
    tx: float = 0.0
    ty: float = 0.0

    @property
    def matrix(self) -> NDArray[np.float64]:
        """The 2x2 rotation matrix."""
        c, s = math.cos(math.radians(self.angle)), math.sin(math.radians(self.angle))
        return np.array([[c, -s], [s, c]])

    def apply(self, xy: ArrayLike) -> NDArray[np.float64]:
        """Map fold-frame points ``(k, 2)`` to the sheet's own frame ``(k, 2)``."""
        p = np.asarray(xy, dtype=float)
        return p @ self.matrix.T + np.array([self.tx, self.ty])

    def apply_direction(self, v: ArrayLike) -> NDArray[np.float64]:
        """Rotate direction vectors ``(k, 2)`` into the sheet's own frame."""
        return np.asarray(v, dtype=float) @ self.matrix.T

    def inverse(self, xy: ArrayLike) -> NDArray[np.float64]:
        """Map sheet-frame points ``(k, 2)`` back to the fold frame."""
        p = np.asarray(xy, dtype=float) - np.array([self.tx, self.ty])
        return p @ self.matrix


def _cross(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _check_simple(p: NDArray[np.float64], name: str) -> None:
    """Raise if two non-adjacent edges of the closed polygon ``p`` touch or cross."""
    n = len(p)
    a, b = p, np.roll(p, -1, axis=0)
    scale = float(np.max(np.abs(p)))
    eps = 1e-12 * scale * scale
    for i in range(n):  # O(n^2) work, vectorized over the second edge
        j = np.arange(i + 1, n)
        j = j[(j != (i + 1) % n) & ((j + 1) % n != i)]
        if j.size == 0:
            continue
        e = b[i] - a[i]
        f = b[j] - a[j]
        d1 = _cross(e, a[j] - a[i])
        d2 = _cross(e, b[j] - a[i])
        d3 = _cross(f, a[i] - a[j])
        d4 = _cross(f, b[i] - a[j])
        proper = (d1 * d2 < -eps) & (d3 * d4 < -eps)
        # an endpoint of one edge lying on the other edge (collinear overlaps included)
        ee = float(e @ e)
        ff = np.einsum("ij,ij->i", f, f)
        t_aj = ((a[j] - a[i]) @ e) / ee
        t_bj = ((b[j] - a[i]) @ e) / ee
        s_ai = np.einsum("ij,ij->i", a[i] - a[j], f) / ff
        s_bi = np.einsum("ij,ij->i", b[i] - a[j], f) / ff
        inside = (-1e-12, 1.0 + 1e-12)
        touching = (np.abs(d1) <= eps) & (t_aj >= inside[0]) & (t_aj <= inside[1])
        touching |= (np.abs(d2) <= eps) & (t_bj >= inside[0]) & (t_bj <= inside[1])
        touching |= (np.abs(d3) <= eps) & (s_ai >= inside[0]) & (s_ai <= inside[1])
        touching |= (np.abs(d4) <= eps) & (s_bi >= inside[0]) & (s_bi <= inside[1])
        hit = proper | touching
        if np.any(hit):
            k = int(j[np.argmax(hit)])
            raise InvalidSheetError(
                name,
                f"polygon self-intersects: edge {i} ({a[i].tolist()} -> {b[i].tolist()}) "
                f"meets edge {k} ({a[k].tolist()} -> {b[k].tolist()}); "
                "a simple polygon is required",
            )


def boundary_distance(polygon: ArrayLike, point: ArrayLike = (0.0, 0.0)) -> float:
    """Distance from ``point`` to the boundary of the closed polygon ``(n, 2)``
    (length): the largest circle about ``point`` that stays inside it."""
    v = np.asarray(polygon, dtype=float) - np.asarray(point, dtype=float)
    e = np.roll(v, -1, axis=0) - v
    t = np.clip(-(v * e).sum(axis=1) / (e * e).sum(axis=1), 0.0, 1.0)
    return float(np.min(np.hypot(*(v + t[:, None] * e).T)))


def _insert_axis_crossings(p: NDArray[np.float64]) -> NDArray[np.float64]:
    """Return ``p`` with the x-axis crossings inserted, starting at the +x crossing."""
    out: list[NDArray[np.float64]] = []
    n = len(p)
    for i in range(n):
        a, b = p[i], p[(i + 1) % n]
        out.append(a)
        if a[1] * b[1] < 0.0:
            t = a[1] / (a[1] - b[1])
            out.append(np.array([a[0] + t * (b[0] - a[0]), 0.0]))
    q = np.array(out)
    on_axis = np.flatnonzero((q[:, 1] == 0.0) & (q[:, 0] > 0.0))
    start = int(on_axis[0])
    q = np.roll(q, -start, axis=0)
    q[:, 1] = np.where(q[:, 1] == 0.0, 0.0, q[:, 1])  # no negative zeros
    return q


@dataclass(frozen=True, eq=False)
class Sheet:
    """A flat sheet in the fold frame (H at the origin, fold line on the x axis).

    Build it with :meth:`polygon`, :meth:`quadrilateral` or :meth:`rectangle`.

    Attributes:
        vertices: ``(n, 2) float`` counter-clockwise, vertex 0 on the +x axis,
            every x-axis crossing a vertex (length).
        to_sheet: the motion from the fold frame to the sheet's own frame
            (identity for polygons and quadrilaterals; for a rectangle, a corner
            at the origin and its sides on the axes).
        kind: 'polygon', 'quadrilateral' or 'rectangle'.
        inputs: the values the sheet was made from (for reports).
    """

    vertices: NDArray[np.float64]
    to_sheet: Placement2D = field(default_factory=Placement2D)
    kind: str = "polygon"
    inputs: dict[str, object] = field(default_factory=dict)

    # -- constructors -------------------------------------------------------
    @classmethod
    def polygon(
        cls,
        points: ArrayLike | Sequence[Sequence[float]],
        *,
        name: str = "polygon",
        to_sheet: Placement2D | None = None,
        kind: str = "polygon",
        inputs: dict[str, object] | None = None,
    ) -> Sheet:
        """Validate a polygon given in the fold frame and return the sheet.

        Args:
            points: ``(n, 2)`` vertices, either orientation, not repeating the
                first vertex at the end.
            name: the parameter name used in error messages.

        Raises:
            InvalidSheetError: fewer than 3 vertices, non-finite coordinates,
                repeated vertices, self-intersection, H not strictly inside, or
                not strictly star-shaped about H.
        """
        try:
            p = np.array(points, dtype=float)
        except (TypeError, ValueError):
            raise InvalidSheetError(name, "must be a list of (x, y) pairs") from None
        if p.ndim != 2 or p.shape[1] != 2:
            raise InvalidSheetError(name, f"must be a list of (x, y) pairs, got shape {p.shape}")
        if len(p) > 1 and np.array_equal(p[0], p[-1]):
            p = p[:-1]
        if len(p) < 3:
            raise InvalidSheetError(name, f"needs at least 3 vertices, got {len(p)}")
        if not np.all(np.isfinite(p)):
            raise InvalidSheetError(name, "vertex coordinates must be finite numbers (no NaN/inf)")
        scale = float(np.max(np.abs(p)))
        p[np.abs(p[:, 1]) <= 1e-12 * scale, 1] = 0.0  # on the fold line up to rounding
        nxt = np.roll(p, -1, axis=0)
        seglen = np.hypot(*(nxt - p).T)
        if scale == 0.0 or np.any(seglen <= 1e-12 * scale):
            k = int(np.argmin(seglen))
            raise InvalidSheetError(name, f"vertices {k} and {(k + 1) % len(p)} coincide")
        _check_simple(p, name)
        signed_area = 0.5 * float(np.sum(_cross(p, nxt)))
        if signed_area < 0.0:
            p = p[::-1].copy()
            nxt = np.roll(p, -1, axis=0)
        r = np.hypot(p[:, 0], p[:, 1])
        if np.any(r <= 1e-12 * scale):
            raise InvalidSheetError(
                name, "H (the origin) must lie strictly inside, not on a vertex"
            )
        # Winding number of the (simple) polygon about H.
        steps = np.arctan2(_cross(p, nxt), np.einsum("ij,ij->i", p, nxt))
        winding = float(np.sum(steps)) / _TWO_PI
        edge_dist = np.abs(_cross(p, nxt - p)) / seglen
        on_edge = (edge_dist <= 1e-12 * scale) & (np.einsum("ij,ij->i", p, nxt) <= 0.0)
        if np.any(on_edge) or abs(winding) < 0.5:
            raise InvalidSheetError(
                name, "H (the origin of the fold frame) must lie strictly inside the polygon"
            )
        if np.any(steps <= 1e-12) or np.any(steps >= math.pi):
            k = int(np.argmin(steps))
            raise InvalidSheetError(
                name,
                "polygon must be star-shaped about H: seen from H its vertices must turn "
                f"strictly counter-clockwise, but edge {k} ({p[k].tolist()} -> "
                f"{nxt[k].tolist()}) turns back or lies on a ray from H",
            )
        q = _insert_axis_crossings(p)
        q.setflags(write=False)
        return cls(q, to_sheet or Placement2D(), kind, dict(inputs or {"polygon": p.tolist()}))

    @classmethod
    def quadrilateral(cls, x_plus: float, x_minus: float, y_plus: float, y_minus: float) -> Sheet:
        """The paper's quadrilateral (section 3.4) with vertices on the axes.

        Args:
            x_plus, x_minus: distances from H to the vertices on the +x and -x
                axis (X+ and X-), > 0.
            y_plus, y_minus: distances from H to the vertices on the +y and -y
                axis (Y+ and Y-), > 0.
        """
        xp = positive("x_plus", x_plus)
        xm = positive("x_minus", x_minus)
        yp = positive("y_plus", y_plus)
        ym = positive("y_minus", y_minus)
        pts = [(xp, 0.0), (0.0, yp), (-xm, 0.0), (0.0, -ym)]
        inputs = {"x_plus": xp, "x_minus": xm, "y_plus": yp, "y_minus": ym}
        return cls.polygon(pts, kind="quadrilateral", inputs=inputs)

    @classmethod
    def rectangle(cls, width: float, height: float, apex_fraction: float = 0.5) -> Sheet:
        """A ``width`` x ``height`` rectangle folded along its diagonal.

        The sheet's own frame has a corner at the origin and its sides on the
        axes; the fold runs along the diagonal from (0, 0) to (width, height)
        and H lies at ``apex_fraction`` of the way along it. The fold frame's
        +x axis points towards (width, height).
        """
        w = positive("width", width)
        h = positive("height", height)
        f = open_interval("apex_fraction", apex_fraction, 0.0, 1.0)
        angle = math.degrees(math.atan2(h, w))
        place = Placement2D(angle, f * w, f * h)
        corners = np.array([(0.0, 0.0), (w, 0.0), (w, h), (0.0, h)])
        pts = place.inverse(corners)
        pts[[0, 2], 1] = 0.0  # the diagonal's ends lie on the fold line exactly
        inputs = {"width": w, "height": h, "apex_fraction": f}
        return cls.polygon(pts, to_sheet=place, kind="rectangle", inputs=inputs)

    # -- measures -----------------------------------------------------------
    @property
    def edges(self) -> NDArray[np.float64]:
        """``(n, 2, 2)`` edge endpoints (closed)."""
        v = self.vertices
        return np.stack([v, np.roll(v, -1, axis=0)], axis=1)

    @property
    def area(self) -> float:
        """Flat area (length^2)."""
        v = self.vertices
        return 0.5 * float(np.sum(_cross(v, np.roll(v, -1, axis=0))))

    @property
    def perimeter(self) -> float:
        """Flat perimeter (length)."""
        v = self.vertices
        return float(np.sum(np.hypot(*(np.roll(v, -1, axis=0) - v).T)))

    @property
    def size(self) -> float:
        """The sheet's largest distance from H (length), a scale for tolerances."""
        return float(np.max(np.hypot(self.vertices[:, 0], self.vertices[:, 1])))

    @cached_property
    def minus_x_index(self) -> int:
        """Index of the vertex where the boundary crosses the -x axis."""
        v = self.vertices
        return int(np.flatnonzero((v[:, 1] == 0.0) & (v[:, 0] < 0.0))[0])

    @cached_property
    def crease_lengths(self) -> tuple[float, float]:
        """Flat lengths of the fold line from H towards +x and towards -x."""
        v = self.vertices
        return float(v[0, 0]), float(-v[self.minus_x_index, 0])

    @cached_property
    def polar_angles(self) -> NDArray[np.float64]:
        """``(n,)`` polar angle of each vertex in [0, 2 pi) (radians, CCW from +x);
        read-only, computed once."""
        v = self.vertices
        a = np.arctan2(v[:, 1], v[:, 0]) % _TWO_PI
        a[0] = 0.0
        a.setflags(write=False)
        return a

    @cached_property
    def _side_angles(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Flat angles theta (radians, read-only) of the vertices of the upper
        (y >= 0, counter-clockwise from +x) and the lower side (clockwise from
        +x), each sorted from 0 to pi, both ends included."""
        a = self.polar_angles
        k = self.minus_x_index
        upper = np.concatenate([a[: k + 1], [math.pi]])
        lower = np.concatenate([[0.0], _TWO_PI - a[k:]])
        upper[0] = lower[0] = 0.0
        out = np.unique(np.clip(upper, 0.0, math.pi)), np.unique(np.clip(lower, 0.0, math.pi))
        for side in out:
            side.setflags(write=False)
        return out

    @cached_property
    def _edge_table(self) -> tuple[NDArray[np.float64], ...]:
        """Per edge k (vertex k to k + 1): its x and y extent and the cross
        product vertex_k x edge_k, for :meth:`_rays`."""
        v = self.vertices
        e = np.roll(v, -1, axis=0) - v
        return e[:, 0].copy(), e[:, 1].copy(), _cross(v, e)

    def _rays(
        self, psi: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """Distances from H to the boundary along polar angles ``psi`` (radians,
        any), with cos(psi) and sin(psi): three ``(k,)`` arrays. Exact: one line
        intersection per ray, ``rho = (v_k x e_k) / (d x e_k)`` with d the ray's
        unit direction and e_k the edge the ray meets."""
        return self._rays_at(np.asarray(psi, dtype=float) % _TWO_PI)

    def _rays_at(
        self, ang: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """:meth:`_rays` for polar angles ``ang`` already in [0, 2 pi) (fold
        builds them so, which saves the reduction)."""
        # polar_angles is increasing from 0 and ang >= 0, so the index is in [0, n - 1]
        i = self.polar_angles.searchsorted(ang, side="right")
        i -= 1
        ex, ey, moment = self._edge_table
        c, s = np.cos(ang), np.sin(ang)
        den = c * ey.take(i)
        den -= s * ex.take(i)
        return np.divide(moment.take(i), den, out=den), c, s

    def ray_lengths(self, psi: ArrayLike) -> NDArray[np.float64]:
        """Distance from H to the boundary along polar angles ``psi`` (radians, any).

        Returns ``(k,)`` lengths; exact (one line intersection per ray).
        """
        return self._rays(psi)[0]

    def sample_boundary(self, max_step: float) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
        """Points along the closed boundary no further apart than ``max_step``.

        Returns ``(points (m, 2), vertex_index (n,))``: the samples (vertices
        included, not repeating the first) and where each vertex sits in them.
        """
        v = self.vertices
        nxt = np.roll(v, -1, axis=0)
        seg = np.hypot(*(nxt - v).T)
        counts = np.maximum(1, np.ceil(seg / positive("max_step", max_step)).astype(int))
        pts = [v[k] + (nxt[k] - v[k]) * (np.arange(c)[:, None] / c) for k, c in enumerate(counts)]
        index = np.concatenate([[0], np.cumsum(counts)[:-1]])
        return np.concatenate(pts), index.astype(np.int64)

    def __repr__(self) -> str:
        return f"Sheet(kind={self.kind!r}, vertices={len(self.vertices)}, area={self.area:.6g})"
