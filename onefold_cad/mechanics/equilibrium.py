"""Static equilibrium of a shell: supports, the ground as contact, reactions, and
load paths (continuation).

The ground is the plane ``z = height``, an active set of touching nodes:
``anchored`` fixes a touching node in x, y and z, ``frictionless`` in z only (the
caller then supplies a minimal in-plane restraint). Nodes that sink below the
ground join the set (put on it), nodes whose reaction pulls leave it; repeat
until neither happens. Reactions (N) are the energy's gradient at the fixed
coordinates: the forces the supports exert on the sheet.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.errors import ConvergenceError, InvalidParameterError
from onefold_cad.mechanics.energy import Evaluation, evaluate
from onefold_cad.mechanics.newton import FactorReuse, NewtonResult, Progress, minimize
from onefold_cad.mechanics.predictor import extrapolate
from onefold_cad.mechanics.shell import Shell, unpack

__all__ = [
    "Equilibrium",
    "Ground",
    "PathStalled",
    "solve_equilibrium",
    "solve_directors",
    "solve_path",
]

F = NDArray[np.float64]

#: The fewest equilibria a predicted start is drawn through: not a line
#: through two (a J2 strip released at R sigma_y / (E t) = 0.3,
#: tests/mechanics/j2/test_layered.py: 95 Newton iterations with the line's
#: start against 61 from the last state, 61 from the third step on).
_PREDICT_FROM = 3


@dataclass(frozen=True)
class Ground:
    """The ground plane as a one-sided contact.

    Attributes:
        mode: ``"anchored"`` (touching nodes fixed in x, y, z) or ``"frictionless"`` (z only).
        height: the plane's z (m).
    """

    mode: Literal["anchored", "frictionless"] = "anchored"
    height: float = 0.0

    def __post_init__(self) -> None:
        if self.mode not in ("anchored", "frictionless"):
            raise InvalidParameterError(
                "supports", f"must be anchored or frictionless, got {self.mode!r}"
            )


@dataclass(frozen=True)
class Equilibrium:
    """A converged equilibrium.

    Attributes:
        q: (N,) the state (see ``shell``).
        positions: (n, 3) node positions (m).
        energy: total energy (J); ``parts`` its terms.
        reactions: (n, 3) support forces on the sheet (N), zero at free coordinates.
        director_reactions: (n_dir,) support moments at fixed director angles (N m).
        contacts: (n,) bool, nodes on the ground.
        iterations: Newton steps over all passes; ``passes`` the solves.
        residual: the last solve's residual (N) and ``tolerance`` its bound.
    """

    q: F
    positions: F
    energy: float
    parts: dict[str, float]
    reactions: F
    director_reactions: F
    contacts: NDArray[np.bool_]
    iterations: int
    passes: int
    residual: float
    tolerance: float


def _dof_mask(shell: Shell, dofs: ArrayLike) -> NDArray[np.bool_]:
    mask = np.zeros(shell.mesh.n_dofs, dtype=bool)
    d = np.asarray(dofs, dtype=np.int64).ravel()
    if d.size:
        mask[d] = True
    return mask


def _residual_scale(shell: Shell, length: float | None) -> F:
    n = shell.mesh.n_nodes
    length = float(np.mean(shell.mesh.edge_lengths)) if length is None else length
    return np.concatenate([np.ones(3 * n), np.full(shell.mesh.n_directors, 1.0 / length)])


class _Energy:
    """``shell``'s energy as Newton calls it, keeping its last evaluation with
    a gradient: Newton's result is where it last evaluated the Hessian, so the
    equilibrium's energy, parts and reactions need no second evaluation."""

    def __init__(self, shell: Shell) -> None:
        self.shell = shell
        self._last: tuple[F, Evaluation] | None = None

    def __call__(self, state: F, order: int):
        ev = evaluate(self.shell, state, order)
        if order >= 1:
            self._last = (state.copy(), ev)  # a copy: callers move their states in place
        return ev.energy, ev.gradient, ev.hessian

    def at(self, q: F) -> Evaluation:
        """The energy and gradient at ``q``: the last evaluation if it was there."""
        if self._last is not None and np.array_equal(self._last[0], q):
            return self._last[1]
        return evaluate(self.shell, q, 1)


