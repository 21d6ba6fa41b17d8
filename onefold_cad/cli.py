"""The ``onefold`` command: build, solve and list templates.

``main(argv=None) -> int`` is the entry point (``onefold`` and ``python -m
onefold_cad``), so tests can call it directly. Every error of the package,
every usage error and every OSError becomes one line ``onefold: error: ...``
on stderr and exit status 2; warnings are lines ``onefold: warning: ...``.
``build`` stages every file and commits the whole set at once
(:mod:`onefold_cad.export.atomic`); Ctrl-C and SIGTERM leave the output
folder as it was.

The parser is the standard library's ``argparse``: the command starts in a
few milliseconds, and nothing heavier than numpy is imported before a
command needs it (``solve``: numpy and the geometry core; ``build``: the
writers of the chosen formats).
"""

from __future__ import annotations

import argparse
import contextlib
import gc
import os
import re
import signal
import sys
import textwrap
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn

from onefold_cad import __version__
from onefold_cad.errors import InvalidParameterError, OneFoldError
from onefold_cad.export.writers import COMPENSATIONS, PLACEMENTS, WRITERS, files_help
from onefold_cad.flags import (
    BODIES,
    DESIGN_FLAGS,
    FLAG_OF,
    Job,
    load_jobs,
    parse_choice,
    parse_float,
    parse_int,
)
from onefold_cad.summary import material_lines, summary
from onefold_cad.templates import DEFAULT_TEMPLATE

if TYPE_CHECKING:
    from onefold_cad.design import Design

__all__ = ["build_parser", "help_text", "main"]

PROG = "onefold"


class UsageError(Exception):
    """A command line the parser cannot read (one line, exit status 2)."""


class Interrupted(BaseException):
    """SIGTERM or SIGHUP, raised like KeyboardInterrupt is for SIGINT."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


# -- the parser --------------------------------------------------------------------
class _Parser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are exceptions (main prints one line)."""

    def error(self, message: str) -> NoReturn:
        if message.startswith("unrecognized arguments: "):
            words = message.split(": ", 1)[1].split()
            opts = [w for w in words if w.startswith("-")]
            message = (
                f"no such option: {opts[0].split('=')[0]}"
                if opts
                else f"unexpected argument {words[0]!r}"
            )
        if message.startswith("argument "):  # 'argument --alpha: ...' -> '--alpha: ...'
            message = message[len("argument ") :]
            flag, _, rest = message.partition(": ")
            message = f"{flag.split('/')[-1]}: {rest}"
        raise UsageError(message)


def _formatter(prog: str) -> argparse.HelpFormatter:
    return argparse.HelpFormatter(prog, max_help_position=30, width=100)


def _fill(text: str) -> str:
    """``text`` wrapped for a raw help description (100 columns, words whole)."""
    return textwrap.fill(text, 100, break_on_hyphens=False)


def _raw_formatter(prog: str) -> argparse.HelpFormatter:
    """Like :func:`_formatter`, the description and epilog kept as written."""
    return argparse.RawDescriptionHelpFormatter(prog, max_help_position=30, width=100)


def _add_design_flags(p: argparse.ArgumentParser) -> None:
    # A value may start with a minus sign ('--polygon -1,0;...', '--hc -5'):
    # argparse reads '-<digit>...' as a value, not as an option.
    p._negative_number_matcher = re.compile(r"^-\.?\d")  # type: ignore[attr-defined]
    groups: dict[str, Any] = {}
    for f in DESIGN_FLAGS:
        g = groups.get(f.group) or groups.setdefault(f.group, p.add_argument_group(f.group))
        g.add_argument(f.flag, dest=f.dest, type=f.kind, metavar=f.metavar, help=f.help)


def _add_common(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--name", help="the design's name (file stem); default: the template's, with the "
        "flags given appended; without a template, made from the flags"
    )  # fmt: skip
    p.add_argument(
        "-q", "--quiet", action="store_true", help="no progress or material lines on stderr "
        "(warnings and errors are still printed)"
    )  # fmt: skip


