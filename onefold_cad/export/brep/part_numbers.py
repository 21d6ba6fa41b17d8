"""The report's ``step`` section: the numbers of the part a writer built
(its fit to the design, its volume against the blank's), never computed
for the report alone (the report does not run the CAD kernel)."""

from __future__ import annotations

from typing import Any

from onefold_cad.errors import OneFoldError
from onefold_cad.export.build_context import BuildContext

__all__ = ["part_numbers"]


def part_numbers(ctx: BuildContext) -> dict[str, Any] | None:
    """The report's ``step`` section when a writer built the part (else None:
    the report never runs the CAD kernel)."""
    from onefold_cad.fabrication.rules import default_body  # numpy: not for --help

    part = ctx.built_part
    if part is None:
        return None
    volume = getattr(part, "solid_volume", None)
    blank = None
    if volume is not None:
        try:
            blank = ctx.pattern.area * ctx.design.material.thickness
        except OneFoldError:  # no flat pattern: the report's warnings say why
            blank = None
    return {
        "body": ctx.body or default_body(ctx.design),
        "placement": ctx.placement,
        "fit_deviation": float(part.fit_deviation),
        "fit_tolerance": float(part.fit_tolerance),
        # the solid's volume (design unit^3; null for a shell) and its excess
        # over the blank's, flat_area x thickness, that the mass weighs: the
        # mitre at the crease (about +0.1 % on patkau-one-fold)
        "volume": None if volume is None else float(volume),
        "volume_over_blank": None if not blank or volume is None else float(volume / blank - 1.0),
    }
