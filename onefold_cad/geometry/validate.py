"""Small checks shared by the frozen parameter dataclasses."""

from __future__ import annotations

import math
import numbers

import numpy as np

from onefold_cad.errors import InvalidParameterError

__all__ = ["cross3", "finite", "positive", "open_interval", "closed_interval", "integer_at_least"]


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


def cross3(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross product of 3-vectors along the last axis (numpy's np.cross without
    its axis-juggling overhead, which dominates for the small arrays here)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a1 * b2 - a2 * b1
    out[..., 1] = a2 * b0 - a0 * b2
    out[..., 2] = a0 * b1 - a1 * b0
    return out
