"""The linear response of a shell state to external loads.

About an equilibrium ``q`` (the sheet standing under its weight), a load
``f`` moves the unknowns by ``u`` with ``K_ff u_f = f_f`` (``K`` the energy's
Hessian at ``q``: the tangent stiffness, the weight's stresses included;
``_f`` the free unknowns, the supports' held ones at zero) and changes the
supports' forces on the sheet by ``r_s = K_sf u_f - f_s``. One factorisation
serves every load: the cases are superposed (small movements, the loads'
directions fixed: a pressure does not turn with the surface).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse.linalg as spla

from onefold_cad.errors import ConvergenceError
from onefold_cad.geometry.numeric import Array
from onefold_cad.mechanics.energy import evaluate
from onefold_cad.mechanics.shell import Shell

__all__ = ["LinearResponse", "linear_response", "node_dofs"]


def node_dofs(nodes: Array) -> Array:
    """The x, y, z unknowns of ``nodes`` (ids into ``q``)."""
    n = np.asarray(nodes, dtype=np.int64).ravel()
    return (3 * n[:, None] + np.arange(3)).ravel()


@dataclass(frozen=True)
class LinearResponse:
    """The responses to a set of loads.

    Attributes:
        moves: ``(k, N)`` each load's change of the unknowns (m, rad).
        reactions: ``(k, n, 3)`` each load's change of the supports' forces on
            the sheet at every node (N; zero where nothing is held).
    """

    moves: Array
    reactions: Array


def linear_response(shell: Shell, q: Array, fixed: Array, loads: Array) -> LinearResponse:
    """The responses of the state ``q`` (m) with the unknowns ``fixed`` held to
    the nodal loads ``loads`` ``(k, n, 3)`` (N).

    Raises:
        ConvergenceError: the held unknowns leave the sheet free to move (a
            singular stiffness).
    """
    n = shell.mesh.n_nodes
    big = shell.mesh.n_dofs
    hess = evaluate(shell, q, 2).hessian.tocsc()
    held = np.zeros(big, dtype=bool)
    held[np.asarray(fixed, dtype=np.int64)] = True
    free = np.flatnonzero(~held)
    f = np.zeros((len(loads), big))
    f[:, : 3 * n] = np.asarray(loads, dtype=float).reshape(len(loads), 3 * n)
    k_ff = hess[free][:, free].tocsc()
    try:
        lu = spla.splu(k_ff)
    except RuntimeError as err:
        raise ConvergenceError(
            f"the supports leave the standing sheet free to move ({err})",
            iterations=0,
            residual=float("nan"),
        ) from err
    moves = np.zeros_like(f)
    moves[:, free] = lu.solve(f[:, free].T).T
    if not np.all(np.isfinite(moves)):
        raise ConvergenceError(
            "the supports leave the standing sheet free to move (singular stiffness)",
            iterations=0,
            residual=float("nan"),
        )
    r = (hess @ moves.T).T - f
    r[:, ~held] = 0.0
    return LinearResponse(moves, r[:, : 3 * n].reshape(len(loads), n, 3))
