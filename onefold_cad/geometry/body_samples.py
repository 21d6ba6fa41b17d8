"""A body's samples and its evaluation: the side of
:class:`~onefold_cad.geometry.body.FoldedBody` that lays out its pieces' grids,
evaluates them a family at a time (:mod:`.body_families`), and finds the
lowest points of many brackets at once (:mod:`.zoom`). Points relative to the
apex; lengths in the design unit.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from onefold_cad.geometry.body_families import Sectors
from onefold_cad.geometry.numeric import Array, sorted_unique
from onefold_cad.geometry.pieces import Piece, end_minimum
from onefold_cad.geometry.zoom import zoom_many

__all__ = ["Rows", "Sampled"]


@dataclass(frozen=True)
class Rows:
    """A body's grid rows (one per piece and grid parameter, ``M`` in all,
    piece by piece), as its samples hold them.

    Attributes:
        piece, t: the piece of each row and its parameter ``(M,)``.
        first, last: whether a row starts or ends its piece.
        comes: whether a corner came or went since the row before (the cut
            at y = 0 sweeping a thick section's corners).
        start, count: where a row's corners start among the pieces' samples
            (after the fixed points) and how many (0: an empty section).
    """

    piece: NDArray[np.int64]
    t: Array
    first: NDArray[np.bool_]
    last: NDArray[np.bool_]
    comes: NDArray[np.bool_]
    start: NDArray[np.int64]
    count: NDArray[np.int64]


class Sampled:
    """The sampling and evaluation of a body's pieces (a mixin of
    :class:`~onefold_cad.geometry.body.FoldedBody`, which sets the attributes)."""

    pieces: list[Piece]
    fixed: Array
    thickness: float
    _lowest: dict[tuple[int, float, float, bytes], tuple[float, Array]]

    @cached_property
    def _groups(self) -> tuple[NDArray[np.int64], list[list[int]]]:
        """Per piece the group it is evaluated with (the pieces of one family,
        or the piece alone), and each group's pieces."""
        gid = np.zeros(len(self.pieces), dtype=np.int64)
        groups: list[list[int]] = []
        seen: dict[int, int] = {}
        for k, piece in enumerate(self.pieces):
            key = id(piece.family) if piece.family is not None else -1 - k
            if key not in seen:
                seen[key] = len(groups)
                groups.append([])
            gid[k] = seen[key]
            groups[gid[k]].append(k)
        return gid, groups

    def _corners(self, group: int, pieces: NDArray[np.int64], t: Array) -> Array:
        """Corners ``(k, V, 3)`` of ``pieces`` (all of one group) at ``t``."""
        first = self.pieces[int(pieces[0])]
        if first.family is None:
            return first.points(t)
        return first.family.points(self._members[pieces], t)

    @cached_property
    def _members(self) -> NDArray[np.int64]:
        """Each piece's index in its family."""
        return np.array([p.member for p in self.pieces], dtype=np.int64)

    @cached_property
    def sections(self) -> list[Array]:
        """Per piece: the section corners ``(n, V, 3)`` at its grid (one
        evaluation per family)."""
        return self._sampled[0]

    @cached_property
    def boxes(self) -> list[Array | None]:
        """Per piece: the corners ``(n, 4, 3)`` of the uncut rectangle about
        each of the solid's sheet-edge sections (every point of the section
        lies in it), or None."""
        return self._sampled[1]

    @cached_property
    def _sampled(self) -> tuple[list[Array], list[Array | None]]:
        out: list[Array] = [np.zeros((0, 1, 3))] * len(self.pieces)
        boxes: list[Array | None] = [None] * len(self.pieces)
        for g, group in enumerate(self._groups[1]):
            owner, t, corners = self._group_rows[g]
            family = self.pieces[group[0]].family
            box = None
            if isinstance(family, Sectors):
                corners, box = family.sections(self._members[owner], t, box=True)
            else:
                corners = self._corners(g, owner, t)
            self._group_rows[g] = (owner, t, corners)
            cuts = np.cumsum([len(self.pieces[k].grid) for k in group])[:-1]
            parts = np.split(box, cuts) if box is not None else [None] * len(group)
            for k, part, b in zip(group, np.split(corners, cuts), parts, strict=True):
                out[k], boxes[k] = part, b
        return out, boxes

    @cached_property
    def _group_rows(self) -> list[tuple[NDArray[np.int64], Array, Array]]:
        """Per group: the piece of each of its rows, their parameters and
        (once :attr:`sections` has them) their corners ``(n, V, 3)``."""
        out = []
        for group in self._groups[1]:
            grids = [self.pieces[k].grid for k in group]
            owner = np.repeat(np.array(group, dtype=np.int64), [len(x) for x in grids])
            out.append((owner, np.concatenate(grids), np.zeros((0, 1, 3))))
        return out

    @cached_property
    def _grouped(self) -> bool:
        """Whether the groups hold the pieces in order, each of two rows or
        more: what is per piece can then be done per group (the same values)."""
        order = [k for group in self._groups[1] for k in group]
        return (
            bool(order)
            and order == list(range(len(self.pieces)))
            and all(len(p.grid) >= 2 for p in self.pieces)
        )

    def lowest_corners(self, pieces: NDArray[np.int64], t: Array, g: Array) -> tuple[Array, Array]:
        """At each (piece, parameter, direction ``(k, 3)``): the lowest corner's
        height along the direction ``(k,)`` (+inf where the section is empty)
        and that corner ``(k, 3)``; one evaluation per family."""
        v = np.empty(len(t))
        p = np.empty((len(t), 3))
        gid = self._groups[0][pieces]
        for group in sorted_unique(gid):
            sel = (gid == group).nonzero()[0]
            pts = self._corners(int(group), pieces[sel], t[sel])
            h = np.einsum("kvj,kj->kv", pts, g[sel])
            h[np.isnan(h)] = np.inf
            i = h.argmin(axis=1)
            rows = np.arange(len(sel))
            v[sel] = h[rows, i]
            p[sel] = pts[rows, i]
        return v, p

    @cached_property
    def spacings(self) -> Array:
        """Per piece ``(n,)``: the largest distance between neighbouring
        samples (length), in 3D or along the piece (on the flat sheet), plus
        the thickness: no point of the piece lies further than that from its
        nearest sample (the thickness covers the offsets of a thick sheet)."""
        out = np.zeros(len(self.pieces))
        if self._grouped:
            self.sections  # noqa: B018 (the groups' corners)
            for group, (owner, _, corners) in zip(self._groups[1], self._group_rows, strict=True):
                d = np.diff(corners, axis=0)
                # np.linalg.norm's sum of squares, its three terms in its order
                steps = d[..., 0] * d[..., 0]
                steps += d[..., 1] * d[..., 1]
                steps += d[..., 2] * d[..., 2]
                np.sqrt(steps, out=steps)
                steps[owner[1:] != owner[:-1]] = np.nan  # between two pieces: none
                # per piece (its rows' steps, then the NaN to the next piece's)
                starts = np.searchsorted(owner, group)
                most = np.fmax.reduce(np.fmax.reduceat(steps, starts, axis=0), axis=1)
                most = np.where(np.isnan(most), 0.0, most)
                step = np.array([self.pieces[k].step for k in group])
                out[group] = np.maximum(step, most)
            return out + self.thickness
        for i, (piece, corners) in enumerate(zip(self.pieces, self.sections, strict=True)):
            steps = np.linalg.norm(np.diff(corners, axis=0), axis=-1)
            steps = steps[~np.isnan(steps)]
            out[i] = max(piece.step, float(steps.max()) if len(steps) else 0.0)
        return out + self.thickness

    @cached_property
    def samples(self) -> tuple[Array, NDArray[np.int64], Array]:
        """Sample points ``(N, 3)`` of every piece and fixed point, with the
        piece each belongs to ``(N,)`` (-1: a fixed point) and its parameter:
        the fixed points, then each piece's section corners, row by row."""
        pts = [self.fixed]
        owner = [np.full(len(self.fixed), -1, dtype=np.int64)]
        param = [np.zeros(len(self.fixed))]
        if self._grouped:
            self.sections  # noqa: B018 (the groups' corners)
            for rows, t, p in self._group_rows:
                ok = ~np.isnan(p[..., 0])
                pts.append(p[ok])
                owner.append(np.broadcast_to(rows[:, None], ok.shape)[ok])
                param.append(np.broadcast_to(t[:, None], ok.shape)[ok])
            return np.concatenate(pts), np.concatenate(owner), np.concatenate(param)
        for i, (piece, p) in enumerate(zip(self.pieces, self.sections, strict=True)):
            ok = ~np.isnan(p[..., 0])
            pts.append(p[ok])
            owner.append(np.full(int(ok.sum()), i, dtype=np.int64))
            param.append(np.broadcast_to(piece.grid[:, None], ok.shape)[ok])
        return np.concatenate(pts), np.concatenate(owner), np.concatenate(param)

    @cached_property
    def rows(self) -> Rows:
        """The pieces' grid rows as :attr:`samples` holds them (:class:`Rows`)."""
        sizes = [len(c) for c in self.sections]
        piece = np.repeat(np.arange(len(sizes), dtype=np.int64), sizes)
        first = np.zeros(len(piece), dtype=bool)
        first[np.cumsum([0, *sizes[:-1]])[np.array(sizes) > 0]] = True
        if self._grouped:  # a group's rows at once, the pieces' first rows after
            gone = [np.isnan(c[..., 0]) for _, _, c in self._group_rows]
            count = np.concatenate([(~g).sum(axis=1) for g in gone])
            comes = np.zeros(len(piece), dtype=bool)
            at = 0
            for g in gone:  # a corner came or went since the row before
                comes[at + 1 : at + len(g)] = np.any(g[1:] != g[:-1], axis=1)
                at += len(g)
            comes &= ~first
        else:
            gone = [np.isnan(c[..., 0]) for c in self.sections]
            count = np.concatenate([(~g).sum(axis=1) for g in gone]) if gone else np.zeros(0)
            comes = np.zeros(len(piece), dtype=bool)
            for k, g in enumerate(gone):  # a corner came or went since the row before
                at = int(np.cumsum([0, *sizes])[k])
                comes[at + 1 : at + len(g)] = np.any(g[1:] != g[:-1], axis=1)
        start = np.concatenate([[0], np.cumsum(count)[:-1]]).astype(np.int64)
        t = np.concatenate([p.grid for p in self.pieces]) if self.pieces else np.zeros(0)
        last = np.append(first[1:], True)
        return Rows(piece, t, first, last, comes, start, count.astype(np.int64))

    @cached_property
    def row_boxes(self) -> Array:
        """:attr:`boxes` of every row ``(M, 4, 3)`` (NaN for pieces without)."""
        return np.concatenate(
            [
                np.full((len(c), 4, 3), np.nan) if b is None else b
                for c, b in zip(self.sections, self.boxes, strict=True)
            ]
        )

    def lowest_many(
        self,
        asks: list[tuple[int, float, float, Array]],
        group: NDArray[np.int64] | None = None,
        ceiling: Array | None = None,
        known: Array | None = None,
        margin: float = 0.0,
    ) -> list[tuple[float, Array]]:
        """:meth:`lowest` for many (piece, lo, hi, direction) at once: the zooms
        not known yet run together (:func:`~onefold_cad.geometry.zoom.zoom_many`),
        but for a bracket at a piece's end whose samples show the lowest point
        there (:func:`~onefold_cad.geometry.pieces.end_minimum`). With ``group``,
        ``ceiling`` and ``known`` (see ``zoom_many``), a zoom that cannot matter
        stops early: its answer is a point of the bracket, not kept."""
        keys = [
            (k, float(lo), float(hi), (np.asarray(g, dtype=float) + 0.0).tobytes())
            for k, lo, hi, g in asks
        ]
        todo: dict[tuple[int, float, float, bytes], int] = {}
        for i, key in enumerate(keys):
            if key in self._lowest or key in todo:
                continue
            k, lo, hi, g = asks[i]
            end = end_minimum(self.pieces[k].grid, self.sections[k], lo, hi, np.asarray(g))
            if end is not None:  # its samples show it at an end: no zoom
                self._lowest[key] = end
            else:
                todo[key] = i
        found: dict[tuple[int, float, float, bytes], tuple[float, Array]] = {}
        if todo:
            idx = list(todo.values())
            pieces = np.array([asks[i][0] for i in idx], dtype=np.int64)
            gs = np.array([asks[i][3] for i in idx], dtype=float).reshape(-1, 3)

            def f(jobs: NDArray[np.int64], t: Array) -> tuple[Array, Array]:
                return self.lowest_corners(pieces[jobs], t, gs[jobs])

            los = np.array([asks[i][1] for i in idx], dtype=float)
            his = np.array([asks[i][2] for i in idx], dtype=float)
            sub = None if group is None else np.asarray(group)[idx]
            ts, _, ps, done = zoom_many(f, los, his, sub, ceiling, known, margin)
            for j, key in enumerate(todo):
                (self._lowest if done[j] else found)[key] = (float(ts[j]), ps[j])
        out = []
        for key in keys:
            t, p = self._lowest[key] if key in self._lowest else found[key]
            out.append((t, p.copy()))
        return out
