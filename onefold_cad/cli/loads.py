"""``onefold loads``: the designed sheet standing outdoors
(:func:`onefold_cad.mechanics.loads.outdoors.outdoors`).

Prints the check (text, or the report with its ``outdoors`` section as
JSON); with ``-o DIR`` writes NAME-loads.json, NAME-loads.csv (the cases)
and NAME-loads.png (the governing case), all or nothing. Bad input is one
line naming it (exit status 2) before the model is built.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from onefold_cad.cli.build import check_outdir, make_outdir
from onefold_cad.cli.loads_parser import load_spec_values
from onefold_cad.cli.output import warn, wrote
from onefold_cad.flags.jobs import load_jobs
from onefold_cad.flags.parser import design_flag_values

__all__ = ["cmd_loads", "loads_lines"]


def _kn(v: float) -> str:
    return f"{v / 1e3:.3g}"


def loads_lines(name: str, data: dict[str, Any]) -> list[str]:
    """The text ``loads`` prints, from the report's ``outdoors`` section."""
    u = data["units"]
    i = data["inputs"]
    if i["velocity_pressure_kPa"] is not None:
        wind = f"q_p {i['velocity_pressure_kPa']:g} kPa given"
    else:
        z, q = data["reference_height_m"], data["peak_velocity_pressure_kPa"]
        wind = (
            f"v_b {i['wind_speed']:g} m/s, terrain {i['terrain']}, z_e {z:.3g} m: q_p {q:.3g} kPa"
        )
    extra = f"; snow s_k {i['snow_kPa']:g} kPa" if i["snow_kPa"] > 0 else ""
    if i["person_kN"] > 0 and data["person_at"] is not None:
        at = data["person_at"]
        extra += f"; person {i['person_kN']:g} kN at ({at[0]:.4g}, {at[1]:.4g}) {u} on the flat"
    mu = f" (mu {i['friction']:g})" if i["supports"] != "anchored" else ""
    out = [
        f"{name}  outdoors on {i['supports']} feet{mu}: weight {data['weight_N']:.5g} N; wind "
        f"{wind}, c_f +{i['cf_down']:g} / {i['cf_up']:g}, {i['directions']} directions{extra}",
        f"  mesh {data['mesh']['nodes']} nodes, {data['mesh']['triangles']} triangles; "
        f"{len(data['cases'])} cases (EN 1990 EQU, STR, SLS)",
        f"  {'foot':<6}{'at (' + u + ')':<22}{'pull kN':>9}{'shear kN':>10}{'push kN':>9}"
        f"{'ballast kg':>12}",
    ]
    for k, f in enumerate(data["feet"], 1):
        at = f"({f['at'][0]:.0f}, {f['at'][1]:.0f})"
        out.append(f"  {k:<6}{at:<22}{_kn(f['tension_N']):>9}{_kn(f['shear_N']):>10}"
                   f"{_kn(f['compression_N']):>9}{f['ballast_kg']:>12.4g}")  # fmt: skip
    t = data["totals"]
    out.append(
        f"  total: {t['anchored_feet']} of {t['feet']} feet pulled up ({_kn(t['tension_N'])} kN "
        f"in all), ballast {t['ballast_kg']:.4g} kg in all (instead of anchors)"
    )
    verdict = "stands in every case" if data["stands"] else "does NOT stand in every case"
    out.append(f"  {verdict}; governing {data['governing']}; strength governed by "
               f"{data['governing_strength']}")  # fmt: skip
    for c in data["nonlinear"]:
        reached = "all" if c["reached"] >= 1 else f"{100 * c['reached']:.3g} %"
        moved = "-" if c["max_deflection"] is None else f"{c['max_deflection']:.4g} {u}"
        out.append(f"  full model, {c['case']}: carried {reached} of it, moved {moved}")
    out += _strength_lines(data, u)
    out.append(f"  {'case':<34}{'feet z kN':<24}{'H/muV':>7}{'moves':>10}{'el/f_y':>7}"
               f"{'r_R':>7}  verdict")  # fmt: skip
    for c in data["cases"]:
        z = " ".join(_kn(r[2]) for r in c["reactions_N"])
        ratio = "lifts" if c["slide_ratio"] is None else f"{c['slide_ratio']:.3g}"
        verdict = "ok" if c["stands"] else c["reason"]
        s = c["strength"]
        r_r = "-" if s is None else _ratio(s)
        out.append(f"  {c['name']:<34}{z:<24}{ratio:>7}{c['max_deflection']:>10.4g}"
                   f"{c['utilisation']:>7.3g}{r_r:>7}  {verdict}")  # fmt: skip
    return out


