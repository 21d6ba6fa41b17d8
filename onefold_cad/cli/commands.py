"""The ``onefold`` commands other than ``build``: ``solve``, ``templates``,
``explore``, ``fit``, ``hops``, ``sweep``, ``simulate``
(:mod:`onefold_cad.cli.simulate`), ``compensate``
(:mod:`onefold_cad.cli.compensate`) and ``site`` (:mod:`onefold_cad.cli.site`),
each ``cmd_NAME(namespace) -> exit status``, and the table :data:`COMMANDS` of
all of them."""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
from collections.abc import Callable

from onefold_cad.cli.build import STATE, cmd_build
from onefold_cad.cli.compensate import cmd_compensate
from onefold_cad.cli.loads import cmd_loads
from onefold_cad.cli.output import warn
from onefold_cad.cli.parser import build_parser
from onefold_cad.cli.simulate import cmd_simulate
from onefold_cad.cli.site import cmd_site
from onefold_cad.cli.summary import summary
from onefold_cad.flags.jobs import load_jobs
from onefold_cad.flags.parser import design_flag_values

__all__ = ["COMMANDS"]


def cmd_templates(ns: argparse.Namespace) -> int:
    """List the shipped templates, one line each, then the shipped site files."""
    from onefold_cad.templates import list_sites, list_templates

    infos, sites = list_templates(), list_sites()
    width = max((len(t.name) for t in [*infos, *sites]), default=0)
    for t in infos:
        print(f"{t.name:<{width}}  {t.description}")
    if sites:
        print(f"\n{SITES_HEADING}")
        for t in sites:
            print(f"{t.name:<{width}}  {t.description}")
    return 0


#: The line before the shipped site files in ``onefold templates``.
SITES_HEADING = "sites (several sheets on one site: onefold site NAME):"


def cmd_solve(ns: argparse.Namespace) -> int:
    """Solve one design and print it (text or JSON); warnings on stderr."""
    from onefold_cad.design import fold_design
    from onefold_cad.fabrication.report import check_finite, design_report, report_json

    (job,) = load_jobs([ns.template] if ns.template else [], design_flag_values(ns), ns.name)
    report = design_report(job.design, fold_design(job.design), sources=job.sources)
    check_finite(report)  # a NaN is an error naming its key, in the text as in the JSON
    text = report_json(report) if ns.json else summary(report) + "\n"
    for w in report["warnings"]:
        warn(w)
    sys.stdout.write(text)
    return 0


def cmd_explore(ns: argparse.Namespace) -> int:
    """Serve the explorer page until Ctrl-C."""
    from onefold_cad.explore.server import serve

    STATE["interrupted"] = "the explorer has stopped (it writes no files)"
    serve(ns.template, port=ns.port, open_browser=not ns.no_browser)
    return 0


def cmd_fit(ns: argparse.Namespace) -> int:
    """Inverse design: the frame whose resting form has the target size."""
    import json

    from onefold_cad.cli.output import one_line
    from onefold_cad.fit import fit_design
    from onefold_cad.templates import DEFAULT_TEMPLATE

    template = ns.template or DEFAULT_TEMPLATE  # as solve and build: the default template
    (job,) = load_jobs([template], {})
    design = job.design

    def progress(text: str) -> None:
        if not ns.quiet:
            os.write(2, f"[fit] {design.name}: {one_line(text)}\n".encode())

    result = fit_design(
        design, ns.height, ns.span, ns.depth, ns.min_tipping_margin, progress=progress
    )
    f = result.design.frame
    progress(f"found after {result.evaluations} solved frames")
    if ns.outdir is not None:  # the build's list of files goes to stderr under --json
        frame = ["--alpha", repr(f.alpha), "--beta", repr(f.beta), "--hc", repr(f.h_c)]
        # named after the template and the fit, not after the flags' values
        name = ["--name", f"{design.name}-fit"]
        argv = [template, "-o", str(ns.outdir), *frame, *name, *(["-q"] if ns.quiet else [])]
        with contextlib.redirect_stdout(sys.stderr) if ns.json else contextlib.nullcontext():
            status = cmd_build(build_parser()["build"].parse_intermixed_args(argv))
        if status:
            return status
    u = design.units.value
    data = result.to_data()
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


def cmd_hops(ns: argparse.Namespace) -> int:
    """Serve the Grasshopper Hops components until Ctrl-C (``onefold_cad.hops``)."""
    from onefold_cad.hops.launch import serve

    STATE["interrupted"] = "the Hops server has stopped (it writes no files)"
    serve(ns.host, ns.port, ns.templates, ns.allow_host)
    return 0


def cmd_sweep(ns: argparse.Namespace) -> int:
    """Evaluate many designs of one template (``onefold_cad.sweep``)."""
    import os

    from onefold_cad.flags.parser import UsageError
    from onefold_cad.sweep.backends import check_dask
    from onefold_cad.sweep.plan import SIMULATION_SETTINGS, make_plan
    from onefold_cad.sweep.runner import run_sweep

    if ns.scheduler is not None and not ns.scheduler.strip():
        raise UsageError(
            "--scheduler: empty; give PROTOCOL://HOST:PORT (tcp://10.0.0.5:8786) or local"
        )
    scheduler = ns.scheduler or os.environ.get("DASK_SCHEDULER_ADDRESS") or None
    if scheduler:
        check_dask()
    if ns.jobs is not None and ns.jobs < 1:
        raise UsageError(f"--jobs: must be at least 1, got {ns.jobs}")
    if ns.outdir.exists() and not ns.outdir.is_dir():
        raise UsageError(f"-o {ns.outdir}: exists and is not a folder")
    plan = make_plan(
        ns.template,
        ns.vary,
        fixed=design_flag_values(ns),
        sampler=ns.sampler,
        samples=ns.samples,
        seed=ns.seed,
        measures=[m for text in ns.measure for m in text.split(",") if m.strip()],
        objectives=ns.objectives,
        images=ns.images,
        simulation={k: getattr(ns, k) for k in SIMULATION_SETTINGS},
    )
    STATE["interrupted"] = (
        f"the finished designs are kept in {ns.outdir / 'journal.jsonl'} and the files "
        "rebuilt from them; rerun the same command to resume"
    )
    run = run_sweep(plan, ns.outdir, jobs=ns.jobs, scheduler=scheduler, quiet=ns.quiet)
    f = run.files
    failed = f" ({run.failed} failed: see the error column)" if run.failed else ""
    front = f", {f.front} on the Pareto front" if plan.objectives else ""
    names = ", ".join(p.name for p in f.files)
    print(f"{ns.outdir}: {f.rows} designs{failed}{front}; wrote {names}")
    return 0


COMMANDS: dict[str, Callable[[argparse.Namespace], int]] = {
    "build": cmd_build,
    "solve": cmd_solve,
    "templates": cmd_templates,
    "explore": cmd_explore,
    "fit": cmd_fit,
    "hops": cmd_hops,
    "sweep": cmd_sweep,
    "simulate": cmd_simulate,
    "compensate": cmd_compensate,
    "site": cmd_site,
    "loads": cmd_loads,
}
