"""What a compensation aims at, checked before any simulation runs.

Two kinds of target (:class:`Target`):

- ``design``: the designed form itself, as it stands on its feet (the least
  squares of the steel's distance from it);
- ``size``: a height and span (and optionally a depth) of the standing
  steel. Whether the sheet's family of folds reaches them at all is
  asked of :func:`onefold_cad.fit.fit_design` first (geometry only, a
  fraction of a second): an unreachable size is refused in one line with
  the ranges the family reaches, before any simulation. The fitted fold is
  the compensation's start.

Lengths are in the design's unit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from onefold_cad.design import Design
from onefold_cad.errors import InvalidParameterError

__all__ = ["Target", "make_target"]


@dataclass(frozen=True)
class Target:
    """A compensation's target.

    Attributes:
        kind: 'design' (the form) or 'size' (height and span).
        form: the design whose standing form is the target ('design'), or the
            fold whose designed form has the target size ('size': the start).
        height, span, depth: the size targets (design unit), None for 'design'
            (depth None when not given).
    """

    kind: str
    form: Design
    height: float | None = None
    span: float | None = None
    depth: float | None = None

    def sizes(self) -> dict[str, float]:
        """The size targets given: ``{'height': ..., 'span': ..., 'depth': ...}``."""
        out = {"height": self.height, "span": self.span, "depth": self.depth}
        return {k: v for k, v in out.items() if v is not None}


def _length(flag: str, value: float | None) -> None:
    if value is not None and not (math.isfinite(value) and value > 0.0):
        raise InvalidParameterError(flag, f"must be a finite length > 0, got {value!r}")


def make_target(
    design: Design,
    kind: str,
    height: float | None = None,
    span: float | None = None,
    depth: float | None = None,
) -> Target:
    """Check and make the target (no simulation runs here).

    Raises:
        InvalidParameterError: a design without steel data (named value), a
            size that is not a positive length, a size target without both
            height and span, sizes with ``--target design``.
        OutOfReachError: ('target') no fold of the sheet has that size; the
            line gives the ranges the family reaches.
    """
    from onefold_cad.mechanics.model import check_simulable

    check_simulable(design)
    for flag, value in (("--height", height), ("--span", span), ("--depth", depth)):
        _length(flag, value)
    sized = any(v is not None for v in (height, span, depth))
    if kind == "design":
        if sized:
            raise InvalidParameterError(
                "--target", "design takes no --height, --span or --depth (drop --target design)"
            )
        return Target("design", design)
    if kind != "size":
        raise InvalidParameterError("--target", f"must be 'design' or a size, got {kind!r}")
    if height is None or span is None:
        missing = "--height" if height is None else "--span"
        raise InvalidParameterError(missing, "a size target needs both --height and --span")
    from onefold_cad.fit import fit_design

    fit = fit_design(design, height, span, depth)
    form = fit.design.with_changes(name=design.name)
    return Target("size", form, float(height), float(span), None if depth is None else float(depth))
