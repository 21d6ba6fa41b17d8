"""Convergence of the bending discretisation: square plates under uniform load against
Navier's and Timoshenko's series, over four meshes."""

from __future__ import annotations

import numpy as np
import pytest

from onefold_cad.mechanics import (
    BOUNDARY,
    Shell,
    ShellMaterial,
    flat_positions,
    pack,
    solve_equilibrium,
)
from tests.mechanics.helpers import rectangle
from tests.mechanics.reference import clamped_centre, navier_centre

PLATE = ShellMaterial(youngs_modulus=200e9, poisson=0.3, thickness=0.01, density=470.0)
DIVISIONS = (6, 12, 24, 48)


def plate_centre(divisions: int, support: str) -> float:
    """Centre deflection of the unit square plate over q a^4 / D (small load: w / t ~ 1e-3)."""
    mesh = rectangle(1.0, 1.0, 1.0 / divisions)
    rim = mesh.boundary_nodes
    edges = np.flatnonzero(mesh.edge_kind == BOUNDARY)
    held = (3 * rim[:, None] + np.arange(3)).ravel()
    shell = Shell.create(mesh, PLATE, gravity=(0, 0, -9.80665))
    if support == "clamped":  # the rim's directors held along the flat normal
        held = np.concatenate([held, 3 * mesh.n_nodes + edges])
    eq = solve_equilibrium(
        shell, pack(flat_positions(mesh), np.zeros(mesh.n_directors)), fixed=held, rtol=1e-7
    )
    centre = np.argmin(np.hypot(*(mesh.nodes - 0.5).T))
    assert np.hypot(*(mesh.nodes[centre] - 0.5)) < 1e-12
    return -eq.positions[centre, 2] * PLATE.bending_stiffness / PLATE.areal_weight


@pytest.mark.parametrize(
    ("support", "reference"), [("simply supported", navier_centre), ("clamped", clamped_centre)]
)
def test_plate_convergence_order(support, reference):
    expected = reference()
    errors = [abs(plate_centre(n, support) / expected - 1) for n in DIVISIONS]
    order = -np.polyfit(np.log(DIVISIONS), np.log(errors), 1)[0]
    assert order > 1.8, (errors, order)
    assert errors[-1] < 0.01
    assert all(a > b for a, b in zip(errors, errors[1:], strict=False)), "monotone"
