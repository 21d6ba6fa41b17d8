"""``--vary NAME=SPEC``: which design flag varies and over what.

NAME is a design flag (:data:`~onefold_cad.flags.design_flags.DESIGN_FLAGS`),
written as the flag without its dashes (``alpha``, ``hc``, ``apex-fraction``;
``apex_fraction`` too). SPEC is one of:

* ``LO:HI:N`` -- N values evenly spaced from LO to HI, both included (a
  number flag; a whole-number flag's values are rounded, repeats dropped);
* ``LO:HI`` -- the range alone: ``--sampler lhs|sobol`` samples it, and the
  grid takes ``--samples`` values from it;
* ``V,V,...`` -- a list of values, each read as the flag reads it
  (``rectangle=3048x7315.2,2438x6096``, ``model=exact,paper``); a polygon
  flag's list is separated by ``|`` (its vertices already use ``,`` and ``;``);
* ``V`` -- one value.

Values are read with the flag's own parser, so ``--vary alpha=30`` is the
value ``--alpha 30`` gives. Whether a value is in the design's allowed range
is checked by building the design (:mod:`onefold_cad.sweep.plan`). Standard
library only.
"""

from __future__ import annotations

import argparse
import math
from dataclasses import dataclass
from typing import Any

from onefold_cad.errors import shown
from onefold_cad.flags.design_flags import DESIGN_FLAGS, Flag, parse_float, parse_int
from onefold_cad.flags.parser import UsageError

__all__ = ["MAX_COUNT", "VarySpec", "flag_named", "is_number_flag", "parse_vary", "unit_kind"]

#: The most values one range may have (a study of 10^6 designs is already days).
MAX_COUNT = 1_000_000

#: The unit kind of each flag, from its metavar in the flag table.
_UNIT_OF_METAVAR = {"DEG": "deg", "LENGTH": "length", "DIAMETER": "length", "KG/M3": "kg/m^3"}


@dataclass(frozen=True)
class VarySpec:
    """One ``--vary``.

    Attributes:
        flag: the design flag it varies.
        text: the ``NAME=SPEC`` as given (for messages).
        values: the values (grid and lists), as the flag's parser reads
            them; empty for a range without a count.
        low, high: the range's ends (None for a list).
        count: the number of values a range asked for (None: not given).
    """

    flag: Flag
    text: str
    values: tuple[Any, ...]
    low: float | None = None
    high: float | None = None
    count: int | None = None

    @property
    def dest(self) -> str:
        """The flag's name in flag dicts (``alpha``, ``apex_fraction``)."""
        return self.flag.dest

    @property
    def is_range(self) -> bool:
        """A ``LO:HI`` or ``LO:HI:N`` range (else a list or one value)."""
        return self.low is not None

    def with_count(self, count: int) -> VarySpec:
        """The range with ``count`` grid values (``--samples`` for ``LO:HI``)."""
        assert self.low is not None and self.high is not None
        return VarySpec(
            self.flag, self.text, _spaced(self, self.low, self.high, count), self.low, self.high,
            count,
        )  # fmt: skip


def is_number_flag(flag: Flag) -> bool:
    """Whether ``flag`` takes a number (so it may vary over a range)."""
    return flag.kind in (parse_float, parse_int)


def unit_kind(flag: Flag) -> str:
    """The unit kind of ``flag``'s values (``deg``, ``length``, ``kg/m^3`` or
    ``''``), read from the flag table's metavar."""
    return _UNIT_OF_METAVAR.get(flag.metavar or "", "")


def flag_named(name: str, where: str | None = None) -> Flag:
    """The design flag ``name`` (``alpha``, ``apex-fraction``, ``--hc``);
    ``where``: the ``--vary`` text to name in the error (default ``name``).

    Raises:
        UsageError: no design flag has that name.
    """
    key = name.strip().lstrip("-").replace("-", "_").lower()
    for f in DESIGN_FLAGS:
        if key == f.dest:
            return f
    names = ", ".join(f.flag[2:] for f in DESIGN_FLAGS)
    raise UsageError(
        f"--vary {where or name}: {name.strip()!r} is not a design flag (one of: {names})"
    )


def _value(flag: Flag, text: str, where: str) -> Any:
    try:
        return flag.kind(text.strip())
    except argparse.ArgumentTypeError as exc:
        raise UsageError(f"--vary {where}: {flag.flag[2:]} {exc}") from None


def _spaced(spec: VarySpec, low: float, high: float, count: int) -> tuple[Any, ...]:
    if count == 1:
        raw = [low]
    else:
        raw = [low + (high - low) * i / (count - 1) for i in range(count)]
        raw[-1] = high
    if spec.flag.kind is parse_int:
        return tuple(dict.fromkeys(int(round(v)) for v in raw))
    return tuple(raw)


def _parse_range(flag: Flag, parts: list[str], text: str) -> VarySpec:
    if not is_number_flag(flag):
        raise UsageError(
            f"--vary {text}: {flag.flag[2:]} takes no range (it is not a number); "
            "give a list of values V,V,..."
        )
    if len(parts) > 3:
        raise UsageError(f"--vary {text}: a range is LO:HI or LO:HI:N")
    low, high = (_value(flag, p, text) for p in parts[:2])
    if not (math.isfinite(low) and math.isfinite(high)):
        raise UsageError(f"--vary {text}: the range's ends must be finite numbers")
    if not low < high:
        raise UsageError(
            f"--vary {text}: empty range: LO must be below HI (got {shown(low)} and {shown(high)})"
        )
    spec = VarySpec(flag, text, (), float(low), float(high))
    if len(parts) == 2:
        return spec
    try:
        count = parse_int(parts[2])
    except argparse.ArgumentTypeError as exc:
        raise UsageError(f"--vary {text}: the count N {exc}") from None
    if not 2 <= count <= MAX_COUNT:
        raise UsageError(f"--vary {text}: the count N must be in [2, {MAX_COUNT}], got {count}")
    return spec.with_count(count)


def parse_vary(text: str) -> VarySpec:
    """The ``--vary`` ``text`` (``alpha=10:80:15``) read.

    Raises:
        UsageError: an unknown flag, a malformed or empty SPEC, a value the
            flag cannot read (one line naming it).
    """
    name, eq, body = text.partition("=")
    if not eq or not name.strip():
        raise UsageError(
            f"--vary {text}: must be NAME=SPEC (e.g. alpha=10:80:15 or hc-fraction=-0.5,0,0.5)"
        )
    flag = flag_named(name, text)
    body = body.strip()
    if not body:
        raise UsageError(f"--vary {text}: no values after '='")
    sep = "|" if flag.dest == "polygon" else ","
    if ":" in body and flag.dest != "polygon":
        return _parse_range(flag, body.split(":"), text)
    items = [p for p in body.split(sep)]
    if any(not p.strip() for p in items):
        raise UsageError(f"--vary {text}: an empty value in the list")
    values = tuple(dict.fromkeys(_value(flag, p, text) for p in items))
    if is_number_flag(flag) and not all(math.isfinite(v) for v in values):
        raise UsageError(f"--vary {text}: values must be finite numbers")
    return VarySpec(flag, text, values)
