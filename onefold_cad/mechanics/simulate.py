"""``onefold simulate``'s computation: a design's sheet as steel.

:func:`simulate` runs the stages on the mesh of the chosen level and again on
the next finer one (twice the nodes; or, with ``check_mesh='coarser'``, on the
next coarser level's mesh) and reports the first with the change of the
largest deviation between the two (``convergence.max_deviation_change``).

- reference 'flat' (default): the sheet is cut flat and stress-free, bent into
  the design (``formed``: where it yields), let go (``released``: the
  springback), and stood on the ground under its weight (``standing``);
- reference 'designed': the designed form is taken as stress-free (as an
  engineer checks a built shell in an FE program) and stood on its resting
  contacts under its weight (``designed``: sag and stress).

Progress goes to ``progress(stage, iteration, residual_N)``.
"""

from __future__ import annotations

import functools
import time
from collections.abc import Callable
from dataclasses import replace

import numpy as np
from threadpoolctl import threadpool_limits

from onefold_cad.choices import CheckMesh, Law, MeshLevel, Reference, Supports
from onefold_cad.design import Design
from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.mechanics.equilibrium import PathStalled
from onefold_cad.mechanics.j2.simulate import form_j2, run_j2
from onefold_cad.mechanics.model import FINER, SheetModel, check_cone_forming, sheet_model
from onefold_cad.mechanics.reserve import ReserveCheck, carried
from onefold_cad.mechanics.results import Designed, FormedResult, Released, Simulation
from onefold_cad.mechanics.shell import director_angles, pack, unpack
from onefold_cad.mechanics.stages import Placed, form, place, release, stand
from onefold_cad.mechanics.standing_measures import (
    aligned_deviation,
    area_share,
    stalled,
    standing_result,
)
from onefold_cad.mechanics.stress import face_stress
from onefold_cad.mechanics.verdicts import (
    CONVERGED,
    RESERVE_PENDING,
    convergence_report,
    past_converged,
    simulation_warnings,
    with_reserve,
)

__all__ = [
    "CONVERGED",
    "REFERENCES",
    "SUPPORTS",
    "aligned_deviation",
    "formed_only",
    "run",
    "simulate",
]


SUPPORTS = tuple(c.value for c in Supports)
REFERENCES = tuple(c.value for c in Reference)

Progress = Callable[[str, int, float], None]
#: ``stage_done(stage, cpu_seconds)``: a stage of :func:`run` finished.
StageDone = Callable[[str, float], None]


def _stage_progress(progress: Progress | None, stage: str):
    if progress is None:
        return None
    return lambda it, res, energy: progress(stage, it, res)


def _formed_result(model: SheetModel, formed) -> FormedResult:
    shell, mesh = model.shell, model.mesh
    yielded = formed.state.plastic(model.material)
    area = shell.ref_area
    centroid = mesh.nodes[mesh.triangles].mean(axis=1)
    radius = np.hypot(centroid[:, 0], centroid[:, 1])
    return FormedResult(
        bending_energy_J=float(formed.work.sum()),
        plastic_area_share=float(area[yielded].sum() / area.sum()),
        plastic_radius_max=float(radius[yielded].max() / model.scale) if yielded.any() else 0.0,
    )


def formed_only(
    design: Design,
    folded: FoldedSheet,
    *,
    level: str = "normal",
    h_max: float | None = None,
    yield_stress_MPa: float | None = None,
    law: str = "moment",
) -> FormedResult:
    """The ``formed`` stage alone (the flat sheet bent into the design: where it
    yields and the work of bending), on the mesh :func:`run` would use; the
    same numbers as ``run(...).formed`` without the stages after it."""
    check_cone_forming(design, Law.parse(law).value, Reference.FLAT.value)
    model = sheet_model(design, folded, h_max=h_max, level=level, yield_stress_MPa=yield_stress_MPa)
    if Law.parse(law) is Law.J2:
        return form_j2(model).result
    return _formed_result(model, form(model))


