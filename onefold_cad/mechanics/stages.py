"""The forming sequence of a sheet model, each stage an equilibrium.

- :func:`form`: the flat sheet bent into the design (imposed: every node on
  the designed form, every director along its normal); each face's plastic
  state follows from its curvature on the moment-curvature skeleton.
- :func:`release`: the machine lets go: no gravity, rigid motion restrained
  by a statically determinate 3-2-1 support (which carries nothing), the
  creases at their set angles; each face unloads elastically to its plastic
  rest curvature (the rest form ramps from the formed curvature to it).
- :func:`stand`: on the ground under its own weight (gravity ramped from 0),
  anchored where it touches or on frictionless feet.

Every stage either converges or raises :class:`~onefold_cad.errors.ConvergenceError`
(a stand that finds no equilibrium under the full weight raises
:class:`~onefold_cad.mechanics.equilibrium.PathStalled`, which says how much of
the weight it carried).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NotRequired, TypedDict

import numpy as np

from onefold_cad.geometry.numeric import Array
from onefold_cad.geometry.resting.placement import rotation_to_up
from onefold_cad.geometry.resting.topple import roll
from onefold_cad.mechanics import plastic
from onefold_cad.mechanics.deviation import best_fit
from onefold_cad.mechanics.energy import second_fundamental_form
from onefold_cad.mechanics.equilibrium import Equilibrium, Ground, solve_path
from onefold_cad.mechanics.forming import form_sheet
from onefold_cad.mechanics.model import GRAVITY, SheetModel
from onefold_cad.mechanics.newton import Progress
from onefold_cad.mechanics.shell import Shell, moved, rigid_dofs, unpack

__all__ = [
    "Formed",
    "PathOptions",
    "Placed",
    "Stage",
    "form",
    "in_plane_restraint",
    "place",
    "release",
    "stand",
    "standing_path",
]

#: Newton's tolerance: the residual force relative to the sheet's weight
#: (patkau-one-fold: 6.2 mN at any node; Abaqus's default is 5e-3 of the
#: average nodal force, about 10 mN there). Newton converges quadratically
#: to it: on patkau's coarse mesh the step from a residual of 98 N lands at
#: 6 mN, and one more step to 1e-7 of the weight (0.5 mN, the round-off
#: floor) moved the springback and the standing form by 2 micrometres
#: (275.2321 -> 275.2337 mm), at an iteration of the 17 the Steel view's
#: simulation took (docs/mechanics.md, "Newton's tolerance").
RTOL = 1e-6
#: The standing's load steps: at most this share of the sheet's size of
#: movement per step (so the load path is followed and a limit point stalls
#: it), no step smaller than this share of the weight, and at most this many
#: Newton steps for a step short of the full weight.
MAX_MOVE, MIN_LOAD_STEP, STEP_ITERATIONS = 0.05, 1 / 32, 12


@dataclass(frozen=True)
class Formed:
    """The sheet bent into the design.

    Attributes:
        q: the state (designed nodes, directors along the designed normals).
        curvature: ``(m, 3)`` each face's formed second fundamental form.
        state: the faces' plastic states.
        work: ``(m,)`` the work of bending each face into the form (J).
    """

    q: Array
    curvature: Array
    state: plastic.PlasticState
    work: Array


@dataclass(frozen=True)
class Stage:
    """A converged stage.

    Attributes:
        equilibrium: the equilibrium (positions, reactions, contacts, iterations).
        state: the faces' plastic states after it.
        reloaded: ``(m,)`` bool, faces whose curvature went past their elastic
            range (the law takes them on plastically; the stage unloads every
            face elastically, so it underestimates the motion there).
        reverse: ``(m,)`` bool, faces past a rectangular section's reverse
            yield (``plastic.check``).
    """

    equilibrium: Equilibrium
    state: plastic.PlasticState
    reloaded: np.ndarray
    reverse: np.ndarray


@dataclass(frozen=True)
class Placed:
    """A form stood rigidly on the ground before it carries its weight.

    Attributes:
        q: the placed state (resting frame, m), its director angles measured in
            ``shell``'s frames.
        contacts: ``(n,)`` bool, its nodes on the ground.
        rotation, translation: the rigid motion from the state it came from.
        shell: the model's shell moved with it (``shell.moved``: its reference
            in the resting frame), the one to evaluate ``q`` and the states
            after it with.
    """

    q: Array
    contacts: np.ndarray
    rotation: Array
    translation: Array
    shell: Shell


def form(model: SheetModel) -> Formed:
    """Bend the flat sheet into the designed form along the plastic skeleton."""
    eq, state, work = form_sheet(model.shell, model.designed, model.normals, rtol=RTOL)
    b = second_fundamental_form(model.shell, eq.q)
    return Formed(eq.q, b, state, work)


def _unloading(shell: Shell, eq: Equilibrium, state: plastic.PlasticState) -> Stage:
    """A stage solved with every face unloading elastically from its plastic
    state, and the faces that went past where they yielded (reloading: the law
    would take them on plastically; :attr:`Stage.reloaded`)."""
    b = second_fundamental_form(shell, eq.q)
    kform, mat = shell.form, shell.material
    s = plastic.equivalent_curvature(kform, b - state.rest)
    m, _, _ = plastic.moment(mat, s, state.accumulated)
    past = m < mat.bending_stiffness * s * (1 - 1e-9)
    return Stage(eq, state, past, plastic.check(mat, kform, b, state))


def release(model: SheetModel, formed: Formed, progress: Progress | None = None) -> Stage:
    """Let the formed sheet go: springback with no gravity and no supports (a
    3-2-1 restraint removes rigid motion and carries nothing); every face
    unloads elastically from its formed state (its rest form ramps from the
    formed curvature to its plastic rest form)."""
    shell = model.shell
    fixed = rigid_dofs(model.designed)
    b_f, b_p = formed.curvature, formed.state.rest
    eq = solve_path(
        lambda s: shell.with_changes(rest_curvature=b_f + s * (b_p - b_f)),
        formed.q,
        fixed=fixed,
        force_scale=model.weight_N,
        first_step=1.0,
        rtol=RTOL,
        callback=progress,
    )
    return _unloading(shell.with_changes(rest_curvature=b_p), eq, formed.state)


def place(model: SheetModel, q: Array) -> Placed:
    """Stand a state rigidly on the ground: brought closest to the designed form
    (mass-weighted), put in the designed resting frame, then toppled about its
    lowest points until it rests (``geometry.topple.roll``), its lowest point on
    z = 0."""
    shell = model.shell
    x = unpack(model.mesh, q)[0]
    mass = shell.node_mass
    fit = best_fit(x, model.designed, mass)
    r_rest, t_rest = model.standing_frame()
    rot = r_rest @ fit.rotation
    shift = r_rest @ fit.translation + t_rest
    p = x @ rot.T + shift
    com = mass @ p / mass.sum()
    size = float(np.ptp(p, axis=0).max())
    up, _ = roll(p, com, np.array([0.0, 0.0, 1.0]), 1e-9 * size)
    tilt = rotation_to_up(up)
    rot = tilt @ rot
    shift = tilt @ (shift - com) + com
    shift[2] -= float(np.min(x @ rot[2] + shift[2]))
    shell, placed = moved(shell, q, rot, shift)
    z = unpack(model.mesh, placed)[0][:, 2]
    return Placed(placed, z <= 1e-9 * size, rot, shift, shell)


def in_plane_restraint(x: Array, contacts: np.ndarray) -> list[int]:
    """DOF ids that remove a frictionless stand's in-plane rigid motion (x and y
    of one contact, the other horizontal direction of the farthest one): they
    carry nothing, for the weight is vertical."""
    ids = np.flatnonzero(contacts)
    i = int(ids[0])
    j = int(ids[np.argmax(np.linalg.norm(x[ids, :2] - x[i, :2], axis=1))])
    d = x[j, :2] - x[i, :2]
    return [3 * i, 3 * i + 1, 3 * j + (1 if abs(d[0]) >= abs(d[1]) else 0)]


class PathOptions(TypedDict):
    """:func:`standing_path`'s keywords for ``solve_path`` (``**`` into it):
    its load steps, and the options it passes on to ``solve_equilibrium``.

    Attributes:
        fixed: unknowns' ids held (the frictionless feet's in-plane restraint).
        ground: the ground (z = 0) and how the feet hold on it.
        contacts: ``(n,)`` bool, the placed nodes on the ground.
        force_scale: the sheet's weight (N), Newton's tolerance scale.
        first_step, min_step: the first and the smallest load step (share of
            the weight).
        step_iter: Newton steps allowed for a step short of the full weight.
        max_move: the largest movement in a step (m).
        rtol: Newton's tolerance relative to ``force_scale``.
        max_solves: the solves allowed (``solve_path``'s default when absent).
    """

    fixed: list[int]
    ground: Ground
    contacts: np.ndarray
    force_scale: float
    first_step: float
    min_step: float
    step_iter: int
    max_move: float
    rtol: float
    max_solves: NotRequired[int]


def standing_path(model: SheetModel, placed: Placed, supports: str) -> PathOptions:
    """``solve_path``'s options for carrying the weight from ``placed`` on
    ``supports`` ('anchored' or 'frictionless'): the ground, the placed
    contacts, the in-plane restraint of frictionless feet, the load steps."""
    x = unpack(model.mesh, placed.q)[0]
    fixed = in_plane_restraint(x, placed.contacts) if supports == "frictionless" else []
    return {
        "fixed": fixed,
        "ground": Ground(supports),  # type: ignore[arg-type]
        "contacts": placed.contacts,
        "force_scale": model.weight_N,
        "first_step": 1.0,
        "min_step": MIN_LOAD_STEP,
        "step_iter": STEP_ITERATIONS,
        "max_move": MAX_MOVE * model.size,
        "rtol": RTOL,
    }


def stand(
    model: SheetModel,
    placed: Placed,
    rest_curvature: Array,
    state: plastic.PlasticState | None,
    supports: str,
    progress: Progress | None = None,
) -> Stage:
    """Carry the sheet's weight on the ground from ``placed``.

    Args:
        model: the model.
        placed: the form stood on the ground (:func:`place`).
        rest_curvature: ``(m, 3)`` the faces' rest form (plastic, or designed).
        state: the faces' plastic states (None: elastic, no plastic check).
        supports: 'anchored' or 'frictionless'.

    Raises:
        PathStalled: no equilibrium under the full weight (``reached`` says how
            much of it the sheet carried).
        ConvergenceError: Newton or the contact iteration failed otherwise.
    """
    base = placed.shell.with_changes(rest_curvature=rest_curvature)
    g = np.array([0.0, 0.0, -GRAVITY])
    eq = solve_path(
        lambda s: base.with_changes(gravity=s * g),
        placed.q,
        callback=progress,
        **standing_path(model, placed, supports),
    )
    if state is None:
        n = model.mesh.n_faces
        return Stage(eq, plastic.virgin_state(n), np.zeros(n, dtype=bool), np.zeros(n, dtype=bool))
    return _unloading(base, eq, state)
