"""``onefold compensate``: the fold to form so that the steel stands as the
target (``onefold_cad.compensate``).

Checks everything it can before the first simulation (the output folder, the
design's steel data, the target's values and, for a height and span, whether
any fold of the sheet reaches them); then searches with progress and an ETA
on stderr, and prints the report (text, or the JSON report with its
``compensation`` section). With ``-o DIR`` it writes, all or nothing:
NAME-compensated.toml (the compensated design as a template every command
takes), the compensated design's build files (as ``onefold build`` writes
them; the annotated DXF's notes and the bend sheet with the angle to fold
to and the angle after springback), NAME-compensated-standing.glb and NAME-compensated-standing.step
(the steel as it stands: the mid-surface), NAME-compensation.png (design,
uncompensated and compensated steel side by side) and NAME-compensation.json.
A size target the steel does not meet within 1 % is refused (exit 2, one
line: the best found and what limits it), and nothing is written.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path
from typing import Any

from onefold_cad.choices import Compensation
from onefold_cad.cli.build import check_outdir
from onefold_cad.cli.output import warn, wrote
from onefold_cad.errors import InvalidParameterError
from onefold_cad.flags.jobs import load_jobs
from onefold_cad.flags.parser import design_flag_values

__all__ = ["cmd_compensate", "compensation_lines", "picture_title"]


def _length(value: float | None, unit: str) -> str:
    return "-" if value is None else f"{value:.5g} {unit}"


def _form_line(label: str, f: dict[str, Any], u: str) -> str:
    margin = f["tipping_margin_deg"]
    conv = f["convergence"]
    stands = "stands" if f["stands"] else "does NOT stand"
    return (
        f"  {label:<16} deviation max {_length(f['max_deviation'], u)}, rms "
        f"{_length(f['rms_deviation'], u)}; height {_length(f['height'], u)}, span "
        f"{_length(f['span'], u)}; {stands}, tipping margin "
        f"{'-' if margin is None else f'{margin:.3g} deg'}"
        + ("" if conv is None else f"; mesh change {100 * conv:.2g} %")
    )


#: How the text names each bending law.
_LAWS = {"moment": "the moment law", "j2": "J2 through the thickness"}


def picture_title(name: str, c: dict[str, Any]) -> str:
    """The compensation picture's heading: what was compensated, by which law."""
    return f"{name}: springback and weight compensated ({_LAWS[c.get('law', 'moment')]})"


def compensation_lines(name: str, c: dict[str, Any]) -> list[str]:
    """The text ``compensate`` prints, from the report's ``compensation`` section."""
    u = c["units"]
    t = c["target"]
    if t["kind"] == "design":
        d = c["designed"]
        aim = f"its own design (height {_length(d['height'], u)}, span {_length(d['span'], u)})"
    else:
        aim = ", ".join(f"{k} {_length(v, u)}" for k, v in t.items() if k != "kind")
    s, k = c["start"], c["compensated"]
    out = [
        f"{name}  compensated for springback and weight ({_LAWS[c.get('law', 'moment')]}): "
        f"target {aim}",
        _form_line("uncompensated", c["before"], u),
        _form_line("compensated", c["after"], u),
        f"  {'fold to':<16} alpha {k['alpha']:.5g} deg (was {s['alpha']:.5g}), beta "
        f"{k['beta']:.5g} deg (was {s['beta']:.5g}), h_c {k['h_c']:.5g} {u} (was "
        f"{s['h_c']:.5g}), crease overbend {k.get('overbend', 0.0):.3g} deg (was "
        f"{s.get('overbend', 0.0):.3g})",
    ]
    cf = c.get("cone_forming", {})
    if cf.get("compensated") == "compensated":
        was = "" if cf.get("start") == "compensated" else " (was formed to the design's)"
        out.append(f"  {'cones':<16} formed past their springback{was}: the radius to form "
                   "each station to is in NAME-cones.csv")  # fmt: skip
    for cr in c["crease"]:
        out.append(
            f"  {'crease ' + cr['half']:<16} set to {cr['fold_to_deg']:.4g} deg ({cr['bend']}); "
            f"standing it is {cr['after_springback_deg']:.4g} deg"
        )
    for knob, rec in c["sensitivity"].items():
        unit = "deg" if knob != "h_c" else u
        parts = ", ".join(f"{q} {v:+.3g} {u}" for q, v in rec.items())
        out.append(f"  {'per ' + unit + ' ' + knob:<16} {parts}")
    out.append(f"  {'simulations':<16} {c['simulations']} ({c['cpu_s']:.0f} s CPU); {c['verdict']}")
    return out


