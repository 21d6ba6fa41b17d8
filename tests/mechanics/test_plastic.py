"""The elastic-perfectly-plastic law (mechanics/plastic.py) and the plastic solves:
Gardiner's springback, no set below yield, an elastic-plastic cantilever."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from onefold_cad.mechanics import (
    Shell,
    ShellMaterial,
    flat_positions,
    form_sheet,
    pack,
    plastic,
    second_fundamental_form,
    solve_equilibrium,
    solve_plastic,
)
from onefold_cad.mechanics.plastic import skeleton_moment, skeleton_work
from tests.mechanics.helpers import cantilever, circle_radius, cylinder, rectangle
from tests.mechanics.reference import gardiner_ratio

STEEL = ShellMaterial(
    youngs_modulus=200e9, poisson=0.3, thickness=1e-3, density=7850.0, yield_stress=250e6
)


def test_skeleton_law():
    mat = STEEL
    ky, d = mat.yield_curvature, mat.bending_stiffness
    assert math.isclose(mat.yield_moment, d * ky, rel_tol=1e-14), "M_y = D kappa_y"
    below, above = skeleton_moment(mat, [ky * (1 - 1e-12), ky * (1 + 1e-12)])
    assert math.isclose(below, above, rel_tol=1e-10), "continuous at yield"
    assert math.isclose(float(skeleton_moment(mat, 1e6 * ky)), mat.plastic_moment, rel_tol=1e-11)
    k = np.linspace(0.1, 6, 40) * ky
    step = 1e-7 * ky
    dw = (skeleton_work(mat, k + step) - skeleton_work(mat, k - step)) / (2 * step)
    np.testing.assert_allclose(dw, skeleton_moment(mat, k), rtol=1e-7)
    # Gardiner from the law itself: unload with slope D from k_i = 1 / R_i.
    for x in (0.02, 0.2, 0.45):
        ri = x * mat.plane_modulus * mat.thickness / mat.yield_stress
        kf = 1 / ri - float(skeleton_moment(mat, 1 / ri)) / d
        assert math.isclose(kf * ri, gardiner_ratio(x), rel_tol=1e-12)


def test_forming_and_the_return_mapping():
    """Form four faces (one below yield), then move them on: one bends further
    (it yields again, its moment the skeleton's at its whole curvature), one
    below yield goes past it, one unloads (elastic: nothing changes), one
    unloads past a rectangular section's reverse yield (2 M_y, reported) and past
    the model's own (-M_r: isotropic hardening), so it yields in reverse."""
    mat = STEEL
    form_k = np.tile(np.diag([1.0, 0.5, 1.0])[None], (4, 1, 1))  # nu = 0, orthonormal
    ky, d = mat.yield_curvature, mat.bending_stiffness
    b = np.array([[3 * ky, 0, 0], [0.5 * ky, 0, 0], [3 * ky, 0, 0], [3 * ky, 0, 0]])
    state, work = plastic.form(mat, form_k, b, np.ones(4))
    assert list(state.plastic(mat)) == [True, False, True, True]
    assert np.all(state.rest[1] == 0), "no set below yield"
    np.testing.assert_allclose(work, skeleton_work(mat, np.abs(b[:, 0])), rtol=1e-14)
    # the rest form unloads the skeleton's moment elastically: b_p = b - M_s(b) / D
    np.testing.assert_allclose(state.rest[0, 0], 3 * ky - float(skeleton_moment(mat, 3 * ky)) / d)
    now = np.array([[3.3 * ky, 0, 0], [1.2 * ky, 0, 0], [2 * ky, 0, 0], [-0.5 * ky, 0, 0]])
    after, yielded = plastic.update(mat, form_k, now, state)
    assert list(yielded) == [True, True, False, True]
    for i, k in ((0, 3.3 * ky), (1, 1.2 * ky)):  # on the skeleton again, as if bent at once
        m, _, _ = plastic.moment(mat, abs(now[i, 0] - after.rest[i, 0]), after.accumulated[i])
        assert math.isclose(float(m), float(skeleton_moment(mat, k)), rel_tol=1e-9)
    assert np.all(after.rest[2] == state.rest[2]), "unloading is elastic"
    # reverse yield at -M_r: the moment after it is -M_s at the new skeleton curvature
    m, _, _ = plastic.moment(mat, abs(now[3, 0] - after.rest[3, 0]), after.accumulated[3])
    assert math.isclose(float(m), mat.bending_stiffness * abs(now[3, 0] - after.rest[3, 0]))
    reverse = plastic.check(mat, form_k, now, state)
    assert list(reverse) == [False, False, False, True], "moment change 3.5 M_y > 2 M_y"


def test_the_moment_law_is_continuous_and_its_energy_integrates_it():
    mat = STEEL
    ky = mat.yield_curvature
    for alpha in (0.0, 0.5 * ky, 4 * ky):
        s = np.linspace(1e-3, 3, 3001) * ky
        m, slope, work = plastic.moment(mat, s, np.full_like(s, alpha))
        assert np.all(np.diff(m) > 0), "increasing"
        np.testing.assert_allclose(np.gradient(work, s)[1:-1], m[1:-1], rtol=2e-3)
        # the tangent jumps where the law leaves the elastic line: a central
        # difference straddling that jump (at the two samples beside it) is no test
        smooth = np.ones_like(s, dtype=bool)
        smooth[[0, -1]] = False
        jumps = np.flatnonzero(np.abs(np.diff(slope)) > 0.05 * mat.bending_stiffness)
        # at most one jump: where a face that has yielded (alpha > 0) meets its
        # skeleton again (the virgin law's tangent is continuous at M_y)
        assert len(jumps) == (alpha > 0), "one kink, past the elastic range"
        smooth[jumps] = smooth[jumps + 1] = False
        np.testing.assert_allclose(
            np.gradient(m, s)[smooth], slope[smooth], rtol=0.05, atol=1e-3 * mat.bending_stiffness
        )


@pytest.fixture(scope="module")
def strip():
    return rectangle(0.5, 0.1, 0.02)


def _springback(mesh, x: float):
    """Form a strip to R_i = 1 m with the yield stress that makes R_i sigma_y / (E' t) = x,
    release it (3-2-1 restraint); returns (R_i / R_f, the formed state, released b)."""
    radius = 1.0
    mat = STEEL.with_changes(yield_stress=x * STEEL.plane_modulus * STEEL.thickness / radius)
    shell = Shell.create(mesh, mat)
    pos, normals = cylinder(mesh, radius)
    formed, state, _ = form_sheet(shell, pos, normals)
    formed_b = second_fundamental_form(shell, formed.q)
    xy = mesh.nodes
    a, b, c = np.argmin(xy.sum(1)), np.argmin(xy[:, 0] - xy[:, 1]), np.argmax(xy[:, 0] - xy[:, 1])
    fixed = [3 * a, 3 * a + 1, 3 * a + 2, 3 * b, 3 * b + 2, 3 * c + 2]  # AB stays on the y axis
    released = solve_equilibrium(
        shell.with_changes(rest_curvature=state.rest), formed.q, fixed=fixed
    )
    p = released.positions
    return (
        radius / circle_radius(p[:, 0], p[:, 2]),
        state,
        second_fundamental_form(shell, released.q),
        p,
        formed_b,
    )


@pytest.mark.parametrize("x", [0.02, 0.1, 0.2, 0.3, 0.4, 0.45])
def test_gardiner_springback(strip, x):
    ratio, state, _, _, _ = _springback(strip, x)
    assert state.plastic(STEEL.with_changes(yield_stress=1.0)).all()
    assert abs(ratio / gardiner_ratio(x) - 1) < 0.01


@pytest.mark.parametrize("x", [0.5, 0.7])
def test_no_set_below_yield(strip, x):
    _, state, b, p, formed_b = _springback(strip, x)
    # At x = 0.5 the faces' discrete curvature is 1/R_i (1 + O(h^2)): at yield to 1e-4,
    # which leaves a set of the second order, 1e-8 of the formed curvature.
    formed = np.abs(formed_b).max()
    assert np.abs(state.rest).max() <= 1e-7 * formed, "no plastic set"
    assert np.abs(b).max() <= 1e-7 * formed, "released flat"
    centred = p - p.mean(axis=0)
    assert np.linalg.svd(centred, compute_uv=False)[2] < 1e-7 * np.ptp(p, axis=0).max()
    if x > 0.5:
        assert np.all(state.rest == 0)


def _cantilever_tip(q: float, length: float, mat: ShellMaterial) -> float:
    """Small-deflection tip of an elastic-plastic cantilever under its weight q (N/m^2):
    the integral of k(M(s)) (L - s), M = q (L - s)^2 / 2, k from the skeleton."""
    d, my, mp, ky = mat.bending_stiffness, mat.yield_moment, mat.plastic_moment, mat.yield_curvature

    def curvature(s: float) -> float:
        m = q * (length - s) ** 2 / 2
        return m / d if m <= my else ky / math.sqrt(3 * (1 - m / mp))

    s_yield = length - math.sqrt(2 * my / q)
    return quad(
        lambda s: curvature(s) * (length - s), 0, length, points=[s_yield], epsabs=0, epsrel=1e-12
    )[0]


def test_plastic_cantilever():
    """A strip that yields near its clamp under its own weight (root moment 1.2 M_y),
    loaded in increments with the elastic-plastic law: the tip matches the integral."""
    length = 1.0
    mesh = rectangle(length, 0.1, 0.025)
    base = ShellMaterial(youngs_modulus=200e9, poisson=0.0, thickness=2e-3, density=7850.0)
    g = 1e-3 * base.bending_stiffness / (base.density * base.thickness * length**3)  # q L^3 / D
    q = base.density * g * base.thickness
    mat = base.with_changes(yield_stress=6 * (q * length**2 / 2) / (1.2 * base.thickness**2))
    shell, fixed = cantilever(mesh, mat, g)
    start = pack(flat_positions(mesh), np.zeros(mesh.n_directors))
    result = solve_plastic(
        lambda s: shell.with_changes(gravity=s * shell.gravity),
        start,
        plastic.virgin_state(mesh.n_faces),
        fixed=fixed,
    )
    tip = -result.equilibrium.positions[mesh.nodes[:, 0] > length - 1e-12, 2].mean()
    expected = _cantilever_tip(q, length, mat)
    assert result.updates > 0 and result.state.plastic(mat).any()
    assert not result.reverse.any()
    assert abs(tip / expected - 1) < 0.01