def _standing(
    model: SheetModel,
    folded: FoldedSheet,
    placed: Placed,
    rest_curvature,
    state,
    supports,
    progress,
    unit: str,
    coarse: bool = False,
    reserve: bool = True,
):
    """The standing stage of the moment law (or of the designed reference) and
    its measures (a stall is an answer: it does not stand). On the ``coarse``
    preview mesh a sheet that stands must carry
    :data:`~onefold_cad.mechanics.reserve.COARSE_RESERVE` times its weight to
    be a plain yes (:mod:`onefold_cad.mechanics.reserve`); with ``reserve``
    False that check is left for later (the standing "uncertain":
    :data:`~onefold_cad.mechanics.verdicts.RESERVE_PENDING`): the last item
    returned is then its standing equilibrium (else None)."""
    try:
        stage = stand(model, placed, rest_curvature, state, supports, progress)
    except PathStalled as err:
        return stalled(model, placed, err, supports, unit), None, None, None
    eq = stage.equilibrium
    loaded = placed.shell.with_changes(rest_curvature=rest_curvature)
    stress = face_stress(loaded, eq.q, state if state is not None else None) / 1e6
    standing, dev = standing_result(
        model,
        folded,
        placed,
        eq,
        stress,
        model.material.yield_stress / 1e6,
        reloaded_area_share=area_share(model, stage.reloaded),
    )
    if coarse and standing.stands:
        if not reserve:
            return replace(standing, uncertain=RESERVE_PENDING), stress, dev, eq
        standing = with_reserve(standing, carried(model, placed, eq, rest_curvature, supports))
    return standing, stress, dev, None


def _one_blas_thread(fn: Callable[..., Simulation]) -> Callable[..., Simulation]:
    """``fn`` with BLAS limited to one thread while it runs."""

    @functools.wraps(fn)
    def wrapped(*args: object, **kwargs: object) -> Simulation:
        with threadpool_limits(limits=1, user_api="blas"):
            return fn(*args, **kwargs)

    return wrapped


