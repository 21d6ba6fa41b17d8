"""``onefold site SITE -o DIR``: every sheet of a site file built as ``onefold
build`` builds it (its files in DIR/NAME/), its part stood where the site
places it, the clearance between the sheets checked, then the site's files
(:data:`onefold_cad.export.site.writers.SITE_WRITERS`) written; everything
staged and committed at once (:mod:`onefold_cad.export.atomic`), nothing
written when a sheet or the clearance check fails. ``-j N`` builds N sheets
at a time in worker processes (:func:`onefold_cad.cli.build.run_tasks`).
"""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from onefold_cad.choices import Compensation, Placement
from onefold_cad.cli.build import (
    STATE,
    BuildTask,
    check_jobs,
    check_outdir,
    output_folder,
    run_tasks,
    say_cones_left_out,
    say_removed,
    task_context,
    write_task,
)
from onefold_cad.cli.output import one_line, warn
from onefold_cad.errors import InvalidParameterError, not_installed

if TYPE_CHECKING:
    from onefold_cad.design import Design
    from onefold_cad.export.site.context import SiteContext
    from onefold_cad.geometry.resting.placement import RestingPlacement

__all__ = ["SheetBuilt", "cmd_site"]


@dataclass(frozen=True)
class SheetBuilt:
    """What a worker sends back for one sheet (picklable).

    Attributes:
        files: the sheet's files, in its staging folder.
        part: its part standing in its resting frame (build123d shape).
        resting: how it stands.
        report: its report (as its NAME.json holds it).
    """

    files: tuple[str, ...]
    part: Any
    resting: RestingPlacement
    report: dict[str, Any]


def _build_sheet(task: BuildTask) -> SheetBuilt:
    """Write one sheet's files (as ``build``) and keep its part and report."""
    from onefold_cad.export.writers import context_report

    ctx = task_context(task)
    files = write_task(task, ctx)
    return SheetBuilt(tuple(str(p) for p in files), ctx.part, ctx.resting, context_report(ctx))


def _say(quiet: bool, name: str, text: str) -> None:
    if not quiet:
        os.write(2, f"[site] {name}: {one_line(text)}\n".encode())


def _sheet_formats(text: str | None, designs: Sequence[Design] = ()) -> tuple[str, ...]:
    """The sheets' writers of ``--sheet-formats`` (``none``: no sheet files); all
    of them name the cones' forming sheet where one of ``designs`` has its cones
    formed past their springback, as ``onefold build`` does."""
    from onefold_cad.export.writers import parse_formats

    if text is not None and text.strip().lower() == "none":
        return ()
    return parse_formats(text, flag="--sheet-formats", designs=designs)


def _site_context(spec: Any, jobs: list[Any], built: list[SheetBuilt]) -> SiteContext:
    from onefold_cad.design import fold_design
    from onefold_cad.export.site.context import SiteContext, SiteSheet
    from onefold_cad.site.placement import SitePlacement

    sheets = [
        SiteSheet(
            s.name,
            job.design,
            fold_design(job.design),
            b.part,
            b.resting,
            b.report,
            SitePlacement(s.x, s.y, s.rotation_deg),
        )
        for s, job, b in zip(spec.sheets, jobs, built, strict=True)
    ]
    return SiteContext(spec.name, spec.description, spec.units, sheets)


