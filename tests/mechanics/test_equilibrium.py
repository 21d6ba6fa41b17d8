"""Equilibria (mechanics/equilibrium.py) against beam theory, the heavy elastica, a
folded crease and a propped contact."""

from __future__ import annotations

import math

import numpy as np
import pytest
import qdldl

from onefold_cad.mechanics import (
    Ground,
    Shell,
    ShellMaterial,
    flat_positions,
    newton,
    pack,
    rigid_dofs,
    solve_equilibrium,
    solve_path,
)
from onefold_cad.mechanics.kinematics.triangles import dihedral
from tests.mechanics.helpers import cantilever, rectangle
from tests.mechanics.reference import heavy_elastica_tip

# nu = 0: a plate strip in cylindrical bending is then exactly a beam with EI = D.
STEEL0 = ShellMaterial(youngs_modulus=200e9, poisson=0.0, thickness=2e-3, density=7850.0)
LENGTH, WIDTH = 1.0, 0.1


@pytest.fixture(scope="module")
def strip():
    return rectangle(LENGTH, WIDTH, 0.025)


def _gravity_for(load: float) -> float:
    """The gravity (m/s^2) that makes q L^3 / D = load."""
    mat = STEEL0
    return load * mat.bending_stiffness / (mat.density * mat.thickness * LENGTH**3)


def _start(mesh):
    return pack(flat_positions(mesh), np.zeros(mesh.n_directors))


def _propped(mesh):
    """The propped cantilever: clamped at h0 = q L^4 / (16 D) above the ground,
    its last tenth starting on it. Returns (shell, fixed, start, touching, q)."""
    g = _gravity_for(1e-3)
    q = STEEL0.density * g * STEEL0.thickness
    h0 = q * LENGTH**4 / (16 * STEEL0.bending_stiffness)
    shell, fixed = cantilever(mesh, STEEL0, g, height=h0)
    start = _start(mesh)
    start[2 : 3 * mesh.n_nodes : 3] = h0
    return shell, fixed, start, mesh.nodes[:, 0] > 0.9 * LENGTH, q


def _tip(mesh, positions):
    at_tip = mesh.nodes[:, 0] > LENGTH - 1e-12
    return -positions[at_tip, 2].mean(), LENGTH - positions[at_tip, 0].mean()


def test_cantilever_small_deflection(strip):
    """Tip deflection q L^4 / (8 D) at q L^3 / D = 1e-3 (tip 1.25e-4 L), and the
    reactions carry the weight."""
    g = _gravity_for(1e-3)
    shell, fixed = cantilever(strip, STEEL0, g)
    eq = solve_equilibrium(shell, _start(strip), fixed=fixed)
    q = STEEL0.density * g * STEEL0.thickness
    expected = q * LENGTH**4 / (8 * STEEL0.bending_stiffness)
    drop, _ = _tip(strip, eq.positions)
    assert abs(drop / expected - 1) < 0.01
    assert math.isclose(eq.reactions[:, 2].sum(), shell.weight, rel_tol=1e-9)
    assert abs(eq.reactions[:, :2].sum(axis=0)).max() < 1e-6 * shell.weight


def test_heavy_elastica(strip):
    """At q L^3 / D = 2 the tip sags by 24 % of the length: the inextensible heavy
    elastica (solve_bvp) gives its drop and pull-in."""
    load = 2.0
    shell, fixed = cantilever(strip, STEEL0, _gravity_for(load))
    eq = solve_path(
        lambda s: shell.with_changes(gravity=s * shell.gravity), _start(strip), fixed=fixed
    )
    drop, pull = _tip(strip, eq.positions)
    drop_ref, pull_ref = heavy_elastica_tip(load)
    assert drop_ref > 0.1
    assert abs(drop / (drop_ref * LENGTH) - 1) < 0.01
    assert abs(pull / (pull_ref * LENGTH) - 1) < 0.01


