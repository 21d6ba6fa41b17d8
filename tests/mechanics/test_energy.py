"""The energies (mechanics/energy.py): exact derivatives, rigid-motion invariance, the
membrane patch test and the discrete shape operator of a cylinder."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from onefold_cad.mechanics import (
    Shell,
    ShellMaterial,
    director_angles,
    evaluate,
    flat_positions,
    pack,
    second_fundamental_form,
    solve_equilibrium,
)
from onefold_cad.mechanics.assembly import pattern_of
from onefold_cad.mechanics.energy import _directors
from onefold_cad.mechanics.kinematics.triangles import face_metric
from onefold_cad.mechanics.material import invert_metric
from tests.mechanics.helpers import central_difference, cylinder, rectangle

RNG = np.random.default_rng(3)
STEEL = ShellMaterial(youngs_modulus=200e9, poisson=0.3, thickness=2e-3, density=7850.0)


@pytest.fixture(scope="module")
def random_state():
    """A creased sheet with a curved reference, rest curvature and gravity, at a random
    configuration."""
    mesh = rectangle(1.0, 0.6, 0.2, creases=[[(0.5, 0.0), (0.5, 0.6)]])
    ref = flat_positions(mesh) + RNG.normal(scale=0.02, size=(mesh.n_nodes, 3))
    material = ShellMaterial(youngs_modulus=1e3, poisson=0.3, thickness=0.05, density=10.0)
    shell = Shell.create(
        mesh,
        material,
        reference=ref,
        rest_curvature=RNG.normal(scale=0.3, size=(mesh.n_faces, 3)),
        crease_angle=0.4,
        gravity=(0.1, 0.2, -9.8),
    )
    x = flat_positions(mesh) + RNG.normal(scale=0.02, size=(mesh.n_nodes, 3))
    x[:, 2] += 0.3 * np.sin(3 * x[:, 0])
    q = pack(x, RNG.normal(scale=0.1, size=mesh.n_directors))
    return shell, q


def test_gradient_and_hessian_against_finite_differences(random_state):
    shell, q = random_state
    ev = evaluate(shell, q)
    assert all(abs(v) > 0 for v in ev.parts.values()), "every term is exercised"
    g = central_difference(lambda y: np.array([evaluate(shell, y, 0).energy]), q, 1e-4)[:, 0]
    scale = np.abs(ev.gradient).max()
    assert np.abs(g - ev.gradient).max() / scale < 1e-6
    h = central_difference(lambda y: evaluate(shell, y, 1).gradient, q, 1e-4)
    dense = ev.hessian.toarray()
    assert np.abs(h - dense).max() / np.abs(dense).max() < 1e-6
    assert np.abs(dense - dense.T).max() <= 1e-12 * np.abs(dense).max()
    # Each face couples only its own 3 nodes and 3 director angles.
    assert ev.hessian.nnz == pattern_of(shell.mesh).nnz


def test_chunks_of_faces_add_up_to_the_whole(random_state, monkeypatch):
    """The face terms in runs of a few faces (``energy.CHUNK``, the last run shorter) give what one
    run of all the faces gives, to rounding."""
    from onefold_cad.mechanics import energy

    shell, q = random_state
    whole = evaluate(shell, q)
    monkeypatch.setattr(energy, "CHUNK", 9)
    assert shell.mesh.n_faces > 3 * 9 and shell.mesh.n_faces % 9
    runs = evaluate(shell, q)
    assert runs.energy == pytest.approx(whole.energy, rel=1e-13)
    np.testing.assert_allclose(
        runs.gradient, whole.gradient, rtol=0, atol=1e-13 * abs(whole.gradient).max()
    )
    diff = abs(runs.hessian - whole.hessian).max()
    assert diff <= 1e-13 * abs(whole.hessian).max()


def _random_rigid(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    rot = Rotation.from_rotvec([0.4, -0.7, 0.5]).as_matrix()
    return x @ rot.T + np.array([0.3, -1.2, 2.0]), rot


def test_rigid_motions_cost_nothing(random_state):
    shell, q = random_state
    mesh = shell.mesh
    x = q[: 3 * mesh.n_nodes].reshape(-1, 3)
    theta = q[3 * mesh.n_nodes :]
    # Make the random state stress-free: it is its own reference, rest form and fold
    # (its directors kept: their angles from the new reference directors).
    directors = _directors(shell, x, theta, 0)[0]
    own = shell.with_changes(reference=x.copy(), gravity=np.zeros(3))
    theta = director_angles(own, x, directors)
    q = pack(x, theta)
    own = own.with_changes(
        rest_curvature=second_fundamental_form(own, q),
        crease_angle=theta[mesh.crease_edges] - theta[mesh.n_edges :],
    )
    assert abs(evaluate(own, q, 0).energy) < 1e-20
    # Move the sheet and its directors rigidly: no energy.
    moved, rot = _random_rigid(x)
    again = pack(moved, director_angles(own, moved, directors @ rot.T))
    assert abs(evaluate(own, again, 0).energy) < 1e-20
    # And the flat sheet, moved rigidly with its normals, has no energy at all.
    flat = Shell.create(mesh, STEEL)
    moved, rot = _random_rigid(flat_positions(mesh))
    up = np.tile(rot[:, 2], (mesh.n_directors, 1))
    assert evaluate(flat, pack(moved, director_angles(flat, moved, up)), 0).energy < 1e-18


@pytest.mark.parametrize("plane", ["stress", "strain"])
def test_membrane_patch(plane):
    """A uniform stretch of an irregular mesh: interior nodes follow the affine map and
    the edge reactions carry the St Venant-Kirchhoff stress, exactly."""
    length, width, e11 = 1.0, 0.5, 0.02
    mesh = rectangle(length, width, 0.09)
    mat = STEEL
    nu = mat.poisson
    e22 = -nu * e11 if plane == "stress" else 0.0
    lam = np.sqrt(1 + 2 * np.array([e11, e22]))
    if plane == "stress":
        s11, s22 = mat.youngs_modulus * e11, 0.0
    else:
        s11, s22 = mat.plane_modulus * e11, mat.plane_modulus * nu * e11
    exact = flat_positions(mesh) * np.array([lam[0], lam[1], 1.0])
    x0 = flat_positions(mesh)
    x0[:, :2] += RNG.normal(scale=0.01, size=(mesh.n_nodes, 2))
    left = np.flatnonzero(mesh.nodes[:, 0] < 1e-12)
    right = np.flatnonzero(mesh.nodes[:, 0] > length - 1e-12)
    bottom = np.flatnonzero(mesh.nodes[:, 1] < 1e-12)
    top = np.flatnonzero(mesh.nodes[:, 1] > width - 1e-12)
    fixed = [3 * np.arange(mesh.n_nodes) + 2]  # flat: z held
    if plane == "stress":  # x held on the ends, y at one node: the long sides are free
        x0[left, 0], x0[right, 0] = 0.0, exact[right, 0]
        x0[left[0], 1] = exact[left[0], 1]
        fixed += [3 * left, 3 * right, [3 * left[0] + 1]]
    else:  # every boundary node held
        b = mesh.boundary_nodes
        x0[b] = exact[b]
        fixed += [3 * b, 3 * b + 1]
    shell = Shell.create(mesh, mat)
    eq = solve_equilibrium(
        shell, pack(x0, np.zeros(mesh.n_directors)), fixed=np.concatenate(fixed), rtol=1e-13
    )
    assert np.abs(eq.positions - exact).max() < 1e-10 * length
    t = mat.thickness
    assert math.isclose(eq.reactions[right, 0].sum(), s11 * lam[0] * t * width, rel_tol=1e-9)
    assert math.isclose(eq.reactions[left, 0].sum(), -s11 * lam[0] * t * width, rel_tol=1e-9)
    if plane == "strain":
        assert math.isclose(eq.reactions[top, 1].sum(), s22 * lam[1] * t * length, rel_tol=1e-9)
        assert math.isclose(eq.reactions[bottom, 1].sum(), -s22 * lam[1] * t * length, rel_tol=1e-9)


def _principal_curvatures(shell, q, x):
    b = second_fundamental_form(shell, q)
    inv = invert_metric(face_metric(x[shell.mesh.triangles])[0])
    a_inv = np.stack(
        [np.stack([inv[:, 0], inv[:, 1]], -1), np.stack([inv[:, 1], inv[:, 2]], -1)], -2
    )
    bb = np.stack([np.stack([b[:, 0], b[:, 1]], -1), np.stack([b[:, 1], b[:, 2]], -1)], -2)
    return np.sort(np.linalg.eigvals(a_inv @ bb).real, axis=1)


def test_cylinder_shape_operator_converges():
    """A mesh rolled onto a cylinder of radius R, directors along its normals: the
    faces' shape operators have eigenvalues 1/R and 0, to O(h^2)."""
    radius = 1.0
    errors, sizes = [], [0.1, 0.05, 0.025]
    for h in sizes:
        mesh = rectangle(1.0, 0.5, h)
        x, normals = cylinder(mesh, radius)
        shell = Shell.create(mesh, STEEL)
        k = _principal_curvatures(shell, pack(x, director_angles(shell, x, normals)), x)
        assert np.abs(k[:, 0]).max() * radius < 1e-10, "no curvature along the generators"
        errors.append(np.abs(k[:, 1] * radius - 1).max())
    order = np.polyfit(np.log(sizes), np.log(errors), 1)[0]
    assert order > 1.8
    assert errors[-1] < 3e-4


