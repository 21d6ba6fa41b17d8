"""How far the coarse preview may be trusted on "stands".

The coarse mesh's few large triangles are much stiffer than the sheet: on
patkau-one-fold at t = 3 mm the coarse mesh carries 1.875 times the sheet's
weight before its load path ends, the normal mesh 0.906 (it does not stand),
at t = 3.57 mm the coarse 2.375 (the moment law; :func:`carried` on each
level's model, tests/mechanics/test_reserve.py): the coarse mesh overstates
the load a sheet carries by about two. So a coarse "stands" is
a yes only when the coarse sheet carries :data:`COARSE_RESERVE` times its
weight; below that, or where the check cannot show it, the answer is
"uncertain: run --mesh normal".
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from onefold_cad.geometry.numeric import Array
from onefold_cad.mechanics.equilibrium import Equilibrium, PathStalled, solve_path
from onefold_cad.mechanics.model import GRAVITY, SheetModel
from onefold_cad.mechanics.newton import Progress
from onefold_cad.mechanics.shell import Shell
from onefold_cad.mechanics.stages import Placed, standing_path

__all__ = ["COARSE_RESERVE", "ReserveCheck", "carried", "shows_carried"]

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
    progress: Progress | None = None,
) -> float:
    """A multiple of its weight the standing sheet is shown to carry: ``up_to``
    when it does, else 1 (its weight, carried already): :func:`shows_carried`
    with the moment law's shell, so a sheet it cannot show to carry ``up_to``
    may carry more (the answer is then "uncertain", which asks for the
    normal mesh, never a wrong yes). ``progress`` hears its Newton steps."""
    base = placed.shell.with_changes(rest_curvature=rest_curvature)
    return up_to if shows_carried(model, placed, base, standing, supports, up_to, progress) else 1.0


def shows_carried(
    model: SheetModel,
    placed: Placed,
    shell: Shell,
    standing: Equilibrium,
    supports: str,
    up_to: float,
    progress: Progress | None = None,
) -> bool:
    """Whether ``shell`` (either law's, in the resting frame) standing in
    ``standing`` carries ``up_to`` times its weight: its gravity goes from 1
    to ``up_to`` in one Newton solve of the standing stage's iterations, its
    contacts and step limits. A check, not the load path: False may be a
    sheet that carries more."""
    g = np.array([0.0, 0.0, -GRAVITY])
    options = standing_path(model, placed, supports)
    options.update({"contacts": standing.contacts, "first_step": 1.0, "max_solves": 1})
    try:
        solve_path(
            lambda s: shell.with_changes(gravity=(1.0 + s * (up_to - 1.0)) * g),
            standing.q,
            callback=progress,
            **options,
        )
    except PathStalled:
        return False
    return True


@dataclass(frozen=True, eq=False)
class ReserveCheck:
    """A coarse standing's reserve check left for later
    (``simulate.run(..., reserve=False)``; ``verdicts.settle_reserve`` runs it).

    Attributes:
        model: the sheet model.
        placed: the form stood on the ground before it carried its weight.
        standing: the standing equilibrium.
        shell: the shell the check solves with, in the resting frame (the
            moment law's with the faces' rest form; J2's with the stand's
            internal variables too).
        supports: 'anchored' or 'frictionless'.
        law: the run's law ('moment' or 'j2'; its warnings' wording).
        size: the sheet's size (design unit; its warnings' wording).
    """

    model: SheetModel
    placed: Placed
    standing: Equilibrium
    shell: Shell
    supports: str
    law: str
    size: float

    def carried(self, progress: Progress | None = None) -> float:
        """:data:`COARSE_RESERVE` when the standing sheet is shown to carry it,
        else 1 (its weight, carried already): :func:`shows_carried`."""
        ok = shows_carried(
            self.model, self.placed, self.shell, self.standing, self.supports, COARSE_RESERVE,
            progress,
        )  # fmt: skip
        return COARSE_RESERVE if ok else 1.0
