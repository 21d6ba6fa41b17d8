"""Many minimisations at once: :func:`~onefold_cad.geometry.resting.pieces.zoom_min`
for a batch of brackets, each with its own function, evaluated together.

A body's search for its lowest points asks for the minimum of many pieces
in many brackets and directions; one by one, each zoom's numpy calls are
small and their overhead is the cost. :func:`zoom_many` runs them in
lockstep: every round lays the 33-point grid over each bracket still
zooming, and evaluates all of them, with the parabola vertices the
previous round predicted, in one call. Per bracket it takes the same
decisions as ``zoom_min`` (the grid, the shrinking bracket, the parabola
test, the stops at an end and at 1e-13 of the first bracket), so it finds
the same minima; the parabola's check is only evaluated one call later,
together with the next round's grid, which is discarded if it says stop.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from onefold_cad.geometry.numeric import Array
from onefold_cad.geometry.resting.pieces import ZOOM_GRID

__all__ = ["zoom_many"]

#: f(jobs (k,), t (k,)) -> (values (k,), points (k, 3)): the value of job j's
#: function at t, and the point it belongs to.
Batch = Callable[[NDArray[np.int64], Array], tuple[Array, Array]]

_STEPS = np.arange(ZOOM_GRID, dtype=float)
_LAST = ZOOM_GRID - 1


def zoom_many(
    f: Batch,
    lo: Array,
    hi: Array,
    group: NDArray[np.int64] | None = None,
    ceiling: Array | None = None,
    known: Array | None = None,
    margin: float = 0.0,
) -> tuple[Array, Array, Array, NDArray[np.bool_]]:
    """The minima of many continuous functions, each on its own bracket
    [lo_j, hi_j] ``(m,)`` (see the module docstring): their parameters,
    values ``(m,)``, points ``(m, 3)``, and whether each was zoomed to the end.

    With ``group`` ``(m,)`` (indices into ``ceiling`` and ``known``), a zoom
    stops early once its bracket cannot hold a value at or below its group's
    ``ceiling`` nor within ``margin`` of the lowest value its group is known
    to reach (``known``, or found here): only a group's lowest value matters,
    and what lies below a height. Its grid's lowest value less the rise to
    the higher of its neighbours bounds it from below (a smooth minimum
    between them, or a kink, lies no lower). Its value is then that of its
    best point so far, not its minimum."""
    lo = np.array(lo, dtype=float)
    hi = np.array(hi, dtype=float)
    m = len(lo)
    span = hi - lo
    best_t, best_v = lo.copy(), np.full(m, np.inf)
    best_p = np.full((m, 3), np.nan)
    at_end = np.zeros(m, dtype=np.int64)
    zooming = np.ones(m, dtype=bool)  # its grid is laid again
    exact = np.ones(m, dtype=bool)
    # the parabola vertex of the last round, checked in the next call
    pend = np.zeros(m, dtype=bool)
    tp, predicted, limit = np.zeros(m), np.zeros(m), np.zeros(m)
    for rounds in range(21):
        grid = zooming.nonzero()[0]
        check = pend.nonzero()[0]
        if not len(grid) and not len(check):
            break
        t = lo[grid, None] + _STEPS * ((hi[grid] - lo[grid]) / _LAST)[:, None]
        t[:, -1] = hi[grid]
        jobs = np.concatenate([check, np.repeat(grid, ZOOM_GRID)])
        vals, pts = f(jobs, np.concatenate([tp[check], t.ravel()]))
        # the last round's parabola vertices first, as zoom_min takes them
        vp, pp = vals[: len(check)], pts[: len(check)]
        better = vp < best_v[check]
        best_t[check] = np.where(better, tp[check], best_t[check])
        best_v[check] = np.where(better, vp, best_v[check])
        best_p[check] = np.where(better[:, None], pp, best_p[check])
        done = np.abs(vp - predicted[check]) <= limit[check]
        zooming[check[done]] = False
        pend[:] = False
        keep = zooming[grid]
        grid, t = grid[keep], t[keep]
        v = vals[len(check) :].reshape(-1, ZOOM_GRID)[keep]
        p = pts[len(check) :].reshape(-1, ZOOM_GRID, 3)[keep]
        if not len(grid):
            continue
        rows = np.arange(len(grid))
        i = v.argmin(axis=1)
        vi = v[rows, i]
        better = vi < best_v[grid]
        best_t[grid] = np.where(better, t[rows, i], best_t[grid])
        best_v[grid] = np.where(better, vi, best_v[grid])
        best_p[grid] = np.where(better[:, None], p[rows, i], best_p[grid])
        finite = np.isfinite(best_v[grid])
        inner = (i > 0) & (i < _LAST) & finite & (rounds >= 1)
        a = v[rows, np.maximum(i - 1, 0)]
        c = v[rows, np.minimum(i + 1, _LAST)]
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            curv = a - 2.0 * vi + c
            fit = inner & (curv > 0.0)
            step = t[:, 1] - t[:, 0]
            tp[grid] = np.where(fit, t[rows, i] + 0.5 * step * (a - c) / curv, 0.0)
            predicted[grid] = np.where(fit, vi - (a - c) ** 2 / (8.0 * curv), 0.0)
            limit[grid] = np.where(fit, 1e-3 * (np.maximum(a, c) - vi), 0.0)
        pend[grid[fit]] = True
        at_end[grid] = np.where((i == 0) | (i == _LAST), at_end[grid] + 1, 0)
        new_lo = t[rows, np.maximum(i - 1, 0)]
        new_hi = t[rows, np.minimum(i + 1, _LAST)]
        lo[grid], hi[grid] = new_lo, new_hi
        stop = ~finite | (new_hi - new_lo <= 1e-13 * span[grid]) | (at_end[grid] >= 3)
        stop |= rounds >= 19
        pend[grid[~finite]] = False
        zooming[grid[stop]] = False
        if group is not None and ceiling is not None:
            # the rise to the higher neighbour (a finite one where the
            # function ends beside the minimum: a section that empties)
            rise = np.fmax(np.where(np.isfinite(a), a, np.nan), np.where(np.isfinite(c), c, np.nan))
            with np.errstate(invalid="ignore", over="ignore"):
                bound = np.where(finite & np.isfinite(rise), 2.0 * vi - rise, -np.inf)
            lowest = (
                np.full(len(ceiling), np.inf) if known is None else np.array(known, dtype=float)
            )
            np.minimum.at(lowest, group, best_v)
            gj = group[grid]
            hopeless = bound > np.maximum(ceiling[gj], lowest[gj] + margin)
            cut = grid[hopeless & zooming[grid]]
            zooming[cut], pend[cut], exact[cut] = False, False, False
    return best_t, best_v, best_p, exact
