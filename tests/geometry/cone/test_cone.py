"""The exact cone's frames at flat angles (geometry/cone/cone.py): one call over many
angles, one call per angle, and an independent developed angle."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from onefold_cad import FrameCurve
from onefold_cad.geometry.solver import solve
from tests.geometry import mp_reference as mp_ref


def _cone(alpha: float, beta: float, place: float):
    frame = FrameCurve(alpha, beta, place * 100.0 * math.cos(math.radians(alpha)), 100.0, 90)
    return frame, solve(frame, "exact").surface


def _angles(total: float, seed: int) -> np.ndarray:
    """Both ends, angles just inside them, a uniform grid and random angles."""
    near = np.geomspace(1e-15, 1e-2, 14)
    rng = np.random.default_rng(seed)
    return np.concatenate(
        [[0.0, total], near, total - near, np.linspace(0.0, total, 41), rng.uniform(0, total, 40)]
    )


@settings(max_examples=20, deadline=None)
@given(
    alpha=st.floats(5.0, 85.0),
    beta=st.floats(5.0, 85.0),
    place=st.floats(-0.99, 0.99),
    seed=st.integers(0, 2**16),
)
def test_frames_of_many_angles_in_one_call_are_each_angles_own(
    alpha: float, beta: float, place: float, seed: int
) -> None:
    # every angle is iterated until its own Newton step is small: the batch
    # does not change an angle's s beyond the rounding of the vectorised sums,
    # so u and e (unit vectors) agree to a few rounding errors
    _, cone = _cone(alpha, beta, place)
    theta = _angles(cone.total_angle, seed)
    u, e = cone.frames(theta)
    for t, ui, ei in zip(theta, u, e, strict=True):
        u1, e1 = cone.frames(np.array([t]))
        np.testing.assert_allclose(u1[0], ui, rtol=0, atol=2e-15)
        np.testing.assert_allclose(e1[0], ei, rtol=0, atol=2e-15)
    # and reordering the batch changes nothing either
    order = np.random.default_rng(seed).permutation(len(theta))
    ur, _ = cone.frames(theta[order])
    np.testing.assert_allclose(ur, u[order], rtol=0, atol=2e-15)


def test_the_crease_ends_are_the_arc_ends_exactly() -> None:
    _, cone = _cone(32.0, 34.0, 0.3)
    _, plus, s = cone._split(np.array([0.0, cone.total_angle]))
    assert plus.tolist() == [True, False]
    assert s.tolist() == [0.0, 0.0]


def test_the_ruling_at_a_flat_angle_develops_to_it_independently() -> None:
    # the ray from the apex along u(theta) meets the arc at a point whose
    # developed angle, integrated by mpmath from the inputs alone, is theta to
    # a few rounding errors (u itself is rounded)
    for alpha, beta, place in ((32.0, 34.0, 0.68), (50.0, 45.0, 0.0), (80.0, 10.0, -0.95)):
        frame, cone = _cone(alpha, beta, place)
        total = cone.total_angle
        theta = np.array([1e-3, 0.2, 0.5, 0.8, 1.0 - 1e-3]) * total
        u, _ = cone.frames(theta)
        for t, ui in zip(theta, u, strict=True):
            got = mp_ref.developed_angle(frame, cone.height, tuple(ui))
            assert abs(got - t) <= 1e-14, (alpha, beta, place, t, got - t)


def test_frames_at_arc_parameters_are_the_frames_at_their_flat_angles() -> None:
    # frames_at_arc(phi) is frames(theta) at phi = phi_of_theta(theta) (frames
    # is checked against mpmath above) without inverting theta, both ends and
    # both halves of the arc included
    for alpha, beta, place in ((32.0, 34.0, 0.68), (50.0, 45.0, 0.0), (80.0, 10.0, -0.95)):
        _, cone = _cone(alpha, beta, place)
        theta = _angles(cone.total_angle, 5)
        u, e = cone.frames_at_arc(cone.phi_of_theta(theta))
        u0, e0 = cone.frames(theta)
        np.testing.assert_allclose(u, u0, rtol=0, atol=2e-15)
        np.testing.assert_allclose(e, e0, rtol=0, atol=2e-15)