def build_parser() -> dict[str, argparse.ArgumentParser]:
    """The parsers of the commands, by name (``""`` is ``onefold`` itself)."""
    top = _Parser(
        prog=PROG,
        usage=f"{PROG} [-h] [--version] COMMAND [ARGS]",
        description=_fill(
            "Design One-Fold curved-origami forms and write the files to make them: STEP, "
            "DXF (annotated and cut-only), bend sheet, FOLD, GLB, JSON report and previews."
        ),
        epilog="commands:\n"
        "  build      write the files of one or more designs (all or nothing)\n"
        "  solve      solve a design and print the result (writes nothing)\n"
        "  templates  list the shipped templates\n"
        "  explore    explore a design in the browser (sliders, 3D form, flat pattern)\n"
        "  fit        find the frame whose resting form has a target height and span\n\n"
        f"'{PROG} COMMAND --help' shows a command's options.",
        formatter_class=lambda prog: argparse.RawDescriptionHelpFormatter(prog, width=100),
        allow_abbrev=False,
    )
    top.add_argument("--version", action="version", version=f"{PROG} {__version__}")

    build = _Parser(
        prog=f"{PROG} build",
        usage=f"{PROG} build [TEMPLATE ...] [options]",
        description=_fill(
            "Write the files below for each template's design (every one, or those "
            "--formats names): all files of all designs, or none. Flags change every "
            "template given; without a template they change the default one "
            f"({DEFAULT_TEMPLATE})."
        ),
        epilog=f"files (--formats NAME,NAME,...; default: all):\n{files_help()}",
        formatter_class=_raw_formatter,
        allow_abbrev=False,
    )
    build.add_argument(
        "templates", nargs="*", metavar="TEMPLATE", help="template file or shipped template "
        f"name (default: {DEFAULT_TEMPLATE})"
    )  # fmt: skip
    out = build.add_argument_group("output")
    out.add_argument("-o", "--outdir", type=Path, default=Path("out"), metavar="DIR",
                     help="output folder (default: out)")  # fmt: skip
    out.add_argument(
        "--formats", metavar="LIST", help="comma-separated formats to write (default: all): "
        f"{', '.join(WRITERS)} (see the files below)"
    )  # fmt: skip
    out.add_argument(
        "--body", type=parse_choice(BODIES), default="auto", metavar="auto|solid|shell",
        help="STEP body: 'solid' (the sheet's thickness, exact model), 'shell' (the "
        "reference surface) or 'auto' (solid with thickness and a relief hole, else shell)",
    )  # fmt: skip
    out.add_argument(
        "--compensation", type=parse_choice(COMPENSATIONS), default=COMPENSATIONS[0],
        metavar="sharp|none", help="flat pattern: bend compensation of the sharp-crease "
        "model (default), or none (the designed sheet uncompensated, said in the notes); "
        "a STEP solid past the bend model's limits is written only with none",
    )  # fmt: skip
    out.add_argument(
        "--placement", type=parse_choice(PLACEMENTS), default=PLACEMENTS[0],
        metavar="rest|frame", help="where the STEP, GLB and 3D preview put the form: 'rest' "
        "(default: standing on the ground z = 0 as the report's resting numbers say) or "
        "'frame' (the fold frame: H at the origin, the fold line on x, the apex above H)",
    )  # fmt: skip
    out.add_argument(
        "-j", "--jobs", type=parse_int, default=1, metavar="N",
        help="build N designs at a time in separate processes (default 1)",
    )  # fmt: skip
    _add_common(out)
    _add_design_flags(build)

    solve = _Parser(
        prog=f"{PROG} solve",
        usage=f"{PROG} solve [TEMPLATE] [options]",
        description="Solve a design and print the result; nothing is written. Fabrication "
        "problems are warnings here (exit status 0); only build refuses.",
        formatter_class=_formatter,
        allow_abbrev=False,
    )
    solve.add_argument(
        "template", nargs="?", metavar="TEMPLATE", help="template file or shipped template "
        f"name (default: {DEFAULT_TEMPLATE})"
    )  # fmt: skip
    o = solve.add_argument_group("output")
    o.add_argument("--json", action="store_true", help="print the JSON report")
    _add_common(o)
    _add_design_flags(solve)

    templates = _Parser(
        prog=f"{PROG} templates",
        usage=f"{PROG} templates",
        description="List the shipped templates, one line each: name and description.",
        formatter_class=_formatter,
        allow_abbrev=False,
    )
    explore = _Parser(
        prog=f"{PROG} explore",
        usage=f"{PROG} explore [TEMPLATE] [--port N] [--no-browser]",
        description="Explore a design in the browser: sliders, the 3D form, the flat pattern, "
        "downloads. Serves a page on 127.0.0.1 until Ctrl-C; the solver runs here, the page "
        "only draws.",
        formatter_class=_formatter,
        allow_abbrev=False,
    )
    explore.add_argument(
        "template", nargs="?", metavar="TEMPLATE", help="template file or shipped template "
        f"name (default: {DEFAULT_TEMPLATE})"
    )  # fmt: skip
    explore.add_argument("--port", type=parse_int, default=8765, metavar="N",
                         help="port on 127.0.0.1 (0: any free port; default 8765)")  # fmt: skip
    explore.add_argument("--no-browser", action="store_true",
                         help="only print the address; do not open a browser")  # fmt: skip
    fit = _Parser(
        prog=f"{PROG} fit",
        usage=f"{PROG} fit TEMPLATE --height H --span S [--depth D] [--min-tipping-margin DEG] "
        "[--json] [-o DIR]",
        description="Find alpha, beta and h_c whose resting form has the target height and "
        "span (footprint width), and depth if given, each within 0.5 %. The template's sheet, "
        "material and model are kept; lengths are in its unit. A target out of reach is an "
        "error that gives the ranges the template's sheet can reach.",
        formatter_class=_formatter,
        allow_abbrev=False,
    )
    fit.add_argument(
        "template",
        metavar="TEMPLATE",
        help="template file or shipped template name: sheet and material",
    )
    fit.add_argument(
        "--height",
        type=parse_float,
        required=True,
        metavar="H",
        help="height of the form as it rests on the ground, > 0",
    )
    fit.add_argument(
        "--span",
        type=parse_float,
        required=True,
        metavar="S",
        help="footprint width of the resting form (along the fold line), > 0",
    )
    fit.add_argument(
        "--depth",
        type=parse_float,
        metavar="D",
        help="footprint depth of the resting form (across it), > 0",
    )
    fit.add_argument(
        "--min-tipping-margin",
        type=parse_float,
        metavar="DEG",
        help="smallest tipping margin allowed (deg)",
    )
    fit.add_argument("--json", action="store_true", help="print the result as JSON")
    fit.add_argument(
        "-o",
        "--outdir",
        type=Path,
        metavar="DIR",
        help="also build the found design into this folder (as NAME-fit)",
    )
    fit.add_argument("-q", "--quiet", action="store_true",
                     help="no progress lines on stderr when building (-o)")  # fmt: skip
    return {
        "": top,
        "build": build,
        "solve": solve,
        "templates": templates,
        "explore": explore,
        "fit": fit,
    }


