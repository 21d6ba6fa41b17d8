#!/usr/bin/env python3
"""Fuzz the ``onefold`` commands as a user types them: seeded random command
lines through ``solve`` and ``build``, run in-process
(:func:`onefold_cad.cli.main.main`) in forked workers with a time limit.

Each command line draws every design flag the CLI has (model, units, alpha,
beta, h_c, radius, divisions; a quadrilateral, rectangle or polygon sheet
with slivers, H near a corner or an edge, many vertices; thickness, bend
radius, K-factor, kerf, relief hole, density, reference surface), from
ordinary values, both ends of their ranges, and now and then a value out
of range or not a number; ``build`` adds a random set of ``--formats``, a
body, a compensation and a placement. Every run must end in one of:

- ``ok``: exit 0; stderr holds only ``onefold: warning: ...`` lines; no
  Python or numpy warning was issued; a build's listed files exist and are
  not empty;
- ``refused``: exit 2; stderr is exactly one line ``onefold: error: ...``
  naming a parameter (a flag or the API's name) or the design's property;
  a build wrote nothing (its output folder does not exist).

Anything else is a finding: ``unnamed`` (one line, but naming nothing the
user can change), ``crash`` (a traceback, several lines, another exit
status, a warning), ``hang`` (past the time limit; the worker is killed).

Run (from the repository root)::

    .venv/bin/python scripts/fuzz_commands.py       # 2000 solves, 300 builds, seed 38
    .venv/bin/python scripts/fuzz_commands.py --solves 200 --builds 20 --seed 7
    .venv/bin/python scripts/fuzz_commands.py --repro 38:solve:1234   # print one command line

Seeds: command line ``i`` of kind ``k`` under ``--seed s`` is drawn from
``numpy.random.default_rng([s, KINDS.index(k), i])``, so any single one can
be drawn again (``--repro s:k:i``) without the others. tests/test_fuzz.py
runs a small slice.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import math
import multiprocessing as mp
import multiprocessing.connection as mpc
import os
import re
import resource
import shlex
import sys
import tempfile
import time
import traceback
import warnings
from collections import Counter
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

KINDS = ("solve", "build")
TEMPLATES = ("patkau-one-fold", "paper-square", "star-polygon", "broken-vault", "table1-row4")
FORMATS = ("step", "dxf", "cut", "bends", "fold", "glb", "3dm", "png", "svg", "json")
#: Formats drawn often (fast); the slow pictures and 3dm now and then.
_LIGHT = ("step", "dxf", "cut", "bends", "fold", "json")

#: What a refusal may name: the design flags (CLI and API spellings), the
#: build's options, and the design's properties a refusal names when no
#: single flag is to blame.
_NAMES = (
    "alpha", "beta", "h_c", "hc", "radius", "divisions", "x_plus", "x_minus", "y_plus",
    "y_minus", "x-plus", "x-minus", "y-plus", "y-minus", "polygon", "rectangle", "width",
    "height", "apex_fraction", "apex-fraction", "thickness", "bend_radius", "bend-radius",
    "k_factor", "k-factor", "kerf", "relief_hole", "relief-hole", "density", "model", "units",
    "sheet_surface", "sheet-surface", "body", "name", "outdir", "formats", "compensation",
    "placement", "template", "youngs_modulus", "poisson", "yield_stress",
)  # fmt: skip
_PROPERTIES = ("sheet", "crease", "fold", "bend", "the apex", "the relief hole", "the blank")
NAMED = re.compile(
    r"(?<![A-Za-z_])(" + "|".join(map(re.escape, _NAMES + _PROPERTIES)) + r")(?![A-Za-z_])"
)


# -- random command lines -------------------------------------------------------
def _log(rng: np.random.Generator, lo: float, hi: float) -> float:
    return float(10.0 ** rng.uniform(math.log10(lo), math.log10(hi)))


def _num(x: float) -> str:
    return repr(float(x))


_ODD = ("nan", "inf", "-inf", "0", "-0", "-1", "1e-320", "1e308", "abc", "")


def _odd(rng: np.random.Generator, p: float) -> str | None:
    """Now and then (probability ``p``) a value out of any range or not a number."""
    return str(rng.choice(_ODD)) if rng.random() < p else None


def _angle(rng: np.random.Generator) -> float:
    u = rng.random()
    if u < 0.6:
        return float(rng.uniform(1.0, 89.0))
    if u < 0.8:
        return _log(rng, 1e-6, 1.0)
    return 90.0 - _log(rng, 1e-6, 1.0)


def _fraction(rng: np.random.Generator) -> float:
    """In (0, 1), often within 1e-12 .. 1e-2 of either end."""
    u = rng.random()
    if u < 0.2:
        return _log(rng, 1e-12, 1e-2)
    if u < 0.4:
        return 1.0 - _log(rng, 1e-12, 1e-2)
    return float(rng.uniform(0.01, 0.99))


def _polygon(rng: np.random.Generator, size: float) -> str:
    """A polygon about H: star-shaped, with thin slivers, vertices near H, a
    kite of two far tips and two near ones (the issue's slivers), many
    vertices; now and then self-intersecting or not star-shaped."""
    u = rng.random()
    if u < 0.25:  # a kite: tips on the x axis, a waist of width w on the y axis
        w = size * _log(rng, 1e-12, 1.0)
        a, b = size * rng.uniform(0.1, 1.0), size * rng.uniform(0.1, 1.0)
        pts = [(a, 0.0), (0.0, w), (-b, 0.0), (0.0, -w * rng.uniform(0.5, 2.0))]
    else:
        n = int(_log(rng, 3, 200)) if rng.random() < 0.97 else int(rng.integers(200, 1500))
        gaps = rng.dirichlet(np.full(n, 2.0 if rng.random() < 0.7 else 0.3))
        if rng.random() < 0.15:
            k = rng.integers(0, n, size=max(1, n // 4))
            gaps[k] = [_log(rng, 1e-10, 1e-3) for _ in k]
        ang = np.cumsum(gaps / gaps.sum() * 2.0 * math.pi) + rng.uniform(0, 2 * math.pi)
        radii = size * np.array([_log(rng, 1e-9, 1.0) if rng.random() < 0.05 else
                                 rng.uniform(0.2, 1.0) for _ in range(n)])  # fmt: skip
        pts = list(zip(radii * np.cos(ang), radii * np.sin(ang), strict=True))
        if rng.random() < 0.05:  # not a valid sheet: must be refused in one line
            rng.shuffle(pts)
    return ";".join(f"{_num(x)},{_num(y)}" for x, y in pts)


def random_argv(rng: np.random.Generator, kind: str) -> list[str]:
    """One random ``onefold solve`` or ``onefold build`` command line (no
    ``-o``: :func:`run_line` adds a fresh folder)."""
    argv = [kind]
    if rng.random() < 0.3:
        argv.append(str(rng.choice(TEMPLATES)))
    flags: dict[str, str] = {}
    if rng.random() < 0.7:
        flags["--model"] = str(rng.choice(["exact", "paper"]))
    if rng.random() < 0.3:
        flags["--units"] = str(rng.choice(["mm", "in", "ft"]))
    odd = 0.02
    flags["--alpha"] = _odd(rng, odd) or _num(_angle(rng))
    flags["--beta"] = _odd(rng, odd) or _num(_angle(rng))
    radius = _log(rng, 1e-2, 1e4) if rng.random() < 0.95 else _log(rng, 1e-30, 1e30)
    if rng.random() < 0.6:
        flags["--radius"] = _odd(rng, odd) or _num(radius)
    else:
        radius = 100.0
    if rng.random() < 0.5:
        alpha = float(flags["--alpha"]) if flags["--alpha"] not in _ODD else 45.0
        half = radius * math.cos(math.radians(min(max(alpha, 0.0), 90.0)))
        frac = rng.uniform(-1.0, 1.0) if rng.random() < 0.7 else 1.0 - _log(rng, 1e-12, 1e-2)
        flags["--hc"] = _odd(rng, odd) or _num(frac * half * (1 if rng.random() < 0.5 else -1))
    if rng.random() < 0.6:
        d = int(_log(rng, 3, 3000)) if rng.random() < 0.97 else int(rng.integers(1, 10**7))
        flags["--divisions"] = _odd(rng, odd) or str(d)
    size = radius * _log(rng, 0.1, 30.0) if rng.random() < 0.9 else radius * _log(rng, 1e-6, 1e6)
    s = rng.random()
    if s < 0.25:
        for key in ("--x-plus", "--x-minus", "--y-plus", "--y-minus"):
            side = size * (rng.uniform(0.2, 1.0) if rng.random() < 0.85 else _log(rng, 1e-10, 1))
            flags[key] = _odd(rng, odd / 2) or _num(side)
    elif s < 0.5:
        w = size * rng.uniform(0.2, 1.0)
        h = size * (rng.uniform(0.05, 1.0) if rng.random() < 0.8 else _log(rng, 1e-10, 1.0))
        flags["--rectangle"] = _odd(rng, odd) or f"{_num(w)}x{_num(h)}"
        flags["--apex-fraction"] = _odd(rng, odd) or _num(_fraction(rng))
    elif s < 0.85:
        flags["--polygon"] = _polygon(rng, size)
    if rng.random() < 0.7:
        t = 0.0 if rng.random() < 0.4 else size * _log(rng, 1e-9, 5e-2)
        flags["--thickness"] = _odd(rng, odd) or _num(t)
        if rng.random() < 0.5:
            flags["--bend-radius"] = _odd(rng, odd) or _num(
                0.0 if rng.random() < 0.4 else max(t, size * 1e-6) * _log(rng, 1e-3, 10.0)
            )
        if rng.random() < 0.3:
            flags["--k-factor"] = _odd(rng, odd) or _num(rng.uniform(0.0, 1.0))
        if rng.random() < 0.3:
            flags["--sheet-surface"] = str(rng.choice(["INSIDE", "OUTSIDE", "MID"]))
    if rng.random() < 0.3:
        flags["--kerf"] = _odd(rng, odd) or _num(
            0.0 if rng.random() < 0.3 else size * _log(rng, 1e-12, 1e-2)
        )
    if rng.random() < 0.3:
        flags["--relief-hole"] = _odd(rng, odd) or _num(
            0.0 if rng.random() < 0.3 else size * _log(rng, 1e-9, 0.3)
        )
    if rng.random() < 0.2:
        flags["--density"] = _odd(rng, odd) or _num(_log(rng, 1.0, 2e4))
    if kind == "build":
        pick = [f for f in _LIGHT if rng.random() < 0.35]
        pick += [f for f in ("glb", "3dm", "png", "svg") if rng.random() < 0.08]
        flags["--formats"] = ",".join(pick or ["json"])
        if rng.random() < 0.3:
            flags["--body"] = str(rng.choice(["shell", "solid"]))
        if rng.random() < 0.2:
            flags["--compensation"] = str(rng.choice(["sharp", "none"]))
        if rng.random() < 0.2:
            flags["--placement"] = str(rng.choice(["rest", "frame"]))
        argv.append("-q")
    elif rng.random() < 0.5:
        argv.append("--json")
    for k, v in flags.items():
        argv.append(f"{k}={v}")  # '=': a value may start with '-'
    return argv


def draw(seed: int, kind: str, index: int) -> list[str]:
    """Command line ``index`` of ``kind`` under ``seed`` (see the module notes)."""
    return random_argv(np.random.default_rng([seed, KINDS.index(kind), index]), kind)


def shell_line(argv: list[str]) -> str:
    return "onefold " + " ".join(shlex.quote(a) for a in argv)


# -- one run ----------------------------------------------------------------------
@contextlib.contextmanager
def _fd_captured(fd: int) -> Iterator[io.StringIO]:
    """What is written to file descriptor ``fd`` itself (the CLI's lines are
    ``os.write``s), into the StringIO yielded, filled on exit."""
    sys.stdout.flush()
    sys.stderr.flush()
    buf = io.StringIO()
    saved = os.dup(fd)
    with tempfile.TemporaryFile() as tmp:
        os.dup2(tmp.fileno(), fd)
        try:
            yield buf
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            os.dup2(saved, fd)
            os.close(saved)
            tmp.seek(0)
            buf.write(tmp.read().decode(errors="replace"))


def run_line(argv: list[str]) -> dict[str, Any]:
    """Run one command line in this process and classify it (module notes)."""
    from onefold_cad.cli.main import main

    with tempfile.TemporaryDirectory() as td:
        outdir = Path(td) / "out"
        args = argv + (["-o", str(outdir)] if argv[0] == "build" else [])
        err, out = io.StringIO(), io.StringIO()
        t0 = time.perf_counter()
        with (
            _fd_captured(2) as raw_err,
            _fd_captured(1) as raw_out,
            warnings.catch_warnings(record=True) as caught,
            contextlib.redirect_stderr(err),
            contextlib.redirect_stdout(out),
        ):
            warnings.simplefilter("always")
            try:
                rc: int | str = main(args)
            except BaseException as exc:  # noqa: BLE001 (the finding itself)
                rc = "raised " + "".join(traceback.format_exception_only(exc)).strip()
        seconds = time.perf_counter() - t0
        text = raw_err.getvalue() + err.getvalue()
        stdout = raw_out.getvalue() + out.getvalue()
        lines = text.splitlines()
        files = [Path(p) for p in stdout.splitlines()] if argv[0] == "build" and rc == 0 else []
        missing = [str(p) for p in files if not (p.is_file() and p.stat().st_size > 0)]
        left = outdir.exists()
    found = [f"{w.category.__name__}: {w.message}" for w in caught]
    problems = []
    if found:
        problems.append("warning issued: " + found[0])
    if "Traceback" in text:
        problems.append("traceback")
    if rc == 0:
        bad = [x for x in lines if not x.startswith("onefold: warning: ")]
        if bad:
            problems.append(f"stderr line not a warning: {bad[0][:200]}")
        if argv[0] == "build" and (not files or missing):
            problems.append(f"files listed but missing or empty: {missing or 'none listed'}")
        if argv[0] == "solve" and not stdout.strip():
            problems.append("no answer on stdout")
    elif rc == 2:
        if len(lines) != 1 or not lines[0].startswith("onefold: error: "):
            problems.append(f"{len(lines)} stderr lines: {' | '.join(x[:160] for x in lines)}")
        if left:
            problems.append("a refused build left its output folder")
    else:
        problems.append(f"exit {rc}")
    line = lines[-1] if lines else ""
    if problems:
        cls = "crash"
    elif rc == 0:
        cls = "ok"
    else:
        cls = "refused" if NAMED.search(line.removeprefix("onefold: error: ")) else "unnamed"
    return {"cls": cls, "rc": rc, "line": line[:400], "problems": problems, "seconds": seconds}


# -- workers --------------------------------------------------------------------------
def _worker(conn: mpc.Connection, memory: int) -> None:
    if memory > 0:  # a runaway allocation is a MemoryError here, not the machine's
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
    while True:
        try:
            job = conn.recv()
        except EOFError:
            return
        if job is None:
            return
        try:
            res = run_line(job)
        except BaseException as exc:  # noqa: BLE001 (report, never die silently)
            res = {"cls": "crash", "rc": None, "line": "", "seconds": 0.0,
                   "problems": [f"harness: {type(exc).__name__}: {exc}"]}  # fmt: skip
        conn.send(res)


def run_all(
    jobs: list[tuple[list[str], float]],
    workers: int,
    done: Callable[[int, dict[str, Any]], None],
    memory: int,
) -> None:
    """Run ``(argv, timeout)`` jobs in ``workers`` forked processes, ``done(i,
    result)`` for each; a job past its time limit is a hang (its worker is
    killed by pid and replaced)."""
    ctx = mp.get_context("fork")

    def start() -> tuple[Any, mpc.Connection]:
        parent, child = ctx.Pipe()
        proc = ctx.Process(target=_worker, args=(child, memory), daemon=True)
        proc.start()
        child.close()
        return proc, parent

    def replace(s: int) -> None:
        proc, conn = slots[s]
        if proc.is_alive():
            os.kill(proc.pid, 9)
        proc.join(5)
        conn.close()
        slots[s] = start()

    slots = [start() for _ in range(max(1, workers))]
    queue = list(range(len(jobs)))[::-1]
    busy: dict[int, tuple[int, float]] = {}
    try:
        while queue or busy:
            for s in range(len(slots)):
                if s not in busy and queue:
                    j = queue.pop()
                    slots[s][1].send(jobs[j][0])
                    busy[s] = (j, time.monotonic() + jobs[j][1])
            conns = {slots[s][1]: s for s in busy}
            wait = max(0.0, min(d for _, d in busy.values()) - time.monotonic())
            for c in mpc.wait(list(conns), timeout=min(wait, 1.0)):
                s = conns[c]  # type: ignore[index]
                j, _ = busy.pop(s)
                try:
                    done(j, c.recv())  # type: ignore[union-attr]
                except (EOFError, OSError):
                    code = slots[s][0].exitcode
                    done(j, {"cls": "crash", "rc": code, "line": "", "seconds": 0.0,
                             "problems": [f"worker died (exit {code})"]})  # fmt: skip
                    replace(s)
            now = time.monotonic()
            for s, (j, deadline) in list(busy.items()):
                if now > deadline:
                    busy.pop(s)
                    done(j, {"cls": "hang", "rc": None, "line": "", "seconds": jobs[j][1],
                             "problems": [f"no result in {jobs[j][1]:g} s"]})  # fmt: skip
                    replace(s)
    finally:
        for proc, conn in slots:
            with contextlib.suppress(OSError):
                conn.send(None)
            proc.join(5)
            if proc.is_alive():
                os.kill(proc.pid, 9)
                proc.join(5)
            conn.close()


def fuzz(
    seed: int = 38,
    solves: int = 2000,
    builds: int = 300,
    workers: int = 2,
    timeout: float = 120.0,
    build_timeout: float = 300.0,
    memory_gb: float = 6.0,
    progress: bool = False,
) -> dict[str, Any]:
    """Run the seeded command lines; return ``{"runs": [(kind, index, argv,
    result)], "seconds": wall time}``."""
    todo = [("solve", i) for i in range(solves)] + [("build", i) for i in range(builds)]
    argvs = [draw(seed, k, i) for k, i in todo]
    jobs = [
        (a, build_timeout if k == "build" else timeout)
        for a, (k, _) in zip(argvs, todo, strict=True)
    ]
    results: list[dict[str, Any] | None] = [None] * len(jobs)
    t0 = time.monotonic()

    def done(j: int, res: dict[str, Any]) -> None:
        results[j] = res
        n = sum(r is not None for r in results)
        if progress and (n % 100 == 0 or n == len(jobs)):
            bad = sum(1 for r in results if r is not None and r["cls"] not in ("ok", "refused"))
            print(f"  {n}/{len(jobs)} in {time.monotonic() - t0:.0f} s, {bad} findings",
                  file=sys.stderr, flush=True)  # fmt: skip

    import onefold_cad.cli.main  # noqa: F401 (imported once, before forking)

    run_all(jobs, workers, done, int(memory_gb * 2**30))
    runs = [(k, i, a, r) for (k, i), a, r in zip(todo, argvs, results, strict=True)]
    return {"runs": runs, "seconds": time.monotonic() - t0, "seed": seed}


def summary(run: dict[str, Any], examples: int = 5) -> str:
    """Counts per kind and class, the slowest runs, and every finding with its
    seed and command line."""
    counts: Counter[tuple[str, str]] = Counter((k, r["cls"]) for k, _, _, r in run["runs"])
    out = [f"{len(run['runs'])} command lines (seed {run['seed']}) in {run['seconds']:.0f} s"]
    for kind in KINDS:
        classes = ("ok", "refused", "unnamed", "crash", "hang")
        row = ", ".join(f"{c} {counts[(kind, c)]}" for c in classes if counts[(kind, c)])
        if row:
            out.append(f"  {kind}: {row}")
    for kind in KINDS:
        times = sorted(r["seconds"] for k, _, _, r in run["runs"] if k == kind)
        if times:
            out.append(f"  {kind} seconds: median {times[len(times) // 2]:.2f}, "
                       f"max {times[-1]:.1f}")  # fmt: skip
    refusals = Counter(
        re.sub(r"[-+]?\d[\d.e+-]*", "#", r["line"].removeprefix("onefold: error: "))[:70]
        for _, _, _, r in run["runs"]
        if r["cls"] == "refused"
    )
    out.append("  most common refusals:")
    out += [f"    {n:5d}  {text}" for text, n in refusals.most_common(examples)]
    for k, i, argv, r in run["runs"]:
        if r["cls"] in ("ok", "refused"):
            continue
        out.append(f"{r['cls'].upper()} {run['seed']}:{k}:{i}: {'; '.join(r['problems'])}")
        out.append(f"    {r['line']}")
        out.append(f"    {shell_line(argv)}")
    return "\n".join(out)


def findings(run: dict[str, Any]) -> list[tuple[str, int, dict[str, Any]]]:
    """The runs that are neither ok nor a named one-line refusal."""
    return [(k, i, r) for k, i, _, r in run["runs"] if r["cls"] not in ("ok", "refused")]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seed", type=int, default=38)
    ap.add_argument("--solves", type=int, default=2000)
    ap.add_argument("--builds", type=int, default=300)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=120.0, help="seconds a solve may take")
    ap.add_argument("--build-timeout", type=float, default=300.0)
    ap.add_argument("--memory-gb", type=float, default=6.0, help="per worker (RLIMIT_AS)")
    ap.add_argument("--repro", metavar="SEED:KIND:I", help="print one command line and exit")
    args = ap.parse_args(argv)
    if args.repro:
        s, k, i = args.repro.split(":")
        print(shell_line(draw(int(s), k, int(i))))
        return 0
    run = fuzz(args.seed, args.solves, args.builds, args.workers, args.timeout,
               args.build_timeout, args.memory_gb, progress=True)  # fmt: skip
    print(summary(run))
    return 1 if findings(run) else 0


if __name__ == "__main__":
    raise SystemExit(main())
