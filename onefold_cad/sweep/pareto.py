"""Pareto objectives and the non-dominated designs.

``--objectives`` is a comma-separated list of ``max:COLUMN``, ``min:COLUMN``
and ``target:COLUMN=VALUE`` (the distance to VALUE, minimised), e.g.
``max:tipping_margin_deg,min:mass,target:height=3000``. A design dominates
another when it is no worse in every objective and better in one; the Pareto
front is the designs no design dominates (:func:`pareto_front`, a sort on the
first objective and a sweep that compares each design with the front found
so far: fast when the front is small, n^2 / 2 comparisons at worst).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from onefold_cad.flags.design_flags import parse_float
from onefold_cad.flags.parser import UsageError
from onefold_cad.geometry.numeric import Array
from onefold_cad.sweep.measures import Column

__all__ = ["Objective", "costs", "dominates", "pareto_front", "parse_objectives"]

_SENSES = ("max", "min", "target")


@dataclass(frozen=True)
class Objective:
    """One objective.

    Attributes:
        sense: 'max', 'min' or 'target'.
        column: the column it reads.
        target: the value aimed at ('target' only; in the column's unit).
    """

    sense: str
    column: str
    target: float | None = None

    @property
    def text(self) -> str:
        """As written on the command line (``target:height=3000``)."""
        aim = f"={self.target:g}" if self.target is not None else ""
        return f"{self.sense}:{self.column}{aim}"

    def cost(self, values: Array) -> Array:
        """The values turned into a cost to minimise (NaN stays NaN)."""
        v = np.asarray(values, dtype=float)
        if self.sense == "max":
            return -v
        if self.sense == "target":
            assert self.target is not None
            return np.abs(v - self.target)
        return v


def parse_objectives(
    text: str, columns: Sequence[Column], hints: Mapping[str, str] | None = None
) -> tuple[Objective, ...]:
    """The objectives of ``text``, each naming a number column of ``columns``.

    Args:
        text: ``max:COLUMN,min:COLUMN,target:COLUMN=VALUE``.
        columns: the sweep's columns (inputs and outputs).
        hints: column -> the measure that would add it (for the message).

    Raises:
        UsageError: a malformed objective or an unknown or non-number column.
    """
    numbers = [c.name for c in columns if c.kind in ("float", "int")]
    out = []
    for part in (p.strip() for p in text.split(",")):
        sense, colon, rest = part.partition(":")
        if not colon or sense not in _SENSES or not rest:
            raise UsageError(
                f"--objectives: {part!r} must be max:COLUMN, min:COLUMN or target:COLUMN=VALUE"
            )
        name, eq, value = rest.partition("=")
        if (sense == "target") != bool(eq):
            need = "needs =VALUE" if sense == "target" else "takes no =VALUE"
            raise UsageError(f"--objectives: {part!r}: {sense} {need}")
        if name not in numbers:
            extra = ""
            if hints and name in hints:
                extra = f"; it needs --measure {hints[name]}"
            raise UsageError(
                f"--objectives: {part!r}: no number column {name!r}{extra} "
                f"(columns: {', '.join(numbers)})"
            )
        try:
            target = parse_float(value) if eq else None
        except Exception as exc:
            raise UsageError(f"--objectives: {part!r}: {exc}") from None
        if target is not None and not np.isfinite(target):
            raise UsageError(f"--objectives: {part!r}: the target must be a finite number")
        out.append(Objective(sense, name, target))
    if len({o.column for o in out}) != len(out):
        raise UsageError("--objectives: a column is named twice")
    return tuple(out)


def costs(objectives: Sequence[Objective], table: Mapping[str, Sequence[float]]) -> Array:
    """``(n, k)`` costs (to minimise) of the n rows of ``table`` (column ->
    values) under the k objectives."""
    return np.column_stack([o.cost(np.asarray(table[o.column], dtype=float)) for o in objectives])


def dominates(a: Array, b: Array) -> bool:
    """Whether cost vector ``a`` dominates ``b``: no worse anywhere, better somewhere."""
    return bool(np.all(a <= b) and np.any(a < b))


def pareto_front(cost: Array) -> Array:
    """The mask ``(n,)`` of the rows of ``cost`` ``(n, k)`` that no row dominates.

    Rows with a NaN cost are never on the front. Equal rows are all on it
    (neither dominates the other).
    """
    c = np.asarray(cost, dtype=float)
    n = len(c)
    mask = np.zeros(n, dtype=bool)
    ok = np.flatnonzero(np.all(np.isfinite(c), axis=1)) if n else np.array([], dtype=int)
    if not len(ok):
        return mask
    # lexicographic order: no row can be dominated by one after it
    order = ok[np.lexsort(c[ok].T[::-1])]
    front: list[int] = []
    for i in order:
        if front:
            f = c[front]
            if np.any(np.all(f <= c[i], axis=1) & np.any(f < c[i], axis=1)):
                continue
        front.append(int(i))
    mask[front] = True
    return mask
