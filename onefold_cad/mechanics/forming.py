"""Forming and the plastic load path: the flat sheet bent into a form along the
plastic skeleton (:func:`form_sheet`), and incremental elastic-plastic
equilibria with the return mapping between increments (:func:`solve_plastic`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.errors import ConvergenceError
from onefold_cad.mechanics import plastic
from onefold_cad.mechanics.energy import second_fundamental_form
from onefold_cad.mechanics.equilibrium import (
    Equilibrium,
    PathStalled,
    solve_directors,
    solve_equilibrium,
)
from onefold_cad.mechanics.newton import Progress
from onefold_cad.mechanics.shell import Shell, director_angles

__all__ = ["PlasticResult", "form_sheet", "solve_plastic"]

F = NDArray[np.float64]


@dataclass(frozen=True)
class PlasticResult:
    """An equilibrium consistent with the plastic law.

    Attributes:
        equilibrium: the converged state.
        state: the faces' plastic states after it.
        updates: faces that yielded along the path.
        reverse: (m,) bool, faces past a rectangular section's reverse yield
            (``plastic.check``: reported, not modelled).
    """

    equilibrium: Equilibrium
    state: plastic.PlasticState
    updates: int
    reverse: NDArray[np.bool_]


def solve_plastic(
    shell_at: Callable[[float], Shell],
    q0: ArrayLike,
    state: plastic.PlasticState,
    *,
    first_step: float = 0.25,
    min_step: float = 1e-3,
    step_iter: int = 25,
    callback: Progress | None = None,
    **options: object,
) -> PlasticResult:
    """Incremental elastic-plastic equilibria along a load path ``shell_at(s)``,
    ``s`` from 0 to 1, from the equilibrium ``q0`` of ``shell_at(0)``.

    Each increment is one Newton solve with every face on the elastic-plastic
    law from its state at the increment's start (``Shell.accumulated``: smooth,
    with its exact tangent); then the states move on (``plastic.update``, the
    return mapping) and the next increment starts. An increment that fails is
    halved, one that converges quickly doubles the next. ``options`` go to
    ``solve_equilibrium``; ``shell_at(s)``'s rest curvature is replaced by the faces'
    plastic rest forms.

    Raises:
        PathStalled: an increment fell below ``min_step`` (holds the last
            equilibrium and how far along the path it is).
    """
    q = np.asarray(q0, dtype=float)
    s, ds, total, yielded = 0.0, first_step, 0, np.zeros(len(state.rest), dtype=bool)
    last: Equilibrium | None = None
    while s < 1.0:
        target = min(1.0, s + ds)
        current = shell_at(target).with_changes(
            rest_curvature=state.rest, accumulated=state.accumulated
        )
        opts: dict[str, Any] = dict(options)
        if target < 1.0:
            opts["max_iter"] = min(int(opts.get("max_iter", 60)), step_iter)
        try:
            eq = solve_equilibrium(current, q, callback=callback, **opts)
        except ConvergenceError as err:
            ds /= 2
            if ds < min_step:
                raise PathStalled(
                    f"the plastic load path stalled at s = {s:.4g}: {err}",
                    iterations=total + err.iterations,
                    residual=err.residual,
                    reached=s,
                    last=last,
                ) from err
            continue
        b = second_fundamental_form(current, eq.q)
        state, now = plastic.update(current.material, current.form, b, state)
        yielded |= now
        q, s, last = eq.q, target, eq
        total += eq.iterations
        if eq.iterations <= 6:
            ds = min(2 * ds, 1.0)
    assert last is not None
    final = shell_at(1.0)
    reverse = plastic.check(final.material, final.form, second_fundamental_form(final, q), state)
    return PlasticResult(replace(last, iterations=total), state, int(yielded.sum()), reverse)


def form_sheet(
    shell: Shell, x: ArrayLike, normals: ArrayLike | None = None, **options: object
) -> tuple[Equilibrium, plastic.PlasticState, F]:
    """Bend the flat sheet into the form ``x`` ((n, 3), m) along the plastic skeleton.

    The form is imposed as a whole: nodes at ``x`` and, given the form's normals
    (see ``director_angles``), every director along them; without normals the
    directors are solved with the elastic law (then the free boundary's directors
    relax, and the faces' curvature is wrong near the boundary by O(1)). Every
    face's plastic state is then set from its curvature (``plastic.form``).

    Returns:
        The formed state, the faces' plastic states, (m,) the work of forming (J).
    """
    mesh = shell.mesh
    p = np.asarray(x, dtype=float).reshape(mesh.n_nodes, 3)
    if normals is None:
        q0 = np.concatenate([p.ravel(), np.zeros(mesh.n_directors)])
        flat = shell.with_changes(rest_curvature=np.zeros_like(shell.rest_curvature))
        eq = solve_directors(flat, q0, **options)
    else:
        q0 = np.concatenate([p.ravel(), director_angles(shell, p, normals)])
        eq = solve_equilibrium(shell, q0, fixed=np.arange(mesh.n_dofs), **options)  # type: ignore[arg-type]
    b = second_fundamental_form(shell, eq.q)
    state, work = plastic.form(shell.material, shell.form, b, shell.ref_area)
    return eq, state, work
