"""``simulate`` on real designs, against results not computed with the model:

- (c) the formed bending energy of a design that never yields equals the cones'
  closed form (D / 2) sum_sides int k(theta)^2 ln(rho(theta) / r_hole) dtheta,
  with k the directrix's geodesic curvature from the fold's own frames and rho
  the sheet's ray lengths; its plastic share equals the area inside
  r = |k| E' t / (2 sigma_y);
- (e) the ground's reactions carry the weight, to 1e-6;
- the structural check against the peer FE program (Kratos, corotational thin
  shell triangles, mesh-converged: benchmarks/kratos_shell.py, docs/mechanics.md):
  patkau-one-fold's largest movement 55.46 mm;
- what cannot be simulated is an error naming the value; a Newton that does not
  converge says so.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from onefold_cad.design import fold_design
from onefold_cad.errors import ConvergenceError, InvalidParameterError
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.mechanics import equilibrium, verdicts
from onefold_cad.mechanics import simulate as sim_module
from onefold_cad.mechanics.simulate import formed_only, run, simulate
from onefold_cad.templates import load_template

#: Kratos 10.4.4, ShellThinElementCorotational3D3N, Richardson-extrapolated from
#: h = 5, 3.5, 2.5 cm (54.99 mm at 2.5 cm): /work notes of the peer run, reproduced
#: by benchmarks/kratos_shell.py patkau-one-fold --h 0.025.
KRATOS_LARGEST_MOVEMENT_MM = 55.46


@pytest.fixture(scope="module")
def patkau():
    design = load_template("patkau-one-fold")
    return design, fold_design(design)


def _cone_integrals(design, folded, k_scale: float = 1.0):
    """``(sum int k^2 ln(rho / r_h) dtheta, area inside r_p(theta))`` from the
    geometry alone (design units), with ``r_p = k_scale |k|``."""
    surface, sheet = folded.solution.surface, design.sheet
    theta = np.linspace(1e-7, surface.total_angle - 1e-7, 40001)
    u, e = surface.frames(theta)
    n = np.cross(u, e)
    k = np.einsum("ij,ij->i", np.gradient(e, theta, axis=0), n)  # geodesic curvature
    r_h = relief_hole_diameter(design, folded) / 2
    energy = area = 0.0
    for side in (1.0, -1.0):
        rho = sheet.ray_lengths(side * theta)
        energy += np.trapezoid(k**2 * np.log(rho / r_h), theta)
        r_p = np.clip(k_scale * np.abs(k), r_h, rho)
        area += np.trapezoid((r_p**2 - r_h**2) / 2, theta)
    return energy, area, r_h


def test_formed_energy_of_a_sheet_that_never_yields_is_the_cones(patkau):
    design, folded = patkau
    m = design.material
    formed = formed_only(design, folded, h_max=0.14, yield_stress_MPa=m.youngs_modulus * 1e3)
    integral, _, _ = _cone_integrals(design, folded)
    e = m.youngs_modulus * 1e9
    t = m.thickness * 1e-3
    d = e * t**3 / (12 * (1 - m.poisson**2))
    expected = d / 2 * integral  # J: (N m) x dimensionless
    assert formed.plastic_area_share == 0.0
    assert abs(formed.bending_energy_J / expected - 1) < 0.01


@pytest.mark.parametrize(
    ("law", "first_yield", "tolerance"),
    [
        # J2: the cone bends in plane strain, its surfaces yield at sigma_y / sqrt(1 - nu + nu^2)
        ("j2", lambda nu: 1 / math.sqrt(1 - nu + nu**2), 0.02),
        # the moment law: a rectangular section in uniaxial stress
        ("moment", lambda nu: 1.0, 0.01),
    ],
)
def test_plastic_share_is_the_area_inside_the_yield_radius(patkau, law, first_yield, tolerance):
    design, folded = patkau
    m = design.material
    formed = formed_only(design, folded, h_max=0.14, law=law)
    e_plane = m.youngs_modulus * 1e9 / (1 - m.poisson**2)
    sigma = m.yield_stress * 1e6 * first_yield(m.poisson)
    scale = e_plane * m.thickness * 1e-3 / (2 * sigma)  # r_p = |k| * scale (m)
    _, area, r_h = _cone_integrals(design, folded, k_scale=scale * 1e3)  # in mm
    sheet_area = design.sheet.area - math.pi * r_h**2
    assert abs(formed.plastic_area_share / (area / sheet_area) - 1) < tolerance
    # the farthest yielded face: the cones' largest |k| (0.888) times the scale
    # (1.75 m uniaxially: r_p = 1.55 m; J2's plane-strain yield: 1.38 m)
    r_max = 0.888 * scale * 1e3
    assert 0.9 * r_max < formed.plastic_radius_max < 1.02 * r_max


@pytest.fixture(scope="module")
def coarse(patkau):
    design, folded = patkau
    return run(design, folded, level="coarse", law="j2")


def test_the_formed_stage_alone_is_the_simulation_s(patkau, coarse):
    design, folded = patkau
    alone = formed_only(design, folded, level="coarse", law="j2")
    assert alone.plastic_area_share == coarse.formed.plastic_area_share
    assert alone.bending_energy_J == coarse.formed.bending_energy_J
    assert alone.max_plastic_strain == coarse.formed.max_plastic_strain


def test_reactions_carry_the_weight(patkau, coarse):
    design, folded = patkau
    sim = coarse
    assert sim.standing.stands
    assert abs(sim.standing.reactions_total_N / sim.weight_N - 1) < 1e-6
    # the weight is the density's: rho g t A, A the flat sheet less its hole
    _, _, r_h = _cone_integrals(design, folded)
    area_m2 = (design.sheet.area - math.pi * r_h**2) * 1e-6
    expected = 8000.0 * 9.80665 * 3.57e-3 * area_m2
    assert abs(sim.weight_N / expected - 1) < 2e-3  # the mesh's polygonal hole


def test_no_stress_above_the_flow_stress_and_the_plastic_strain_is_reported(coarse):
    """The J2 law's report: every face's surface stress at most the flow stress
    (patkau's 304 hardens isotropically: sigma_y + H alpha), the plastic strain
    that forming left never undone by springback and standing, where it is
    largest."""
    sim = coarse
    assert sim.law == "j2" and sim.kinematic_hardening == 0
    formed, standing = sim.formed, sim.standing
    top = sim.yield_stress_MPa + sim.hardening_modulus_MPa * standing.max_plastic_strain
    assert standing.max_stress_MPa <= top * (1 + 1e-9)
    assert np.max(sim.face_stress_MPa) <= top * (1 + 1e-9)
    flow_formed = sim.yield_stress_MPa + sim.hardening_modulus_MPa * formed.max_plastic_strain
    assert sim.yield_stress_MPa < formed.max_stress_MPa <= flow_formed * (1 + 1e-9)
    assert (
        formed.max_plastic_strain > 0 and standing.max_plastic_strain >= formed.max_plastic_strain
    )
    assert standing.plastic_area_share >= formed.plastic_area_share
    # the largest plastic strain is where the cones are tightest: by the hole at H
    assert math.hypot(*formed.max_plastic_strain_at) < 0.2 * formed.plastic_radius_max
    for stage, fields in sim.fields.items():
        assert np.all(fields.stress <= fields.flow * (1 + 1e-9)), stage


def test_hardening_raises_the_flow_stress_it_reports(patkau):
    """Linear hardening (half kinematic) against none: the surfaces' stresses
    pass sigma_y where the sheet has yielded, and never the flow stress;
    forming with H stores more work."""
    design, folded = patkau
    hard = replace(
        design,
        material=design.material.with_changes(hardening_modulus=2000.0, kinematic_hardening=0.5),
    )
    soft = replace(design, material=design.material.with_changes(hardening_modulus=0.0))
    plain = formed_only(soft, fold_design(soft), level="coarse", law="j2")
    assert plain.max_stress_MPa == pytest.approx(design.material.yield_stress, rel=1e-9)
    model_sim = formed_only(hard, fold_design(hard), level="coarse", law="j2")
    assert model_sim.bending_energy_J > plain.bending_energy_J
    assert model_sim.max_stress_MPa > design.material.yield_stress
    # on a proportional path the back stress grows along the stress, so the von
    # Mises stress is sigma_y + (H_iso + H_kin) alpha (uniaxially sigma_y + H eps_p)
    bound = design.material.yield_stress + 2000.0 * model_sim.max_plastic_strain
    assert model_sim.max_stress_MPa <= bound * (1 + 1e-9)


def test_the_structural_check_agrees_with_the_shell_fe_program(patkau):
    """--reference designed --supports anchored, a yield stress never reached."""
    design, folded = patkau
    m = design.material
    sim = run(
        design, folded, reference="designed", h_max=0.14, yield_stress_MPa=m.youngs_modulus * 1e3
    )
    got = sim.designed.max_displacement
    assert abs(got / KRATOS_LARGEST_MOVEMENT_MM - 1) < 0.10
    assert sim.standing.stands and len(sim.standing.contacts) == 3


def test_the_convergence_check_reports_the_change(patkau):
    design, folded = patkau
    sim = simulate(design, folded, level="coarse", convergence=True, law="moment")
    conv = sim.convergence
    assert conv["quantity"] == "standing.max_deviation" and conv["check"] == "finer"
    assert conv["check_mesh"]["nodes"] > 1.5 * sim.nodes
    change = abs(conv["value"] - conv["check_value"]) / conv["check_value"]
    assert conv["max_deviation_change"] == pytest.approx(change)
    warned = any(w.startswith("not mesh-converged") for w in sim.warnings)
    assert warned == (change > 0.02)


def test_a_coarser_check_is_the_coarse_level_s_own_simulation(patkau):
    """``check_mesh='coarser'`` on the normal mesh solves again on the coarse
    level's mesh: the check's value is the coarse simulation's, the change
    relative to the normal mesh's value."""
    design, folded = patkau
    sim = simulate(design, folded, level="normal", check_mesh="coarser", law="moment")
    coarse = simulate(design, folded, level="coarse", convergence=False, law="moment")
    conv = sim.convergence
    assert conv["check"] == "coarser" and conv["quantity"] == "standing.max_deviation"
    assert conv["check_mesh"]["nodes"] == coarse.nodes < sim.nodes / 2
    assert conv["check_value"] == coarse.standing.max_deviation
    a, b = sim.standing.max_deviation, coarse.standing.max_deviation
    assert conv["max_deviation_change"] == pytest.approx(abs(a - b) / a, rel=1e-12)
    assert "convergence_check" in sim.timings_s


def test_a_coarser_mesh_that_does_not_stand_hands_the_check_to_the_finer():
    """broken-vault stands on the normal mesh and finds no standing
    equilibrium on the coarse one, which then cannot bound the answer's
    error: the check runs on the finer mesh instead, and a warning says so."""
    design = load_template("broken-vault")
    folded = fold_design(design)
    coarse = simulate(design, folded, level="coarse", convergence=False, law="moment")
    assert not coarse.standing.stands  # the premise
    sim = simulate(design, folded, level="normal", check_mesh="coarser", law="moment")
    conv = sim.convergence
    assert sim.standing.stands and conv["check"] == "finer"
    assert conv["check_mesh"]["nodes"] > 1.5 * sim.nodes
    assert conv["check_value"] is not None and conv["max_deviation_change"] is not None
    (note,) = [w for w in sim.warnings if "checked on the finer mesh instead" in w]
    assert f"coarser mesh ({coarse.nodes} nodes) does not stand" in note


def test_a_coarser_check_past_the_limit_hands_the_verdict_to_the_finer(patkau, monkeypatch):
    """The coarser mesh's change overstates the error; past the limit the
    finer mesh decides: the reported change and the warning are the finer
    mesh's, and ``coarser_change`` is the coarse level's own simulation's
    change. The limit is lowered to 0.3 % so that the coarse mesh passes it
    (the premise, asserted)."""
    monkeypatch.setattr(verdicts, "CONVERGED", 0.003)
    design, folded = patkau
    sim = simulate(design, folded, level="normal", law="moment")  # the default: coarser
    coarse = simulate(design, folded, level="coarse", convergence=False, law="moment")
    a = sim.standing.max_deviation
    coarser = abs(a - coarse.standing.max_deviation) / a
    assert coarser > 0.003  # the premise: past the limit on the coarse mesh
    conv = sim.convergence
    assert conv["check"] == "finer" and conv["check_mesh"]["nodes"] > 1.5 * sim.nodes
    assert conv["coarser_change"] == pytest.approx(coarser, rel=1e-12)
    b = conv["check_value"]
    assert conv["max_deviation_change"] == pytest.approx(abs(a - b) / b, rel=1e-12)
    warned = any(w.startswith("not mesh-converged") for w in sim.warnings)
    assert warned == (conv["max_deviation_change"] > 0.003)


def test_coarser_on_the_coarse_mesh_is_refused_before_any_simulation(patkau, monkeypatch):
    design, folded = patkau
    monkeypatch.setattr(sim_module, "run", lambda *a, **k: pytest.fail("simulated"))
    with pytest.raises(InvalidParameterError, match="check_mesh: 'coarser'"):
        simulate(design, folded, level="coarse", check_mesh="coarser")
    with pytest.raises(InvalidParameterError, match="check_mesh"):
        simulate(design, folded, level="normal", check_mesh="sideways")


@pytest.mark.parametrize(
    ("template", "changes", "name"),
    [
        ("paper-square", {}, "youngs_modulus"),
        ("star-polygon", {}, "thickness"),
        ("table1-row1", {}, "model"),
        # below the smallest hole its 3.57 mm take without overlapping around H
        # (3.908 mm, thick_map.min_relief_hole; 4 mm simulates)
        ("patkau-one-fold", {"relief_hole": 3.8}, "relief_hole"),
        ("patkau-one-fold", {"relief_hole": 1e-320}, "relief_hole"),
        # no sheet material's density: the stages' tolerances follow the weight
        ("patkau-one-fold", {"density": 7.85e-9}, "density"),
        ("patkau-one-fold", {"density": 8e6}, "density"),
    ],
)
def test_what_cannot_be_simulated_names_the_value(template, changes, name):
    design = load_template(template)
    design = replace(design, material=design.material.with_changes(**changes))
    with pytest.raises(InvalidParameterError) as info:
        run(design, fold_design(design), level="coarse")
    assert info.value.parameter == name


def test_a_newton_that_cannot_converge_says_so(patkau, monkeypatch):
    """One Newton step allowed per solve: the release cannot converge, and the
    simulation raises (naming the residual) instead of reporting a form."""
    design, folded = patkau
    real = equilibrium.minimize
    monkeypatch.setattr(equilibrium, "minimize", lambda *a, **k: real(*a, **{**k, "max_iter": 1}))
    with pytest.raises(ConvergenceError) as info:
        run(design, folded, level="coarse")
    assert math.isfinite(info.value.residual) and info.value.residual > 0
    assert "residual" in str(info.value)
