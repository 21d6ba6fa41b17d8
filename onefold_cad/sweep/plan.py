"""A sweep's plan: the template, the designs and what to measure, checked
before any design runs.

:func:`make_plan` reads the template once, turns the ``--vary`` specs into
design points (:mod:`onefold_cad.sweep.samplers`), checks every value against
the design's allowed range by building the template's design with that value
alone (the check ``onefold solve`` makes, with its message), and keys each
design by a stable hash of its inputs (the template's data and the flags),
so a rerun finds the designs it finished. A value allowed alone may still
be refused in combination (``hc`` beyond ``radius * cos(alpha)`` for a large
alpha): that design's row records the error and the sweep goes on.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any

from onefold_cad.errors import InvalidParameterError
from onefold_cad.flags.design_flags import parse_int
from onefold_cad.flags.jobs import template_job
from onefold_cad.flags.overrides import parse_rectangle
from onefold_cad.flags.parser import UsageError
from onefold_cad.sweep.measures import MEASURES, REST, Column, measure_names
from onefold_cad.sweep.pareto import Objective, parse_objectives
from onefold_cad.sweep.samplers import SAMPLERS, count_of, grid_points, sample_points
from onefold_cad.sweep.spec import VarySpec, parse_vary, unit_kind
from onefold_cad.templates import DEFAULT_TEMPLATE

__all__ = [
    "IMAGES_UP_TO",
    "MAX_DESIGNS",
    "SIMULATION_SETTINGS",
    "SweepPlan",
    "input_values",
    "make_plan",
]

#: Thumbnails are drawn by default for sweeps of at most this many designs.
IMAGES_UP_TO = 1000
#: The most designs one sweep may have.
MAX_DESIGNS = 10_000_000
#: The settings of ``--measure simulate``: ``onefold simulate``'s options.
SIMULATION_SETTINGS = ("supports", "reference", "crease", "law", "mesh", "check")
#: The columns every row has besides its inputs and measures.
ROW_COLUMNS = (
    Column("key", "str", "", "stable hash of the design's inputs (template data and flags)"),
    Column("name", "str", "", "the design's name, as onefold solve names it"),
    Column("status", "str", "", "ok, or error (the error column says why)"),
    Column("error", "str", "", "why the design failed (empty when ok)"),
    Column("seconds", "float", "s", "time to evaluate the design"),
)


@dataclass(frozen=True)
class SweepPlan:
    """Everything a sweep does, checked.

    Attributes:
        template: the template's file (as found) and ``raw`` its TOML data.
        implicit: no template was named (the default one stands in, and the
            designs are named ``onefold-...`` as ``onefold solve`` names them).
        fixed: design flags every design gets (dest -> value).
        specs: the ``--vary`` specs (ranges with their grid values).
        sampler, samples, seed: how the points were made.
        measures: the measures asked for (``rest`` first).
        images: draw a thumbnail per design.
        objectives: the Pareto objectives (may be empty).
        points: the varied flags' values of each design.
        keys: each design's key (``points`` order).
        simulation: ``--measure simulate``'s settings (:data:`SIMULATION_SETTINGS`,
            as ``(name, value)`` pairs; empty without that measure).
    """

    template: str
    raw: dict[str, Any]
    implicit: bool
    fixed: dict[str, Any]
    specs: tuple[VarySpec, ...]
    sampler: str
    samples: int | None
    seed: int
    measures: tuple[str, ...]
    images: bool
    objectives: tuple[Objective, ...]
    points: tuple[dict[str, Any], ...]
    keys: tuple[str, ...]
    simulation: tuple[tuple[str, Any], ...] = ()

    @property
    def settings(self) -> dict[str, Any]:
        """The measures' settings (name -> value): ``simulation``'s."""
        return dict(self.simulation)

    @property
    def measure_tags(self) -> tuple[str, ...]:
        """The measures as the journal records a row's: each name, ``simulate``
        with its settings (a design simulated otherwise is not finished)."""
        sim = ",".join(f"{k}={v}" for k, v in self.simulation)
        return tuple(f"{m}({sim})" if m == "simulate" else m for m in self.measures)

    @property
    def input_columns(self) -> tuple[Column, ...]:
        """The varied flags' columns (a rectangle also as its width and height)."""
        out = []
        for s in self.specs:
            f = s.flag
            kind = "int" if f.kind is parse_int else "float" if s.is_range or _numeric(s) else "str"
            out.append(Column(s.dest, kind, unit_kind(f), f.help))
            if s.dest == "rectangle":
                out += [
                    Column("rectangle_width", "float", "length", "the rectangle's width"),
                    Column("rectangle_height", "float", "length", "the rectangle's height"),
                ]
        return tuple(out)

    @property
    def output_columns(self) -> tuple[Column, ...]:
        """The columns of the measures asked for, in their order."""
        return tuple(c for m in self.measures for c in MEASURES[m].columns)

    def flags_of(self, i: int) -> dict[str, Any]:
        """The design flags of design ``i`` (the fixed ones and its point)."""
        return {**self.fixed, **self.points[i]}


