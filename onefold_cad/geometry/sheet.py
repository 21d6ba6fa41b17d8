"""The flat sheet: a simple polygon, star-shaped about H, in the fold frame.

Fold frame: the fold line is the x axis and H is the origin. Vertices are kept
counter-clockwise, start at the boundary's crossing of the +x axis, and every
crossing of the x axis is a vertex, so the upper (y >= 0) and lower (y <= 0)
boundaries are vertex runs of their own."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property, lru_cache
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.errors import InvalidParameterError, InvalidSheetError
from onefold_cad.geometry.checks import (
    MAX_LENGTH,
    MIN_LENGTH,
    finite,
    float_errors,
    length,
    positive,
    shown,
)
from onefold_cad.geometry.numeric import cross2, edge_lengths_2d, polygon_area, sorted_unique
from onefold_cad.geometry.polygon import TOUCH, boundary_distance, check_simple

__all__ = ["MAX_VERTICES", "MIN_FEATURE", "Placement2D", "Sheet", "sheet_inradius"]

_TWO_PI = 2.0 * math.pi
#: Most vertices a polygon sheet may have. A polygon of 10 000 vertices follows
#: a smooth outline (a circle at the worst) to 1 - cos(pi / 10 000) < 5e-8 of
#: its size, below the 1e-7 tolerance, so a user never needs more; at the cap,
#: validating, folding and writing the flat pattern and DXF take well under
#: a second each (docs/reliability.md).
MAX_VERTICES = 10_000
#: Smallest feature of a quadrilateral or rectangle sheet relative to the
#: sheet's size: a side length, a distance along an axis, H's distance from a
#: corner. The polygon check puts points within 1e-12 of the size of the fold
#: line on it; 1e-9 keeps every vertex a thousand times clear of that.
MIN_FEATURE = 1e-9


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


def _validated(p: NDArray[np.float64], scale: float, name: str) -> NDArray[np.float64]:
    """The checks of :meth:`Sheet.polygon` on finite vertices ``(n, 2)`` whose
    largest coordinate magnitude ``scale`` is within the length bounds; returns
    them counter-clockwise, with coordinates within 1e-12 * scale of the fold
    line set on it.

    A polygon whose vertices, seen from H, turn strictly counter-clockwise (each
    edge by less than 180 deg) once around is simple: its edges lie in disjoint
    angular sectors. That O(n) test accepts every valid sheet; only a polygon
    that fails it goes through the O(n log n) :func:`check_simple`, so that a
    self-intersection is reported as one before the other reasons.
    """
    p = p.copy()
    p[np.abs(p[:, 1]) <= TOUCH * scale, 1] = 0.0  # on the fold line up to rounding
    nxt = np.roll(p, -1, axis=0)
    seglen = np.hypot(*(nxt - p).T)
    if scale == 0.0 or np.any(seglen <= TOUCH * scale):
        k = int(np.argmin(seglen))
        raise InvalidSheetError(name, f"vertices {k} and {(k + 1) % len(p)} coincide")
    if float(np.sum(cross2(p, nxt))) < 0.0:
        p = p[::-1].copy()
        nxt = np.roll(p, -1, axis=0)
        seglen = np.hypot(*(nxt - p).T)
    r = np.hypot(p[:, 0], p[:, 1])
    steps = np.arctan2(cross2(p, nxt), np.einsum("ij,ij->i", p, nxt))
    winding = round(float(np.sum(steps)) / _TWO_PI)
    edge_dist = np.abs(cross2(p, nxt - p)) / seglen
    on_edge = (edge_dist <= TOUCH * scale) & (np.einsum("ij,ij->i", p, nxt) <= 0.0)
    if (
        winding == 1
        and bool(np.all(steps > 1e-12))
        and bool(np.all(steps < math.pi))
        and bool(np.all(r > TOUCH * scale))
        and not bool(np.any(on_edge))
    ):
        return p  # strictly star-shaped about H, hence simple
    check_simple(p, name)
    if np.any(r <= TOUCH * scale):
        raise InvalidSheetError(name, "H (the origin) must lie strictly inside, not on a vertex")
    if np.any(on_edge) or winding == 0:
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
    raise InvalidSheetError(  # a simple polygon winds once about a point inside it
        name, f"polygon self-intersects: it winds {winding} times around H"
    )


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
        inputs: the values it was made from (for reports; 'polygon': [[x, y], ...]).
    """

    vertices: NDArray[np.float64]
    to_sheet: Placement2D = field(default_factory=Placement2D)
    kind: str = "polygon"
    inputs: dict[str, Any] = field(default_factory=dict)

    # -- constructors -------------------------------------------------------
    @classmethod
    def polygon(
        cls,
        points: ArrayLike | Sequence[Sequence[float]],
        *,
        name: str = "polygon",
        to_sheet: Placement2D | None = None,
        kind: str = "polygon",
        inputs: dict[str, Any] | None = None,
    ) -> Sheet:
        """Validate a polygon given in the fold frame and return the sheet.

        Args:
            points: ``(n, 2)`` vertices, either orientation, not repeating the
                first vertex at the end.
            name: the parameter name used in error messages.

        Raises:
            InvalidSheetError: fewer than 3 or more than :data:`MAX_VERTICES`
                (10 000) vertices, non-finite coordinates, the largest
                coordinate magnitude outside [1e-30, 1e30] (see
                :data:`onefold_cad.geometry.checks.MAX_LENGTH`), repeated
                vertices, self-intersection, H not strictly inside, or not
                strictly star-shaped about H. Points within 1e-12 of the
                largest coordinate magnitude of each other coincide.
        """
        try:
            p = np.array(points, dtype=float)
        except (TypeError, ValueError, OverflowError):
            raise InvalidSheetError(name, "must be a list of (x, y) pairs") from None
        if p.ndim != 2 or p.shape[1] != 2:
            raise InvalidSheetError(name, f"must be a list of (x, y) pairs, got shape {p.shape}")
        if len(p) > 1 and np.array_equal(p[0], p[-1]):
            p = p[:-1]
        if len(p) < 3:
            raise InvalidSheetError(name, f"needs at least 3 vertices, got {len(p)}")
        if len(p) > MAX_VERTICES:
            raise InvalidSheetError(
                name,
                f"must have at most {MAX_VERTICES} vertices, got {len(p)} (at {MAX_VERTICES} "
                "a polygon follows any smooth outline to 5e-8 of its size; sample it coarser)",
            )
        if not np.all(np.isfinite(p)):
            raise InvalidSheetError(name, "vertex coordinates must be finite numbers (no NaN/inf)")
        scale = float(np.max(np.abs(p)))
        if scale > MAX_LENGTH or 0.0 < scale < MIN_LENGTH:
            raise InvalidSheetError(
                name,
                f"the largest vertex coordinate magnitude must be in [{MIN_LENGTH:g}, "
                f"{MAX_LENGTH:g}] (design units; beyond, products of lengths leave double "
                f"precision), got {shown(scale)}",
            )
        with float_errors():
            p = _validated(p, scale, name)
        q = _insert_axis_crossings(p)
        q.setflags(write=False)
        return cls(q, to_sheet or Placement2D(), kind, dict(inputs or {"polygon": p.tolist()}))

    @classmethod
    def quadrilateral(cls, x_plus: float, x_minus: float, y_plus: float, y_minus: float) -> Sheet:
        """The paper's quadrilateral (section 3.4) with vertices on the axes.

        Args:
            x_plus, x_minus: distances from H to the vertices on the +x and -x
                axis (X+ and X-), in [1e-30, 1e30].
            y_plus, y_minus: distances from H to the vertices on the +y and -y
                axis (Y+ and Y-), in [1e-30, 1e30].

        Each of the four must be at least :data:`MIN_FEATURE` (1e-9) times the
        largest of them.
        """
        xp = length("x_plus", x_plus)
        xm = length("x_minus", x_minus)
        yp = length("y_plus", y_plus)
        ym = length("y_minus", y_minus)
        values = {"x_plus": xp, "x_minus": xm, "y_plus": yp, "y_minus": ym}
        big = max(values.values())
        for key, v in values.items():
            if v < MIN_FEATURE * big:
                raise InvalidParameterError(
                    key,
                    f"must be at least {MIN_FEATURE:g} times the largest of x_plus, x_minus, "
                    f"y_plus, y_minus ({big:g}), i.e. >= {MIN_FEATURE * big:g}, got {shown(v)} "
                    "(smaller sheet features are lost in the sheet's rounding)",
                )
        pts = [(xp, 0.0), (0.0, yp), (-xm, 0.0), (0.0, -ym)]
        inputs = dict(values)
        return cls.polygon(pts, kind="quadrilateral", inputs=inputs)

    @classmethod
    @lru_cache(maxsize=64)  # a sweep's designs share one (immutable: read-only arrays)
    def rectangle(cls, width: float, height: float, apex_fraction: float = 0.5) -> Sheet:
        """A ``width`` x ``height`` rectangle folded along its diagonal (the
        same sheet again for the same arguments, with what it has derived).

        The sheet's own frame has a corner at the origin and its sides on the
        axes; the fold runs along the diagonal from (0, 0) to (width, height)
        and H lies at ``apex_fraction`` of the way along it. The fold frame's
        +x axis points towards (width, height).

        Args:
            width, height: side lengths in [1e-30, 1e30], the shorter at least
                :data:`MIN_FEATURE` (1e-9) times the longer.
            apex_fraction: in [1e-9, 1 - 1e-9], i.e. the open (0, 1) less the
                last 1e-9 of the diagonal at each end.
        """
        w = length("width", width)
        h = length("height", height)
        short, long_ = ("width", "height") if w < h else ("height", "width")
        if min(w, h) < MIN_FEATURE * max(w, h):
            raise InvalidParameterError(
                short,
                f"must be at least {MIN_FEATURE:g} times the {long_} ({max(w, h):g}), got "
                f"{min(w, h):g} (a thinner sheet is lost in its rounding)",
            )
        f = finite("apex_fraction", apex_fraction)
        if not MIN_FEATURE <= f <= 1.0 - MIN_FEATURE:
            raise InvalidParameterError(
                "apex_fraction",
                f"must be in [{MIN_FEATURE:g}, 1 - {MIN_FEATURE:g}] (within (0, 1), H at least "
                f"{MIN_FEATURE:g} of the diagonal from a corner), got {shown(f)}",
            )
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
        return polygon_area(self.vertices)

    @property
    def perimeter(self) -> float:
        """Flat perimeter (length)."""
        return float(np.sum(edge_lengths_2d(self.vertices)))

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
    def side_angles(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Flat angles theta (radians, read-only) of the vertices of the upper
        (y >= 0, counter-clockwise from +x) and the lower side (clockwise from
        +x), each sorted from 0 to pi, both ends included."""
        a = self.polar_angles
        k = self.minus_x_index
        upper = np.concatenate([a[: k + 1], [math.pi]])
        lower = np.concatenate([[0.0], _TWO_PI - a[k:]])
        upper[0] = lower[0] = 0.0
        out = (
            sorted_unique(np.clip(upper, 0.0, math.pi)),
            sorted_unique(np.clip(lower, 0.0, math.pi)),
        )
        for side in out:
            side.setflags(write=False)
        return out

    @cached_property
    def _vertex_radii(self) -> NDArray[np.float64]:
        """``(n,)`` each vertex's distance from H (length)."""
        return np.hypot(self.vertices[:, 0], self.vertices[:, 1])

    @cached_property
    def _ray_table(self) -> NDArray[np.float64]:
        """``(5, n + 1)`` per edge k (vertex k to k + 1), in column k + 1: its x
        and y extent, the cross product vertex_k x edge_k, the polar angle of
        vertex k and its distance from H, for :meth:`rays_at` (column 0
        repeats edge 0; ``polar_angles.searchsorted(angle, 'right')`` indexes
        it). Read-only."""
        v = self.vertices
        e = np.roll(v, -1, axis=0) - v
        table = np.empty((5, len(v) + 1))
        rows = table[:, 1:]
        rows[0], rows[1] = e[:, 0], e[:, 1]
        rows[2] = cross2(v, e)
        rows[3] = self.polar_angles
        rows[4] = self._vertex_radii
        table[:, 0] = rows[:, 0]
        table.setflags(write=False)
        return table

    def _rays(
        self, psi: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """Distances from H to the boundary along polar angles ``psi`` (radians,
        any), with cos(psi) and sin(psi): three ``(k,)`` arrays. Exact: one line
        intersection per ray, ``rho = (v_k x e_k) / (d x e_k)`` with d the ray's
        unit direction and e_k the edge the ray meets."""
        return self.rays_at(np.asarray(psi, dtype=float) % _TWO_PI)

    def rays_at(
        self, ang: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """:meth:`_rays` for polar angles ``ang`` already in [0, 2 pi) (fold
        builds them so, which saves the reduction)."""
        # polar_angles is increasing from 0 and ang >= 0: the edge index is in
        # [0, n - 1], and the table's column is one more
        ex, ey, moment, start, radius = self._ray_table.take(
            self.polar_angles.searchsorted(ang, side="right"), axis=1
        )
        c, s = np.cos(ang), np.sin(ang)
        den = c * ey
        den -= s * ex
        rho = np.divide(moment, den, out=den)
        # a ray at a vertex's own angle ends at the vertex: the edge from it may
        # run almost along the ray (an edge passing 1e-9 of the size from H),
        # where the intersection would lose up to 1e-7 of the size
        np.copyto(rho, radius, where=start == ang)
        return rho, c, s

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


def sheet_inradius(sheet: Sheet) -> float:
    """Distance from H to the nearest point of the sheet's boundary (length)."""
    return boundary_distance(sheet.vertices)
