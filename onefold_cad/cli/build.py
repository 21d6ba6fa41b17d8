"""``onefold build``: every design solves and every writer's checks pass before
any file is written; the files are staged and committed all at once
(:mod:`onefold_cad.export.atomic`), several designs at a time in worker
processes (``-j``), the CAD libraries' modules moved out of the garbage
collector's way once a writer has imported them.
"""

from __future__ import annotations

import argparse
import contextlib
import functools
import gc
import signal
import sys
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from onefold_cad.choices import Body, Compensation, Placement
from onefold_cad.cli.summary import material_lines
from onefold_cad.errors import InvalidParameterError, OneFoldError, memory_message
from onefold_cad.export.writers import WRITERS
from onefold_cad.flags.design_flags import (
    FLAG_OF,
)
from onefold_cad.flags.jobs import Job, load_jobs

if TYPE_CHECKING:
    from onefold_cad.design import Design
    from onefold_cad.export.build_context import BuildContext
from onefold_cad.cli.output import Progress, os_message, warn
from onefold_cad.flags.parser import design_flag_values

__all__ = [
    "STATE",
    "BuildTask",
    "check_jobs",
    "check_outdir",
    "cmd_build",
    "interrupted_text",
    "make_outdir",
    "output_folder",
    "run_tasks",
    "say_removed",
    "task_context",
    "write_task",
]


@dataclass
class BuildTask:
    """What a build worker needs for one design (picklable)."""

    index: int
    total: int
    job: Job
    formats: tuple[str, ...]
    body: Body | None
    compensation: Compensation
    folder: str
    quiet: bool
    warnings: tuple[str, ...] = ()
    placement: Placement = Placement.REST
    freeze: bool = False  # the command runs as its own process (see _freeze_imports)


#: Libraries whose modules a build moves out of the cyclic collector's way
#: once a writer has imported them (:func:`_freeze_imports`).
_LIBRARIES = ("build123d", "matplotlib")


def _freeze_imports(frozen: set[str]) -> None:
    """gc.freeze() after a writer has imported build123d (with OCP, scipy and
    sklearn: a third of a million objects) or matplotlib: the cyclic garbage
    collector would otherwise walk their modules' objects, which live as long
    as the process, at every full collection of the build (0.1 s of a default
    build). The first freeze keeps whatever the import left (a full collection
    there finds nothing and costs as much); a later one collects the
    writers' garbage first (the rest being frozen, that is cheap). Only
    ``onefold`` running as its own process does this (:func:`main`)."""
    new = [m for m in _LIBRARIES if m in sys.modules and m not in frozen]
    if not new:
        return
    if frozen:
        gc.collect()
    gc.freeze()
    frozen.update(new)


def task_context(task: BuildTask) -> BuildContext:
    """The build context of one task's design (solved here, or taken from the
    fold cache when the parent solved it before the fork)."""
    from onefold_cad.design import fold_design
    from onefold_cad.export.writers import BuildContext

    d = task.job.design
    return BuildContext(
        d,
        fold_design(d),
        task.body,
        task.compensation,
        task.job.sources,
        task.warnings,
        placement=task.placement,
    )


def write_task(task: BuildTask, ctx: BuildContext | None = None) -> list[Path]:
    """Solve and write one design into its staging folder (in this process),
    with ``ctx`` if given (:func:`task_context`)."""
    from onefold_cad.export.writers import write_design

    d = task.job.design
    progress = Progress(task.quiet)
    t0 = time.perf_counter()
    ctx = task_context(task) if ctx is None else ctx

    frozen: set[str] = set()

    def stage(label: str, seconds: float) -> None:
        if task.freeze:
            _freeze_imports(frozen)
        progress.line(task.index, task.total, d.name, f"{label} {seconds:.2f} s")

    files = write_design(ctx, Path(task.folder), task.formats, stage)
    progress.line(task.index, task.total, d.name, f"done in {time.perf_counter() - t0:.1f} s")
    return files


def _worker_init() -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent handles Ctrl-C
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # terminate() ends a worker at once
    signal.signal(signal.SIGHUP, signal.SIG_DFL)