def cmd_site(ns: argparse.Namespace) -> int:
    """Build a site: its sheets' files and the site's, all or nothing."""
    from onefold_cad.export.atomic import FileSet, Staging, check_targets, pause_point, recover
    from onefold_cad.export.site.clearance import measure_clearance
    from onefold_cad.export.site.writers import SITE_WRITERS, site_file_names
    from onefold_cad.export.writers import WRITERS, file_names, parse_formats
    from onefold_cad.flags.site_jobs import site_jobs
    from onefold_cad.site.spec import read_site

    if ns.jobs < 1:
        raise InvalidParameterError("--jobs", f"must be >= 1, got {ns.jobs}")
    formats = parse_formats(ns.formats, SITE_WRITERS)
    _sheet_formats(ns.sheet_formats)  # a bad name: refused before the site is read
    spec = read_site(ns.site)
    outdir = Path(ns.outdir)
    check_outdir(outdir)
    jobs = site_jobs(spec)
    sheet_formats = _sheet_formats(ns.sheet_formats, [j.design for j in jobs])
    # the site's STEP, GLB, IFC and clearance need every sheet's part: its checks too
    found = check_jobs(jobs, tuple(dict.fromkeys([*sheet_formats, "step"])), ns)
    say_cones_left_out([j.design for j in jobs], sheet_formats)
    if not ns.allow_touching:  # sheets whose surfaces cross: refused before building them
        from onefold_cad.site.overlap import check_plan
        from onefold_cad.site.placement import SitePlacement

        check_plan(
            [(s.name, j.design, SitePlacement(s.x, s.y, s.rotation_deg))
             for s, j in zip(spec.sheets, jobs, strict=True)],
            spec.units,
        )  # fmt: skip
    n = len(jobs)
    targets = [
        f"{j.design.name}/{f}" for j in jobs for f in file_names(j.design.name, sheet_formats)
    ]
    site_names = site_file_names(spec.name, formats)
    with output_folder(outdir):
        recover(outdir, say=warn)
        check_targets(outdir, [*targets, *site_names])
        with Staging(outdir, say=warn) as staging:
            STATE["staging"] = staging
            tasks = [
                BuildTask(i, n, job, sheet_formats, None, Compensation.parse(ns.compensation),
                          str(staging.path / job.design.name), ns.quiet, found[i - 1],
                          Placement.REST, bool(STATE.get("process")))
                for i, job in enumerate(jobs, 1)
            ]  # fmt: skip
            built: list[SheetBuilt] = run_tasks(tasks, ns.jobs, _build_sheet)
            if spec.loads is not None:
                _outdoors(spec.loads, jobs, built, ns.quiet)
            ctx = _site_context(spec, jobs, built)
            t0 = time.perf_counter()
            ctx.clearance = measure_clearance(ctx.sheets)
            _report_clearance(ctx, ns, time.perf_counter() - t0)
            ctx.clearance.check(spec.units, ns.allow_touching)
            ctx.files = [staging.path / name for name in site_names]
            for name, path in zip(formats, ctx.files, strict=True):
                t0 = time.perf_counter()
                SITE_WRITERS[name].write(ctx, path)
                _say(
                    ns.quiet,
                    spec.name,
                    f"{SITE_WRITERS[name].stage} {time.perf_counter() - t0:.2f} s",
                )
            if "ifc" in ctx.sections:
                _say(ns.quiet, spec.name, _ifc_text(ctx.sections["ifc"], spec.units))
            files = [Path(f) for b in built for f in b.files] + ctx.files
            pause_point("staged")
            sets = [
                FileSet(j.design.name, tuple(file_names(j.design.name, list(WRITERS))),
                        folder=j.design.name)
                for j in jobs
            ]  # fmt: skip
            sets.append(FileSet(spec.name, tuple(site_file_names(spec.name, list(SITE_WRITERS)))))
            for p in staging.commit(files, targets=[*targets, *site_names], sets=sets):
                print(p, flush=True)
            say_removed(staging.removed)
    if ns.formats is None or ns.formats.strip().lower() == "all":
        for w in SITE_WRITERS.values():  # what a missing optional package left out
            if not w.available:
                why = not_installed(f"the {w.name} file", [w.requires], w.extra)
                warn(f"{spec.name}{w.suffix} not written: {why}")
    return 0


def _outdoors(loads: dict[str, Any], jobs: list[Any], built: list[SheetBuilt], quiet: bool) -> None:
    """``onefold loads`` on every sheet: its report's ``outdoors`` section
    (SITE-order.csv's anchor columns read it)."""
    from onefold_cad.design import fold_design
    from onefold_cad.mechanics.loads.outdoors import outdoors
    from onefold_cad.mechanics.loads.spec import LoadSpec

    fields = dict(loads)
    mesh = fields.pop("mesh")
    spec = LoadSpec(**fields)
    for job, b in zip(jobs, built, strict=True):
        t0 = time.perf_counter()
        result = outdoors(job.design, fold_design(job.design), spec, level=mesh)
        b.report["outdoors"] = result.to_data()
        for w in result.warnings:
            warn(f"{job.design.name}: {w}")
        t = b.report["outdoors"]["totals"]
        _say(quiet, job.design.name,
             f"outdoors ({spec.supports} feet): {t['feet']} feet, {t['anchored_feet']} pulled "
             f"up ({t['tension_N'] / 1e3:.3g} kN), ballast {t['ballast_kg']:.4g} kg; governing "
             f"{result.governing} ({time.perf_counter() - t0:.1f} s)")  # fmt: skip


def _report_clearance(ctx: SiteContext, ns: argparse.Namespace, seconds: float) -> None:
    c = ctx.clearance
    u = ctx.units
    if c is None or c.smallest is None:
        return
    for p in c.pairs:
        _say(ns.quiet, ctx.name, f"clearance {p.a} - {p.b}: {p.distance:.3f} {u}")
    s = c.smallest
    _say(
        ns.quiet,
        ctx.name,
        f"smallest clearance {s.distance:.1f} {u} ({s.a} - {s.b}; exact B-reps, within "
        f"{c.accuracy:.2g} {u} of the designed sheets) in {seconds:.2f} s",
    )
    if ns.allow_touching:
        for p in c.touching:
            warn(f"{p.a} and {p.b} touch or overlap (allowed by --allow-touching)")


def _ifc_text(section: dict[str, Any], units: str) -> str:
    if section["geometry"] == "advanced_brep":
        return "IFC plates: advanced B-rep from the exact solids"
    return (
        f"IFC plates: triangulated face sets (ifcopenshell cannot serialise the solids: "
        f"{section['why']}), within {section['deviation']:.3g} {units} of them; area error "
        f"at most {100 * section['max_area_error']:.3f} %"
    )
