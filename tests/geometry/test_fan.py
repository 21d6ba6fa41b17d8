"""A paper fan over chosen division points (geometry/fan.py, ArcSpacing): the
paper's equal steps passed explicitly change nothing, to the bit; a graded
fan meets the angle condition and folds isometrically, both checked here from
the frame curve's own formula (paper section 3.2) without the fan's code."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from onefold_cad import FrameCurve, InvalidParameterError, NoSolutionError, Sheet, fold, solve
from onefold_cad.geometry.arc import ArcSpacing
from onefold_cad.geometry.fan import PaperFan


def _fractions(spacing: ArcSpacing) -> np.ndarray:
    """The division points' arc parameters as fractions of the span, +x end first."""
    s = np.asarray(spacing.steps)
    return np.concatenate((s[: spacing.front], spacing.per_span - s[spacing.front :])) / (
        spacing.per_span
    )


def _paper_points(frame: FrameCurve, t: np.ndarray) -> np.ndarray:
    """Frame-curve points at span fractions ``t`` by the paper's formula:
    phi = -alpha + t (180 + 2 alpha), x = R cos(phi) - h_c,
    d = R (sin(alpha) + sin(phi)), placed at (x, d cos(beta), d sin(beta))."""
    a, b = math.radians(frame.alpha), math.radians(frame.beta)
    phi = -a + t * (math.pi + 2.0 * a)
    x = frame.radius * np.cos(phi) - frame.h_c
    d = frame.radius * (math.sin(a) + np.sin(phi))
    return np.stack([x, d * math.cos(b), d * math.sin(b)], axis=1)


@pytest.mark.parametrize("n", [2, 7, 10, 90, 3000])
def test_equal_steps_passed_explicitly_change_nothing(n):
    frame = FrameCurve(50.0, 45.0, 12.0, 100.0, n)
    a, b = solve(frame, "paper"), solve(frame, "paper", ArcSpacing.uniform(n))
    assert a.apex_height == b.apex_height
    assert np.array_equal(a.surface.gammas, b.surface.gammas)
    assert np.array_equal(a.surface.directions, b.surface.directions)
    assert a.surface.spacing is None and b.surface.spacing is not None


@settings(max_examples=30, deadline=None)
@given(
    alpha=st.floats(10.0, 80.0),
    beta=st.floats(10.0, 80.0),
    frac=st.floats(-0.8, 0.8),
    n=st.integers(3, 24),
    first=st.tuples(st.floats(1e-3, 0.2), st.floats(1e-3, 0.2)),
)
def test_a_graded_fan_meets_the_angle_condition_and_folds_isometrically(
    alpha, beta, frac, n, first
):
    """Its directions point at the frame curve's points at the spacing's arc
    parameters; their apex angles (atan2(|a x b|, a . b) from the points and
    the apex) add up to 180 deg per side; each folded triangle A, A + r u_k,
    A + s u_k+1 of the fan has the edge lengths of its flat triangle H,
    r e^(i theta_k), s e^(i theta_k+1), and so has a pair of flat points inside
    one wedge."""
    frame = FrameCurve(alpha, beta, frac * 100.0 * math.cos(math.radians(alpha)), 100.0, n)
    spacing = ArcSpacing.graded(n, first, 3.0)
    try:
        sol = solve(frame, "paper", spacing)
    except NoSolutionError:
        return
    apex = np.array([0.0, 0.0, sol.apex_height])
    v = _paper_points(frame, _fractions(spacing)) - apex
    u = v / np.linalg.norm(v, axis=1, keepdims=True)
    np.testing.assert_allclose(sol.surface.directions, u, atol=1e-12)
    a, b = v[:-1], v[1:]
    gammas = np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), np.einsum("ij,ij->i", a, b))
    assert float(np.sum(gammas)) == pytest.approx(math.pi, abs=1e-11)

    folded = fold(sol, Sheet.quadrilateral(300.0, 300.0, 300.0, 300.0))
    theta = np.concatenate(([0.0], np.cumsum(gammas)))
    rng = np.random.default_rng(5)
    for k in range(n):
        r, s = rng.uniform(1.0, 50.0, 2)
        flat = np.array(
            [
                [0.0, 0.0],
                [r * math.cos(theta[k]), r * math.sin(theta[k])],
                [s * math.cos(theta[k + 1]), s * math.sin(theta[k + 1])],
            ]
        )
        w = theta[k] + rng.uniform(0.0, 1.0, 2) * gammas[k]  # two points inside wedge k
        inside = rng.uniform(1.0, 50.0, 2)[:, None] * np.stack([np.cos(w), np.sin(w)], axis=1)
        for pts in (flat, inside):
            p3 = folded.map_points(pts)
            d2 = np.linalg.norm(pts[:, None] - pts[None], axis=2)
            d3 = np.linalg.norm(p3[:, None] - p3[None], axis=2)
            np.testing.assert_allclose(d3, d2, rtol=1e-9, atol=1e-9)


def test_a_spacing_of_another_division_count_is_refused_naming_spacing():
    frame = FrameCurve(50.0, 45.0, 0.0, 100.0, 10)
    with pytest.raises(InvalidParameterError) as err:
        PaperFan(frame, ArcSpacing.uniform(12))
    assert err.value.parameter == "spacing"
    with pytest.raises(InvalidParameterError) as err:
        solve(frame, "exact", ArcSpacing.uniform(10))
    assert err.value.parameter == "spacing"