def _files(task: BuildTask) -> list[str]:
    return [str(p) for p in write_task(task)]


def _worker(fn: Callable[[Any], Any], task: Any) -> tuple[str, Any]:
    """Pool entry point: ('ok', fn(task)) or ('error', (kind, message))."""
    try:
        return "ok", fn(task)
    except OneFoldError as exc:  # their pickled form cannot be rebuilt: send the text
        return "error", ("onefold", str(exc))
    except OSError as exc:
        return "error", ("os", os_message(exc))
    except MemoryError as exc:  # numpy's cannot be unpickled in the parent: send the text
        return "error", ("memory", memory_message(exc))


def run_tasks(tasks: Sequence[Any], jobs: int, fn: Callable[[Any], Any]) -> list[Any]:
    """``fn(task)`` for every task, in order: in this process (``jobs`` 1), else
    ``jobs`` at a time in worker processes (``fn`` a module's function, the
    tasks and results picklable). The first error ends the pool and is raised
    here (OneFoldError, its message).

    The workers come from a forkserver (spawned where there is none), never
    forked from this process: a process that has meshed with OCCT (a test
    run, a site's second build) holds its thread pool's locks, and a child
    forked then waits on them for ever."""
    if jobs <= 1 or len(tasks) <= 1:
        return [fn(t) for t in tasks]
    import multiprocessing

    ctx: multiprocessing.context.BaseContext
    if "forkserver" in multiprocessing.get_all_start_methods():
        server = multiprocessing.get_context("forkserver")
        server.set_forkserver_preload(["onefold_cad.export.writers", fn.__module__])
        ctx = server
    else:
        ctx = multiprocessing.get_context("spawn")
    pool = ctx.Pool(min(jobs, len(tasks)), initializer=_worker_init)
    try:
        results = [pool.apply_async(_worker, (fn, t)) for t in tasks]
        out: list[Any] = []
        for r in results:
            status, value = r.get()
            if status == "error":
                pool.terminate()
                raise OneFoldError(value[1])
            out.append(value)
        pool.close()
        return out
    finally:
        pool.terminate()
        pool.join()


def check_jobs(
    jobs: Sequence[Job], formats: Sequence[str], ns: argparse.Namespace
) -> list[tuple[str, ...]]:
    """Solve every design and run every writer's checks of ``formats`` before
    any file is written (``ns``: ``body``, ``compensation``, ``placement``,
    ``quiet``); print the material, the bend table and the warnings; return
    each design's warnings.

    Raises:
        OneFoldError: what a design or a writer refuses (named by the design
            when there are several).
    """
    from onefold_cad.design import fold_design
    from onefold_cad.export.write_checks import check_before_writing
    from onefold_cad.export.writers import BuildContext
    from onefold_cad.fabrication.report import design_warnings

    body = None if ns.body == "auto" else Body.parse(ns.body)
    compensation = Compensation.parse(ns.compensation)
    n = len(jobs)
    progress = Progress(ns.quiet)
    found: list[tuple[str, ...]] = []
    # Every design solves, and every writer's checks pass, before any file is written.
    for i, job in enumerate(jobs, 1):
        d = job.design
        # a design's lines wait for its checks: a refusal is the one line on stderr
        lines = [f"started: {_describe(d)}"]
        t0 = time.perf_counter()
        folded = fold_design(d)
        lines += [*_material_text(d, folded, job), f"solve {time.perf_counter() - t0:.2f} s"]
        ctx = BuildContext(
            d, folded, body, compensation, job.sources, placement=Placement.parse(ns.placement)
        )
        t0 = time.perf_counter()
        try:
            check_before_writing(ctx, formats)
        except OneFoldError as exc:
            exc = _flag_named(exc, ns)
            if n == 1:
                raise exc from None
            raise _prefixed(exc, d.name) from None
        for text in lines:
            progress.line(i, n, d.name, text)
        if any(WRITERS[f].needs_flat_pattern for f in formats):
            progress.line(i, n, d.name, f"flat pattern {time.perf_counter() - t0:.2f} s")
            from onefold_cad.fabrication.bend_table import bend_table

            for text in bend_table(ctx.pattern, rulings=False).splitlines():
                progress.line(i, n, d.name, text)
        notes = tuple(design_warnings(d, folded, compensation, body))
        for w in notes:
            warn(f"{d.name}: {w}")
        if "fold" in formats:  # the file's: in the file and the report, not on stderr
            from onefold_cad.export.fold.file import fold_note

            note = fold_note(d, folded)
            notes += () if note is None else (note,)
        found.append(notes)
    return found


