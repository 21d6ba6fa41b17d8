"""The thick solid's edge curves (export/brep/solid.py): fit_curve."""

from __future__ import annotations

import numpy as np

from onefold_cad.export.brep.bspline_fit import fit_curve


def _values(curve, t: np.ndarray) -> np.ndarray:
    return np.array([[p.X(), p.Y(), p.Z()] for p in (curve.Value(float(x)) for x in t)])


def test_fit_curve_evaluates_each_parameter_once_and_meets_its_tolerance():
    """A helix (length 100): the fit reuses the points of the probes it adds
    as nodes (no parameter is evaluated twice), passes through its first
    nodes and the node asked for, and lies within the tolerance reached of
    the helix on a dense sample of its own (up to the interpolant's bulge
    between probes, a few percent)."""
    calls: list[np.ndarray] = []

    def helix(t: np.ndarray) -> np.ndarray:
        calls.append(np.array(t, dtype=float))
        return np.stack([30.0 * np.cos(3.0 * t), 30.0 * np.sin(3.0 * t), 20.0 * t], axis=1)

    tol = 1e-6
    curve, reached = fit_curve(helix, 0.0, 1.0, tol, "a helix", nodes=np.array([0.7]))
    assert len(calls) >= 4  # dense sample, first nodes, then probes until within tol
    every = np.concatenate(calls[1:])
    assert len(np.unique(every)) == len(every)
    assert 0.7 in calls[1]
    first = calls[1]
    np.testing.assert_allclose(_values(curve, first), helix(first), rtol=0, atol=1e-10)
    assert reached <= tol
    t = np.linspace(0.0, 1.0, 4001)
    assert float(np.max(np.linalg.norm(_values(curve, t) - helix(t), axis=1))) <= 1.2 * tol
