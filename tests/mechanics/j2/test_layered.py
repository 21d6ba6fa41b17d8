"""The shell's faces as J2 sections (Shell.plasticity): an elastic section is
today's elastic shell exactly; the energy's gradient and Hessian are exact
in a plastic increment; a state carried over from forming gives the
springback a strip of the same law has by the section's own closed forms."""

from __future__ import annotations

import numpy as np
import pytest

from onefold_cad.mechanics import Shell, ShellMaterial, evaluate, flat_positions, pack
from onefold_cad.mechanics.j2.law import J2Law
from onefold_cad.mechanics.j2.layered import Plasticity, cartesian_map
from onefold_cad.mechanics.j2.section import ThicknessRule
from onefold_cad.mechanics.material import strain_form
from tests.counting import count_calls
from tests.mechanics.helpers import central_difference, rectangle

RNG = np.random.default_rng(7)


def test_the_cartesian_map_carries_the_strain_energy_s_form():
    """(L s)^T C (L s) / E' = s^T K s for random reference metrics."""
    g = RNG.normal(size=(20, 2, 2))
    a = np.einsum("mki,mkj->mij", g, g)
    abar = np.stack([a[:, 0, 0], a[:, 0, 1], a[:, 1, 1]], axis=1)
    nu = 0.29
    c = np.array([[1, nu, 0], [nu, 1, 0], [0, 0, (1 - nu) / 2]])
    lmap = cartesian_map(abar)
    assert np.allclose(lmap.transpose(0, 2, 1) @ c @ lmap, strain_form(abar, nu), rtol=1e-12,
                       atol=1e-12 * np.abs(strain_form(abar, nu)).max())  # fmt: skip


def _state(shell_material: ShellMaterial, yield_stress: float, points: int = 5):
    mesh = rectangle(1.0, 0.6, 0.2, creases=[[(0.5, 0.0), (0.5, 0.6)]])
    ref = flat_positions(mesh) + RNG.normal(scale=0.02, size=(mesh.n_nodes, 3))
    shell = Shell.create(mesh, shell_material, reference=ref, crease_angle=0.4,
                         gravity=(0.1, 0.2, -9.8))  # fmt: skip
    law = J2Law(shell_material.youngs_modulus, shell_material.poisson, yield_stress, 30.0, 50.0)
    plastic = shell.with_changes(
        plasticity=Plasticity.virgin(
            law, ThicknessRule(shell_material.thickness, points), mesh.n_faces
        )
    )
    x = flat_positions(mesh) + RNG.normal(scale=0.02, size=(mesh.n_nodes, 3))
    x[:, 2] += 0.3 * np.sin(3 * x[:, 0])
    q = pack(x, RNG.normal(scale=0.1, size=mesh.n_directors))
    return shell, plastic, q


MATERIAL = ShellMaterial(youngs_modulus=1e3, poisson=0.3, thickness=0.05, density=10.0)


def test_an_elastic_section_is_the_elastic_shell():
    shell, layered, q = _state(MATERIAL, np.inf)
    a, b = evaluate(shell, q), evaluate(layered, q)
    assert b.energy == pytest.approx(a.energy, rel=1e-12)
    assert b.parts["membrane"] == pytest.approx(a.parts["membrane"], rel=1e-12)
    assert np.allclose(b.gradient, a.gradient, rtol=0, atol=1e-11 * np.abs(a.gradient).max())
    diff = abs(b.hessian - a.hessian).max()
    assert diff <= 1e-11 * abs(a.hessian).max()


def test_a_plastic_increment_s_gradient_and_hessian_are_exact():
    """At a state where most points flow: central differences of the energy
    and of the gradient (the consistent tangent makes the Hessian exact)."""
    elastic, layered, q = _state(MATERIAL, 0.5)
    ev = evaluate(layered, q)
    # flowing lowers the increment's energy below the elastic one (no flow is admissible)
    assert ev.energy < evaluate(elastic, q, 0).energy - 0.1 * abs(ev.parts["bending"])
    g = central_difference(lambda y: np.array([evaluate(layered, y, 0).energy]), q, 1e-6)[:, 0]
    scale = np.abs(ev.gradient).max()
    assert np.abs(g - ev.gradient).max() / scale < 1e-5
    h = central_difference(lambda y: evaluate(layered, y, 1).gradient, q, 1e-6)
    hs = ev.hessian.toarray()
    assert np.abs(h - hs).max() / np.abs(hs).max() < 1e-4


# -- forming and springback of a strip as J2 sections ------------------------------
STRIP_STEEL = ShellMaterial(youngs_modulus=200e9, poisson=0.3, thickness=2e-3, density=7850.0)