def help_text(command: str = "") -> str:
    """The ``--help`` text of ``onefold`` or of one of its commands."""
    return build_parser()[command].format_help()


# -- text output --------------------------------------------------------------------
class Progress:
    """Progress lines on stderr, ``[i/n] NAME: ...``; silent when quiet.

    Each line is one ``write`` (so lines of parallel workers never mix)."""

    def __init__(self, quiet: bool) -> None:
        self.quiet = quiet

    def line(self, i: int, n: int, name: str, text: str) -> None:
        if not self.quiet:
            os.write(2, f"[{i}/{n}] {name}: {text}\n".encode())


def warn(text: str) -> None:
    """One warning line on stderr (printed even with --quiet)."""
    os.write(2, f"onefold: warning: {_one_line(text)}\n".encode())


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


# -- commands -------------------------------------------------------------------------
def _design_flags(ns: argparse.Namespace) -> dict[str, Any]:
    return {f.dest: getattr(ns, f.dest) for f in DESIGN_FLAGS}


def cmd_templates(ns: argparse.Namespace) -> int:
    """List the shipped templates, one line each."""
    from onefold_cad.templates import list_templates

    infos = list_templates()
    width = max((len(t.name) for t in infos), default=0)
    for t in infos:
        print(f"{t.name:<{width}}  {t.description}")
    return 0


def cmd_solve(ns: argparse.Namespace) -> int:
    """Solve one design and print it (text or JSON); warnings on stderr."""
    from onefold_cad.design import build_design
    from onefold_cad.export.report import check_finite, design_report, report_json

    (job,) = load_jobs([ns.template] if ns.template else [], _design_flags(ns), ns.name)
    report = design_report(job.design, build_design(job.design), sources=job.sources)
    check_finite(report)  # a NaN is an error naming its key, in the text as in the JSON
    text = report_json(report) if ns.json else summary(report) + "\n"
    for w in report["warnings"]:
        warn(w)
    sys.stdout.write(text)
    return 0


