"""The value checks shared by the frozen parameter dataclasses, and the bounds
on magnitudes that double precision can fold.

Bounds (the reasons are in the docstrings of the constants and in
docs/reliability.md):

- every length of the geometry (radius, sheet sizes, vertex coordinates) is
  within [:data:`MIN_LENGTH`, :data:`MAX_LENGTH`] = [1e-30, 1e30] design
  units; the material's lengths (thickness, bend radius, kerf, relief hole)
  within [0, :data:`MAX_LENGTH`];
- the sheet's size is within [:data:`MIN_SHEET_TO_RADIUS`,
  :data:`MAX_SHEET_TO_RADIUS`] = [1e-6, 1e6] times the frame radius
  (:func:`sheet_to_radius`, called by :class:`onefold_cad.design.Design`).

The checks themselves run under :func:`float_errors`, so an overflow or an
invalid operation while checking is an error naming the parameter, never a
numpy warning line.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterator
from contextlib import contextmanager
from fractions import Fraction

import numpy as np

from onefold_cad.errors import InvalidParameterError, shown

__all__ = [
    "MAX_LENGTH",
    "MAX_SHEET_TO_RADIUS",
    "MIN_LENGTH",
    "MIN_SHEET_TO_RADIUS",
    "check_magnitudes",
    "closed_interval",
    "finite",
    "float_errors",
    "shown",
    "integer_at_least",
    "length",
    "open_interval",
    "positive",
    "sheet_to_radius",
]


#: Largest length accepted (design units). The core forms products of up to
#: four lengths (the paper fan's sin^2 of a triangle's apex angle times its two
#: sides squared, the simplicity check's products of two cross products) and
#: then divides them; with lengths <= 1e30 and the sheet within 1e6 of R, such
#: products stay below 1e150, far from double overflow (1.8e308), with room
#: for the intermediate sums. (At 1e77 a fourth power already overflows.)
MAX_LENGTH = 1e30
#: Smallest non-zero length accepted (design units): the mirror image of
#: :data:`MAX_LENGTH`; products of up to four lengths stay above 1e-150, far
#: from the subnormal range (< 2.2e-308) where doubles lose digits.
MIN_LENGTH = 1e-30
#: Smallest sheet size (largest distance from H to the boundary) relative to
#: the frame radius R. Every folded point is A + r u with the apex A at height
#: h < 3 R, so it carries A's rounding, 2.2e-16 h < 6.7e-16 R; that must stay
#: below 1e-7 of the sheet's size (the tolerance every length is checked to),
#: which needs size > 6.7e-9 R. The bound 1e-6 leaves a factor of 150.
MIN_SHEET_TO_RADIUS = 1e-6
#: Largest sheet size relative to R. The sheet's coordinates are rounded to
#: 2.2e-16 of its size; the frame curve and the apex (at height ~R), which
#: set every fold angle and direction, must be resolved far below the 1e-7
#: tolerance in those coordinates: at 1e6 the rounding is 2.2e-10 R.
MAX_SHEET_TO_RADIUS = 1e6

# Floating-point errors that the checks turn into exceptions. Underflow is
# left at numpy's default (ignored): a product below 1e-308 of values that
# pass the bounds only ever meets larger terms, where it is lost in rounding
# just as a zero would be.
_FLOAT_ERRORS = {"over": "raise", "divide": "raise", "invalid": "raise", "under": "ignore"}


@contextmanager
def float_errors() -> Iterator[None]:
    """Run the enclosed numpy work with overflow, division by zero and invalid
    operations raising ``FloatingPointError`` (underflow ignored)."""
    with np.errstate(**_FLOAT_ERRORS):  # type: ignore[arg-type]
        yield


def finite(name: str, value: object) -> float:
    """Return ``value`` as a float, or raise if it is not a finite real number."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise InvalidParameterError(name, f"must be a finite number, got {value!r}")
    x = float(value)
    if not math.isfinite(x):
        raise InvalidParameterError(name, f"must be a finite number, got {x!r}")
    return x


def positive(name: str, value: object, unit: str = "") -> float:
    """Return ``value`` if it is finite and > 0."""
    x = finite(name, value)
    if x <= 0.0:
        raise InvalidParameterError(name, f"must be > 0{unit}, got {shown(x)}")
    return x


