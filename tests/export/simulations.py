"""Simulations the export tests share."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from onefold_cad.mechanics.results import Simulation, Standing


def stalled_copy(sim: Simulation) -> Simulation:
    """``sim`` as a simulation whose standing stage found no equilibrium, built
    as simulate builds it on a stalled load path (a real stall takes minutes:
    patkau on frictionless supports stands; a 0.5 mm sheet stalls in ~3 min)."""
    reason = (
        "no equilibrium under its full weight on anchored supports: the load path ends at "
        "0.31 of the weight (Newton's residual there 12.3 N)"
    )
    standing = Standing(
        stands=False,
        reason=reason,
        load_factor=0.31,
        max_deviation=None,
        rms_deviation=None,
        max_displacement=None,
        height=None,
        span=None,
        reactions_total_N=None,
        contacts=np.zeros((0, 3)),
        tipping_margin_deg=None,
        max_stress_MPa=None,
        utilisation=None,
        max_stress_at=None,
        iterations=40,
        reloaded_area_share=0.0,
    )
    return replace(
        sim, standing=standing, standing_positions=None, deviation=None, face_stress_MPa=None
    )
