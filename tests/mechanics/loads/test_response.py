"""The linear response to external loads: closed forms of plates and strips."""

from __future__ import annotations

import numpy as np

from onefold_cad.mechanics import Shell, ShellMaterial, flat_positions, mesh_sheet, pack
from onefold_cad.mechanics.loads.feet import resultant, three_feet_reactions
from onefold_cad.mechanics.loads.response import linear_response, node_dofs
from onefold_cad.mechanics.loads.surface import pressure_load
from tests.mechanics.helpers import cantilever, rectangle

# nu = 0: a plate strip in cylindrical bending is then exactly a beam with EI = D.
STEEL0 = ShellMaterial(youngs_modulus=200e9, poisson=0.0, thickness=2e-3, density=7850.0)


def _start(mesh):
    return pack(flat_positions(mesh), np.zeros(mesh.n_directors))


def test_cantilever_under_uniform_pressure():
    """A strip clamped at x = 0 under a uniform pressure p on its top: the tip
    drops by q L^4 / (8 D), q = p (per unit width; Euler-Bernoulli)."""
    length, width, p = 1.0, 0.1, 1.0
    mesh = rectangle(length, width, 0.025)
    shell, fixed = cantilever(mesh, STEEL0, 0.0)
    x = flat_positions(mesh)
    load = pressure_load(x, mesh.triangles, np.full(mesh.n_faces, p))
    assert np.isclose(load[:, 2].sum(), -p * length * width, rtol=1e-12)
    resp = linear_response(shell, _start(mesh), fixed, load[None])
    n = mesh.n_nodes
    drop = -resp.moves[0, : 3 * n].reshape(n, 3)[mesh.nodes[:, 0] > length - 1e-12, 2].mean()
    expected = p * length**4 / (8 * STEEL0.bending_stiffness)
    assert abs(drop / expected - 1) < 0.01
    # the clamp carries the load
    assert np.isclose(resp.reactions[0][:, 2].sum(), p * length * width, rtol=1e-9)


def test_flat_plate_on_three_feet_reactions_by_statics():
    """A flat plate 2 x 1 m on feet at (0, 0), (2, 0), (1, 1) under a uniform
    pressure: the feet carry P/4, P/4 and P/2 (moments about the two axes
    through the centroid (1, 0.5)), and the FE model's vertical reactions (a
    three-legged table is statically determinate) equal the statics' to 1e-9."""
    outline = [[0, 0], [2, 0], [2, 1], [0, 1]]
    mesh = mesh_sheet(outline, size=(0.1, 0.0, 0.1), boundary_points=[[1.0, 1.0]])
    feet = [
        int(np.argmin(np.linalg.norm(mesh.nodes - p, axis=1))) for p in ([0, 0], [2, 0], [1, 1])
    ]
    assert np.allclose(mesh.nodes[feet], [[0, 0], [2, 0], [1, 1]], atol=1e-12)
    shell = Shell.create(mesh, STEEL0)
    x = flat_positions(mesh)
    p = 500.0
    load = pressure_load(x, mesh.triangles, np.full(mesh.n_faces, p))
    total = p * 2.0
    resp = linear_response(shell, _start(mesh), node_dofs(feet), load[None])
    fe = resp.reactions[0][feet, 2]
    assert np.allclose(fe, [total / 4, total / 4, total / 2], rtol=0, atol=1e-9 * total)
    force, moment = resultant(x, load)
    statics = three_feet_reactions(mesh.nodes[feet], force, moment)
    assert np.allclose(statics, [total / 4, total / 4, total / 2], rtol=0, atol=1e-9 * total)