def _newton(
    fun: _Energy,
    q: F,
    fixed: NDArray[np.bool_],
    *,
    rtol: float,
    max_iter: int,
    force_scale: float | None,
    length_scale: float | None,
    start_scales: bool,
    callback: Progress | None,
    reuse: FactorReuse | None,
) -> NewtonResult:
    shell = fun.shell
    mat = shell.material
    x = unpack(shell.mesh, q)[0]
    # The membrane forces' round-off is about eps E' t |x| (measured: 1.1 times that).
    size = max(float(np.max(np.abs(x))), float(np.ptp(shell.reference, axis=0).max()))
    atol = 10 * np.finfo(float).eps * mat.membrane_stiffness * size
    return minimize(
        fun,
        q,
        fixed,
        residual_scale=_residual_scale(shell, length_scale),
        force_scale=shell.weight if force_scale is None else force_scale,
        rtol=rtol,
        atol=atol,
        max_iter=max_iter,
        start_scales=start_scales,
        callback=callback,
        reuse=reuse,
    )


def solve_equilibrium(
    shell: Shell,
    q0: ArrayLike,
    *,
    fixed: ArrayLike = (),
    ground: Ground | None = None,
    contacts: ArrayLike | None = None,
    rtol: float = 1e-9,
    max_iter: int = 60,
    max_passes: int = 30,
    force_scale: float | None = None,
    length_scale: float | None = None,
    start_scales: bool = True,
    callback: Progress | None = None,
    reuse: FactorReuse | None = None,
) -> Equilibrium:
    """The equilibrium nearest ``q0`` (Newton from it), with supports and ground.

    Args:
        shell: the model.
        q0: (N,) start.
        fixed: DOF ids held at their start values (supports, clamps, rigid restraints).
        ground: the ground contact, or None.
        contacts: (n,) bool, nodes on the ground at the start (default: those at or
            below it); they are moved onto the plane. Nodes held in z by ``fixed``
            are never contacts.
        rtol: residual tolerance relative to ``force_scale`` (default: the weight,
            or the start's residual when that is larger).
        length_scale: turns director moments into forces (default: mean edge length).
        start_scales: whether ``q0``'s residual may raise the tolerance
            (``newton.minimize``; False for a predicted start).
        callback: progress, ``callback(iteration, residual N, energy J)``.
        reuse: the factors of earlier solves (``newton.FactorReuse``); default:
            one for this solve's contact passes.

    Raises:
        ConvergenceError: a Newton solve or the contact iteration did not converge.
    """
    mesh = shell.mesh
    n = mesh.n_nodes
    q = np.array(q0, dtype=float)
    base = _dof_mask(shell, fixed)
    if ground is None:
        active = np.zeros(n, dtype=bool)
    elif contacts is None:
        active = unpack(mesh, q)[0][:, 2] <= ground.height
    else:
        active = np.asarray(contacts, dtype=bool).copy()
    held_z = base[2 : 3 * n : 3]  # nodes the caller holds in z cannot be contacts
    active &= ~held_z
    total_iter = 0
    result = None
    passes = 0
    energy = _Energy(shell)
    reuse = FactorReuse() if reuse is None else reuse
    for _ in range(max_passes):
        passes += 1
        fixed_mask = base.copy()
        if ground is not None:
            x = q[: 3 * n].reshape(n, 3)
            x[active, 2] = ground.height
            fixed_mask[3 * np.flatnonzero(active) + 2] = True
            if ground.mode == "anchored":
                fixed_mask[3 * np.flatnonzero(active)] = True
                fixed_mask[3 * np.flatnonzero(active) + 1] = True
        result = _newton(
            energy,
            q,
            fixed_mask,
            rtol=rtol,
            max_iter=max_iter,
            force_scale=force_scale,
            length_scale=length_scale,
            start_scales=start_scales,
            callback=callback,
            reuse=reuse,
        )
        total_iter += result.iterations
        q = result.q
        if ground is None:
            break
        x = q[: 3 * n].reshape(n, 3)
        rz = result.gradient[2 : 3 * n : 3]
        slack = max(result.tolerance, 1e-12 * max(shell.weight, 1e-300))
        sinking = ~active & ~held_z & (x[:, 2] < ground.height - 1e-9 * (1.0 + abs(ground.height)))
        pulling = active & (rz < -slack)
        if not sinking.any() and not pulling.any():
            break
        active = (active & ~pulling) | sinking
    else:
        raise ConvergenceError(
            f"the ground contact did not settle in {max_passes} passes",
            iterations=total_iter,
            residual=result.residual if result else float("nan"),
        )
    ev = energy.at(q)
    assert ev.gradient is not None
    fixed_final = base.copy()
    if ground is not None:
        fixed_final[3 * np.flatnonzero(active) + 2] = True
        if ground.mode == "anchored":
            fixed_final[3 * np.flatnonzero(active)] = True
            fixed_final[3 * np.flatnonzero(active) + 1] = True
    react = np.where(fixed_final, ev.gradient, 0.0)
    node_react = react[: 3 * n].reshape(n, 3).copy()
    return Equilibrium(
        q=q,
        positions=q[: 3 * n].reshape(n, 3).copy(),
        energy=ev.energy,
        parts=ev.parts,
        reactions=node_react,
        director_reactions=react[3 * n :],
        contacts=active,
        iterations=total_iter,
        passes=passes,
        residual=result.residual,
        tolerance=result.tolerance,
    )


