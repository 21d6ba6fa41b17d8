"""The whole compensation: the search, then the answer checked on the normal
mesh with its convergence check, beside the uncompensated fold.

:func:`compensate` returns a :class:`Compensation`: before and after (the
standing form's max and rms distance from the target, height, span, depth,
tipping margin), the compensated design, the crease angles to fold to and
after springback, the knobs' sensitivities, how many simulations it took and,
when the target is not met, what limits it. Lengths are in the design's unit,
angles in degrees.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from onefold_cad.choices import ConeForming, Knob, Law
from onefold_cad.compensate.evaluate import (
    Standing,
    crease_springback,
    designed_sizes,
    node_weights,
    standing_measures,
)
from onefold_cad.compensate.optimise import Search, fold_knobs, formed_to, search
from onefold_cad.compensate.parallel import Evaluator
from onefold_cad.compensate.target import Target
from onefold_cad.design import Design, fold_design
from onefold_cad.errors import ConvergenceError, InvalidParameterError
from onefold_cad.geometry.numeric import Array
from onefold_cad.mechanics.verdicts import CONVERGED

__all__ = ["SIZE_TOLERANCE", "Compensation", "FormReport", "compensate"]

#: Height and span (and a size target) are met within this (relative).
SIZE_TOLERANCE = 0.01
#: A design target is met when the largest deviation shrinks at least this much.
SHRINK = 5.0


@dataclass(frozen=True)
class FormReport:
    """One standing form against the target.

    Attributes:
        stands: it stands (positive tipping margin).
        max_deviation, rms_deviation: its distance from the target's form
            (design unit), after the horizontal alignment.
        height, span, depth: standing (design unit).
        tipping_margin_deg: deg.
        convergence: the largest deviation's relative change on the finer mesh.
        deviation: ``(n,)`` per node (for the picture).
        aligned: ``(n, 3)`` the aligned standing nodes (for the files).
    """

    stands: bool
    max_deviation: float | None
    rms_deviation: float | None
    height: float | None
    span: float | None
    depth: float | None
    tipping_margin_deg: float | None
    convergence: float | None
    deviation: Array | None = field(default=None, repr=False)
    aligned: Array | None = field(default=None, repr=False)

    def to_data(self) -> dict[str, Any]:
        """The report's form section (no arrays)."""
        return {
            "stands": self.stands,
            "max_deviation": self.max_deviation,
            "rms_deviation": self.rms_deviation,
            "height": self.height,
            "span": self.span,
            "depth": self.depth,
            "tipping_margin_deg": self.tipping_margin_deg,
            "convergence": self.convergence,
        }


@dataclass(frozen=True)
class Compensation:
    """A compensation's answer (see the module docstring).

    Attributes:
        target: what the steel should match.
        designed: the target's own designed form as it rests: height, span, depth.
        start, compensated: the fold formed without and with compensation.
        before, after: their standing steel against the target (normal mesh).
        before_sim, after_sim: their simulations (mesh, nodes, faces).
        crease: per crease half: name, bend, fold_to_deg (the compensated
            fold's angle plus its crease overbend: the angle the crease is
            set to) and after_springback_deg (as the steel stands).
        found: the search (candidates, knobs, sensitivity, limits).
        reached: the target is met; ``verdict``: one sentence.
    """

    target: Target
    designed: dict[str, float]
    start: Design
    compensated: Design
    before: FormReport
    after: FormReport
    before_sim: Standing
    after_sim: Standing
    crease: tuple[dict[str, Any], ...]
    found: Search
    reached: bool
    verdict: str

    @property
    def simulations(self) -> int:
        """Every simulation run: the search's and the two checks (each on two meshes)."""
        return len(self.found.candidates) + 2

    @property
    def cpu_s(self) -> float:
        """CPU seconds of every simulation."""
        return self.found.cpu_s + self.before_sim.cpu_s + self.after_sim.cpu_s

    def to_data(self) -> dict[str, Any]:
        """The report's ``compensation`` section."""
        u = self.compensated.units.value
        return {
            "units": u,
            "target": {"kind": self.target.kind, **self.target.sizes()},
            "designed": self.designed,
            "before": self.before.to_data(),
            "after": self.after.to_data(),
            "start": fold_knobs(self.start),
            "compensated": fold_knobs(self.compensated),
            "cone_forming": {
                "start": self.start.material.cones_formed,
                "compensated": self.compensated.material.cones_formed,
            },
            "knobs": list(self.found.knobs),
            "sensitivity": self.found.sensitivity,
            "crease": [dict(c) for c in self.crease],
            "simulations": self.simulations,
            "cpu_s": self.cpu_s,
            "reached": self.reached,
            "verdict": self.verdict,
            "limits": list(self.found.limits),
            "warnings": list(self.after_sim.warnings),
        }


