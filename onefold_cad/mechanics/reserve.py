"""How far the coarse preview may be trusted on "stands".

The coarse mesh's few large triangles are much stiffer than the sheet: on
patkau-one-fold at t = 3 mm the coarse mesh carries 1.875 times the sheet's
weight before its load path ends, the normal mesh 0.906 (it does not stand),
at t = 3.57 mm the coarse 2.375 (the moment law; :func:`carried` on each
level's model, tests/mechanics/test_reserve.py): the coarse mesh overstates
the load a sheet carries by about two. So a coarse "stands" is
a yes only when the coarse sheet carries :data:`COARSE_RESERVE` times its
weight; below that the answer is "uncertain: run --mesh normal".
"""

from __future__ import annotations

import numpy as np

from onefold_cad.geometry.numeric import Array
from onefold_cad.mechanics.equilibrium import Equilibrium, PathStalled, solve_path
from onefold_cad.mechanics.model import GRAVITY, SheetModel
from onefold_cad.mechanics.stages import Placed, standing_path

__all__ = ["COARSE_RESERVE", "carried"]

#: The multiple of its weight a coarse sheet must carry for a plain "stands":
#: the coarse-to-normal ratio of the load carried (1.875 / 0.906 = 2.07,
#: patkau-one-fold at t = 3 mm) with a margin.
COARSE_RESERVE = 2.5


def carried(
    model: SheetModel,
    placed: Placed,
    standing: Equilibrium,
    rest_curvature: Array,
    supports: str,
    up_to: float = COARSE_RESERVE,
) -> float:
    """The multiple of its weight the standing sheet carries, its gravity
    ramped on from 1 to ``up_to`` (``up_to`` when it carries all of it; the
    moment law's shell, contacts and load steps of the standing stage)."""
    base = placed.shell.with_changes(rest_curvature=rest_curvature)
    g = np.array([0.0, 0.0, -GRAVITY])
    options = standing_path(model, placed, supports)
    options["contacts"] = standing.contacts
    try:
        solve_path(
            lambda s: base.with_changes(gravity=(1.0 + s * (up_to - 1.0)) * g),
            standing.q,
            **options,  # type: ignore[arg-type]
        )
    except PathStalled as err:
        return 1.0 + err.reached * (up_to - 1.0)
    return up_to
