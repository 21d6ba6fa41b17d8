"""The design points of a sweep: the values of the varied flags, one dict per design.

* ``grid``: every combination of the specs' values (the first ``--vary``
  varies slowest).
* ``lhs`` and ``sobol``: ``--samples`` space-filling points of the ranges
  (scipy.stats.qmc: a Latin hypercube, stratified in each range, or a
  scrambled Sobol' sequence, balanced when ``--samples`` is a power of two),
  reproducible from ``--seed``; lists and single values are crossed with the
  samples (every sample with each of them). A whole-number flag's samples are
  rounded.

scipy is imported by the space-filling samplers only.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from typing import Any

from onefold_cad.flags.design_flags import parse_int
from onefold_cad.sweep.spec import VarySpec

__all__ = ["SAMPLERS", "count_of", "grid_points", "sample_points", "unit_samples"]

#: The samplers ``--sampler`` takes.
SAMPLERS = ("grid", "lhs", "sobol")


def grid_points(specs: Sequence[VarySpec]) -> list[dict[str, Any]]:
    """Every combination of the specs' values (each spec has its values)."""
    names = [s.dest for s in specs]
    return [
        dict(zip(names, combo, strict=True))
        for combo in itertools.product(*(s.values for s in specs))
    ]


def unit_samples(method: str, n: int, d: int, seed: int) -> Any:
    """``(n, d)`` points in the unit cube [0, 1)^d: 'lhs' (a Latin hypercube:
    each of the n equal slices of every axis holds one point) or 'sobol' (a
    scrambled Sobol' sequence), from ``seed``."""
    import inspect
    import warnings

    from scipy.stats import qmc

    cls = qmc.LatinHypercube if method == "lhs" else qmc.Sobol
    key = "rng" if "rng" in inspect.signature(cls).parameters else "seed"
    engine = cls(d, **{key: seed})
    with warnings.catch_warnings():  # Sobol' of n not a power of 2: still well spread
        warnings.simplefilter("ignore", UserWarning)
        return engine.random(n)


def sample_points(
    specs: Sequence[VarySpec], method: str, n: int, seed: int
) -> list[dict[str, Any]]:
    """``n`` space-filling points of the ranges among ``specs``, each crossed
    with every combination of the other specs' values."""
    ranges = [s for s in specs if s.is_range]
    others = [s for s in specs if not s.is_range]
    unit = unit_samples(method, n, len(ranges), seed) if ranges else [[]] * n
    sampled = []
    for row in unit:
        point = {}
        for s, u in zip(ranges, row, strict=True):
            assert s.low is not None and s.high is not None
            v = s.low + (s.high - s.low) * float(u)
            point[s.dest] = int(round(v)) if s.flag.kind is parse_int else v
        sampled.append(point)
    rest = grid_points(others) if others else [{}]
    order = [s.dest for s in specs]
    out = []
    for a, b in itertools.product(sampled, rest):
        merged = {**a, **b}
        out.append({k: merged[k] for k in order})
    return out


def count_of(specs: Sequence[VarySpec], method: str, n: int | None) -> int:
    """How many designs the specs make (before any is made)."""
    if method == "grid":
        return math.prod(len(s.values) for s in specs)
    return (n or 0) * math.prod(len(s.values) for s in specs if not s.is_range)