def _numeric(spec: VarySpec) -> bool:
    return all(isinstance(v, int | float) for v in spec.values)


def input_values(point: dict[str, Any]) -> dict[str, Any]:
    """A point's input columns (a rectangle also as its width and height)."""
    out = dict(point)
    if "rectangle" in point:
        out["rectangle_width"], out["rectangle_height"] = parse_rectangle(point["rectangle"])
    return out


def _check_value(
    base: tuple[dict[str, Any], str, bool, dict[str, Any]],
    spec: VarySpec,
    value: Any,
    simulated: bool = False,
) -> None:
    """Build the template's design with the fixed flags and ``value`` alone
    (``simulated``: and check that simulate can take it)."""
    raw, path, implicit, fixed = base
    if spec.flag.kind is parse_int:
        value = int(round(value))
    flags = {**fixed, spec.dest: value}
    try:
        design = template_job(raw, path, flags, None, implicit).design
        if simulated:
            from onefold_cad.mechanics.model import check_simulable

            check_simulable(design)
    except InvalidParameterError as exc:
        raise UsageError(f"--vary {spec.text}: {exc}") from None


def _design_key(template_digest: str, flags: dict[str, Any]) -> str:
    text = template_digest + json.dumps(flags, sort_keys=True, default=str)
    return hashlib.sha1(text.encode()).hexdigest()[:16]


def _specs(texts: Sequence[str], fixed: dict[str, Any]) -> list[VarySpec]:
    if not texts:
        raise UsageError("--vary: at least one NAME=SPEC is needed (e.g. --vary alpha=10:80:15)")
    specs: list[VarySpec] = []
    for t in texts:
        s = parse_vary(t)
        if any(o.dest == s.dest for o in specs):
            raise UsageError(f"--vary {t}: {s.flag.flag[2:]} is varied twice")
        if s.dest in fixed:
            raise UsageError(f"--vary {t}: {s.flag.flag} is also given as a fixed flag")
        specs.append(s)
    return specs


def _points(
    specs: list[VarySpec], sampler: str, samples: int | None, seed: int
) -> tuple[list[VarySpec], list[dict[str, Any]]]:
    if sampler not in SAMPLERS:
        raise UsageError(f"--sampler: must be one of {', '.join(SAMPLERS)}, got {sampler!r}")
    if samples is not None and not 1 <= samples <= MAX_DESIGNS:
        raise UsageError(f"--samples: must be in [1, {MAX_DESIGNS}], got {samples}")
    if sampler == "grid":
        out = []
        for s in specs:
            if s.is_range and s.count is None:
                if samples is None or samples < 2:
                    raise UsageError(
                        f"--vary {s.text}: a grid range needs a count (LO:HI:N) or "
                        "--samples N >= 2 (values per range)"
                    )
                s = s.with_count(samples)
            out.append(s)
        specs = out
    else:
        for s in specs:
            if s.count is not None:
                raise UsageError(
                    f"--vary {s.text}: the count N is for --sampler grid; --sampler {sampler} "
                    "samples the range LO:HI (--samples N points)"
                )
        if not any(s.is_range for s in specs):
            raise UsageError(f"--sampler {sampler}: samples ranges, and no --vary is LO:HI")
        if samples is None:
            raise UsageError(f"--sampler {sampler}: needs --samples N (points to sample)")
    n = count_of(specs, sampler, samples)
    if n > MAX_DESIGNS:
        raise UsageError(f"--vary: {n} designs; a sweep has at most {MAX_DESIGNS}")
    if sampler == "grid":
        return specs, grid_points(specs)
    assert samples is not None  # refused above without --samples
    return specs, sample_points(specs, sampler, samples, seed)


def _measures(names: Sequence[str]) -> tuple[str, ...]:
    known = measure_names()
    out = [REST.name]
    for n in names:
        n = n.strip().lower()
        if n not in known:
            raise UsageError(f"--measure: {n!r} is not a measure (one of: {', '.join(known)})")
        if n not in out:
            out.append(n)
    return tuple(out)


