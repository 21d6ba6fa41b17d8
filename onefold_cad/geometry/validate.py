"""Small checks shared by the frozen parameter dataclasses."""

from __future__ import annotations

import math
import numbers

from onefold_cad.errors import InvalidParameterError

__all__ = ["finite", "positive", "open_interval", "closed_interval", "integer_at_least"]


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
        raise InvalidParameterError(name, f"must be > 0{unit}, got {x:g}")
    return x


def open_interval(name: str, value: object, lo: float, hi: float, unit: str = "") -> float:
    """Return ``value`` if it is finite and lo < value < hi."""
    x = finite(name, value)
    if not lo < x < hi:
        raise InvalidParameterError(name, f"must be in ({lo:g}, {hi:g}){unit}, got {x:g}")
    return x


def closed_interval(name: str, value: object, lo: float, hi: float, unit: str = "") -> float:
    """Return ``value`` if it is finite and lo <= value <= hi."""
    x = finite(name, value)
    if not lo <= x <= hi:
        raise InvalidParameterError(name, f"must be in [{lo:g}, {hi:g}]{unit}, got {x:g}")
    return x


def integer_at_least(name: str, value: object, lo: int, hi: int | None = None) -> int:
    """Return ``value`` if it is an integer (not bool) >= lo (and <= hi if given)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        if isinstance(value, float) and math.isfinite(value) and value.is_integer():
            value = int(value)
        else:
            rng = f">= {lo}" if hi is None else f"in [{lo}, {hi}]"
            raise InvalidParameterError(name, f"must be an integer {rng}, got {value!r}")
    n = int(value)  # type: ignore[arg-type]
    if n < lo or (hi is not None and n > hi):
        rng = f">= {lo}" if hi is None else f"in [{lo}, {hi}]"
        raise InvalidParameterError(name, f"must be an integer {rng}, got {n}")
    return n
