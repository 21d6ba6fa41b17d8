"""Simulations the export tests share."""

from __future__ import annotations

from dataclasses import replace

from onefold_cad.mechanics.results import Simulation, Standing


def stalled_copy(sim: Simulation) -> Simulation:
    """``sim`` as a simulation whose standing stage found no equilibrium, built
    as simulate builds it on a stalled load path (a real stall takes minutes:
    patkau on frictionless supports stands; a 0.5 mm sheet stalls in ~3 min)."""
    reason = (
        "no equilibrium under its full weight on anchored supports: the load path ends at "
        "0.31 of the weight (Newton's residual there 12.3 N)"
    )
    standing = Standing.stalled(reason, 0.31, 40)
    return replace(
        sim, standing=standing, standing_positions=None, deviation=None, face_stress_MPa=None
    )