@dataclass
class _Task:
    """What a build worker needs for one design (picklable)."""

    index: int
    total: int
    job: Job
    formats: tuple[str, ...]
    body: str | None
    compensation: str
    folder: str
    quiet: bool
    warnings: tuple[str, ...] = ()
    placement: str = PLACEMENTS[0]
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


def _write_task(task: _Task) -> list[Path]:
    """Solve and write one design into its staging folder (in this process)."""
    from onefold_cad.design import build_design
    from onefold_cad.export.writers import BuildContext, write_design

    d = task.job.design
    progress = Progress(task.quiet)
    t0 = time.perf_counter()
    ctx = BuildContext(
        d,
        build_design(d),
        task.body,
        task.compensation,
        task.job.sources,
        task.warnings,
        placement=task.placement,
    )

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


def _worker(task: _Task) -> tuple[str, Any]:
    """Pool entry point: ('ok', files) or ('error', (kind, message))."""
    try:
        return "ok", [str(p) for p in _write_task(task)]
    except OneFoldError as exc:  # their pickled form cannot be rebuilt: send the text
        return "error", ("onefold", str(exc))
    except OSError as exc:
        return "error", ("os", _os_message(exc))


def _write_all(tasks: list[_Task], jobs: int) -> list[Path]:
    if jobs <= 1 or len(tasks) <= 1:
        return [p for t in tasks for p in _write_task(t)]
    import multiprocessing

    method = "fork" if sys.platform.startswith("linux") else "spawn"
    ctx = multiprocessing.get_context(method)
    pool = ctx.Pool(min(jobs, len(tasks)), initializer=_worker_init)
    try:
        results = [pool.apply_async(_worker, (t,)) for t in tasks]
        files: list[Path] = []
        for r in results:
            status, value = r.get()
            if status == "error":
                pool.terminate()
                raise OneFoldError(value[1])
            files += [Path(p) for p in value]
        pool.close()
        return files
    finally:
        pool.terminate()
        pool.join()


def cmd_build(ns: argparse.Namespace) -> int:
    """Write the files of every design of the call, all or nothing."""
    from onefold_cad.design import build_design
    from onefold_cad.export.atomic import Staging, check_targets, recover
    from onefold_cad.export.report import design_warnings
    from onefold_cad.export.writers import (
        BuildContext,
        check_before_writing,
        file_names,
        parse_formats,
    )

    refs = list(ns.templates)
    if ns.name is not None and len(refs) > 1:
        raise InvalidParameterError("--name", f"needs exactly one template, got {len(refs)}")
    if ns.jobs < 1:
        raise InvalidParameterError("--jobs", f"must be >= 1, got {ns.jobs}")
    formats = parse_formats(ns.formats)
    body = None if ns.body == "auto" else ns.body
    jobs = load_jobs(refs, _design_flags(ns), ns.name)
    stems = [j.design.name for j in jobs]
    dup = sorted({s for s in stems if stems.count(s) > 1})
    if dup:
        raise InvalidParameterError(
            "templates", f"two designs share the name {dup[0]!r}; their files would collide"
        )
    n = len(jobs)
    progress = Progress(ns.quiet)
    found: list[tuple[str, ...]] = []
    # Every design solves, and every writer's checks pass, before any file is written.
    for i, job in enumerate(jobs, 1):
        d = job.design
        progress.line(i, n, d.name, f"started: {_describe(d)}")
        t0 = time.perf_counter()
        folded = build_design(d)
        for text in _material_text(d, folded, job):
            progress.line(i, n, d.name, text)
        progress.line(i, n, d.name, f"solve {time.perf_counter() - t0:.2f} s")
        ctx = BuildContext(d, folded, body, ns.compensation, job.sources, placement=ns.placement)
        t0 = time.perf_counter()
        try:
            check_before_writing(ctx, formats)
        except OneFoldError as exc:
            exc = _flag_named(exc, ns)
            if n == 1:
                raise exc from None
            raise _prefixed(exc, d.name) from None
        if any(WRITERS[f].needs_flat_pattern for f in formats):
            progress.line(i, n, d.name, f"flat pattern {time.perf_counter() - t0:.2f} s")
            from onefold_cad.export.bend_sheet import bend_table

            for text in bend_table(ctx.pattern, rulings=False).splitlines():
                progress.line(i, n, d.name, text)
        notes = tuple(design_warnings(d, folded, ns.compensation, body))
        for w in notes:
            warn(f"{d.name}: {w}")
        found.append(notes)
    outdir = Path(ns.outdir)
    created = not outdir.exists()
    try:
        outdir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InvalidParameterError(
            "--outdir", f"cannot create {str(outdir)!r}: {exc.strerror or exc}"
        ) from None
    try:
        for p in recover(outdir):
            warn(f"finished an interrupted earlier build: {p}")
        check_targets(outdir, [f for j in jobs for f in file_names(j.design.name, formats)])
        with Staging(outdir) as staging:
            _STATE["staging"] = staging
            tasks = [
                _Task(i, n, job, formats, body, ns.compensation, str(staging.path / str(i)),
                      ns.quiet, found[i - 1], ns.placement, bool(_STATE.get("process")))
                for i, job in enumerate(jobs, 1)
            ]  # fmt: skip
            files = _write_all(tasks, ns.jobs)
            _test_pause("staged")
            for p in staging.commit(files):
                print(p, flush=True)
    finally:
        with contextlib.suppress(OSError):
            if created and outdir.is_dir() and not any(outdir.iterdir()):
                outdir.rmdir()
    return 0