class PathStalled(ConvergenceError):
    """A continuation that found no equilibrium past ``reached`` (0..1) of its path.

    Attributes:
        reached: the path parameter of the last equilibrium found.
        last: that equilibrium (None when even the first step failed).
    """

    def __init__(
        self,
        message: str,
        *,
        iterations: int,
        residual: float,
        reached: float,
        last: Equilibrium | None,
    ) -> None:
        super().__init__(message, iterations=iterations, residual=residual)
        self.reached = reached
        self.last = last


def solve_path(
    shell_at: Callable[[float], Shell],
    q0: ArrayLike,
    *,
    first_step: float = 0.25,
    min_step: float = 1e-3,
    step_iter: int = 25,
    max_move: float | None = None,
    max_solves: int = 64,
    grow_iter: int = 6,
    predict: int = 0,
    callback: Progress | None = None,
    accepted: Callable[[float, Equilibrium], None] | None = None,
    may_grow: Callable[[], bool] | None = None,
    **options: object,
) -> Equilibrium:
    """Continuation: equilibria of ``shell_at(s)`` for ``s`` from 0 to 1, each solve
    started from the last (a load or rest-form ramp for large motions).

    The step in ``s`` halves when a solve fails, or when its equilibrium lies
    more than ``max_move`` (m) from the last one at some node (Newton jumped to
    another branch: the path is followed, so a limit point stalls it instead of
    snapping through), and doubles after one that took at most ``grow_iter``
    iterations (and for which ``may_grow()``, asked after ``accepted``, is
    true, when given); every solve (``solve_equilibrium``'s ``options``) gets at most
    ``step_iter`` Newton iterations (a step that needs more is halved); at
    most ``max_solves`` solves in all. With ``predict`` = k > 0 each solve
    once the path has three equilibria (the start among them) starts from the
    polynomial through the last k + 1 of them (fewer while there are fewer;
    ``predictor.extrapolate``) at the step's end, the fixed unknowns and the
    nodes on the ground (the last equilibrium's and the starting
    ``contacts``) held, and its tolerance is ``rtol`` times ``force_scale``
    alone (not raised by the predicted start's residual).
    ``accepted(s, equilibrium)`` is called after each step the path keeps
    (a path-dependent material moves its internal variables on there, so
    ``shell_at`` gives the next step's shell with them). The steps share one
    ``newton.FactorReuse`` (unless ``options`` give one): each structure of
    their Hessians is ordered and analysed once.

    Raises:
        PathStalled: the step fell below ``min_step``, or ``max_solves`` solves
            did not reach the end (a ConvergenceError that holds the last
            equilibrium and how far along the path it is).
    """
    q = np.asarray(q0, dtype=float)
    s, ds, total, failed = 0.0, first_step, 0, float("nan")
    options.setdefault("reuse", FactorReuse())  # every step's structures analysed once
    last: Equilibrium | None = None
    passed: list[tuple[float, F]] = [(s, q)]
    for _ in range(max_solves):
        target = min(1.0, s + ds)
        opts: dict[str, Any] = dict(options)
        # every solve, the last one too, gets at most step_iter iterations: a step
        # Newton cannot finish quickly is halved, never ground through
        opts["max_iter"] = min(int(opts.get("max_iter", 60)), step_iter)
        shell, start = shell_at(target), q
        if predict > 0 and len(passed) >= _PREDICT_FROM:
            assert last is not None
            held = _held(shell, options, last)
            start = extrapolate(passed[-(predict + 1) :], target, held)
            opts["start_scales"] = False
        try:
            eq = solve_equilibrium(shell, start, callback=callback, **opts)
            n = shell.mesh.n_nodes
            moved = float(np.max(np.linalg.norm((eq.q - q)[: 3 * n].reshape(n, 3), axis=1)))
            if max_move is not None and moved > max_move:
                raise ConvergenceError(
                    f"the step to s = {target:.4g} moved a node {moved:.3g} m (more than "
                    f"{max_move:.3g} m): another branch",
                    iterations=eq.iterations,
                    residual=eq.residual,
                )
        except ConvergenceError as err:
            total += err.iterations
            failed = err.residual
            ds /= 2
            if ds < min_step:
                raise PathStalled(
                    f"continuation stalled at s = {s:.4g} (step {2 * ds:.3g}): {err}",
                    iterations=total,
                    residual=err.residual,
                    reached=s,
                    last=last,
                ) from err
            continue
        total += eq.iterations
        q, s, last = eq.q, target, eq
        passed.append((s, q))
        if accepted is not None:
            accepted(s, eq)
        if s >= 1.0:
            return replace(eq, iterations=total)
        if eq.iterations <= grow_iter and (may_grow is None or may_grow()):
            ds = min(2 * ds, 1.0)
    raise PathStalled(
        f"continuation did not reach the end in {max_solves} solves (at s = {s:.4g}; the last "
        f"failed Newton's residual {failed:.3g} N)",
        iterations=total,
        residual=failed,
        reached=s,
        last=last,
    )


def _held(shell: Shell, options: dict[str, object], last: Equilibrium) -> NDArray[np.bool_]:
    """The unknowns a predicted start keeps at ``last``'s values: the fixed
    ones and every coordinate of a node on the ground there or among the
    solves' starting ``contacts`` (anchored feet stay where they stand)."""
    held = _dof_mask(shell, np.asarray(options.get("fixed", ()), dtype=np.int64))
    on = last.contacts.copy()
    if options.get("contacts") is not None:
        on |= np.asarray(options["contacts"], dtype=bool)
    held[: 3 * shell.mesh.n_nodes] |= np.repeat(on, 3)
    return held


def solve_directors(shell: Shell, q0: ArrayLike, **options: object) -> Equilibrium:
    """Hold every node where ``q0`` puts it and solve for the director angles (an
    imposed form: the directors' moments balance)."""
    n = shell.mesh.n_nodes
    return solve_equilibrium(shell, q0, fixed=np.arange(3 * n), **options)  # type: ignore[arg-type]
