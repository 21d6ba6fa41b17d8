"""Frozen, validated inputs of the construction: the frame curve and the model.

Angles are in degrees at this edge of the API; lengths are in the design's unit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from enum import StrEnum
from typing import Any

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.validate import finite, integer_at_least, open_interval, positive

__all__ = ["FrameCurve", "Model", "MAX_DIVISIONS"]

#: Upper limit on ``divisions`` (memory guard: 10 million triangles).
MAX_DIVISIONS = 10_000_000


class Model(StrEnum):
    """Which direction-surface the solver uses.

    PAPER: the fan of ``divisions`` planar triangles over the division points
    of the frame curve, exactly as in the paper.
    EXACT: the continuous cone over the circular arc (the limit of infinitely
    many divisions); independent of ``divisions``.
    """

    PAPER = "paper"
    EXACT = "exact"

    @classmethod
    def parse(cls, value: object) -> Model:
        """Return the model named by ``value`` ('paper' or 'exact')."""
        if isinstance(value, cls):
            return value
        try:
            return cls(str(value).lower())
        except ValueError:
            raise InvalidParameterError(
                "model", f"must be one of 'exact', 'paper', got {value!r}"
            ) from None


@dataclass(frozen=True)
class FrameCurve:
    """The frame curve of paper section 3.2 (one side; the other is its mirror).

    A circular arc of radius ``radius`` and central angle 180 + 2*alpha whose
    chord (the f-line, length 2 R cos(alpha)) lies on the x axis, tilted about
    the x axis so that its plane makes the angle ``beta`` with the y axis.

    Attributes:
        alpha: arc opening in degrees, in (0, 90).
        beta: tilt of the arc's plane from the y axis in degrees, in (0, 90).
        h_c: offset of H from the f-line midpoint (length); positive puts H on
            the +x side of the midpoint. |h_c| < radius * cos(alpha).
        radius: arc radius R (length), > 0. The paper's H_c values assume 100.
        divisions: number of triangles of the paper model's fan, >= 1.
    """

    alpha: float
    beta: float
    h_c: float = 0.0
    radius: float = 100.0
    divisions: int = 90

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(self, "alpha", open_interval("alpha", self.alpha, 0.0, 90.0, " deg"))
        set_(self, "beta", open_interval("beta", self.beta, 0.0, 90.0, " deg"))
        set_(self, "radius", positive("radius", self.radius))
        set_(self, "h_c", finite("h_c", self.h_c))
        set_(self, "divisions", integer_at_least("divisions", self.divisions, 1, MAX_DIVISIONS))
        half = self.half_chord
        if not abs(self.h_c) < half:
            raise InvalidParameterError(
                "h_c",
                f"H must lie strictly inside the f-line: |h_c| < radius*cos(alpha) = "
                f"{half:.6g}, i.e. h_c in ({-half:.6g}, {half:.6g}), got {self.h_c:g}",
            )

    @property
    def half_chord(self) -> float:
        """Half the f-line length, R cos(alpha) (length)."""
        return self.radius * math.cos(math.radians(self.alpha))

    @property
    def paper_lower_bound(self) -> float:
        """The paper's lower bisection bound l = (R + R sin alpha) sin beta (length)."""
        a, b = math.radians(self.alpha), math.radians(self.beta)
        return (self.radius + self.radius * math.sin(a)) * math.sin(b)

    def with_changes(self, **changes: Any) -> FrameCurve:
        """Return a copy with some fields replaced (validated again)."""
        return replace(self, **changes)