def test_propped_by_the_ground(strip):
    """A cantilever clamped at h0 = q L^4 / (16 D) above the ground: its tip comes to
    rest on it, and the ground carries 3 q L / 16 (a propped cantilever with the prop
    settled by h0; contact at the tip only since h0 > q L^4 / (72 D)). The nodes of the
    last tenth start on the ground: those that pull are released."""
    for mode in ("anchored", "frictionless"):
        shell, fixed, start, touching, q = _propped(strip)
        eq = solve_equilibrium(shell, start, fixed=fixed, ground=Ground(mode), contacts=touching)
        at_tip = strip.nodes[:, 0] > LENGTH - 1e-12
        assert np.array_equal(eq.contacts, at_tip)
        ground = eq.reactions[eq.contacts, 2].sum()
        assert abs(ground / (3 * q * LENGTH * WIDTH / 16) - 1) < 0.01
        assert math.isclose(eq.reactions[:, 2].sum(), shell.weight, rel_tol=1e-9)
        assert eq.positions[:, 2].min() >= -1e-12


@pytest.mark.parametrize("degrees", [60.0, -90.0])
def test_crease_folds_flat_panels(degrees):
    """A sheet with a straight crease (no apex, no gravity) released from flat: two flat
    panels at the set fold angle."""
    mesh = rectangle(1.0, 0.4, 0.05, creases=[[(0.5, 0.0), (0.5, 0.4)]])
    material = ShellMaterial(youngs_modulus=200e9, poisson=0.3, thickness=1e-3)
    angle = math.radians(degrees)
    shell = Shell.create(mesh, material, crease_angle=angle)
    x = flat_positions(mesh)
    eq = solve_path(
        lambda s: shell.with_changes(crease_angle=s * shell.crease_angle),
        pack(x, np.zeros(mesh.n_directors)),
        fixed=rigid_dofs(x),
    )
    p = eq.positions
    normals = []
    for side in range(2):
        nodes = np.unique(mesh.triangles[mesh.face_side == side])
        centred = p[nodes] - p[nodes].mean(axis=0)
        _, s, vt = np.linalg.svd(centred)
        assert s[2] < 1e-8 * s[0], "the panel is flat"
        normals.append(vt[2])
    between = math.degrees(math.acos(abs(normals[0] @ normals[1])))
    assert abs(between - abs(degrees)) < 1e-6
    ce = mesh.crease_edges
    psi = dihedral(p[np.concatenate([mesh.edges[ce], mesh.edge_opposite[ce]], axis=1)], 0)[0]
    np.testing.assert_allclose(psi, angle, atol=1e-8)


def test_a_predicted_path_takes_fewer_iterations_to_the_same_equilibrium(strip):
    """The heavy elastica's gravity ramp in eight fixed steps: started from the
    cubic through the last equilibria (``predict=3``) the solves take fewer
    Newton iterations than from the last one, end at the same state, and hold
    the same tolerance (the predicted start's residual does not raise it)."""
    shell, fixed = cantilever(strip, STEEL0, _gravity_for(2.0))
    runs = {}
    for k in (0, 3):
        seen: list[int] = []
        runs[k] = solve_path(
            lambda s: shell.with_changes(gravity=s * shell.gravity),
            _start(strip),
            fixed=fixed,
            first_step=0.125,
            grow_iter=0,
            predict=k,
            callback=lambda it, res, e, seen=seen: seen.append(it),
        )
        assert seen.count(0) == 8  # eight solves, none failed
    assert runs[3].iterations < runs[0].iterations
    np.testing.assert_allclose(runs[3].positions, runs[0].positions, atol=1e-9)
    assert runs[3].tolerance == runs[0].tolerance