@_one_blas_thread
def run(
    design: Design,
    folded: FoldedSheet,
    *,
    supports: str = "anchored",
    reference: str = "flat",
    crease: str = "held",
    law: str = "moment",
    level: str = "normal",
    h_max: float | None = None,
    yield_stress_MPa: float | None = None,
    refine: float = 1.0,
    progress: Progress | None = None,
    stage_done: StageDone | None = None,
    reserve: bool = True,
) -> Simulation:
    """The stages on one mesh (see the module docstring); no convergence check.
    ``progress`` hears every Newton step, ``stage_done`` every stage's end
    (``mesh``, ``formed``, ``released``, ``standing``) with its CPU time.

    With ``reserve`` False the coarse preview's reserve check is left for later
    (``Simulation.pending_reserve``; ``verdicts.settle_reserve`` runs it):
    until then a standing sheet is "uncertain" (``verdicts.RESERVE_PENDING``;
    J2's is not kept for later: it stays "uncertain").

    BLAS runs on one thread meanwhile (``threadpoolctl``): the model's dense
    algebra is thousands of tiny products, where OpenBLAS's threads only spin
    (the same wall time at about two thirds of the CPU time, measured).
    """
    supports = Supports.parse(supports).value
    reference = Reference.parse(reference).value
    law = Law.parse(law).value
    check_cone_forming(design, law, reference)
    times: dict[str, float] = {}
    clock = time.process_time()

    def lap(name: str) -> None:
        nonlocal clock
        now = time.process_time()
        times[name] = now - clock
        clock = now
        if stage_done is not None:
            stage_done(name, times[name])

    model = sheet_model(
        design,
        folded,
        h_max=h_max,
        level=level,
        crease=crease,
        yield_stress_MPa=yield_stress_MPa,
        refine=refine,
    )
    lap("mesh")
    s, mat = model.scale, model.material
    formed_result = released = designed = released_at = None
    fields = stage_positions = None
    reverse = 0
    pending = None
    if reference == "flat" and law == "j2":
        j2 = run_j2(
            model, folded, supports, design.units.value,
            lambda stage: _stage_progress(progress, stage), lap,
            coarse=MeshLevel.parse(level) is MeshLevel.COARSE and refine == 1.0,
            reserve=reserve, size=design.sheet.size,
        )  # fmt: skip
        formed_result, released, standing = j2.formed, j2.released, j2.standing
        stress, dev, released_at = j2.stress_MPa, j2.deviation, j2.released_at / s
        fields, stage_positions = j2.fields, j2.positions
        pending = j2.pending
    else:
        if reference == "flat":
            formed = form(model)
            formed_result = _formed_result(model, formed)
            lap("formed")
            rel = release(model, formed, _stage_progress(progress, "released"))
            xr = rel.equilibrium.positions
            max_dev, rms_dev = aligned_deviation(model, folded, xr)
            placed = place(model, rel.equilibrium.q)
            xp = unpack(model.mesh, placed.q)[0]
            released_at = xp / s
            released = Released(
                max_dev,
                rms_dev,
                float(xp[:, 2].max() / s),
                float(np.ptp(xp[:, 0]) / s),
                rel.equilibrium.iterations,
                area_share(model, rel.reloaded),
            )
            reverse = int(rel.reverse.sum())
            rest_curvature, state = rel.state.rest, rel.state
            lap("released")
        else:
            q = pack(model.designed, director_angles(model.shell, model.designed, model.normals))
            placed = place(model, q)
            rest_curvature, state = model.shell.rest_curvature, None
        standing, stress, dev, left = _standing(
            model,
            folded,
            placed,
            rest_curvature,
            state,
            supports,
            _stage_progress(progress, "standing"),
            design.units.value,
            coarse=MeshLevel.parse(level) is MeshLevel.COARSE and refine == 1.0,
            reserve=reserve,
        )
        if left is not None:
            shell = placed.shell.with_changes(rest_curvature=rest_curvature)
            pending = ReserveCheck(model, placed, left, shell, supports, law, design.sheet.size)
        lap("standing")
    if reference == "designed":
        designed = Designed(standing.max_displacement, standing.max_stress_MPa)
    warnings = simulation_warnings(
        law,
        released,
        standing,
        reverse,
        coarse=MeshLevel.parse(level) is MeshLevel.COARSE,
        size=design.sheet.size,
        unit=design.units.value,
        yield_stress_MPa=mat.yield_stress / 1e6,
    )
    return Simulation(
        unit=design.units.value,
        supports=supports,
        reference=reference,
        crease=crease,
        weight_N=model.weight_N,
        nodes=model.mesh.n_nodes,
        triangles=model.mesh.n_faces,
        h_max=model.h_max / s,
        youngs_modulus_GPa=mat.youngs_modulus / 1e9,
        poisson=mat.poisson,
        yield_stress_MPa=mat.yield_stress / 1e6,
        thickness=mat.thickness / s,
        density_kg_m3=mat.density,
        formed=formed_result,
        released=released,
        standing=standing,
        designed=designed,
        convergence=None,
        reverse_yield_faces=reverse,
        law=law if reference == "flat" else "elastic",
        hardening_modulus_MPa=(mat.hardening_iso + mat.hardening_kin) / 1e6,
        kinematic_hardening=(
            mat.hardening_kin / (mat.hardening_iso + mat.hardening_kin)
            if mat.hardening_iso + mat.hardening_kin > 0
            else 0.0
        ),
        crease_overbend_deg=design.material.overbend_deg,
        cone_forming=design.material.cones_formed if reference == "flat" else "design",
        fields=fields,
        stage_positions=stage_positions,
        warnings=warnings,
        timings_s=times,
        face_stress_MPa=stress,
        deviation=dev,
        faces=model.mesh.triangles,
        flat=model.mesh.nodes / s,
        designed_positions=(
            model.designed @ model.standing_frame()[0].T + model.standing_frame()[1]
        )
        / s,
        standing_positions=None if standing.positions is None else standing.positions / s,
        released_positions=released_at,
        pending_reserve=pending,
    )


def _measure(sim: Simulation) -> tuple[str, float | None]:
    """The quantity the convergence check follows: the standing form's largest
    deviation, or the released form's when it does not stand."""
    if sim.standing.max_deviation is not None:
        return "standing.max_deviation", sim.standing.max_deviation
    if sim.released is not None:
        return "released.max_deviation", sim.released.max_deviation
    return "standing.load_factor", sim.standing.load_factor


