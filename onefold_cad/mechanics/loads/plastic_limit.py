"""The strength of the sheet under a load case by a materially and
geometrically nonlinear analysis (EN 1993-1-6:2007 6.2.3, GMNA): the case's
design actions ``F_Ed`` scaled by a load ratio ``r`` and ramped from the
unloaded form, every face a J2 section (:mod:`onefold_cad.mechanics.j2`) of
an ideal elastic-plastic material at ``f_yd = f_yk / gamma_M0`` (no
hardening, 6.2.3(3)), Newton on the full shell at every step (large
movements); the plastic limit ``r_R`` is the largest ratio the path reaches
(a limit point: the path stalls there) or, when it carries them all, at
least :data:`R_MAX`.

The verdict (8.7.2: ``r_Rd = r_Rk / gamma_M1``): the sheet resists the case
when ``r_R >= gamma_M1`` (:data:`GAMMA_M1` = 1.1, the recommended minimum,
8.5.2(2)): a geometrically nonlinear path's limit point may be a buckling
(LS3) as well as the plastic limit (LS1, ``gamma_M0 = 1.0``), so the larger
factor is taken. The shell is perfect (GMNA, not GMNIA: no imperfections).

The plastic strain the case itself leaves (``r = 1``, or the last ratio
reached below it) is reported: its largest, where, and its area share.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TypedDict

from onefold_cad.errors import ConvergenceError
from onefold_cad.geometry.numeric import Array, Index
from onefold_cad.mechanics.energy import section_response
from onefold_cad.mechanics.equilibrium import Equilibrium, PathStalled, solve_path
from onefold_cad.mechanics.j2.law import J2Law
from onefold_cad.mechanics.j2.layered import Plasticity
from onefold_cad.mechanics.j2.section import ThicknessRule
from onefold_cad.mechanics.shell import Shell

__all__ = [
    "GAMMA_M0",
    "GAMMA_M1",
    "R_MAX",
    "LoadRatio",
    "ideal_plastic",
    "load_ratio",
]

#: Partial factors: the plastic limit (EN 1993-1-6 LS1, on ``f_yd``) and the
#: buckling resistance (LS3, 8.5.2(2): at least 1.1), recommended values.
GAMMA_M0, GAMMA_M1 = 1.0, 1.1
#: The largest load ratio the path is taken to: beyond it the reserve is
#: reported as ``>= R_MAX``.
R_MAX = 1.5
#: The first step of each leg (a share of its ratio) and the smallest one:
#: ``r_R`` is found to within a smallest step below the limit.
FIRST_STEP, MIN_STEP = 0.25, 1 / 128
#: Newton's tolerance relative to ``force_scale``, the most movement of a node
#: in one step (share of the sheet's size: a larger jump is another branch) and
#: the most solves of each leg.
RTOL, MAX_MOVE, MAX_SOLVES = 1e-7, 0.05, 48
#: Where the path has no limit point (the sheet stiffens as it moves: a hinge
#: turning under loads of fixed direction), the largest equivalent plastic
#: strain bounds it: the plastic limit is the ratio at which it reaches 5 %
#: (EN 1993-1-5:2006 C.8(1), Note 1: the limiting principal strain of a finite
#: element analysis of plated structures).
STRAIN_LIMIT = 0.05


def ideal_plastic(shell: Shell) -> Shell:
    """``shell`` with virgin J2 sections of its material, ideal elastic-plastic
    at ``f_yd = f_yk / gamma_M0`` (EN 1993-1-6 6.2.3(3)); its rest form kept
    (stress-free where it stands)."""
    mat = shell.material
    law = J2Law(mat.youngs_modulus, mat.poisson, mat.yield_stress / GAMMA_M0)
    rule = ThicknessRule(mat.thickness)
    return shell.with_changes(plasticity=Plasticity.virgin(law, rule, shell.mesh.n_faces))


@dataclass(frozen=True, eq=False)
class LoadRatio:
    """A J2 load path's answer.

    Attributes:
        ratio: ``r_R``, the largest load ratio the path reached (``R_MAX``
            when it reached it: at least that).
        carried: it reached ``R_MAX`` (no limit point below it).
        limit: what ended the path: ``carried`` (it reached ``R_MAX``),
            ``strain`` (the largest plastic strain reached :data:`STRAIN_LIMIT`)
            or ``stalled`` (a limit point: no equilibrium past it).
        at: the ratio of ``plasticity`` and ``equilibrium``: 1, or the last
            step kept when the path stops below 1 (0: none).
        plasticity: the faces' internal variables there (the plastic strains).
        equilibrium: the equilibrium there (None: not even the first step).
    """

    ratio: float
    carried: bool
    limit: str
    at: float
    plasticity: Plasticity
    equilibrium: Equilibrium | None


class _Held(TypedDict):
    p: Plasticity
    s: float
    peeq: float


class _StrainLimit(Exception):
    """The largest equivalent plastic strain passed the limit in a step."""

    def __init__(self, s: float) -> None:
        super().__init__(s)
        self.s = s


def _largest(p: Plasticity) -> float:
    e = p.state.equivalent
    return float(e.max()) if e.size else 0.0


def _leg(
    shell_at: Callable[[float], Shell],
    q0: Array,
    plasticity: Plasticity,
    lo: float,
    hi: float,
    limit: float,
    options: dict[str, object],
) -> tuple[float, str, float, Plasticity, Equilibrium | None]:
    """The path from ratio ``lo`` (state ``q0``, ``plasticity``) to ``hi``: the
    ratio reached (``hi``; a limit point; or where the largest plastic strain
    reaches ``limit``, interpolated in the step that passed it), what ended it
    (:class:`LoadRatio`'s ``limit``), and the ratio, internal variables and
    equilibrium of the last step kept."""
    held: _Held = {"p": plasticity, "s": 0.0, "peeq": _largest(plasticity)}
    last: dict[str, Equilibrium] = {}

    def at(s: float) -> Shell:
        return shell_at(lo + s * (hi - lo)).with_changes(plasticity=held["p"])

    def accepted(s: float, eq: Equilibrium) -> None:
        p = held["p"].moved_on(section_response(at(s), eq.q).state)
        peeq = _largest(p)
        if peeq > limit:
            share = (limit - held["peeq"]) / (peeq - held["peeq"])
            raise _StrainLimit(held["s"] + share * (s - held["s"]))
        held["p"], held["s"], held["peeq"] = p, s, peeq
        last["eq"] = eq

    reached, why = 1.0, "carried"
    try:
        solve_path(at, q0, accepted=accepted, **options)  # type: ignore[arg-type]
    except _StrainLimit as stop:
        reached, why = stop.s, "strain"
    except PathStalled as err:
        reached, why = err.reached, "stalled"
    except ConvergenceError:
        reached, why = 0.0, "stalled"
    kept = lo + held["s"] * (hi - lo)
    return lo + reached * (hi - lo), why, kept, held["p"], last.get("eq")


def load_ratio(
    shell_at: Callable[[float], Shell],
    q0: Array,
    fixed: Index,
    force_scale: float,
    size: float,
    r_max: float = R_MAX,
) -> LoadRatio:
    """The load ratio a J2 shell carries: ``shell_at(r)`` the shell (with its
    J2 sections, :func:`ideal_plastic`) under ``r`` times the design actions,
    ``q0`` its equilibrium at ``r = 0``, ``fixed`` its held unknowns;
    ``force_scale`` (N) Newton's force unit, ``size`` (m) the sheet's.

    The path goes to 1 (the internal variables kept there), then on to
    ``r_max``; each accepted step moves the sections' internal variables on.
    """
    p0 = shell_at(0.0).plasticity
    assert p0 is not None
    options: dict[str, object] = {
        "fixed": fixed,
        "force_scale": force_scale,
        "rtol": RTOL,
        "first_step": FIRST_STEP,
        "min_step": MIN_STEP,
        "max_move": MAX_MOVE * size,
        "max_solves": MAX_SOLVES,
    }
    r, why, kept, p1, eq1 = _leg(shell_at, q0, p0, 0.0, 1.0, STRAIN_LIMIT, options)
    if r < 1.0 or eq1 is None or r_max <= 1.0:
        return LoadRatio(r, r >= r_max, why, kept, p1, eq1)
    r2, why2 = _leg(shell_at, eq1.q, p1, 1.0, r_max, STRAIN_LIMIT, options)[:2]
    return LoadRatio(r2, r2 >= r_max, why2, 1.0, p1, eq1)