def test_a_predicted_path_keeps_anchored_feet_where_they_stand(strip):
    """The propped cantilever (see above) loaded in steps of 1/4, with and
    without ``predict=2``: the same nodes end on the ground, where the
    unpredicted path anchored them (a prediction moves only the free
    unknowns), and the same equilibrium."""
    shell, fixed, start, touching, q = _propped(strip)
    runs = [
        solve_path(
            lambda s: shell.with_changes(gravity=s * shell.gravity),
            start,
            fixed=fixed,
            ground=Ground("anchored"),
            contacts=touching,
            first_step=0.25,
            grow_iter=0,
            predict=k,
        )
        for k in (0, 2)
    ]
    at_tip = strip.nodes[:, 0] > LENGTH - 1e-12
    assert np.array_equal(runs[0].contacts, at_tip) and np.array_equal(runs[1].contacts, at_tip)
    np.testing.assert_allclose(runs[1].positions[at_tip], runs[0].positions[at_tip], atol=1e-12)
    np.testing.assert_allclose(runs[1].positions, runs[0].positions, atol=1e-9)
    ground = runs[1].reactions[runs[1].contacts, 2].sum()
    assert abs(ground / (3 * q * LENGTH * WIDTH / 16) - 1) < 0.01


def test_a_step_grows_only_when_may_grow_says_so(strip):
    """The heavy elastica's ramp from steps of 1/8 that converge quickly: they
    double unless ``may_grow()`` (asked after each accepted step) says no."""
    shell, fixed = cantilever(strip, STEEL0, _gravity_for(2.0))
    solves = {}
    for answer in (True, False):
        seen: list[int] = []
        solve_path(
            lambda s: shell.with_changes(gravity=s * shell.gravity),
            _start(strip),
            fixed=fixed,
            first_step=0.125,
            grow_iter=100,
            may_grow=lambda answer=answer: answer,
            callback=lambda it, res, e, seen=seen: seen.append(it),
        )
        solves[answer] = seen.count(0)
    assert solves[False] == 8
    assert solves[True] == 4  # 1/8, 1/4, 1/2 and the rest (1/8)


def test_the_equilibrium_is_read_from_newtons_last_evaluation(strip, monkeypatch):
    """The energy, its parts and the reactions come from Newton's last
    evaluation (the Hessian's, at the converged state): no evaluation after
    it, and they are bit for bit those of a fresh evaluation there, through
    contact passes that move the state in place between solves."""
    from onefold_cad.mechanics import equilibrium
    from onefold_cad.mechanics.energy import evaluate

    shell, fixed, start, touching, q = _propped(strip)
    orders: list[int] = []

    def counted(sh, state, order=2):
        orders.append(order)
        return evaluate(sh, state, order)

    monkeypatch.setattr(equilibrium, "evaluate", counted)
    eq = solve_equilibrium(shell, start, fixed=fixed, ground=Ground("anchored"), contacts=touching)
    assert eq.passes > 1, "the case should take several contact passes"
    assert orders[-1] == 2 and 1 not in orders, "no evaluation after Newton's last"
    fresh = evaluate(shell, eq.q, 1)
    assert eq.energy == fresh.energy and eq.parts == fresh.parts
    assert fresh.gradient is not None
    z = 3 * np.flatnonzero(eq.contacts) + 2
    assert np.array_equal(eq.reactions[eq.contacts, 2], fresh.gradient[z])
    reactions = np.concatenate([eq.reactions.ravel(), eq.director_reactions])
    assert np.array_equal(reactions[fixed], fresh.gradient[fixed])


def test_a_path_analyses_each_structure_once(strip, monkeypatch):
    """A load path's steps share their factors: QDLDL orders and analyses the
    Hessian's structure once, however many steps and iterations."""
    made = []
    real = qdldl.Solver

    def counted(*args, **kwargs):
        made.append(1)
        return real(*args, **kwargs)

    monkeypatch.setattr(newton.qdldl, "Solver", counted)
    mesh = strip
    shell, fixed = cantilever(mesh, STEEL0, _gravity_for(2.0))
    steps: list[float] = []
    eq = solve_path(lambda s: shell.with_changes(gravity=s * shell.gravity), _start(mesh),
                    fixed=fixed, first_step=0.125, grow_iter=0,
                    accepted=lambda s, e: steps.append(s))  # fmt: skip
    assert len(steps) >= 3 and eq.iterations > len(steps)
    assert len(made) == 1