def _check_level(level: str, h_max: float | None, check_mesh: str | None) -> MeshLevel | None:
    """The level a 'coarser' check runs on (None: the check is 'finer'; a
    ``check_mesh`` of None: :meth:`CheckMesh.default_for`'s); refuses a mesh
    with no coarser level below it."""
    if check_mesh is None:
        check_mesh = CheckMesh.default_for(level, h_max).value
    if CheckMesh.parse(check_mesh) is CheckMesh.FINER:
        return None
    coarser = MeshLevel.parse(level).coarser
    if coarser is None or h_max is not None:
        raise InvalidParameterError(
            "check_mesh",
            "'coarser' checks a normal or fine mesh against the level below it; the coarse "
            "mesh and a mesh of a given h_max have none (use 'finer')",
        )
    return coarser


def simulate(
    design: Design,
    folded: FoldedSheet,
    *,
    convergence: bool = True,
    level: str = "normal",
    h_max: float | None = None,
    check_mesh: str | None = None,
    progress: Progress | None = None,
    stage_done: StageDone | None = None,
    **options: object,
) -> Simulation:
    """:func:`run` on the level's mesh and, with ``convergence``, on a second
    mesh: the first's results with the relative change of their largest
    deviation on the second (``convergence.max_deviation_change``, relative to
    the finer mesh's value). The second mesh is the next finer one (every
    edge / sqrt 2, ``check_mesh`` 'finer') or the next coarser level's
    ('coarser': normal against coarse, fine against normal; the default
    where there is one and no ``h_max`` is given; where that mesh
    stands and this one does not, or the other way round, it cannot bound this
    one's error, and the check runs on the finer mesh instead, with a
    warning; where it changes the answer by more than :data:`CONVERGED`, the
    finer mesh decides too, and ``convergence.coarser_change`` keeps the
    coarser mesh's change). The second run's stages reach ``progress`` and ``stage_done``
    named ``convergence check: STAGE``.

    Raises:
        InvalidParameterError: the design cannot be simulated (named value), or
            ``check_mesh`` is 'coarser' on the coarse level or a given ``h_max``.
        ConvergenceError: a stage did not converge (never an unconverged result).
    """
    coarser = _check_level(level, h_max, check_mesh)
    base = run(
        design, folded, level=level, h_max=h_max, progress=progress, stage_done=stage_done,
        **options,
    )  # fmt: skip
    if not convergence:
        return base
    named = "convergence check: {}".format

    def again(coarser: MeshLevel | None) -> Simulation:
        return run(
            design,
            folded,
            level=level if coarser is None else coarser.value,
            h_max=h_max,
            refine=FINER if coarser is None else 1.0,
            reserve=False,  # the check wants its deviation, not the coarse verdict's reserve
            progress=None if progress is None else lambda st, i, r: progress(named(st), i, r),
            stage_done=None if stage_done is None else lambda st, t: stage_done(named(st), t),
            **options,
        )

    name, a = _measure(base)
    check = again(coarser)
    notes, spent, bound = [], 0.0, None
    if coarser is not None:
        kind, b = _measure(check)
        if kind != name:
            # the coarser mesh finds another kind of answer (a standing form on
            # one mesh, none on the other): it cannot bound this one's error
            notes.append(
                f"the convergence check's coarser mesh ({check.nodes} nodes) "
                f"{'stands' if check.standing.stands else 'does not stand'} where this one "
                f"{'stands' if base.standing.stands else 'does not stand'}: checked on the "
                f"finer mesh instead"
            )
        else:
            # past the limit on the coarser mesh, whose change overstates the
            # error (by far where the coarse mesh is outside the asymptotic
            # range): the finer mesh decides
            bound = past_converged(a, b)
        if kind != name or bound is not None:
            spent = sum(check.timings_s.values())
            coarser, check = None, again(None)
    mesh = {"nodes": check.nodes, "triangles": check.triangles, "h_max": check.h_max}
    data, warned = convergence_report((name, a), _measure(check), coarser is None, mesh, bound)
    times = dict(base.timings_s)
    times["convergence_check"] = float(spent + sum(check.timings_s.values()))
    warnings = list(base.warnings) + notes + warned
    return replace(base, convergence=data, timings_s=times, warnings=type(base.warnings)(warnings))
