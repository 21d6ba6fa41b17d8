"""How fast the paper model's solve + fold could be with numpy: its arithmetic alone.

:func:`floor_solve_fold` runs the numerical work of
``fold(solve(frame, "paper"), sheet)`` by calling the package's own
arithmetic -- :class:`~onefold_cad.geometry.fan.PaperFan` (division points and
the search's quadratic coefficients), its batched ``excesses`` for the
12-height probe and the 5-height probe, the search's written-out inverse
interpolation (``neville6``, ``neville5``, ``slope5``), ``set_apex`` (the
unit directions and Kahan's apex angles) and the sheet's ray table
(``Sheet.rays_at``) -- with everything around it removed: no validation, no
second search when the first probe does not bracket the root, no
verification bound, no record of the evaluations, no dataclasses, no vertex
rays, no crease halves.

It is not a solver: it trusts that the first probe brackets the root and the
second converges, which holds for the paper's Table 1 rows it is timed on
(and is checked there: it must return the same apex height as ``solve``).
``bench_solver.py`` times it beside ours: the gap between the two is what
cutting Python overhead could still win; the floor's own ratio to the paper's
method is as far as this numpy arithmetic can go.
"""

from __future__ import annotations

import math

import numpy as np

from onefold_cad import FrameCurve, Sheet
from onefold_cad.geometry.fan import PaperFan
from onefold_cad.geometry.root import GRID_HEIGHTS, SPACING, neville5, neville6, slope5

__all__ = ["floor_solve_fold"]


def floor_solve_fold(frame: FrameCurve, sheet: Sheet) -> tuple[float, np.ndarray, np.ndarray]:
    """The apex height (length), the flat and the folded ruling ends ``(m, 2)``
    and ``(m, 3)`` of both sides (the fan's division rays only)."""
    fan = PaperFan(frame)
    g = fan.geometry
    l0 = (1.0 + g.sin_alpha) * g.sin_beta
    hs = (GRID_HEIGHTS * l0).tolist()
    fs = fan.excesses(GRID_HEIGHTS * l0).tolist()
    k = next(i for i, f in enumerate(fs) if f < 0.0)  # the first height past the root
    j = min(max(k - 3, 0), len(hs) - 6)
    est = neville6(fs[j : j + 6], hs[j : j + 6])
    delta = SPACING * est
    h5 = [est + delta * i for i in (-2, -1, 0, 1, 2)]
    f5 = fan.excesses(np.array(h5)).tolist()
    h = neville5(f5, h5)
    slope5(h5, f5, h)
    r = frame.radius
    fan.set_apex(h * r)
    assert fan.thetas is not None and fan.directions is not None
    theta = fan.thetas
    ang = np.concatenate((theta, 2.0 * math.pi - theta))
    ang[len(theta)] = 0.0
    rho, cos, sin = sheet.rays_at(ang % (2.0 * math.pi))
    flat = np.stack((rho * cos, rho * sin), axis=1)
    ends = np.concatenate((fan.directions, fan.directions)) * rho[:, None]
    ends[len(theta) :, 1] *= -1.0
    ends[:, 2] += h * r
    return h * r, flat, ends