def cones_knob(knobs: tuple[str, ...] | None, law: str) -> bool:
    """Whether the search forms the cones past their springback: where the
    knobs name ``cones``, or are all (None) and the law is J2 (the moment
    law has no springback the table inverts).

    Raises:
        InvalidParameterError: ``cones`` named with the moment law.
    """
    if knobs is None:
        return Law.parse(law) is Law.J2
    if Knob.CONES.value not in knobs:
        return False
    if Law.parse(law) is not Law.J2:
        raise InvalidParameterError(
            "knobs", f"'cones' forms the cones past the J2 law's springback; with --law {law} "
            "leave it out (--knobs alpha,beta,h_c,overbend) or use --law j2"
        )  # fmt: skip
    return True


def with_compensated_cones(design: Design) -> Design:
    """``design`` with its cones formed past their springback."""
    material = design.material.with_changes(cone_forming=ConeForming.COMPENSATED)
    return design.with_changes(material=material)


def _form(target: Target, samples: Array, weights: Array, s: Standing) -> FormReport:
    if s.positions is None or not s.stands:
        return FormReport(False, None, None, s.height, s.span, s.depth, s.tipping_margin_deg,
                          s.convergence)  # fmt: skip
    m = standing_measures(target.form, samples, weights, s)
    return FormReport(
        True, m.max_deviation, m.rms_deviation, s.height, s.span, s.depth,
        s.tipping_margin_deg, s.convergence, m.deviation, m.aligned,
    )  # fmt: skip


def _miss(got: float | None, want: float) -> float:
    return math.inf if got is None else abs(got - want) / want


def _verdict(target: Target, designed: dict[str, float], before: FormReport,
             after: FormReport, found: Search) -> tuple[bool, str]:  # fmt: skip
    u = target.form.units.value
    if not after.stands:
        reach = ""
        if before.stands and before.height is not None and before.span is not None:
            reach = (f" (uncompensated, the start stands {before.height:.5g} {u} high and "
                     f"{before.span:.5g} {u} wide)")  # fmt: skip
        return False, "the compensated fold does not stand" + reach
    if target.kind == "size":
        misses = {k: _miss(getattr(after, k), v) for k, v in target.sizes().items()}
        ok = all(m <= SIZE_TOLERANCE for m in misses.values())
        text = ", ".join(f"{k} {getattr(after, k):.5g} {u} ({100 * m:.2g} % off)"
                         for k, m in misses.items())  # fmt: skip
        return _converged(ok, text, before, after)
    sizes = {k: _miss(getattr(after, k), designed[k]) for k in ("height", "span")}
    assert after.max_deviation is not None
    shrink = math.inf if not before.max_deviation else before.max_deviation / after.max_deviation
    ok = shrink >= SHRINK and all(m <= SIZE_TOLERANCE for m in sizes.values())
    text = (
        f"max deviation {after.max_deviation:.4g} {u}, {shrink:.3g} times smaller than "
        f"uncompensated (needed {SHRINK:g}); height {100 * sizes['height']:.2g} % and span "
        f"{100 * sizes['span']:.2g} % off the design's"
    )
    return _converged(ok, text, before, after)