def _ratio(s: dict[str, Any]) -> str:
    return (">=" if s["load_ratio_capped"] else "") + f"{s['load_ratio']:.3g}"


def _strength_lines(data: dict[str, Any], u: str) -> list[str]:
    """The STR cases' J2 load paths, one line each, and the elastic peak's
    place (information)."""
    st = data.get("strength", {})
    out = [f"  strength (STR, J2 load path from the designed form taken as stress-free, "
           f"r_R >= gamma_M1 = 1.1): {len(st.get('cases_checked', []))} case(s) checked in "
           f"{st.get('cpu_s', 0.0):.3g} s CPU"]  # fmt: skip
    for c in data["cases"]:
        s = c["strength"]
        if s is None:
            continue
        at = s["max_plastic_strain_at"]
        where = "" if at is None else f" at ({at[0]:.4g}, {at[1]:.4g}) {u}"
        el = c["utilisation_at"]
        out.append(
            f"    {c['name']}: r_R {_ratio(s)} ({s['limit']}); at {s['plastic_at_ratio']:.3g} x "
            f"the case: plastic strain {100 * s['max_plastic_strain']:.3g} %{where}, "
            f"{100 * s['plastic_area_share']:.2g} % of the area; peak elastic stress "
            f"{c['utilisation']:.3g} x f_y at ({el[0]:.4g}, {el[1]:.4g}) {u} (information)"
        )
    return out


def _write(outdir: Path, name: str, report: dict[str, Any], result: Any) -> list[Path]:
    """NAME-loads.json, NAME-loads.csv and NAME-loads.png into ``outdir``, all or nothing."""
    from onefold_cad.cli.build import say_removed
    from onefold_cad.export.atomic import FileSet, Staging, check_targets, recover
    from onefold_cad.export.loads.cases_csv import write_cases_csv
    from onefold_cad.export.loads.picture import render_governing
    from onefold_cad.fabrication.report import report_json

    names = [f"{name}-loads{s}" for s in (".json", ".csv", ".png")]
    make_outdir(outdir)
    recover(outdir, say=warn)
    check_targets(outdir, names)
    with Staging(outdir, say=warn) as stage:
        paths = [stage.path / n for n in names]
        paths[0].write_text(report_json(report))
        write_cases_csv(report["outdoors"], paths[1])
        render_governing(result, paths[2], title=name)
        done = stage.commit(paths, sets=[FileSet(f"{name}-loads", tuple(names))])
    say_removed(stage.removed)
    return done


def cmd_loads(ns: argparse.Namespace) -> int:
    """Check one design outdoors; print it; with ``-o`` write its files."""
    from onefold_cad.design import fold_design
    from onefold_cad.fabrication.report import check_finite, design_report, report_json
    from onefold_cad.mechanics.loads.outdoors import outdoors
    from onefold_cad.mechanics.loads.spec import LoadSpec

    spec = LoadSpec(**load_spec_values(ns))  # bad loads: one line before anything runs
    (job,) = load_jobs([ns.template] if ns.template else [], design_flag_values(ns), ns.name)
    design = job.design
    if ns.outdir is not None:
        check_outdir(ns.outdir)
    folded = fold_design(design)
    result = outdoors(design, folded, spec, level=ns.mesh, nonlinear=ns.nonlinear_check,
                      strength_cases=ns.strength_cases)  # fmt: skip
    report = design_report(design, folded, sources=job.sources)
    report["outdoors"] = result.to_data()
    check_finite(report)
    for w in result.warnings:
        warn(w)
    if ns.outdir is not None:
        wrote(_write(ns.outdir, design.name, report, result), ns.quiet)
    if ns.json:
        sys.stdout.write(report_json(report))
    else:
        sys.stdout.write("\n".join(loads_lines(design.name, report["outdoors"])) + "\n")
    return 0