def length(name: str, value: object, *, zero: bool = False) -> float:
    """Return ``value`` if it is a finite length within [MIN_LENGTH, MAX_LENGTH]
    (or exactly 0 when ``zero`` is true); the error names ``name`` and the range."""
    x = finite(name, value)
    if zero and x == 0.0:
        return x
    if x <= 0.0:
        rng = ">= 0" if zero else "> 0"
        raise InvalidParameterError(
            name, f"must be {rng} (a length in [{MIN_LENGTH:g}, {MAX_LENGTH:g}]), got {shown(x)}"
        )
    if not MIN_LENGTH <= x <= MAX_LENGTH:
        low = "0 or " if zero else ""
        raise InvalidParameterError(
            name,
            f"must be {low}in [{MIN_LENGTH:g}, {MAX_LENGTH:g}] (design units; beyond, "
            f"products of lengths leave double precision), got {shown(x)}",
        )
    return x


def sheet_to_radius(size: float, radius: float) -> None:
    """Raise unless the sheet's size is within [MIN_SHEET_TO_RADIUS,
    MAX_SHEET_TO_RADIUS] times the frame radius (both lengths in design units).

    Raises:
        InvalidParameterError: naming 'frame.radius' (the design's field), with
            the allowed radius range for this sheet and the reason.
    """
    exact = Fraction(size) / Fraction(radius)  # no rounding at the bounds
    if Fraction(MIN_SHEET_TO_RADIUS) <= exact <= Fraction(MAX_SHEET_TO_RADIUS):
        return
    ratio = size / radius
    lo, hi = size / MAX_SHEET_TO_RADIUS, size / MIN_SHEET_TO_RADIUS
    why = (
        "the apex's rounding would exceed 1e-7 of the sheet"
        if ratio < MIN_SHEET_TO_RADIUS
        else "the frame curve would be lost in the sheet's rounding"
    )
    raise InvalidParameterError(
        "frame.radius",
        f"must be within [{1 / MAX_SHEET_TO_RADIUS:g}, {1 / MIN_SHEET_TO_RADIUS:g}] times the "
        f"sheet's size (its largest distance from H, {size:g}), i.e. in [{lo:g}, {hi:g}], "
        f"got {shown(radius)} ({why})",
    )


def check_magnitudes(radius: float, sheet_size: float, material: object) -> None:
    """The design-level magnitude bounds, called by ``Design.__post_init__``.

    Args:
        radius: the frame radius R (length, already within the length bounds).
        sheet_size: the sheet's largest distance from H (length).
        material: a :class:`~onefold_cad.geometry.material.Material`; its
            ``thickness``, ``bend_radius``, ``kerf`` and ``relief_hole`` must
            be at most MAX_LENGTH (or None for the hole). They have no lower
            bound: they only enter as additions to sheet-sized lengths
            (offsets, r + K t), where a value below the sheet's rounding is
            lost just as 0 would be.

    Raises:
        InvalidParameterError: naming 'frame.radius' (:func:`sheet_to_radius`)
            or the material length out of range ('material.thickness', ...).
    """
    with float_errors():
        sheet_to_radius(sheet_size, radius)
        for key in ("thickness", "bend_radius", "kerf", "relief_hole"):
            value = getattr(material, key)
            if value is not None and not 0.0 <= value <= MAX_LENGTH:
                raise InvalidParameterError(
                    f"material.{key}",
                    f"must be in [0, {MAX_LENGTH:g}] (design units; beyond, products of lengths "
                    f"leave double precision), got {shown(value)}",
                )


def open_interval(name: str, value: object, lo: float, hi: float, unit: str = "") -> float:
    """Return ``value`` if it is finite and lo < value < hi."""
    x = finite(name, value)
    if not lo < x < hi:
        raise InvalidParameterError(name, f"must be in ({lo:g}, {hi:g}){unit}, got {shown(x)}")
    return x


def closed_interval(name: str, value: object, lo: float, hi: float, unit: str = "") -> float:
    """Return ``value`` if it is finite and lo <= value <= hi."""
    x = finite(name, value)
    if not lo <= x <= hi:
        raise InvalidParameterError(name, f"must be in [{lo:g}, {hi:g}]{unit}, got {shown(x)}")
    return x


def integer_at_least(name: str, value: object, lo: int, hi: int | None = None) -> int:
    """Return ``value`` if it is an integer (not bool) >= lo (and <= hi if given)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        if isinstance(value, float) and math.isfinite(value) and value.is_integer():
            value = int(value)
        else:
            rng = f">= {lo}" if hi is None else f"in [{lo}, {hi}]"
            raise InvalidParameterError(name, f"must be an integer {rng}, got {value!r}")
    n = int(value)
    if n < lo or (hi is not None and n > hi):
        rng = f">= {lo}" if hi is None else f"in [{lo}, {hi}]"
        raise InvalidParameterError(name, f"must be an integer {rng}, got {n}")
    return n
