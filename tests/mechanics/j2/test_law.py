"""The plane-stress J2 law at material points: on the yield surface after
every step, the stress the gradient of its incremental energy, the tangent
the derivative of the stress (finite differences), uniaxial hardening and the
Bauschinger effect by hand, and its refusals."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from onefold_cad.errors import ConvergenceError, InvalidParameterError
from onefold_cad.mechanics.j2 import law as j2
from onefold_cad.mechanics.j2.law import J2Law, J2State, elastic_matrix, update, von_mises

E, NU, SY = 200e9, 0.29, 215e6
EY = SY / E  # the uniaxial yield strain


def _laws():
    return st.builds(
        J2Law,
        st.just(E),
        st.floats(-0.9, 0.49),
        st.just(SY),
        st.sampled_from([0.0, 1e8, 2e9, 5e10]),
        st.sampled_from([0.0, 1e8, 2e9, 5e10]),
    )


_STRAINS = st.lists(st.floats(-30.0, 30.0), min_size=3, max_size=3)


@given(_laws(), _STRAINS, _STRAINS)
def test_every_step_ends_on_or_inside_the_yield_surface(law, a, b):
    state = J2State.virgin(())
    for strain in (np.array(a) * EY, np.array(b) * EY):
        r = update(law, strain, state)
        kappa = law.yield_stress + law.hardening_iso * r.state.equivalent
        excess = von_mises(r.stress - r.state.back_stress) / kappa
        assert excess <= 1 + 1e-10
        if r.plastic:
            assert excess == pytest.approx(1, abs=1e-10)
        state = r.state


@given(_laws(), _STRAINS, _STRAINS)
def test_gradient_and_tangent_are_the_derivatives(law, a, b):
    """Central differences of the incremental energy give the stress, of the
    stress the consistent tangent (symmetric), from a state after a first step."""
    state = update(law, np.array(a) * EY, J2State.virgin(())).state
    eps = np.array(b) * EY
    r = update(law, eps, state)
    h = 1e-7 * EY * (1 + np.max(np.abs(b)))
    for i in range(3):
        up, down = eps.copy(), eps.copy()
        up[i] += h
        down[i] -= h
        ru, rd = update(law, up, state), update(law, down, state)
        if bool(ru.plastic) != bool(rd.plastic) or bool(ru.plastic) != bool(r.plastic):
            continue  # a step across the yield surface: the law has a kink there
        grad = (ru.energy - rd.energy) / (2 * h)
        assert grad == pytest.approx(r.stress[i], abs=1e-5 * SY)
        col = (ru.stress - rd.stress) / (2 * h)
        assert col == pytest.approx(r.tangent[:, i], abs=1e-4 * E)
    assert np.allclose(r.tangent, r.tangent.T, atol=1e-9 * E)


def _uniaxial(law, strains):
    """sigma_11 of a point in uniaxial stress (s22 = s12 = 0) along eps_11 = strains."""
    state, e22, out = J2State.virgin(()), 0.0, []
    for e11 in strains:
        for _ in range(50):
            r = update(law, np.array([e11, e22, 0.0]), state)
            if abs(r.stress[1]) < 1e-9 * SY:
                break
            e22 -= r.stress[1] / r.tangent[1, 1]
        state = r.state
        out.append(r.stress[0])
    return np.array(out)


@pytest.mark.parametrize(("hi", "hk"), [(0.0, 0.0), (2e9, 0.0), (0.0, 2e9), (1e9, 3e9)])
def test_uniaxial_tension_yields_at_sigma_y_and_hardens_with_h_iso_plus_h_kin(hi, hk):
    """By hand: elastic slope E to sigma_y, then eps = sigma / E + (sigma - sigma_y) / H."""
    law = J2Law(E, NU, SY, hi, hk)
    strains = np.linspace(0, 20 * EY, 81)[1:]
    sigma = _uniaxial(law, strains)
    h = hi + hk
    if h > 0:  # eps = s / E + (s - sigma_y) / h
        plastic = (strains + SY / h) / (1 / E + 1 / h)
    else:
        plastic = np.full_like(strains, SY)
    expected = np.where(strains <= EY, E * strains, plastic)
    assert sigma == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize(("hi", "hk"), [(0.0, 0.0), (0.0, 5e9), (5e9, 0.0)])
def test_reverse_yield_isotropic_against_kinematic(hi, hk):
    """Loaded to sigma_1 in tension and reversed: kinematic hardening yields
    again at sigma_1 - 2 sigma_y (Bauschinger), isotropic at -sigma_1."""
    law = J2Law(E, NU, SY, hi, hk)
    up = np.linspace(0, 10 * EY, 41)[1:]
    down = np.linspace(10 * EY, -10 * EY, 801)[1:]
    sigma = _uniaxial(law, np.concatenate([up, down]))
    s1 = sigma[len(up) - 1]
    back = sigma[len(up) :]
    elastic_end = s1 - E * (10 * EY - down)  # the elastic unloading line
    first = int(np.argmax(back > elastic_end + 1e-6 * SY))  # first point off the line
    reverse_yield = back[first - 1]
    expected = s1 - 2 * SY if hk > 0 else -s1
    if hi == hk == 0:
        expected = -SY
    assert reverse_yield == pytest.approx(expected, abs=E * 20 * EY / 800 + 1e-6 * SY)


def test_the_elastic_matrix_is_plane_stress():
    c = elastic_matrix(J2Law(E, NU, SY))
    sigma = c @ np.array([1e-3, 0.0, 0.0])
    assert sigma[0] == pytest.approx(E / (1 - NU**2) * 1e-3)
    assert sigma[1] == pytest.approx(NU * sigma[0])
    assert c[2, 2] == pytest.approx(E / (2 * (1 + NU)))


@pytest.mark.parametrize(
    ("field", "value"),
    [("hardening_iso", -1.0), ("hardening_kin", math.nan), ("hardening_kin", math.inf),
     ("yield_stress", 0.0), ("poisson", 0.5)],
)  # fmt: skip
def test_a_bad_law_is_refused_naming_the_field(field, value):
    values = {"youngs_modulus": E, "poisson": NU, "yield_stress": SY, field: value}
    with pytest.raises(InvalidParameterError) as info:
        J2Law(**values)
    assert info.value.parameter == field


def test_a_return_mapping_that_cannot_converge_says_so_with_its_residual(monkeypatch):
    """One iteration allowed: a point far outside its yield surface cannot be
    brought back, and the update raises (naming the return mapping and its
    residual) instead of answering with a stress off the surface."""
    monkeypatch.setattr(j2, "MAX_ITERATIONS", 1)
    law = J2Law(200e9, 0.3, 250e6, 1e9, 0.0)
    with pytest.raises(ConvergenceError) as info:
        update(law, np.array([[0.05, -0.01, 0.02]]), J2State.virgin((1,)))
    assert "return mapping" in str(info.value) and "residual" in str(info.value)
    assert math.isfinite(info.value.residual) and info.value.residual > 0


def test_simulate_says_when_its_return_mapping_fails(monkeypatch, capfd):
    """The same through ``onefold simulate --law j2``: one line, exit 2."""
    from onefold_cad.cli.main import main

    monkeypatch.setattr(j2, "MAX_ITERATIONS", 1)
    rc = main(["simulate", "patkau-one-fold", "--law", "j2", "--mesh", "coarse", "-q"])
    out, err = capfd.readouterr()
    assert rc == 2 and out == ""
    lines = [ln for ln in err.splitlines() if not ln.startswith("onefold: warning: ")]
    assert len(lines) == 1 and "return mapping" in lines[0] and "residual" in lines[0], err


@pytest.mark.parametrize(("hi", "hk"), [(0.0, 0.0), (5e8, 0.0), (0.0, 5e8), (2e9, 5e9)])
def test_the_closed_form_tangent_solves_the_projection_s_linearised_equations(hi, hk):
    """The flowing points' tangent against the 4 x 4 system of the closest-point
    projection's equations in ``(xi, dgamma)`` solved directly (``theta xi +
    dgamma C P xi = xi_trial``, ``phi(xi) = sqrt(2/3) kappa``), from a state
    that flowed before: ``d sigma = theta dxi + 2/3 H_kin xi ddgamma``."""
    law = J2Law(E, NU, SY, hi, hk)
    rng = np.random.default_rng(9)
    e1 = rng.normal(size=(200, 3)) * 4 * EY
    first = update(law, e1, J2State.virgin((200,)))
    r = update(law, 0.7 * e1 + rng.normal(size=(200, 3)) * 1.5 * EY, first.state)
    k = np.flatnonzero(r.plastic)
    assert 20 < len(k) < 180  # some points unload, the rest flow on or reverse
    c = elastic_matrix(law)
    xi = r.stress[k] - r.state.back_stress[k]  # sigma = xi + beta_(n+1)
    pxi = xi @ j2.P
    phi = np.sqrt(np.sum(xi * pxi, axis=1))
    # alpha grows by sqrt(2/3) dgamma phi
    dg = (r.state.equivalent[k] - first.state.equivalent[k]) / (math.sqrt(2 / 3) * phi)
    theta = 1 + 2 / 3 * hk * dg
    jac = np.zeros((len(k), 4, 4))
    jac[:, :3, :3] = theta[:, None, None] * np.eye(3) + dg[:, None, None] * (c @ j2.P)
    jac[:, :3, 3] = 2 / 3 * hk * xi + pxi @ c
    jac[:, 3, :3] = pxi / phi[:, None] * (1 - 2 / 3 * hi * dg)[:, None]
    jac[:, 3, 3] = -2 / 3 * hi * phi
    rhs = np.zeros((len(k), 4, 3))
    rhs[:, :3] = c
    sol = np.linalg.solve(jac, rhs)
    expected = theta[:, None, None] * sol[:, :3] + 2 / 3 * hk * xi[:, :, None] * sol[:, 3:]
    np.testing.assert_allclose(r.tangent[k], expected, rtol=1e-9, atol=1e-9 * abs(c).max())


@pytest.mark.parametrize("direction", [(1.0, 1.0, 0.0), (1.0, -1.0, 0.0), (0.0, 0.0, 1.0)])
@pytest.mark.parametrize(("hi", "hk"), [(0.0, 0.0), (5e8, 0.0), (0.0, 5e8), (2e9, 5e9)])
def test_a_trial_along_an_eigenvector_of_p_returns_in_one_newton_step(
    monkeypatch, direction, hi, hk
):
    """Equibiaxial stress and in-plane pure shear: ``1 / phi`` is linear in
    ``dgamma`` there, so the return mapping's first Newton step lands on the
    yield surface (two passes: the step and the check), from 20 yield
    strains out; a general trial needs more."""
    monkeypatch.setattr(j2, "MAX_ITERATIONS", 2)
    law = J2Law(E, NU, SY, hi, hk)
    c = elastic_matrix(law)
    stress = 20 * SY * np.array(direction)
    r = update(law, np.linalg.solve(c, stress), J2State.virgin(()))
    kappa = SY + hi * r.state.equivalent
    assert r.plastic
    assert von_mises(r.stress - r.state.back_stress) / kappa == pytest.approx(1, abs=1e-10)
    with pytest.raises(ConvergenceError):  # uniaxial stress mixes two eigenvalues
        update(law, np.linalg.solve(c, 20 * SY * np.array([1.0, 0.0, 0.0])), J2State.virgin(()))
