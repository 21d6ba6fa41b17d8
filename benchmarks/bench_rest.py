"""The resting placement per template and body, against the algorithm it
replaced and against the template's solve + fold.

For every shipped template and every body it can be written as ('shell', and
'solid' for an exact-model design with a thickness and a relief hole), in one
process, CPU time, the cases interleaved (``interleave.interleave``, one call
per batch, the order rotated every round):

* ``solve + fold``: ``fold(solve(frame, model), sheet)``, the baseline a
  placement is a multiple of;
* ``rest``: :func:`onefold_cad.geometry.resting.placement.rest_form` on a fresh fold
  (built beforehand, one per call: the fold's own caches, the cone's node
  table, are part of the placement's cost), with the relief hole the STEP is
  built with;
* ``rest, main``: the same with the package as commit ``--baseline`` had it
  (94a5a33, main before the third pass of issue 24; 9567d0a, the placement
  before issue 24, can no longer read the templates that name a Young's
  modulus), extracted from git beside this one (``git_baseline.py``); left
  out when git or that commit is missing or cannot read the template;
* ``solve + fold + rest``: the three together, what a sweep pays per design.

Each cell is the median with its 25th and 75th percentiles; ratios are the
medians of the per-round ratios. The target of issue 24 (the default
template's solid in at most 10 ms) is printed as PASS or FAIL, never asserted.

Run from the repository root::

    .venv/bin/python benchmarks/bench_rest.py [--rounds 21] [--only NAME ...] [--write-docs]
"""

from __future__ import annotations

import argparse
import importlib
import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

import git_baseline  # noqa: E402
from docs_block import machine_line, write_block  # noqa: E402
from interleave import interleave, paired_ratio  # noqa: E402

from onefold_cad.fabrication.relief_hole import relief_hole_diameter  # noqa: E402
from onefold_cad.geometry.folding import fold  # noqa: E402
from onefold_cad.geometry.resting.placement import rest_form  # noqa: E402
from onefold_cad.geometry.solver import solve  # noqa: E402
from onefold_cad.templates import find_template, list_templates, load_template  # noqa: E402

BASELINE = "94a5a33"
TARGET_MS = 10.0
DEFAULT = ("patkau-one-fold", "solid")


def _bodies(design: Any) -> list[str]:
    m = design.material
    solid = design.model.value == "exact" and m.thickness > 0.0 and m.relief_hole_diameter > 0.0
    return ["shell", "solid"] if solid else ["shell"]


def _case(pkg: Any, name: str, body: str) -> tuple[Any, Any]:
    """A zero-argument fresh ``(fold, material)`` maker for ``name`` with ``pkg``
    (today's package, or the baseline's)."""

    def mod(sub: str) -> Any:
        return importlib.import_module(f"{pkg.__name__}.{sub}")

    design = mod("templates").load_template(str(find_template(name)))
    solve_, fold_ = mod("geometry.solver").solve, mod("geometry.folding").fold
    hole = mod("fabrication.relief_hole").relief_hole_diameter

    def make() -> tuple[Any, Any]:
        folded = fold_(solve_(design.frame, design.model), design.sheet)
        return folded, design.material.with_changes(relief_hole=hole(design, folded))

    try:  # today's layout (geometry/resting/) or the baseline's (geometry/)
        rest = mod("geometry.resting.placement").rest_form
    except ModuleNotFoundError:
        rest = mod("geometry.placement").rest_form
    return make, rest


def _fresh(make: Any, rest: Any, body: str, count: int) -> Any:
    """``rest`` on a new fold each call, the folds built beforehand."""
    folds = [make() for _ in range(count)]

    def run() -> Any:
        folded, material = folds.pop()
        return rest(folded, material, body)

    return run


def bench(name: str, body: str, rounds: int, old: Any | None) -> dict[str, Any]:
    """The interleaved cases of one template and body."""
    design = load_template(name)

    def solve_fold() -> Any:
        return fold(solve(design.frame, design.model), design.sheet)

    def whole() -> Any:
        folded = solve_fold()
        m = design.material.with_changes(relief_hole=relief_hole_diameter(design, folded))
        return rest_form(folded, m, body)

    import onefold_cad

    count = rounds + 4  # warm-up and calibration calls too
    cases = {
        "solve + fold": solve_fold,
        "rest": _fresh(*_case(onefold_cad, name, body), body, count),
        "solve + fold + rest": whole,
    }
    why = ""
    if old is not None:
        try:
            cases["rest, main"] = _fresh(*_case(old, name, body), body, count)
        except Exception as exc:  # a template the baseline cannot read (a newer key)
            why = " ".join(f"{type(exc).__name__}: {exc}".split())
            old = None
    res = interleave(cases, rounds=rounds, batch_time=0.0)
    out: dict[str, Any] = {"stats": res, "vs_fold": paired_ratio(res, "rest", "solve + fold")}
    out["why"] = why
    if old is not None:
        out["speedup"] = paired_ratio(res, "rest, main", "rest")
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rounds", type=int, default=21)
    ap.add_argument("--only", nargs="*", default=None, help="template names")
    ap.add_argument("--baseline", default=BASELINE, help="commit of the old placement")
    ap.add_argument("--write-docs", action="store_true")
    args = ap.parse_args(argv)
    old, why = git_baseline.load(args.baseline)
    lines = [
        f"| template | body | solve + fold (ms) | rest (ms) | rest / (solve + fold) "
        f"| rest, {args.baseline} (ms) | speed-up | solve + fold + rest (ms) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    print("\n".join(lines), flush=True)
    verdict = ""
    unread: list[str] = []  # templates the baseline cannot build
    for name in args.only or [t.name for t in list_templates()]:
        for body in _bodies(load_template(name)):
            r = bench(name, body, args.rounds, old)
            s = r["stats"]
            ran = "rest, main" in s
            old_cell = s["rest, main"].fmt(1e3) if ran else "-"
            gain = r["speedup"].fmt(unit="x") if ran else "-"
            if r["why"]:
                unread.append(f"{name}: {r['why']}")
            line = (
                f"| {name} | {body} | {s['solve + fold'].fmt(1e3)} | {s['rest'].fmt(1e3)} | "
                f"{r['vs_fold'].fmt(unit='x')} | {old_cell} | {gain} | "
                f"{s['solve + fold + rest'].fmt(1e3)} |"
            )
            print(line, flush=True)
            lines.append(line)
            if (name, body) == DEFAULT:
                ms = s["rest"].median * 1e3
                verdict = (
                    f"{'PASS' if ms <= TARGET_MS else 'FAIL'}: the default template's solid "
                    f"rests in {ms:.3g} ms (median; target {TARGET_MS:g} ms)"
                )
    if verdict:
        print(verdict)
        lines += ["", verdict]
    if unread:
        print("(no baseline for " + "; ".join(unread) + ")")
        lines += ["", "No baseline for " + "; ".join(unread) + "."]
    if old is None:
        print(f"(no baseline: {why})")
        lines += ["", f"No baseline column: {why}."]
    if args.write_docs:
        head = (
            f"{machine_line()} CPU time in this process, {args.rounds} interleaved rounds "
            "per template and body, one call per round, each on a fresh fold. Each cell: "
            "median [25th, 75th percentile]; ratios: median [spread] of the per-round ratios."
        )
        only = f" --only {' '.join(args.only)}" if args.only else ""
        command = f"python benchmarks/bench_rest.py --write-docs --rounds {args.rounds}{only}"
        write_block("bench_rest", head + "\n\n" + "\n".join(lines), command)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
