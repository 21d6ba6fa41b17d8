"""The consistent tangent is the derivative of the internal force, checked by
central differences in a mixed state (after a first plastic step, a second
one where some points unload elastically, some keep yielding and some yield
again), with hardening off and on: at the section (``d(N, M) / d(eps,
kappa)``) and assembled over a shell (the Hessian of the energy against its
gradient). A tangent that is not the derivative (a return mapping from the
last iterate, a missing back-stress term, the wrong section integral or
geometric part) gives Newton linear convergence; these tests catch it."""

from __future__ import annotations

import numpy as np
import pytest

from onefold_cad.mechanics import Shell, ShellMaterial, evaluate, flat_positions, pack
from onefold_cad.mechanics.energy import section_response
from onefold_cad.mechanics.j2.law import J2Law, J2State, von_mises
from onefold_cad.mechanics.j2.layered import Plasticity
from onefold_cad.mechanics.j2.section import ThicknessRule, section_update
from tests.mechanics.helpers import central_difference, rectangle

E, NU, SY, T = 200e9, 0.29, 215e6, 3.57e-3
KY = 2 * SY / (E * T)  # the curvature at which a bent strip's surfaces yield (1/m)
#: (H_iso, H_kin) (Pa): perfectly plastic, patkau-one-fold's 304 (isotropic),
#: kinematic only, both.
HARDENINGS = [(0.0, 0.0), (507e6, 0.0), (0.0, 507e6), (2e9, 5e9)]


def _mixed_sections(law: J2Law, rule: ThicknessRule, n: int = 24):
    """``n`` sections bent (and stretched) well past yield from virgin, then
    strained again along another direction: the second step's strains and
    the state after the first."""
    rng = np.random.default_rng(11)
    k1 = rng.normal(size=(n, 3)) * 6 * KY
    e1 = rng.normal(size=(n, 3)) * 0.3 * SY / E
    first = section_update(law, rule, e1, k1, J2State.virgin((n, rule.points)))
    # back part of the way, turned: some points unload, some load on, some reverse
    k2 = 0.6 * k1 + rng.normal(size=(n, 3)) * 2 * KY
    e2 = e1 + rng.normal(size=(n, 3)) * 0.5 * SY / E
    return e2, k2, first.state


@pytest.mark.parametrize(("hi", "hk"), HARDENINGS)
def test_the_section_tangent_is_the_derivative_of_its_resultants(hi, hk):
    law = J2Law(E, NU, SY, hi, hk)
    rule = ThicknessRule(T)
    e2, k2, state = _mixed_sections(law, rule)
    r = section_update(law, rule, e2, k2, state)
    was = state.equivalent > 0
    # the state is mixed: points that flowed before and now unload, that flow
    # again, and that flow for the first time
    assert np.any(was & ~r.plastic) and np.any(was & r.plastic) and np.any(~was & r.plastic)
    x = np.concatenate([e2, k2], axis=1)
    scale = np.array([SY / E] * 3 + [KY] * 3)
    checked = 0
    for j in range(6):
        h = 1e-6 * scale[j]
        up, down = x.copy(), x.copy()
        up[:, j] += h
        down[:, j] -= h
        ru = section_update(law, rule, up[:, :3], up[:, 3:], state)
        rd = section_update(law, rule, down[:, :3], down[:, 3:], state)
        same = np.all((ru.plastic == r.plastic) & (rd.plastic == r.plastic), axis=1)
        col = (np.hstack([ru.force, ru.moment]) - np.hstack([rd.force, rd.moment])) / (2 * h)
        # the resultants are the energy's gradient
        grad = (ru.energy - rd.energy) / (2 * h)
        rm = np.hstack([r.force, r.moment])[:, j]
        assert np.allclose(grad[same], rm[same], rtol=1e-5, atol=1e-6 * np.abs(rm).max())
        tcol = r.tangent[:, :, j]
        tol = 1e-5 * np.abs(r.tangent[:, :, j]).max(axis=1, keepdims=True)
        assert np.all(np.abs(col - tcol)[same] <= tol[same])
        checked += int(same.sum())
    assert checked >= 0.8 * 6 * len(x)  # few sections straddle the yield surface
    assert np.allclose(r.tangent, np.swapaxes(r.tangent, -1, -2), rtol=0,
                       atol=1e-9 * np.abs(r.tangent).max())  # fmt: skip


MATERIAL = ShellMaterial(youngs_modulus=1e3, poisson=0.3, thickness=0.05, density=10.0)


@pytest.mark.parametrize(("hi", "hk"), [(0.0, 0.0), (30.0, 0.0), (0.0, 50.0), (30.0, 50.0)])
def test_the_assembled_hessian_is_the_derivative_of_the_gradient_in_a_mixed_state(hi, hk):
    """A shell strained past yield, its internal variables moved on, then
    strained back part of the way (some faces unload, some flow on): the
    Hessian against central differences of the gradient."""
    rng = np.random.default_rng(5)
    mesh = rectangle(1.0, 0.6, 0.2, creases=[[(0.5, 0.0), (0.5, 0.6)]])
    ref = flat_positions(mesh) + rng.normal(scale=0.02, size=(mesh.n_nodes, 3))
    shell = Shell.create(mesh, MATERIAL, reference=ref, crease_angle=0.4, gravity=(0.1, 0.2, -9.8))
    x1 = flat_positions(mesh) + rng.normal(scale=0.02, size=(mesh.n_nodes, 3))
    x1[:, 2] += 0.3 * np.sin(3 * x1[:, 0])
    q1 = pack(x1, rng.normal(scale=0.1, size=mesh.n_directors))

    def sheet(sy: float) -> Shell:
        law = J2Law(MATERIAL.youngs_modulus, MATERIAL.poisson, sy, hi, hk)
        rule = ThicknessRule(MATERIAL.thickness, 5)
        return shell.with_changes(plasticity=Plasticity.virgin(law, rule, mesh.n_faces))

    # the yield stress: the median von Mises stress of the elastic first step
    elastic = section_response(sheet(np.inf), q1).stress
    plastic = sheet(float(np.median(von_mises(elastic))))
    assert plastic.plasticity is not None
    first = section_response(plastic, q1)
    moved = plastic.with_changes(plasticity=plastic.plasticity.moved_on(first.state))
    x2 = 0.5 * x1 + 0.5 * ref + rng.normal(scale=0.01, size=x1.shape)
    q2 = pack(x2, 0.5 * q1[3 * mesh.n_nodes :])
    resp = section_response(moved, q2)
    was = first.plastic
    assert np.any(was & ~resp.plastic) and np.any(was & resp.plastic)
    assert np.any(~was & ~resp.plastic)  # and points that stay elastic
    ev = evaluate(moved, q2)
    h = central_difference(lambda y: evaluate(moved, y, 1).gradient, q2, 1e-6)
    hs = ev.hessian.toarray()
    assert np.abs(h - hs).max() / np.abs(hs).max() < 1e-5
