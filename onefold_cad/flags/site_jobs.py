"""The designs of a site's sheets: each ``[[sheet]]`` entry's template (or
inline design) with its ``flags`` applied as ``onefold build`` applies them
(:func:`~onefold_cad.flags.jobs.template_job`), built in the site's unit and
named after the sheet.
"""

from __future__ import annotations

from typing import Any

from onefold_cad.errors import InvalidParameterError
from onefold_cad.flags.design_flags import DESIGN_FLAGS
from onefold_cad.flags.jobs import Job, template_job
from onefold_cad.flags.parser import UsageError, parse_design_flags
from onefold_cad.site.spec import SheetSpec, SiteSpec

__all__ = ["SITE_FLAG_NAMES", "sheet_flags", "sheet_job", "site_jobs"]

#: The design flags a sheet's ``flags`` table may set, by their name without
#: dashes (``bend-radius``; ``bend_radius`` is read the same). ``units`` is the
#: site's and ``name`` the sheet's, so neither is among them.
SITE_FLAG_NAMES = tuple(f.flag[2:] for f in DESIGN_FLAGS if f.dest not in ("units",))


def sheet_flags(site: SiteSpec, sheet: SheetSpec, units: str | None = None) -> dict[str, Any]:
    """The design flags' values of one sheet (dest -> value, None for a flag
    not given), ``units`` the site's unless the design's (``units``) is the same.

    Raises:
        InvalidParameterError: an unknown flag or a value its flag refuses,
            named ``SITE.toml: sheet N 'NAME': flags.KEY``.
    """
    where = f"{site.path.name}: {sheet.entry}: flags"
    args = []
    for key, value in sheet.flags.items():
        flag = key.replace("_", "-")
        if flag not in SITE_FLAG_NAMES:
            raise InvalidParameterError(
                f"{where}.{key}",
                "unknown design flag (allowed: " + ", ".join(SITE_FLAG_NAMES) + "; units are "
                "the site's)",
            )
        args.append(f"--{flag}={value}")
        try:
            parse_design_flags([args[-1]])
        except UsageError as exc:
            message = str(exc).split(": ", 1)[-1]
            raise InvalidParameterError(f"{where}.{key}", message) from None
    values = parse_design_flags(args)
    if str(units).lower() != site.units:
        values["units"] = site.units
    return values


def sheet_job(site: SiteSpec, sheet: SheetSpec) -> Job:
    """The design of one sheet (its template or inline design, its flags, the
    site's unit), named after the sheet.

    Raises:
        InvalidParameterError: a flag or a design value the design refuses,
            named by the file, the entry and the key.
    """
    data = dict(sheet.data)
    if isinstance(sheet.source, str):  # an inline design states its units, or takes the site's
        data.setdefault("units", site.units)
    flags = sheet_flags(site, sheet, data.get("units"))
    try:
        return template_job(data, sheet.source, flags, name=sheet.name)
    except InvalidParameterError as exc:
        if not exc.parameter.startswith("--"):
            raise
        key = exc.parameter[2:]
        message = str(exc)[len(exc.parameter) + 2 :]
        raise InvalidParameterError(
            f"{site.path.name}: {sheet.entry}: flags.{key}", message
        ) from None


def site_jobs(site: SiteSpec) -> list[Job]:
    """Every sheet's design, in the site file's order."""
    return [sheet_job(site, s) for s in site.sheets]