#: The staging area of the running build (main says whether it was committed).
_STATE: dict[str, Any] = {}


def _interrupted_text() -> str:
    staging = _STATE.get("staging")
    if staging is not None and staging.committed:
        return "every file of the build had been written"
    return "nothing was written (the output folder is as it was)"


def _test_pause(point: str) -> None:
    from onefold_cad.export.atomic import _test_pause as pause

    pause(point)


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
    return type(exc)(flag, str(exc)[len(prefix) :])  # type: ignore[call-arg]


def _prefixed(exc: OneFoldError, name: str) -> OneFoldError:
    """``exc`` with the design's name in front (several designs in one call)."""
    param = getattr(exc, "parameter", None)  # InvalidParameterError, FabricationError
    if isinstance(param, str) and str(exc).startswith(f"{param}: "):
        return type(exc)(f"{name}: {param}", str(exc)[len(param) + 2 :])  # type: ignore[call-arg]
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
    from onefold_cad.design import relief_hole_diameter
    from onefold_cad.templates import design_to_data

    report = {
        "inputs": design_to_data(design),
        "sources": job.sources,
        "units": design.units.value,
        "relief_hole_diameter": relief_hole_diameter(design, folded),
    }
    name, values, origin = material_lines(report)
    return [f"material: {name}; {values}", f"({origin})"]


def cmd_explore(ns: argparse.Namespace) -> int:
    """Serve the explorer page until Ctrl-C."""
    from onefold_cad.explore import serve

    serve(ns.template, port=ns.port, open_browser=not ns.no_browser)
    return 0


def cmd_fit(ns: argparse.Namespace) -> int:
    """Inverse design: the frame whose resting form has the target size."""
    import json

    from onefold_cad.fit import fit_design

    (job,) = load_jobs([ns.template], {})
    design = job.design
    result = fit_design(design, ns.height, ns.span, ns.depth, ns.min_tipping_margin)
    f = result.design.frame
    if ns.outdir is not None:  # the build's list of files goes to stderr under --json
        frame = ["--alpha", repr(f.alpha), "--beta", repr(f.beta), "--hc", repr(f.h_c)]
        # named after the template and the fit, not after the flags' values
        name = ["--name", f"{design.name}-fit"]
        argv = [ns.template, "-o", str(ns.outdir), *frame, *name, *(["-q"] if ns.quiet else [])]
        with contextlib.redirect_stdout(sys.stderr) if ns.json else contextlib.nullcontext():
            status = cmd_build(build_parser()["build"].parse_intermixed_args(argv))
        if status:
            return status
    u = design.units.value
    data = {
        "name": design.name,
        "units": u,
        "frame": {"alpha": f.alpha, "beta": f.beta, "h_c": f.h_c},
        "body": result.body,
        "achieved": {
            "height": result.height,
            "span": result.span,
            "depth": result.depth,
            "tipping_margin_deg": result.tipping_margin_deg,
        },
        "targets": result.targets,
        "relative_errors": result.errors,
        "evaluations": result.evaluations,
    }
    if ns.json:
        print(json.dumps(data, indent=2, allow_nan=False))
        return 0
    print(f"{design.name}: alpha {f.alpha:.6g} deg, beta {f.beta:.6g} deg, h_c {f.h_c:.6g} {u}")
    for key, got in (("height", result.height), ("span", result.span), ("depth", result.depth)):
        want = result.targets.get(key)
        aim = f" (target {want:.6g}, {100 * abs(got - want) / want:.2g} %)" if want else ""
        print(f"  {key:<15} {got:.6g} {u}{aim}")
    print(f"  tipping margin  {result.tipping_margin_deg:.3g} deg ({result.body})")
    return 0