def _strip_springback(x: float) -> tuple[float, float]:
    """A 0.5 x 0.1 m strip formed to R_i = 1 m (imposed: every node on the
    cylinder, every director along its normal) with the yield stress that
    makes R_i sigma_y / (E t) = x, released on a 3-2-1 restraint through the
    law: (R_i / R_f, the formed plastic share of the surfaces)."""
    ratio, share, _ = _strip_release(x)
    return ratio, share


def _strip_release(x: float):
    """:func:`_strip_springback` and the released stage."""
    from onefold_cad.mechanics import director_angles
    from onefold_cad.mechanics.j2.stages import form_to, release_from
    from tests.mechanics.helpers import circle_radius, cylinder

    mesh = rectangle(0.5, 0.1, 0.02)
    radius = 1.0
    sy = x * STRIP_STEEL.youngs_modulus * STRIP_STEEL.thickness / radius
    law = J2Law(STRIP_STEEL.youngs_modulus, STRIP_STEEL.poisson, sy)
    shell = Shell.create(mesh, STRIP_STEEL.with_changes(yield_stress=sy)).with_changes(
        plasticity=Plasticity.virgin(law, ThicknessRule(STRIP_STEEL.thickness, 17), mesh.n_faces)
    )
    pos, normals = cylinder(mesh, radius)
    formed = form_to(shell, pack(pos, director_angles(shell, pos, normals)))
    xy = mesh.nodes
    a, b, c = np.argmin(xy.sum(1)), np.argmin(xy[:, 0] - xy[:, 1]), np.argmax(xy[:, 0] - xy[:, 1])
    fixed = [3 * a, 3 * a + 1, 3 * a + 2, 3 * b, 3 * b + 2, 3 * c + 2]
    released = release_from(shell, formed, fixed, force_scale=1.0)
    p = released.equilibrium.positions
    share = float(np.mean(formed.surface_plastic_strain() > 0))
    return radius / circle_radius(p[:, 0], p[:, 2]), share, released


@pytest.mark.parametrize("x", [0.1, 0.3])
def test_a_strip_formed_and_released_springs_back_as_its_sections_say(x):
    """The released strip's curvature against Gardiner's 4 x^3 - 3 x + 1: the
    strip, 50 thicknesses wide, bends between a narrow strip (x with E and
    sigma_y) and a wide one (x with E' and the plane-strain yield stress
    sigma_y / sqrt(1 - nu + nu^2)), which lie 0.01 apart here."""
    ratio, share = _strip_springback(x)
    nu = STRIP_STEEL.poisson
    narrow = 4 * x**3 - 3 * x + 1
    xw = x * (1 - nu**2) / np.sqrt(1 - nu + nu**2)
    wide = 4 * xw**3 - 3 * xw + 1
    assert min(narrow, wide) - 0.01 <= ratio <= max(narrow, wide) + 0.01
    assert share == 1.0  # every face's surface yielded (x < 1/2)


def test_the_release_s_predicted_steps_take_fewer_iterations_to_the_same_strip(monkeypatch):
    """The strip at x = 0.1 released with each step started from the
    polynomial through the last equilibria (``RELEASE_PREDICTOR``) and from
    the last equilibrium alone (0): the same released form, in fewer Newton
    iterations (22 against 39 when measured)."""
    from onefold_cad.mechanics.j2 import stages as j2_stages

    assert j2_stages.RELEASE_PREDICTOR >= 2
    ratio, _, predicted = _strip_release(0.1)
    monkeypatch.setattr(j2_stages, "RELEASE_PREDICTOR", 0)
    ratio0, _, plain = _strip_release(0.1)
    assert predicted.equilibrium.iterations < plain.equilibrium.iterations
    assert ratio == pytest.approx(ratio0, rel=1e-6)
    np.testing.assert_allclose(predicted.q, plain.q, atol=1e-9)


def test_the_release_s_steps_grow_only_while_few_points_change_yielding(monkeypatch):
    """The strip at x = 0.1 unloads elastically (no point changes between
    yielding and unloading), so its quick steps of 1/8 double; with
    ``GROW_CHANGE`` below 0 they stay at 1/8 (eight accepted steps)."""
    from onefold_cad.mechanics.j2 import stages as j2_stages

    accepted = count_calls(monkeypatch, j2_stages, "section_response")
    _strip_release(0.1)
    grown = len(accepted)
    accepted.clear()
    monkeypatch.setattr(j2_stages, "GROW_CHANGE", -1.0)
    _strip_release(0.1)
    assert len(accepted) == 8 and grown < 8
