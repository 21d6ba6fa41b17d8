"""The text ``onefold solve`` prints, and the material lines ``build`` prints.

Both read the JSON report (:func:`onefold_cad.fabrication.report.design_report`),
so the text and the JSON never disagree.
"""

from __future__ import annotations

from typing import Any

__all__ = ["material_lines", "summary"]


def material_lines(report: dict[str, Any]) -> list[str]:
    """The material used (name; values) and where the values came from: three lines."""
    mat = report["inputs"]["material"]
    src = report.get("sources", {})
    u = report["units"]
    hole = report["relief_hole_diameter"]
    density = mat.get("density")
    values = {
        "material.thickness": ("t", f"t {mat['thickness']:g} {u}"),
        "material.bend_radius": ("r", f"r {mat['bend_radius']:g} {u}"),
        "material.k_factor": ("K", f"K {mat['k_factor']:g}"),
        "material.sheet_surface": (
            "reference surface",
            f"reference surface {mat['sheet_surface']}",
        ),
        "material.kerf": ("kerf", f"kerf {mat['kerf']:g} {u}"),
        "material.relief_hole": ("relief hole", f"relief hole {hole:.4g} {u}"),
        "material.density": (
            "density",
            f"density {density:g} kg/m^3" if density is not None else "no density",
        ),
    }
    # the elastic-plastic values `simulate` needs, when the material has them
    for key, label, text in (
        ("youngs_modulus", "E", "E {:g} GPa"),
        ("poisson", "nu", "nu {:g}"),
        ("yield_stress", "yield stress", "yield stress {:g} MPa"),
    ):
        if mat.get(key) is not None:
            values[f"material.{key}"] = (label, text.format(mat[key]))
    by_source: dict[str, list[str]] = {}
    for key, label in [("material.name", "name"), *((k, v[0]) for k, v in values.items())]:
        by_source.setdefault(src.get(key, "default"), []).append(label)
    common = max(by_source, key=lambda k: len(by_source[k]))
    others = [f"{', '.join(labels)}: {s}" for s, labels in by_source.items() if s != common]
    origin = f"values: {common}" + "".join(f"; {o}" for o in others)
    return [
        mat.get("name") or "(unnamed material)",
        ", ".join(v[1] for v in values.values()),
        origin,
    ]


def _compensation_note(report: dict[str, Any]) -> str:
    """Why the flat pattern is not compensated, if it is not: past the bend
    model's limits (``flat_pattern.bend_problems``: build refuses the DXF), a
    zero-thickness sheet (nothing to compensate), or asked for."""
    fp = report["flat_pattern"]
    if fp["compensation"] != "none":
        return ""
    if fp["bend_problems"]:
        return (
            " (uncompensated: past the bend model's limits, see the warnings; "
            "build refuses the DXF)"
        )
    if report["inputs"]["material"]["thickness"] <= 0.0:
        return " (t = 0: nothing to compensate)"
    return " (uncompensated, as asked)"


def summary(report: dict[str, Any]) -> str:
    """The human-readable result of ``onefold solve``."""
    u = report["units"]
    c = report["crease"]
    r = report["resting"]
    f = report["sheet"]
    ds = report["direction_surface"]
    mat_name, mat_values, mat_origin = material_lines(report)
    lines = [
        f"{report['name']}  ({report['model']} model, {u})",
        f"  material                 {mat_name}",
        f"                           {mat_values}",
        f"                           ({mat_origin})",
        f"  sheet (designed)         {f['kind']}, {f['size'][0]:.6g} x {f['size'][1]:.6g} {u}, "
        f"area {f['area']:.6g} {u}^2",
        f"  folded form (resting)    height {r['height']:.6g} {u}, span {r['span']:.6g} {u}, "
        f"footprint {r['footprint']['width']:.6g} x {r['footprint']['depth']:.6g} {u}"
        + ("" if r["stable"] else " (not stable)"),
        f"  direction-surface apex height h at frame radius R = {ds['frame_radius']:.6g} {u}: "
        f"{ds['apex_height']:.6g} {u}",
        "      (the paper's h: it scales with R, not with the sheet)",
        f"  angle condition error    <= {report['angle_condition_error_deg']:.3g} deg (verified)",
    ]
    for half in ("plus_x", "minus_x"):
        h = c[half]
        ba, bd = (
            "-" if h[k] is None else f"{h[k]:.4g}" for k in ("bend_allowance", "bend_deduction")
        )  # none for a crease folded flat onto itself (its warning says so)
        lines.append(
            f"  crease {half:<8}  fold {h['fold_angle_deg']:.4g} deg {h['bend']:<4}  "
            f"length {h['length']:.6g}  BA {ba}  BD {bd}"
        )
    lines.append(
        f"  relief hole diameter     {report['relief_hole_diameter']:.4g} {u}"
        + (
            f" (a STEP solid needs > {report['solid_min_relief_hole']:.4g} {u})"
            if report["solid_min_relief_hole"] is not None
            else ""
        )
    )
    if report["flat_size"] is not None:
        lines.append(
            f"  flat pattern size        {report['flat_size'][0]:.6g} x "
            f"{report['flat_size'][1]:.6g} {u}, net area {report['flat_area']:.6g} {u}^2"
            + _compensation_note(report)
        )
    else:
        lines.append("  flat pattern             none (see the warnings; build refuses the DXF)")
    lines.append(f"  surface area (folded)    {report['surface_area']:.6g} {u}^2")
    mass = report["mass"]
    if mass is not None:
        lines.append(
            f"  mass                     {mass['value']:.4g} {mass['unit']} "
            f"(density {mass['density']:g} kg/m^3)"
        )
    t = report["timings_s"]
    lines.append(
        f"  timings                  direction-surface {t['direction_surface']:.3g} s, "
        f"final surface {t['final_surface']:.3g} s"
    )
    return "\n".join(lines)