COMMANDS: dict[str, Callable[[argparse.Namespace], int]] = {
    "build": cmd_build,
    "solve": cmd_solve,
    "templates": cmd_templates,
    "explore": cmd_explore,
    "fit": cmd_fit,
}


# -- entry point ---------------------------------------------------------------------
def _os_message(exc: OSError) -> str:
    where = exc.filename if exc.filename is not None else ""
    what = exc.strerror or str(exc)
    return f"{where}: {what}" if where else what


def _raise_interrupted(signum: int, frame: object) -> None:
    raise Interrupted(signum)


@contextlib.contextmanager
def _signal_handlers() -> Iterator[None]:
    """SIGTERM and SIGHUP raise :class:`Interrupted` (as SIGINT raises
    KeyboardInterrupt) while the command runs; the old handlers come back
    afterwards. Only in the main thread (where Python delivers signals)."""
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    old = {s: signal.signal(s, _raise_interrupted) for s in (signal.SIGTERM, signal.SIGHUP)}
    try:
        yield
    finally:
        for s, h in old.items():
            signal.signal(s, h)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``onefold`` command with ``argv`` (default: ``sys.argv[1:]``).

    Called without ``argv``, as the ``onefold`` program and ``python -m
    onefold_cad`` call it, it runs as the process's own command: a build moves
    the modules its writers import out of the cyclic garbage collector's way
    (:func:`_freeze_imports`), and every command freezes what is left when it
    is done, so that the interpreter's collection at exit does not walk them
    once more (0.8 s after a default build, whose output is complete by then).
    A caller passing ``argv`` (the tests, another program) keeps its collector
    as it was.

    Returns:
        The exit status: 0 on success (warnings included), 2 on bad input or a
        file that cannot be written (one line on stderr), 130 on Ctrl-C and
        128 + the signal's number on SIGTERM or SIGHUP (nothing written).
    """
    args = list(sys.argv[1:] if argv is None else argv)
    parsers = build_parser()
    _STATE["process"] = argv is None
    try:
        with _signal_handlers():
            if not args or args[0] not in COMMANDS:
                if args and not args[0].startswith("-"):
                    raise UsageError(f"unknown command {args[0]!r} (choose from build, "
                                     "solve, templates, explore, fit)")  # fmt: skip
                parsers[""].parse_args(args or ["--help"])  # --help, --version or an error
                raise UsageError("a command is needed: build, solve, templates, explore or fit")
            ns = parsers[args[0]].parse_intermixed_args(args[1:])
            return COMMANDS[args[0]](ns)
    except SystemExit as exc:  # --help, --version
        return exc.code if isinstance(exc.code, int) else 0
    except (OneFoldError, UsageError) as exc:
        _error(str(exc))
        return 2
    except OSError as exc:
        _error(_os_message(exc))
        return 2
    except KeyboardInterrupt:
        _error(f"interrupted; {_interrupted_text()}", prefix="")
        return 130
    except Interrupted as exc:
        _error(f"stopped by {exc}; {_interrupted_text()}", prefix="")
        return 128 + exc.signum
    finally:
        if _STATE.get("process"):
            gc.freeze()  # the process ends: its objects need no collecting
        _STATE.clear()


def _error(text: str, prefix: str = "error: ") -> None:
    sys.stdout.flush()
    os.write(2, f"onefold: {prefix}{_one_line(text)}\n".encode())