def test_the_elastic_plastic_law_has_exact_derivatives(random_state):
    """Bending on the elastic-plastic law (``Shell.accumulated``): energy, gradient
    and Hessian against finite differences, with faces of every kind: elastic,
    and past their elastic range with and without earlier yielding."""
    shell, q = random_state
    b = second_fundamental_form(shell, q)
    trial = np.sqrt(
        np.einsum("mi,mij,mj->m", b - shell.rest_curvature, shell.form, b - shell.rest_curvature)
    )
    # a yield curvature at the median trial: about half the faces are past it
    ky = float(np.median(trial))
    mat = shell.material
    sy = ky * mat.plane_modulus * mat.thickness / 2
    accumulated = np.where(
        RNG.random(shell.mesh.n_faces) < 0.5, 0.0, RNG.uniform(0, 2 * ky, shell.mesh.n_faces)
    )
    plastic_shell = shell.with_changes(
        material=mat.with_changes(yield_stress=sy), accumulated=accumulated
    )
    ev = evaluate(plastic_shell, q)
    g = central_difference(lambda y: np.array([evaluate(plastic_shell, y, 0).energy]), q, 1e-5)[
        :, 0
    ]
    assert np.abs(g - ev.gradient).max() / np.abs(ev.gradient).max() < 1e-6
    h = central_difference(lambda y: evaluate(plastic_shell, y, 1).gradient, q, 1e-5)
    dense = ev.hessian.toarray()
    assert np.abs(h - dense).max() / np.abs(dense).max() < 1e-6