def check_outdir(outdir: Path) -> None:
    """Refuse an output folder that cannot be made or written, before any work
    (a build's checks, a simulation): ``outdir`` or the nearest of its parents
    that exists must be a folder this process may write into. Nothing is
    created here.

    Raises:
        InvalidParameterError: ('--outdir') naming the path and why.
    """
    import os

    path = Path(outdir)
    probe = path
    while not probe.exists() and not probe.is_symlink() and probe != probe.parent:
        probe = probe.parent
    if probe.is_symlink() and not probe.exists():
        why = f"{str(probe)!r} is a broken symbolic link"
    elif not probe.is_dir():
        why = f"{str(probe)!r} exists and is not a folder"
    elif not os.access(probe, os.W_OK | os.X_OK):
        why = f"{str(probe)!r} is not writable"
    else:
        return
    raise InvalidParameterError("--outdir", f"cannot write into {str(path)!r}: {why}")


def make_outdir(outdir: Path) -> bool:
    """Create ``outdir`` (and its parents); True when it did not exist before.

    Raises:
        InvalidParameterError: ('--outdir') it cannot be created.
    """
    created = not outdir.exists()
    try:
        outdir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InvalidParameterError(
            "--outdir", f"cannot create {str(outdir)!r}: {exc.strerror or exc}"
        ) from None
    return created


@contextlib.contextmanager
def output_folder(outdir: Path) -> Iterator[Path]:
    """A command's output folder (:func:`make_outdir`), removed again on the
    way out when this call created it and left it empty (a refused or failed
    command leaves no folder behind).

    Raises:
        InvalidParameterError: ('--outdir') it cannot be created.
    """
    created = make_outdir(outdir)
    try:
        yield outdir
    finally:
        with contextlib.suppress(OSError):
            if created and outdir.is_dir() and not any(outdir.iterdir()):
                outdir.rmdir()


def cmd_build(ns: argparse.Namespace) -> int:
    """Write the files of every design of the call, all or nothing."""
    from onefold_cad.export.atomic import Staging
    from onefold_cad.export.files import stage_files
    from onefold_cad.export.writers import parse_formats

    refs = list(ns.templates)
    if ns.name is not None and len(refs) > 1:
        raise InvalidParameterError("--name", f"needs exactly one template, got {len(refs)}")
    if ns.jobs < 1:
        raise InvalidParameterError("--jobs", f"must be >= 1, got {ns.jobs}")
    parse_formats(ns.formats)  # a bad name: refused before any template is read
    body = None if ns.body == "auto" else Body.parse(ns.body)
    jobs = load_jobs(refs, design_flag_values(ns), ns.name, skip_site=warn)
    formats = parse_formats(ns.formats, designs=[j.design for j in jobs])
    stems = [j.design.name for j in jobs]
    dup = sorted({s for s in stems if stems.count(s) > 1})
    if dup:
        raise InvalidParameterError(
            "templates", f"two designs share the name {dup[0]!r}; their files would collide"
        )
    outdir = Path(ns.outdir)
    check_outdir(outdir)
    found = check_jobs(jobs, formats, ns)
    say_cones_left_out([j.design for j in jobs], formats)
    n = len(jobs)
    with output_folder(outdir):

        def write(staging: Staging) -> list[Path]:
            tasks = [
                BuildTask(i, n, job, formats, body, Compensation.parse(ns.compensation),
                          str(staging.path / str(i)), ns.quiet, found[i - 1],
                          Placement.parse(ns.placement), bool(STATE.get("process")))
                for i, job in enumerate(jobs, 1)
            ]  # fmt: skip
            return [Path(p) for fs in run_tasks(tasks, ns.jobs, _files) for p in fs]

        # the one path of a build's files (onefold_cad.write_files takes it too)
        keep = functools.partial(STATE.__setitem__, "staging")  # what Ctrl-C left: main asks
        written, removed = stage_files(outdir, stems, formats, write, warn, keep)
        for p in written:
            print(p, flush=True)
        say_removed(removed)
    return 0


