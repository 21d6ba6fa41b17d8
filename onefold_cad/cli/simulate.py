"""``onefold simulate``: the sheet as steel (``onefold_cad.mechanics.simulate``).

Prints the simulation (text, or the report with its ``simulation`` section as
JSON); with ``-o DIR`` writes NAME.json (the report), NAME-standing.glb and
NAME-released.glb (the simulated forms), NAME-deviation.png and NAME-stress.png,
all or nothing. Progress (stage, Newton step, residual) goes to stderr.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path
from typing import Any

from onefold_cad.choices import MeshLevel
from onefold_cad.cli.build import check_outdir, make_outdir
from onefold_cad.cli.output import warn, wrote
from onefold_cad.flags.jobs import load_jobs
from onefold_cad.flags.parser import design_flag_values

__all__ = ["cmd_simulate", "simulation_lines"]


class _Progress:
    """Progress on stderr: ``onefold: simulate NAME: STAGE done (T s CPU)`` at
    each stage's end; with ``verbose`` also ``...: STAGE: Newton step I,
    residual R N`` (at most one every half second per stage, and its first)."""

    def __init__(self, name: str, verbose: bool = False) -> None:
        self.name = name
        self.verbose = verbose
        self.last: dict[str, float] = {}

    def __call__(self, stage: str, iteration: int, residual: float) -> None:
        if not self.verbose:
            return
        now = time.monotonic()
        if iteration and now - self.last.get(stage, -1.0) < 0.5:
            return
        self.last[stage] = now
        os.write(
            2,
            f"{self.name}: {stage}: Newton step {iteration}, residual {residual:.3g} N\n".encode(),
        )

    def stage_done(self, stage: str, seconds: float) -> None:
        """One line: the stage and its CPU time."""
        os.write(2, f"{self.name}: {stage} done ({seconds:.2f} s CPU)\n".encode())


def _length(value: float | None, unit: str) -> str:
    return "-" if value is None else f"{value:.4g} {unit}"


def _hardening(m: dict[str, Any]) -> str:
    h = m.get("hardening_modulus_MPa") or 0.0
    if h <= 0:
        return ", perfectly plastic"
    return f", hardening {h:g} MPa ({100 * m.get('kinematic_hardening', 0.0):.3g} % kinematic)"


def _overbend(sim: dict[str, Any]) -> str:
    """', set 6 deg past its fold' or ''."""
    ob = sim.get("crease_overbend_deg") or 0.0
    return f", set {ob:g} deg past its fold" if ob else ""


def _cones(sim: dict[str, Any]) -> str:
    """', cones formed past their springback' or ''."""
    return (
        ", cones formed past their springback" if sim.get("cone_forming") == "compensated" else ""
    )


def _peeq(value: float | None, at: list[float] | None, unit: str) -> str:
    """'; largest plastic strain 0.17 at (x, y) unit' or ''."""
    if value is None:
        return ""
    where = f" at ({at[0]:.4g}, {at[1]:.4g}) {unit}" if at else ""
    return f"; largest plastic strain {value:.3g}{where}"


def simulation_lines(name: str, sim: dict[str, Any]) -> list[str]:
    """The text ``simulate`` prints, from the report's ``simulation`` section."""
    u = sim["units"]
    m = sim["material"]
    out = [
        f"{name}  simulated as steel (E {m['youngs_modulus_GPa']:g} GPa, nu {m['poisson']:g}, "
        f"yield stress {m['yield_stress_MPa']:g} MPa{_hardening(m)}, t {m['thickness']:g} {u}; "
        f"law {sim.get('law', 'moment')}, reference {sim['reference']}, supports "
        f"{sim['supports']}, crease {sim['crease']}{_overbend(sim)}{_cones(sim)})",
        f"  {'weight':<24} {sim['weight_N']:.6g} N",
    ]
    mesh = sim["mesh"]
    text = (
        f"{mesh['nodes']} nodes, {mesh['triangles']} triangles (largest edge "
        f"{mesh['h_max']:.4g} {u})"
    )
    conv = sim.get("convergence")
    if conv and conv.get("max_deviation_change") is not None:
        other = conv["check_mesh"]
        text += (
            f"; on {other['nodes']} nodes ({conv['check']} check) {conv['quantity']} "
            f"changes by {100 * conv['max_deviation_change']:.3g} %"
        )
        if conv.get("coarser_change") is not None:
            text += f" (on the coarser mesh by {100 * conv['coarser_change']:.3g} %)"
    out.append(f"  {'mesh':<24} {text}")
    if "formed" in sim:
        f = sim["formed"]
        out.append(
            f"  {'formed':<24} work of bending {f['bending_energy_J']:.5g} J; "
            f"{100 * f['plastic_area_share']:.3g} % of the sheet yields "
            f"(out to {_length(f['plastic_radius_max'], u)} from H)"
            + _peeq(f.get("max_plastic_strain"), f.get("max_plastic_strain_at"), u)
        )
    if "released" in sim:
        r = sim["released"]
        out.append(
            f"  {'released (springback)':<24} deviation max {_length(r['max_deviation'], u)}, rms "
            f"{_length(r['rms_deviation'], u)}; height {_length(r['height'], u)}, span "
            f"{_length(r['span'], u)}"
            + (
                f"; {100 * r['reloaded_area_share']:.3g} % of the sheet yields again"
                if sim.get("law") == "j2"
                else ""
            )
        )
    s = sim["standing"]
    head = f"standing ({sim['supports']})"
    if not s["stands"] and s["max_deviation"] is None:
        out.append(f"  {head:<24} does not stand: {s['reason']}")
        return out
    verdict = "stands" if s["stands"] else f"does not stand ({s['reason']})"
    if s.get("uncertain"):
        verdict = f"uncertain ({s['uncertain']})"
    margin = s["tipping_margin_deg"]
    out.append(
        f"  {head:<24} {verdict}; tipping margin {margin:.3g} deg, {len(s['contacts'])} "
        f"contacts, ground reactions {s['reactions_total_N']:.6g} N"
    )
    out.append(
        f"  {'':<24} deviation max {_length(s['max_deviation'], u)}, rms "
        f"{_length(s['rms_deviation'], u)}; height {_length(s['height'], u)}, span "
        f"{_length(s['span'], u)}; moved up to {_length(s['max_displacement'], u)}"
    )
    at = s["max_stress_at"]
    where = f" at ({at[0]:.4g}, {at[1]:.4g}) {u} on the flat sheet" if at else ""
    what = "von Mises stress at the surfaces" if sim.get("law") == "j2" else "stress"
    out.append(
        f"  {'':<24} largest {what} {s['max_stress_MPa']:.4g} MPa ({s['utilisation']:.3g} x "
        f"yield){where}"
    )
    if s.get("max_plastic_strain") is not None:
        out.append(
            f"  {'':<24} yielded (at some stage): {100 * s['plastic_area_share']:.3g} % of the "
            "sheet" + _peeq(s["max_plastic_strain"], s.get("max_plastic_strain_at"), u)
        )
    if "designed" in sim:
        d = sim["designed"]
        out.append(
            f"  {'designed (stress-free)':<24} largest movement "
            f"{_length(d['max_displacement'], u)}, largest stress {d['max_stress_MPa']:.4g} MPa"
        )
    return out


