"""The designs of templates and flags: :func:`load_jobs` converts a
template's values into ``--units`` first (so flag values are read in that
unit), names each design after what defines it and records where every
material value came from.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from onefold_cad.errors import InvalidParameterError
from onefold_cad.templates import DEFAULT_TEMPLATE

if TYPE_CHECKING:
    from onefold_cad.design import Design
from onefold_cad.flags.overrides import Overrides, changed_flags, derived_name, mark_changes

__all__ = ["Job", "load_jobs", "template_job"]


MATERIAL_KEYS = (
    "name",
    "thickness",
    "bend_radius",
    "k_factor",
    "kerf",
    "relief_hole",
    "density",
    "sheet_surface",
    "youngs_modulus",
    "poisson",
    "yield_stress",
    "hardening_modulus",
    "kinematic_hardening",
    "crease_overbend",
    "cone_forming",
)


@dataclass(frozen=True)
class Job:
    """One design to solve or build, and where its values came from.

    Attributes:
        design: the validated design.
        template: the template it started from.
        sources: template key -> where its value came from: a flag
            (``--thickness``), ``template NAME``, ``inherited from template
            NAME`` (no template was given: the default one's) or ``default``.
    """

    design: Design
    template: str
    sources: dict[str, str] = field(default_factory=dict)


def _sources(
    raw: dict[str, Any], names: dict[str, str], template: str, implicit: bool
) -> dict[str, str]:
    where = f"inherited from template {template}" if implicit else f"template {template}"
    given = raw.get("material")
    table = given if isinstance(given, dict) else {}
    out = {}
    for key in MATERIAL_KEYS:
        full = f"material.{key}"
        out[full] = names.get(full) or (where if key in table else "default")
    for key in ("units", "model"):
        out[key] = names.get(key) or (where if key in raw else "default")
    return out


def load_jobs(
    refs: Sequence[str],
    flags: dict[str, Any],
    name: str | None = None,
    skip_site: Callable[[str], None] | None = None,
) -> list[Job]:
    """The designs of the templates ``refs`` (the default one if none) with the
    design flags applied (:func:`template_job` for each template read).

    A site file among ``refs`` is refused, or, with ``skip_site``, left out
    with that note (``templates/*.toml`` holds both) as long as one design
    remains.

    Raises:
        InvalidParameterError: a site file (named by its path and ``onefold
            site``), or every file given is one with ``skip_site``.
    """
    from onefold_cad.templates import check_design_file, find_template, read_template

    implicit = not refs
    jobs = []
    refused: InvalidParameterError | None = None
    notes = []
    for ref in refs or [DEFAULT_TEMPLATE]:
        path = find_template(ref)
        raw = read_template(path)
        try:
            check_design_file(raw, path)
        except InvalidParameterError as exc:
            if skip_site is None:
                raise
            refused = refused or exc
            notes.append(f"skipped {exc}")  # "skipped PATH: a site file ..."
            continue
        jobs.append(template_job(raw, path, flags, name, implicit))
    if not jobs and refused is not None:
        raise refused
    if skip_site is not None:
        for note in notes:
            skip_site(note)
    return jobs


def template_job(
    raw: dict[str, Any],
    path: str | Path,
    flags: dict[str, Any],
    name: str | None = None,
    implicit: bool = False,
    memo: dict[str, Any] | None = None,
) -> Job:
    """The design of a template's data ``raw`` (read from ``path``) with the
    design flags applied, as ``onefold solve`` makes it.

    ``memo``: an empty dict shared by calls with the same ``raw`` and
    ``path`` (a sweep's designs): what depends on the template and the
    ``--units`` alone (the template's data in those units and its design's
    data, defaults filled in) is made once per unit, not once per design.

    A template's values are converted into ``--units`` first (when given), so
    flag values are read in that unit. The design is named ``name`` if given;
    else the template's name, with the flags given appended; without a
    template (``implicit``: the default one stands in), ``onefold-`` and the
    flags (never the default template's name).

    Raises:
        InvalidParameterError: a flag value the design refuses (named by its
            flag), a template value (named with the template's path), or a
            site file's data (named as one).
    """
    from onefold_cad.templates import check_design_file, design_from_data, template_units

    check_design_file(raw, path)
    units = template_units(raw, path)
    template = str(raw.get("name", Path(path).stem))
    try:
        data, before = _template_data(raw, units, flags.get("units"), memo)
        given = {k: v for k, v in flags.items() if v is not None}
        if name is not None:
            stem = name
        elif implicit:
            stem = derived_name("onefold", given) if given else template
        else:
            stem = derived_name(template, given)
        changed, names = Overrides(**flags, name=stem).apply(data)
        if name is None:
            names.pop("name")
        which = changed_flags(before, changed, names)
        changed = mark_changes(changed, given, which, template, implicit)
        design = design_from_data(changed, key_names=names)
    except InvalidParameterError as exc:
        if exc.parameter.startswith("--"):
            raise
        raise type(exc)(f"{path}: {exc.parameter}", str(exc)[len(exc.parameter) + 2 :]) from None
    return Job(design, template, _sources(raw, names, template, implicit))


def _template_data(
    raw: dict[str, Any], units: str, to: str | None, memo: dict[str, Any] | None
) -> tuple[dict[str, Any], dict[str, Any]]:
    """A template's data ``raw`` (in ``units``) in the units ``to`` (None: its
    own), and that data's design as data with the defaults filled in
    (``design_to_data``): from ``memo`` when it has them (read-only)."""
    from onefold_cad.templates import design_from_data, design_to_data

    key = to or ""
    if memo is not None and key in memo:
        return memo[key]
    data = raw
    if to and to != units.lower():
        data = {**raw, **design_to_data(design_from_data(raw).in_units(to))}
    out = (data, design_to_data(design_from_data(data)))
    if memo is not None:
        memo[key] = out
    return out