class _Say:
    """Progress lines on stderr: ``onefold: compensate NAME: ...``."""

    def __init__(self, name: str, quiet: bool) -> None:
        self.prefix, self.quiet = f"onefold: compensate {name}: ", quiet

    def __call__(self, text: str) -> None:
        if not self.quiet:
            os.write(2, f"{self.prefix}{text}\n".encode())


def _write(outdir: Path, report: dict[str, Any], result: Any, job: Any) -> list[Path]:
    """Write the compensation's files into ``outdir``, all or nothing."""
    import tomli_w

    from onefold_cad.cli.build import make_outdir, say_removed
    from onefold_cad.compensate.evaluate import target_form
    from onefold_cad.design import fold_design
    from onefold_cad.export.atomic import FileSet, Staging, check_targets, recover
    from onefold_cad.export.build_context import BuildContext
    from onefold_cad.export.compensation_picture import Panel, render_compensation
    from onefold_cad.export.standing_form import write_form_glb, write_form_step
    from onefold_cad.export.writers import file_names, parse_formats, write_design
    from onefold_cad.fabrication.report import report_json
    from onefold_cad.templates import design_to_data

    design = result.compensated
    stem = design.name
    base = report["name"] if "name" in report else stem
    formats = parse_formats(None, designs=[design])
    own = [f"{stem}.toml", f"{stem}-standing.glb", f"{stem}-standing.step",
           f"{base}-compensation.png", f"{base}-compensation.json"]  # fmt: skip
    names = [*own, *file_names(stem, formats)]
    make_outdir(outdir)
    recover(outdir, say=warn)
    check_targets(outdir, names)
    u = design.units.value
    after, before = result.after_sim, result.before_sim
    with Staging(outdir, say=warn) as stage:
        paths = [stage.path / n for n in own]
        paths[0].write_text(tomli_w.dumps(design_to_data(design)))
        points = result.after.aligned if result.after.aligned is not None else after.positions
        write_form_glb(points, after.faces, u, result.after.deviation, paths[1])
        write_form_step(points, after.faces, u, paths[2])
        c = report["compensation"]
        panels = [Panel("design (target)", target_form(result.target.form, before.flat),
                        before.faces, None, f"height {c['designed']['height']:.5g} {u}, span "
                        f"{c['designed']['span']:.5g} {u}")]  # fmt: skip
        for label, form, sim in (("uncompensated steel", result.before, before),
                                 ("compensated steel", result.after, after)):  # fmt: skip
            if form.aligned is None:
                continue
            panels.append(Panel(
                label, form.aligned, sim.faces, form.deviation,
                f"max {form.max_deviation:.4g}, rms {form.rms_deviation:.4g} {u}\n"
                f"height {form.height:.5g}, span {form.span:.5g} {u}",
            ))  # fmt: skip
        render_compensation(panels, u, paths[3], title=picture_title(base, c))
        paths[4].write_text(report_json(report))
        ctx = BuildContext(design, fold_design(design), None, Compensation.SHARP, job.sources, ())
        built = write_design(ctx, stage.path / "build", formats)
        _springback_notes(built, stem, result)
        done = stage.commit([*paths, *built], sets=[FileSet(stem, tuple(names))])
    say_removed(stage.removed)
    return done