def _write(outdir: Path, name: str, report: dict[str, Any], sim: Any) -> list[Path]:
    """Write the simulation's files into ``outdir``, all or nothing.

    NAME.json, NAME-deviation.png, NAME-stress.png, NAME.inp (the
    structural check for CalculiX or Abaqus) and NAME.vtu (the stages for
    ParaView) always; NAME-standing.glb
    when the sheet found a standing equilibrium, NAME-released.glb when there
    is a released form (reference 'flat'). A form that does not exist is not
    written, and a warning says which file is missing and why.
    """
    from onefold_cad.cli.build import say_removed
    from onefold_cad.export.atomic import FileSet, Staging, check_targets, recover
    from onefold_cad.export.simulation.glb import write_simulation_glb
    from onefold_cad.export.simulation.inp import write_structural_inp
    from onefold_cad.export.simulation.pictures import render_deviation, render_stress
    from onefold_cad.export.simulation.vtu import write_simulation_vtu
    from onefold_cad.fabrication.report import report_json

    forms = []
    if sim.standing_positions is not None:
        forms.append("standing")
    else:
        warn(f"no {name}-standing.glb: no standing equilibrium ({sim.standing.reason})")
    if sim.released_positions is not None:
        forms.append("released")
    names = [f"{name}{s}" for s in (".json", "-deviation.png", "-stress.png", ".inp", ".vtu")]
    names += [f"{name}-{form}.glb" for form in forms]
    make_outdir(outdir)
    recover(outdir, say=warn)
    check_targets(outdir, names)
    every = [*names[:5], *(f"{name}-{form}.glb" for form in ("standing", "released"))]
    with Staging(outdir, say=warn) as stage:
        paths = [stage.path / n for n in names]
        paths[0].write_text(report_json(report))
        render_deviation(sim, paths[1], title=name)
        render_stress(sim, paths[2], title=name)
        write_structural_inp(sim, paths[3])
        write_simulation_vtu(sim, paths[4])
        for form, path in zip(forms, paths[5:], strict=True):
            write_simulation_glb(sim, path, form)
        done = stage.commit(paths, sets=[FileSet(name, tuple(every))])
    say_removed(stage.removed)
    return done


def cmd_simulate(ns: argparse.Namespace) -> int:
    """Simulate one design; print it; with ``-o`` write its files."""
    from onefold_cad.design import fold_design
    from onefold_cad.fabrication.report import check_finite, design_report, report_json
    from onefold_cad.mechanics.simulate import simulate

    (job,) = load_jobs([ns.template] if ns.template else [], design_flag_values(ns), ns.name)
    design = job.design
    if ns.outdir is not None:  # before the simulation's minutes, not after
        check_outdir(ns.outdir)
    folded = fold_design(design)
    check = ns.check if ns.check is not None else MeshLevel.parse(ns.mesh).checked
    progress = None if ns.quiet else _Progress(f"onefold: simulate {design.name}", ns.verbose)
    sim = simulate(
        design,
        folded,
        supports=ns.supports,
        reference=ns.reference,
        crease=ns.crease,
        law=ns.law,
        level=ns.mesh,
        convergence=check,
        check_mesh=ns.check_mesh,
        progress=progress,
        stage_done=None if progress is None else progress.stage_done,
    )
    report = design_report(design, folded, sources=job.sources)
    report["simulation"] = sim.to_data()
    check_finite(report)
    for w in sim.warnings:
        warn(w)
    if ns.outdir is not None:
        wrote(_write(ns.outdir, design.name, report, sim), ns.quiet)
    if ns.json:
        sys.stdout.write(report_json(report))
    else:
        sys.stdout.write("\n".join(simulation_lines(design.name, report["simulation"])) + "\n")
    return 0