def say_cones_left_out(designs: Sequence[Design], formats: Sequence[str]) -> None:
    """One warning per design whose cones are formed past their springback
    when ``formats`` write its DXF or 3DM (their notes name the forming
    sheet) but not the sheet itself: the shop would get a drawing that points
    to a file it does not have."""
    if "cones" in formats or not {"dxf", "3dm"} & set(formats):
        return
    for d in designs:
        if d.material.cones_compensated:
            warn(f"{d.name}: its cones are formed past their springback and its notes name "
                 f"{d.name}-cones.csv, which --formats leaves out: add cones")  # fmt: skip


def say_removed(removed: Sequence[Path]) -> None:
    """One warning naming the files of the call's designs that an earlier
    run left and the commit removed, none of them written by this call (they
    would not match the new files)."""
    if removed:
        names = ", ".join(str(p) for p in removed)
        warn(f"removed {names}: left by an earlier run, not written by this one (they would "
             "not match its files)")  # fmt: skip


#: The staging area of the running build (main says whether it was committed).
STATE: dict[str, Any] = {}


def interrupted_text() -> str:
    """What a stopped command leaves behind (a command may say it in
    ``STATE["interrupted"]``; a build says whether its files were written)."""
    if "interrupted" in STATE:
        return str(STATE["interrupted"])
    staging = STATE.get("staging")
    if staging is not None and staging.committed:
        return "every file of the build had been written"
    return "nothing was written (the output folder is as it was)"


def _flag_named(exc: OneFoldError, ns: argparse.Namespace) -> OneFoldError:
    """A writer's refusal of an input value (InvalidParameterError: ``kerf``)
    named after the flag the user typed (``--kerf``), as the input checks name
    it; else ``exc`` (a FabricationError names what to change, as the API and
    the explorer spell it)."""
    param = getattr(exc, "parameter", None)
    if not isinstance(exc, InvalidParameterError):
        return exc
    flag = FLAG_OF.get(param) if isinstance(param, str) else None
    prefix = f"{param}: "
    if flag is None or getattr(ns, str(param), None) is None or not str(exc).startswith(prefix):
        return exc
    return type(exc)(flag, str(exc)[len(prefix) :])


def _prefixed(exc: OneFoldError, name: str) -> OneFoldError:
    """``exc`` with the design's name in front (several designs in one call)."""
    param = getattr(exc, "parameter", None)  # InvalidParameterError, FabricationError
    if isinstance(param, str) and str(exc).startswith(f"{param}: "):
        return type(exc)(f"{name}: {param}", str(exc)[len(param) + 2 :])
    return OneFoldError(f"{name}: {exc}")


def _describe(design: Design) -> str:
    s, u = design.sheet, design.units.value
    if s.kind == "rectangle":
        sheet = f"{s.inputs['width']:g} x {s.inputs['height']:g} {u} rectangle"
    else:
        sheet = f"{s.kind} of {len(s.vertices)} vertices"
    fr = design.frame
    return f"{design.model.value} model, alpha {fr.alpha:g}, beta {fr.beta:g}, {sheet}"


def _material_text(design: Design, folded: Any, job: Job) -> list[str]:
    from onefold_cad.fabrication.relief_hole import relief_hole_diameter
    from onefold_cad.templates import design_to_data

    report = {
        "inputs": design_to_data(design),
        "sources": job.sources,
        "units": design.units.value,
        "relief_hole_diameter": relief_hole_diameter(design, folded),
    }
    name, values, origin = material_lines(report)
    return [f"material: {name}; {values}", f"({origin})"]
