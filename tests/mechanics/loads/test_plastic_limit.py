"""The J2 load path's plastic limit against the closed form of a cantilever
strip under a uniform pressure: the clamp's section becomes a hinge at
``q_p = 2 M_p / L^2``.

The strip is in plane strain (its sides held as symmetry planes: no movement
across, no slope across), where the fully plastic moment of a unit width of
a J2 sheet is ``M_p = 2 / sqrt(3) sigma_y t^2 / 4`` (the plane-strain yield
stress ``2 / sqrt(3) sigma_y`` over the two halves of the thickness). A free-
edged strip of a shell is wide at its hinge (its width squared is many times
the hinge's radius times t), so plane strain is the closed form that holds
there; the narrow-beam ``sigma_y b t^2 / 4`` is its lower bound.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from onefold_cad.mechanics import ShellMaterial, flat_positions, pack
from onefold_cad.mechanics.loads.plastic_limit import GAMMA_M1, ideal_plastic, load_ratio
from onefold_cad.mechanics.loads.surface import pressure_load
from onefold_cad.mechanics.mesh import BOUNDARY
from tests.mechanics.helpers import cantilever, rectangle

LENGTH, WIDTH, H = 0.2, 0.02, 0.005
T, SIGMA_Y = 2e-3, 250e6
STEEL = ShellMaterial(youngs_modulus=200e9, poisson=0.3, thickness=T, density=0.0,
                      yield_stress=SIGMA_Y, hardening_iso=5e8)  # fmt: skip
#: The collapse pressure (Pa): q_p L^2 / 2 = M_p per unit width.
M_P = 2 / math.sqrt(3) * SIGMA_Y * T**2 / 4
Q_P = 2 * M_P / LENGTH**2


@pytest.fixture(scope="module")
def strip():
    """The plane-strain cantilever: its J2 shell, rest state, held unknowns and
    the nodal load of the pressure ``Q_P``."""
    mesh = rectangle(LENGTH, WIDTH, H)
    shell, fixed = cantilever(mesh, STEEL, 0.0)
    side = np.abs(mesh.nodes[:, 1] - WIDTH / 2) > WIDTH / 2 - 1e-12
    sides = np.flatnonzero((mesh.edge_kind == BOUNDARY) & side[mesh.edges].all(axis=1))
    across = 3 * np.arange(mesh.n_nodes) + 1
    fixed = np.unique(np.concatenate([fixed, across, 3 * mesh.n_nodes + sides]))
    x = flat_positions(mesh)
    load = np.zeros(mesh.n_dofs)
    load[: 3 * mesh.n_nodes] = pressure_load(x, mesh.triangles, np.full(mesh.n_faces, Q_P)).ravel()
    return ideal_plastic(shell), pack(x, np.zeros(mesh.n_directors)), fixed, load


def _ratio(strip, share: float, r_max: float):
    shell, q0, fixed, load = strip
    return load_ratio(lambda r: shell.with_changes(load=r * share * load), q0, fixed,
                      Q_P * LENGTH * WIDTH, LENGTH, r_max)  # fmt: skip


def test_the_law_is_ideal_plastic(strip):
    """EN 1993-1-6 6.2.3(3): the material's hardening is dropped."""
    law = strip[0].plasticity.law
    assert (law.hardening_iso, law.hardening_kin, law.yield_stress) == (0.0, 0.0, SIGMA_Y)


def test_cantilever_collapses_at_the_hinge_load(strip):
    """The path stops within 3 % above ``q_p`` (the clamp's hinge; the mesh's
    root element and the 5 % strain limit put it a little above)."""
    res = _ratio(strip, 1.0, 1.5)
    assert not res.carried
    assert 1.0 <= res.ratio < 1.03, res.ratio


def test_below_the_hinge_load_the_case_is_carried(strip):
    """At 0.8 ``q_p`` the path carries the whole case and goes on to about
    ``1 / 0.8`` of it; it has yielded where the moment ``0.8 q_p (L - x)^2 / 2``
    passes ``M_y = 2/3 M_p`` (``x < L (1 - sqrt(2 / 2.4))``, to a mesh size)
    and nowhere else."""
    res = _ratio(strip, 0.8, 1.5)
    assert res.at == 1.0
    assert 1.0 / 0.8 <= res.ratio < 1.03 / 0.8
    assert res.ratio >= GAMMA_M1
    e = res.plasticity.state.equivalent.max(axis=1)
    shell = strip[0]
    x = shell.mesh.nodes[shell.mesh.triangles].mean(axis=1)[:, 0]
    x_y = LENGTH * (1 - math.sqrt(2 / 2.4))
    assert np.all(e[x < x_y - H] > 0.0)
    assert np.all(e[x > x_y + H] == 0.0)


def test_below_first_yield_nothing_yields(strip):
    """At 0.6 ``q_p`` (below first yield, 2/3 ``q_p``: ``M_y = 2/3 M_p``) no
    point flows."""
    res = _ratio(strip, 0.6, 1.0)
    assert res.carried and res.at == 1.0
    assert res.plasticity.state.equivalent.max() == 0.0