def _converged(ok: bool, text: str, before: FormReport, after: FormReport) -> tuple[bool, str]:
    """``ok, text`` said as "met" or "not met", unless a checked form's mesh is
    not converged (its largest deviation changes by more than
    :data:`~onefold_cad.mechanics.verdicts.CONVERGED` on the finer mesh): then a
    "met" is only "uncertain", not reached, and the text says which change."""
    loose = [
        f"the {name} fold's largest deviation changes {100 * f.convergence:.2g} % on the "
        f"finer mesh (more than {100 * CONVERGED:g} %)"
        for name, f in (("uncompensated", before), ("compensated", after))
        if f.convergence is not None and f.convergence > CONVERGED
    ]
    if not loose:
        return ok, ("met: " if ok else "not met: ") + text
    why = "; not mesh-converged: " + " and ".join(loose)
    return False, ("uncertain: " if ok else "not met: ") + text + why


def compensate(
    design: Design,
    target: Target,
    evaluator: Evaluator,
    say: Callable[[str], None],
    *,
    coarse: str = "coarse",
    fine: str = "normal",
    check: bool = True,
    knobs: tuple[str, ...] | None = None,
) -> Compensation:
    """Compensate ``design`` for ``target``: the search, then the best fold and
    the uncompensated one simulated on ``fine`` with the convergence check
    (``check``; False: without it, as the explorer's coarse preview runs, and
    the reports' ``convergence`` is None), side by side. ``knobs``: the knobs
    the search moves (None: all of :data:`~onefold_cad.compensate.optimise.KNOBS`).

    Raises:
        ConvergenceError: neither the start nor any candidate stands on ``fine``.
    """
    start = target.form if target.kind == "size" else design
    cones = cones_knob(knobs, evaluator.law)
    forming = with_compensated_cones(start) if cones else start
    found = search(forming, target, evaluator, say, coarse=coarse, fine=fine, knobs=knobs)
    if cones:
        found.knobs = (*found.knobs, Knob.CONES.value)
    best = found.best(fine) or found.best(coarse)
    if best is None:
        raise ConvergenceError(
            f"compensate: no candidate fold stands ({'; '.join(found.limits) or 'every one fell'})",
            iterations=len(found.candidates),
            residual=math.nan,
        )
    compensated = formed_to(forming, best.knobs).with_changes(name=f"{design.name}-compensated")
    say(f"checking the compensated fold and the uncompensated one on the {fine} mesh")
    before_sim, after_sim = evaluator.map([start, compensated], fine, check=check)
    for s in (before_sim, after_sim):
        if isinstance(s, str):
            raise ConvergenceError(
                f"compensate: the check on the {fine} mesh failed: {s}",
                iterations=len(found.candidates),
                residual=math.nan,
            )
    assert not isinstance(before_sim, str) and not isinstance(after_sim, str)
    samples = before_sim.flat
    weights = node_weights(before_sim.flat, before_sim.faces)
    before = _form(target, samples, weights, before_sim)
    after = _form(target, samples, weights, after_sim)
    designed = designed_sizes(target.form)
    reached, verdict = _verdict(target, designed, before, after, found)
    if not reached and found.limits:
        verdict += "; within the family of folds: " + "; ".join(found.limits)
    back = crease_springback(compensated, after_sim)
    crease = tuple(
        {
            "half": c.name,
            "bend": c.bend,
            "fold_to_deg": compensated.material.crease_set_angle(c.fold_angle_deg),
            "after_springback_deg": c.fold_angle_deg
            + back.get("+x" if c.name == "plus_x" else "-x", np.nan),
        }
        for c in fold_design(compensated).crease
    )
    return Compensation(
        target, designed, start, compensated, before, after, before_sim, after_sim, crease,
        found, reached, verdict,
    )  # fmt: skip
