"""The explorer's server state with and without the per-fold cache
(``onefold_cad.design.derived``: the solid's smallest relief hole, the
resting placement).

The default relief hole, the flat pattern's relief-hole check and the report
all need :func:`~onefold_cad.geometry.thick_map.min_relief_hole` (through
``onefold_cad.fabrication.relief_hole.solid_min_relief_hole``); the cache computes it once per
fold and material, and the resting placement once per fold, material and body.
The baseline is the same code with a cache that never keeps anything (each
caller computes again, as before the cache). Both run
:func:`onefold_cad.explore.state.design_state` (a fresh fold each call),
interleaved with :func:`interleave.interleave` (CPU time, medians with the
25th and 75th percentiles); the ratio is the median of the per-round ratios.
Prints only.

Run from the repository root::

    .venv/bin/python benchmarks/bench_min_hole.py [--rounds 15] [--only NAME ...]
"""

from __future__ import annotations

import argparse
import sys
import weakref
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from interleave import interleave, paired_ratio  # noqa: E402

from onefold_cad import design as design_module  # noqa: E402
from onefold_cad.explore.state import design_state  # noqa: E402
from onefold_cad.fabrication import relief_hole  # noqa: E402
from onefold_cad.templates import load_template  # noqa: E402

TEMPLATES = ["patkau-one-fold", "broken-vault", "paper-square"]


class _Forgetful(weakref.WeakKeyDictionary):  # type: ignore[type-arg]
    """A cache that keeps nothing but each design's fold (``fold_design``'s):
    every result derived from a fold is computed again."""

    def __init__(self, real: Any) -> None:
        super().__init__()
        self.real = real

    def setdefault(self, key: Any, default: Any = None) -> Any:
        if isinstance(key, design_module.Design):
            return self.real.setdefault(key, {} if default is None else default)
        return {} if default is None else default


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rounds", type=int, default=15)
    ap.add_argument("--only", nargs="*", default=None)
    args = ap.parse_args(argv)
    cached = design_module.DERIVED
    forgetful = _Forgetful(cached)
    calls = {"n": 0}
    real = relief_hole.min_relief_hole

    def counted(*a: Any) -> Any:
        calls["n"] += 1
        return real(*a)

    print("| template | min_relief_hole calls per state (cached / not) | state, cached "
          "median [q1, q3] | state, not cached | not cached / cached |")  # fmt: skip
    print("|---|---|---|---|---|")
    for name in args.only or TEMPLATES:
        design = load_template(name)

        def state_cached(d: Any = design) -> Any:
            design_module.DERIVED = cached
            return design_state(d)

        def state_uncached(d: Any = design) -> Any:
            design_module.DERIVED = forgetful
            return design_state(d)

        relief_hole.min_relief_hole = counted
        counts = []
        for fn in (state_cached, state_uncached):
            calls["n"] = 0
            fn()
            counts.append(calls["n"])
        relief_hole.min_relief_hole = real
        res = interleave(
            {"cached": state_cached, "uncached": state_uncached},
            rounds=args.rounds,
            batch_time=0.0,
        )
        ratio = paired_ratio(res, "uncached", "cached")
        print(
            f"| {name} | {counts[0]} / {counts[1]} | {res['cached'].fmt(1e3, ' ms')} | "
            f"{res['uncached'].fmt(1e3, ' ms')} | {ratio.fmt(digits=3)} |",
            flush=True,
        )
    design_module.DERIVED = cached
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
