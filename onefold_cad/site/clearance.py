"""The clearance between the sheets of a site: every pair's smallest distance
as they stand (measured by the CAD adapter on the exact solids), the
smallest of them and the pairs that touch or overlap.

Two sheets *touch* when their distance is at most :data:`TOUCH_TOLERANCE`
of the larger sheet's size (the B-reps lie within their fit tolerance, far
below it, of the exact surfaces); they *overlap* when a point of one lies
inside the other (the distance is then 0). How much they overlap is said by
their footprints' shared area on the ground (:func:`convex_overlap`; a
boolean of the two solids takes tens of seconds). Lengths are in the site's
unit, areas in unit^2.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.numeric import Array, polygon_area

__all__ = [
    "TOUCH_TOLERANCE",
    "Clearance",
    "PairDistance",
    "clearance",
    "convex_overlap",
    "nearest_neighbours",
]

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
        footprint_overlap: the area their footprints share on the ground
            (length^2).
        scale: the larger sheet's size (length), the tolerance's scale.
    """

    a: str
    b: str
    distance: float
    point_a: Array
    point_b: Array
    footprint_overlap: float = 0.0
    scale: float = 1.0

    @property
    def touching(self) -> bool:
        """Whether the two touch or overlap."""
        return self.distance <= TOUCH_TOLERANCE * self.scale


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
        at = ", ".join(f"{v:.1f}" for v in (np.asarray(p.point_a) + p.point_b) / 2.0)
        raise InvalidParameterError(
            "sheets",
            f"{p.a!r} and {p.b!r} touch or overlap (distance {p.distance:.3g} {units}, at "
            f"({at}) {units}); their footprints overlap by {p.footprint_overlap:.6g} {units}^2; "
            "move them apart or give --allow-touching for sheets meant to lean on each other",
        )


def convex_overlap(p: Array, q: Array) -> float:
    """The area two convex polygons ``(n, 2)``, ``(m, 2)`` (counter-clockwise)
    share: ``p`` clipped by each edge of ``q`` (Sutherland-Hodgman), its
    area (length^2; 0 when they are apart)."""
    out = [np.asarray(v, dtype=float) for v in np.asarray(p, dtype=float)]
    q = np.asarray(q, dtype=float)
    for a, b in zip(q, np.roll(q, -1, axis=0), strict=True):
        if len(out) < 3:
            return 0.0
        edge = b - a

        def side(v: Array, a: Array = a, edge: Array = edge) -> float:
            return float(edge[0] * (v[1] - a[1]) - edge[1] * (v[0] - a[0]))

        clipped = []
        for u, v in zip(out, out[1:] + out[:1], strict=True):
            su, sv = side(u), side(v)
            if su >= 0.0:
                clipped.append(u)
            if (su >= 0.0) != (sv >= 0.0):
                clipped.append(u + (v - u) * (su / (su - sv)))
        out = clipped
    return polygon_area(np.array(out)) if len(out) >= 3 else 0.0


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
