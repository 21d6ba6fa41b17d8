"""The start of a continuation's next solve: the polynomial through the last
equilibria along the path, extrapolated to the next step's parameter.

A load path that is followed in steps (``equilibrium.solve_path``) knows the
states it has passed. Newton started from the last of them reaches the next
through its first iterate, the tangent's linear prediction, whose error is
of second order in the step; the polynomial of degree ``k`` through the last
``k + 1`` equilibria errs in order ``k + 1``. On the J2 release of
patkau-one-fold (coarse, steps of 1/8) the largest node error of the next
equilibrium's start is 13 to 46 mm from the tangent, 5 to 14 mm from the
line through two, 0.9 to 2.4 mm from the parabola through three and 0.3 to
0.7 mm from the cubic through four.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

__all__ = ["extrapolate"]

F = NDArray[np.float64]


def extrapolate(
    path: Sequence[tuple[float, F]], target: float, held: NDArray[np.bool_] | None = None
) -> F:
    """The polynomial through ``path``'s states at their parameters, at ``target``.

    Args:
        path: ``(s, q)`` pairs, distinct ``s`` (the path parameter, 0..1) and
            ``(N,)`` states; the degree is one less than their number (one
            pair: that state).
        target: the parameter to predict at.
        held: ``(N,)`` bool, or None: unknowns kept at the last state's values
            (supports, nodes on the ground: the next solve holds them where
            they are).

    Returns:
        ``(N,)`` the predicted state.

    Raises:
        ValueError: ``path`` is empty or repeats a parameter.
    """
    if not path:
        raise ValueError("extrapolate needs at least one state")
    params = [float(s) for s, _ in path]
    if len(set(params)) != len(params):
        raise ValueError(f"the path's parameters repeat: {params}")
    last = np.asarray(path[-1][1], dtype=float)
    out = np.zeros_like(last)
    for i, (si, qi) in enumerate(path):
        weight = 1.0
        for j, sj in enumerate(params):
            if j != i:
                weight *= (target - sj) / (si - sj)
        out += weight * np.asarray(qi, dtype=float)
    if held is not None:
        out[held] = last[held]
    return out