def _springback_notes(files: list[Path], stem: str, result: Any) -> None:
    """The angle to fold to and the angle after springback, in the annotated
    DXF's notes and as two columns of the bend sheet."""
    from onefold_cad.export.springback_notes import add_bend_columns, add_dxf_notes

    f0, f1 = result.start.frame, result.compensated.frame
    u = result.compensated.units.value
    ob = result.compensated.material.overbend_deg
    lines = [
        f"springback compensated (onefold compensate): formed to alpha {f1.alpha:.4f}, beta "
        f"{f1.beta:.4f} deg, h_c {f1.h_c:.4g} {u} (design: alpha {f0.alpha:.4g}, beta "
        f"{f0.beta:.4g} deg, h_c {f0.h_c:.4g} {u}); the crease set {ob:.2f} deg past the fold",
    ]
    for c in result.crease:
        lines.append(
            f"fold half {c['half']} to {c['fold_to_deg']:.2f} deg ({c['bend']}); after "
            f"springback it stands at {c['after_springback_deg']:.2f} deg"
        )
    by_name = {p.name: p for p in files}
    if f"{stem}.dxf" in by_name:
        add_dxf_notes(by_name[f"{stem}.dxf"], lines)
    if f"{stem}-bends.csv" in by_name:
        angles = {c["half"]: c["after_springback_deg"] for c in result.crease}
        add_bend_columns(by_name[f"{stem}-bends.csv"], angles)


def cmd_compensate(ns: argparse.Namespace) -> int:
    """Compensate one design; print it; with ``-o`` write its files."""
    from onefold_cad.compensate.evaluate import bend_problem
    from onefold_cad.compensate.parallel import Evaluator
    from onefold_cad.compensate.run import compensate, cones_knob
    from onefold_cad.compensate.target import make_target
    from onefold_cad.design import fold_design
    from onefold_cad.fabrication.report import check_finite, design_report, report_json
    from onefold_cad.mechanics.model import check_cone_forming
    from onefold_cad.sweep.backends import default_workers

    (job,) = load_jobs([ns.template] if ns.template else [], design_flag_values(ns), None)
    design = job.design
    if ns.outdir is not None:
        check_outdir(ns.outdir)
        refusal = bend_problem(design)
        if refusal is not None:  # -o writes build's files, which would refuse at the end
            raise refusal
    cones_knob(ns.knobs, ns.law)  # 'cones' with the moment law: refused before any simulation
    check_cone_forming(design, ns.law, "flat")
    if ns.jobs is not None and ns.jobs < 1:
        raise InvalidParameterError("--jobs", f"must be >= 1, got {ns.jobs}")
    sized = any(v is not None for v in (ns.height, ns.span, ns.depth))
    kind = "size" if sized and ns.target is None else (ns.target or "design")
    target = make_target(design, kind, ns.height, ns.span, ns.depth)
    say = _Say(design.name, ns.quiet)
    t0 = time.monotonic()
    workers = ns.jobs if ns.jobs is not None else min(4, default_workers())
    with Evaluator(workers, ns.scheduler, ns.law) as evaluator:
        result = compensate(design, target, evaluator, say, knobs=ns.knobs)
    say(f"done in {time.monotonic() - t0:.0f} s ({result.cpu_s:.0f} s CPU in simulations)")
    if target.kind == "size" and not result.reached:
        raise InvalidParameterError(
            "target", f"{result.verdict}; the best fold found: alpha "
            f"{result.compensated.frame.alpha:.4g}, beta {result.compensated.frame.beta:.4g} deg"
        )  # fmt: skip
    if not result.reached:
        warn(f"compensate: target {result.verdict}")
    for line in result.after_sim.warnings:  # what onefold simulate says of the compensated steel
        warn(f"compensate: the compensated steel: {line}")
    comp = result.compensated
    report = design_report(comp, fold_design(comp), sources=job.sources)
    report["name"] = design.name
    report["compensation"] = result.to_data() | {
        "law": evaluator.law,
        "cpu_workers_s": evaluator.worker_cpu_s,
    }
    check_finite(report)
    if ns.outdir is not None:
        wrote(_write(ns.outdir, report, result, job), ns.quiet)
    if ns.json:
        sys.stdout.write(report_json(report))
    else:
        sys.stdout.write("\n".join(compensation_lines(design.name, report["compensation"])) + "\n")
    return 0