def _simulation(
    measures: tuple[str, ...], given: dict[str, Any] | None
) -> tuple[tuple[str, Any], ...]:
    """``--measure simulate``'s settings, ``onefold simulate``'s defaults where
    not ``given`` (None values); none without that measure, where any given
    is an error."""
    from onefold_cad.choices import SIMULATION_DEFAULTS, MeshLevel

    given = {k: v for k, v in (given or {}).items() if v is not None}
    for k in given:
        if k not in SIMULATION_SETTINGS:
            raise UsageError(f"simulation: unknown setting {k!r} (one of: "
                             f"{', '.join(SIMULATION_SETTINGS)})")  # fmt: skip
    if "simulate" not in measures:
        if given:
            flag = "--" + next(iter(given))
            flag = "--check/--no-check" if flag == "--check" else flag
            raise UsageError(f"{flag}: is a setting of --measure simulate, which is not asked for")
        return ()
    out: dict[str, Any] = {}
    for name, default in SIMULATION_DEFAULTS.items():
        try:
            out[name] = type(default).parse(given.get(name, default.value)).value
        except InvalidParameterError as exc:
            raise UsageError(f"--{name}: {exc}") from None
    check = given.get("check", MeshLevel.parse(out["mesh"]).checked)
    if not isinstance(check, bool):
        raise UsageError(f"--check: must be True or False, got {check!r}")
    out["check"] = check
    return tuple((k, out[k]) for k in SIMULATION_SETTINGS)


def make_plan(
    template: str | None,
    vary: Sequence[str],
    *,
    fixed: dict[str, Any] | None = None,
    sampler: str = "grid",
    samples: int | None = None,
    seed: int = 0,
    measures: Sequence[str] = (),
    objectives: str | None = None,
    images: bool | None = None,
    simulation: dict[str, Any] | None = None,
) -> SweepPlan:
    """The checked plan of a sweep (nothing is run or written).

    Args:
        template: a template file or shipped name (None: the default one).
        vary: the ``NAME=SPEC`` texts.
        fixed: design flags given for every design (dest -> value; None
            values are dropped).
        sampler, samples, seed: ``--sampler``, ``--samples``, ``--seed``.
        measures: measure names beyond ``rest``.
        objectives: ``--objectives`` text (``max:tipping_margin_deg,...``).
        images: draw thumbnails (None: when there are at most
            :data:`IMAGES_UP_TO` designs).
        simulation: ``--measure simulate``'s settings (:data:`SIMULATION_SETTINGS`;
            None or missing: ``onefold simulate``'s defaults).

    Raises:
        UsageError: anything that would stop a design from running, as one
            line naming the parameter (and its allowed values).
    """
    from onefold_cad.templates import find_template, read_template

    fixed = {k: v for k, v in (fixed or {}).items() if v is not None}
    specs = _specs(vary, fixed)
    mnames = _measures(measures)
    sim = _simulation(mnames, simulation)
    try:
        path = find_template(template or DEFAULT_TEMPLATE)
        raw = read_template(path)
        base = template_job(raw, path, fixed, None, template is None).design
    except InvalidParameterError as exc:
        raise UsageError(str(exc)) from None
    if sim:
        from onefold_cad.mechanics.model import check_simulable

        try:
            check_simulable(base)
        except InvalidParameterError as exc:
            raise UsageError(f"--measure simulate: {exc}") from None
    specs, pts = _points(specs, sampler, samples, seed)
    for s in specs:  # a range's ends, a list's every value
        values = (s.low, s.high) if s.is_range and not s.values else s.values
        if s.is_range and s.values:
            values = (s.values[0], s.values[-1])
        for v in values:
            _check_value((raw, str(path), template is None, fixed), s, v, bool(sim))
    digest = hashlib.sha1(json.dumps(raw, sort_keys=True, default=str).encode()).hexdigest()
    unique: dict[str, dict[str, Any]] = {}
    for p in pts:  # a point made twice (rounded whole numbers) is one design, where first made
        unique.setdefault(_design_key(digest, {**fixed, **p}), p)
    keys, pts = tuple(unique), list(unique.values())
    plan = SweepPlan(
        str(path), raw, template is None, fixed, tuple(specs), sampler, samples, seed, mnames,
        len(pts) <= IMAGES_UP_TO if images is None else images, (), tuple(pts), keys, sim,
    )  # fmt: skip
    if objectives:
        cols = [*plan.input_columns, *plan.output_columns]
        hint = {c.name: m for m in measure_names() for c in MEASURES[m].columns}
        objs = parse_objectives(objectives, cols, hint)
        plan = replace(plan, objectives=objs)
    return plan
