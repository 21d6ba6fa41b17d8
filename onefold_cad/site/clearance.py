"""The clearance between the sheets of a site: every pair's smallest distance
as they stand (measured by the CAD adapter on the exact solids), the
smallest of them and the pairs that touch or overlap.

Two sheets *touch* when their distance is at most :data:`TOUCH_TOLERANCE`
of the larger sheet's size (the B-reps lie within their fit tolerance, far
below it, of the exact surfaces); they *overlap* when they share volume.
Lengths are in the site's unit, volumes in unit^3.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.numeric import Array

__all__ = ["TOUCH_TOLERANCE", "Clearance", "PairDistance", "clearance", "nearest_neighbours"]

#: Sheets closer than this, relative to the larger sheet's size, touch.
TOUCH_TOLERANCE = 1e-6


@dataclass(frozen=True, eq=False)
class PairDistance:
    """The smallest distance between two placed sheets.

    Attributes:
        a, b: the sheets' names (in the site file's order).
        distance: the smallest distance between their solids (length; 0
            when they touch or overlap).
        point_a, point_b: ``(3,)`` where it is reached on each (site frame).
        overlap_volume: the volume the two share (length^3; 0 unless they
            overlap).
        scale: the larger sheet's size (length), the tolerance's scale.
    """

    a: str
    b: str
    distance: float
    point_a: Array
    point_b: Array
    overlap_volume: float = 0.0
    scale: float = 1.0

    @property
    def touching(self) -> bool:
        """Whether the two touch or overlap."""
        return self.distance <= TOUCH_TOLERANCE * self.scale or self.overlap_volume > 0.0


@dataclass(frozen=True, eq=False)
class Clearance:
    """Every pair of a site's sheets and the smallest distance between them.

    Attributes:
        pairs: one :class:`PairDistance` per pair, in the site file's order.
        accuracy: how far the measured distances may lie from the exact
            surfaces' (length): the largest fit tolerance of the sheets' B-reps.
    """

    pairs: tuple[PairDistance, ...]
    accuracy: float

    @property
    def smallest(self) -> PairDistance | None:
        """The closest pair (None for a site of one sheet)."""
        return min(self.pairs, key=lambda p: p.distance, default=None)

    @property
    def touching(self) -> tuple[PairDistance, ...]:
        """The pairs that touch or overlap."""
        return tuple(p for p in self.pairs if p.touching)

    def check(self, units: str, allow_touching: bool = False) -> None:
        """Raise for the first pair that touches or overlaps, naming both
        (unless ``allow_touching``).

        Raises:
            InvalidParameterError: parameter ``sheets``, the two names and
                their overlap.
        """
        if allow_touching or not self.touching:
            return
        p = self.touching[0]
        what = (
            f"overlap by {p.overlap_volume:.6g} {units}^3 of solid"
            if p.overlap_volume > 0.0
            else f"touch (distance {p.distance:.3g} {units})"
        )
        at = ", ".join(f"{v:.1f}" for v in (np.asarray(p.point_a) + p.point_b) / 2.0)
        raise InvalidParameterError(
            "sheets",
            f"{p.a!r} and {p.b!r} {what} near ({at}) {units}; move them apart or give "
            "--allow-touching for sheets meant to lean on each other",
        )


def clearance(pairs: Sequence[PairDistance], accuracy: float) -> Clearance:
    """The site's :class:`Clearance` from its measured pairs."""
    return Clearance(tuple(pairs), float(accuracy))


def nearest_neighbours(c: Clearance, names: Sequence[str]) -> list[PairDistance]:
    """Each sheet's closest other sheet, each pair once, in ``names``' order:
    the distances the site plan draws."""
    out: list[PairDistance] = []
    for n in names:
        mine = [p for p in c.pairs if n in (p.a, p.b)]
        best = min(mine, key=lambda p: p.distance, default=None)
        if best is not None and all(best is not q for q in out):
            out.append(best)
    return out
