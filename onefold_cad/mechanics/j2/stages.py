"""The forming sequence with J2 plasticity through the thickness: forming,
springback and standing, each face a section of the J2 law
(:mod:`onefold_cad.mechanics.j2.layered`) whose internal variables carry the
sheet's history from one stage to the next.

- :func:`form`: the flat sheet bent into the design along forms isometric to
  it: at every point of every face the strain grows in proportion, from 0 to
  the designed curvature times its height (membrane strain 0: the shell's
  membrane reference is the designed triangles, so the discrete form's chord
  strains are not taken for stretching), in :data:`FORMING_STEPS` return
  mappings. The crease is the shell's hinge at its set angle.
- :func:`release`: the forming machine lets go: the forces it held the
  formed sheet with (the energy's gradient there) ramp down to zero, with a
  statically determinate 3-2-1 restraint (which carries nothing) and no
  gravity; each accepted step of the ramp moves the internal variables on,
  so unloading, reverse yielding and the Bauschinger effect follow the law.
- :func:`stand`: on the ground, gravity ramped from 0 (anchored or
  frictionless feet), again step by step through the law.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TypedDict

import numpy as np
from numpy.typing import ArrayLike

from onefold_cad.geometry.numeric import Array
from onefold_cad.mechanics.energy import evaluate, second_fundamental_form, section_response
from onefold_cad.mechanics.equilibrium import Equilibrium, solve_path
from onefold_cad.mechanics.j2.law import J2Law, von_mises
from onefold_cad.mechanics.j2.layered import Plasticity, form_along
from onefold_cad.mechanics.j2.section import SectionResponse, ThicknessRule
from onefold_cad.mechanics.j2.springback import SpringbackTable, compensated_curvatures
from onefold_cad.mechanics.kinematics.triangles import face_metric
from onefold_cad.mechanics.material import ShellMaterial
from onefold_cad.mechanics.model import GRAVITY, SheetModel
from onefold_cad.mechanics.newton import Progress
from onefold_cad.mechanics.shell import Shell, director_angles, pack, rigid_dofs, unpack
from onefold_cad.mechanics.stages import RTOL, Placed, standing_path

__all__ = [
    "FORMING_STEPS",
    "GROW_CHANGE",
    "RELEASE_GROW",
    "RELEASE_ITERATIONS",
    "RELEASE_PREDICTOR",
    "RELEASE_STEP",
    "J2Stage",
    "cartesian_curvatures",
    "form",
    "form_to",
    "j2_section",
    "j2_shell",
    "release",
    "release_from",
    "reserve_shell",
    "stand",
]

#: Return-mapping increments of the forming path (proportional: the answer is
#: the same to rounding for any number on a radial path; a few keep the
#: stress history of non-radial points).
FORMING_STEPS = 4
#: The release ramp's first step (a share of the grip's forces) and Newton's
#: iterations per step before it is halved: on patkau-one-fold (coarse) 1/8
#: and 8 take 153 iterations, a whole first step and 25 take 204 (the same
#: springback to 0.05 %): each step's active set of yielding points then
#: changes less (scripts/j2_trial.py). 12 iterations failed one step of 1/8
#: on the normal mesh (it converged in 15), and the rest of the ramp went in
#: steps of 1/16 at 7 to 9 iterations each (126 in all, 65 s CPU); with 16
#: every step of 1/8 converges (10 to 15 iterations, 100 in all, 46 s; the
#: springback 434.08 -> 434.32 mm, the finer path's 0.06 %).
RELEASE_STEP, RELEASE_ITERATIONS = 0.125, 16
#: The release's and the stand's steps, from the third equilibrium of their
#: path on, start from the cubic through the last four (``solve_path``'s
#: ``predict``), not from the last: on patkau-one-fold (coarse) the
#: release's steps of 1/8 then take 4 to 6 Newton iterations, not 9 to 11
#: (77 -> 48 in all, the springback the same to 1e-10; normal mesh 100 ->
#: 66, 434.32 mm both). A step doubles only after one that took at most
#: ``RELEASE_GROW`` iterations and changed at most ``GROW_CHANGE`` of the
#: material points between yielding and unloading: patkau's steps of 1/8
#: change 2.7 to 3.9 % from the fourth on, and a step of 1/4 after one of 4
#: iterations took 16; broken-vault's steps of 1/16 (its first of 1/8
#: fails) change 1.9 % and take 4, and doubled they take 5 to 10 (release
#: 89 -> 76 iterations, springback 9.2988 -> 9.3030 in).
RELEASE_PREDICTOR, RELEASE_GROW = 3, 4
GROW_CHANGE = 0.025
#: The standing ramp's first step (a share of the weight; the moment law's
#: path takes it whole). Through the J2 law a whole first step rarely
#: converges in the path's iteration budget and is halved after spending it:
#: on patkau-one-fold (coarse) the weight in one step and then a half both
#: failed (24 iterations) before the quarter, half, quarter that carried it
#: (48 -> 24 iterations, 6.3 -> 3.4 s CPU, the same accepted steps); on the
#: normal mesh 64 -> 40 iterations.
STAND_STEP = 0.25


@dataclass(frozen=True)
class J2Stage:
    """A stage of the sheet as J2 sections.

    Attributes:
        q: the state.
        equilibrium: the equilibrium (None for the imposed forming).
        plasticity: the faces' law and internal variables after the stage.
        response: the faces' sections at the stage's end (stresses through
            the thickness, in the faces' reference frames).
    """

    q: Array
    equilibrium: Equilibrium | None
    plasticity: Plasticity
    response: SectionResponse

    def surface_stress(self) -> Array:
        """``(m,)`` the larger von Mises stress of the sheet's two surfaces (Pa)."""
        s = self.response.stress
        return np.maximum(von_mises(s[:, 0]), von_mises(s[:, -1]))

    def surface_plastic_strain(self) -> Array:
        """``(m,)`` the larger equivalent plastic strain of the two surfaces."""
        e = self.plasticity.state.equivalent
        return np.maximum(e[:, 0], e[:, -1])


def j2_section(mat: ShellMaterial, points: int | None = None) -> tuple[J2Law, ThicknessRule]:
    """The J2 law of ``mat`` (its hardening) and its sections' rule
    (``points`` through the thickness, the section's default if None)."""
    rule = ThicknessRule(mat.thickness) if points is None else ThicknessRule(mat.thickness, points)
    return J2Law.of(mat), rule


def j2_shell(model: SheetModel, points: int | None = None) -> Shell:
    """The model's shell with virgin J2 sections (:func:`j2_section`) and
    no rest curvature: the plastic strains carry the formed curvature."""
    law, rule = j2_section(model.material, points)
    shell = model.shell
    return shell.with_changes(
        rest_curvature=np.zeros_like(shell.rest_curvature),
        plasticity=Plasticity.virgin(law, rule, model.mesh.n_faces),
    )


def form_to(shell: Shell, q: Array, compensated: bool = False) -> J2Stage:
    """Bend the flat sheet into the state ``q`` (imposed: nodes and directors)
    along the proportional path, its J2 sections from ``shell.plasticity``;
    the membrane strain is the one at ``q`` about the shell's reference.

    With ``compensated``, each face is formed past ``q``'s curvature to the
    one whose springback leaves it (:func:`springback.compensated_curvatures`)
    and the stage is the sheet held at ``q`` from there (the machine brings it
    back to the design's form before it lets go: the sections unload along
    the law)."""
    assert shell.plasticity is not None
    mesh = shell.mesh
    x = unpack(mesh, q)[0]
    eps = (face_metric(x[mesh.triangles])[0] - shell.ref_metric) / 2
    membrane = np.einsum("mij,mj->mi", shell.cartesian, eps)
    kappa = cartesian_curvatures(shell, q)
    if not compensated:
        resp = form_along(shell.plasticity, membrane, kappa, FORMING_STEPS)
        return J2Stage(q, None, shell.plasticity.moved_on(resp.state), resp)
    p = shell.plasticity
    table = SpringbackTable.of(p.law, p.rule, FORMING_STEPS)
    past = form_along(p, membrane, compensated_curvatures(kappa, table), FORMING_STEPS)
    p = p.moved_on(past.state)
    resp = p.respond(membrane, kappa)
    return J2Stage(q, None, p.moved_on(resp.state), resp)


def form(model: SheetModel, shell: Shell) -> J2Stage:
    """Bend the flat sheet into the design (``shell``: :func:`j2_shell`, whose
    membrane reference is the designed triangles: no membrane strain); past
    the springback where ``model.cones_compensated``."""
    q = pack(model.designed, director_angles(shell, model.designed, model.normals))
    return form_to(shell, q, compensated=model.cones_compensated)


def cartesian_curvatures(shell: Shell, q: Array) -> Array:
    """``(m, 3)`` the faces' Cartesian curvatures at ``q`` about the rest form."""
    b = second_fundamental_form(shell, q) - shell.rest_curvature
    return np.einsum("mij,mj->mi", shell.cartesian, b)


class _Held(TypedDict):
    """:func:`_path`'s internal variables and section responses, moved on at
    every accepted step, and the share of the points whose yielding changed
    in the last one."""

    p: Plasticity
    resp: SectionResponse | None
    changed: float


def _path(
    shell_at, q0: Array, plasticity: Plasticity, **options: object
) -> tuple[Equilibrium, Plasticity, SectionResponse]:
    """``solve_path`` with the internal variables moved on at every accepted
    step; a step grows only if it changed at most :data:`GROW_CHANGE` of the
    points between yielding and unloading."""
    holder: _Held = {"p": plasticity, "resp": None, "changed": 1.0}

    def at(s: float) -> Shell:
        return shell_at(s).with_changes(plasticity=holder["p"])

    def accepted(s: float, eq: Equilibrium) -> None:
        resp = section_response(at(s), eq.q)
        if holder["resp"] is not None:
            holder["changed"] = float(np.mean(resp.plastic != holder["resp"].plastic))
        holder["p"], holder["resp"] = holder["p"].moved_on(resp.state), resp

    def may_grow() -> bool:
        return holder["changed"] <= GROW_CHANGE

    eq = solve_path(at, q0, accepted=accepted, may_grow=may_grow, **options)  # type: ignore[arg-type]
    return eq, holder["p"], holder["resp"]  # type: ignore[return-value]


def release_from(
    shell: Shell,
    formed: J2Stage,
    fixed: ArrayLike,
    force_scale: float,
    progress: Progress | None = None,
) -> J2Stage:
    """Let a formed sheet go: the forces that held it in ``formed`` ramp down
    to zero, ``fixed`` (a statically determinate restraint) held."""
    held = shell.with_changes(plasticity=formed.plasticity)
    grip = evaluate(held, formed.q, 1).gradient
    assert grip is not None
    grip = grip.copy()
    grip[np.asarray(fixed, dtype=np.int64)] = 0.0  # the restraint's own: it carries nothing
    eq, plasticity, resp = _path(
        lambda s: shell.with_changes(load=(1.0 - s) * grip),
        formed.q,
        formed.plasticity,
        fixed=fixed,
        force_scale=force_scale,
        first_step=RELEASE_STEP,
        step_iter=RELEASE_ITERATIONS,
        predict=RELEASE_PREDICTOR,
        grow_iter=RELEASE_GROW,
        max_solves=256,
        rtol=RTOL,
        callback=progress,
    )
    return J2Stage(eq.q, eq, plasticity, resp)


def release(model: SheetModel, shell: Shell, formed: J2Stage, progress: Progress | None = None
            ) -> J2Stage:  # fmt: skip
    """Let the formed design go on a 3-2-1 restraint (see the module docstring)."""
    return release_from(shell, formed, rigid_dofs(model.designed), model.weight_N, progress)


def stand(
    model: SheetModel,
    shell: Shell,
    placed: Placed,
    plasticity: Plasticity,
    supports: str,
    progress: Progress | None = None,
) -> J2Stage:
    """Carry the sheet's weight on the ground from ``placed`` (see
    :func:`onefold_cad.mechanics.stages.stand`), through the law.

    Raises:
        PathStalled: no equilibrium under the full weight.
    """
    g = np.array([0.0, 0.0, -GRAVITY])
    moved = placed.shell.with_changes(
        rest_curvature=shell.rest_curvature, plasticity=shell.plasticity
    )  # the reference in the resting frame, as the placed state's directors are measured
    eq, p, resp = _path(
        lambda s: moved.with_changes(gravity=s * g),
        placed.q,
        plasticity,
        callback=progress,
        **(
            standing_path(model, placed, supports)
            | {"first_step": STAND_STEP, "predict": RELEASE_PREDICTOR, "grow_iter": RELEASE_GROW}
        ),
    )
    return J2Stage(eq.q, eq, p, resp)


def reserve_shell(shell: Shell, placed: Placed, standing: J2Stage) -> Shell:
    """The shell a reserve check of ``standing`` solves with: the placed
    (resting frame) shell with ``shell``'s rest form and the stand's internal
    variables, held through the check's solve."""
    return placed.shell.with_changes(
        rest_curvature=shell.rest_curvature, plasticity=standing.plasticity
    )
