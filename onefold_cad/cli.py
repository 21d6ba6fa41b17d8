"""The ``onefold`` command: build, solve and list templates.

``main(argv=None) -> int`` is the entry point (``onefold`` and ``python -m
onefold_cad``), so tests can call it directly. Every error of the package and
every usage error becomes one line ``onefold: error: ...`` on stderr and exit
status 2; ``build`` writes every file of a design under a temporary name and
renames them into place only when the whole design succeeded.
"""

from __future__ import annotations

import copy
import functools
import inspect
import os
import shutil
import sys
import tempfile
import time
from collections.abc import Callable, Sequence
from enum import StrEnum
from pathlib import Path
from typing import Annotated, Any

import typer

from onefold_cad.design import Design, build_design
from onefold_cad.errors import InvalidParameterError, OneFoldError
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import SheetSurface, Units
from onefold_cad.geometry.params import Model
from onefold_cad.templates import (
    DEFAULT_TEMPLATE,
    design_from_data,
    find_template,
    list_templates,
    read_template,
)

__all__ = ["app", "main", "Overrides"]

app = typer.Typer(
    name="onefold",
    help="Design One-Fold curved-origami forms and write STEP, DXF, JSON and previews.",
    add_completion=False,
    pretty_exceptions_enable=False,
    context_settings={"help_option_names": ["-h", "--help"]},
)

_FRAME = "Frame curve (paper section 3.2)"
_SHEET = "Sheet (fold frame: fold line on the x axis, H at the origin)"
_MAT = "Material"

# -- the flags shared by build and solve (see with_design_flags) -------------
ModelOpt = Annotated[
    Model | None,
    typer.Option(
        "--model",
        help="Direction-surface: the exact cone or the paper's triangle fan "
        "(default: the template's model, exact if it names none).",
    ),
]
Alpha = Annotated[
    float | None, typer.Option(help="Arc opening alpha, deg in (0, 90).", rich_help_panel=_FRAME)
]
Beta = Annotated[
    float | None,
    typer.Option(help="Tilt beta of the arc's plane, deg in (0, 90).", rich_help_panel=_FRAME),
]
Hc = Annotated[
    float | None,
    typer.Option(
        "--hc", help="Offset H_c of H from the f-line's midpoint.", rich_help_panel=_FRAME
    ),
]
Radius = Annotated[
    float | None, typer.Option(help="Frame-curve radius R, > 0.", rich_help_panel=_FRAME)
]
Divisions = Annotated[
    int | None,
    typer.Option(help="Triangles of the paper model's fan, >= 1.", rich_help_panel=_FRAME),
]
XPlus = Annotated[
    float | None,
    typer.Option(help="Quadrilateral: X+ (distance H to +x vertex).", rich_help_panel=_SHEET),
]
XMinus = Annotated[
    float | None,
    typer.Option(help="Quadrilateral: X- (distance H to -x vertex).", rich_help_panel=_SHEET),
]
YPlus = Annotated[
    float | None,
    typer.Option(help="Quadrilateral: Y+ (distance H to +y vertex).", rich_help_panel=_SHEET),
]
YMinus = Annotated[
    float | None,
    typer.Option(help="Quadrilateral: Y- (distance H to -y vertex).", rich_help_panel=_SHEET),
]
Polygon = Annotated[
    str | None,
    typer.Option(help='Polygon sheet "x,y;x,y;...", star-shaped about H.', rich_help_panel=_SHEET),
]
Rectangle = Annotated[
    str | None,
    typer.Option(
        help="Rectangle WIDTHxHEIGHT folded along its diagonal.",
        metavar="WIDTHxHEIGHT",
        rich_help_panel=_SHEET,
    ),
]
ApexFraction = Annotated[
    float | None,
    typer.Option(
        help="Rectangle: where H sits along the diagonal, in (0, 1).", rich_help_panel=_SHEET
    ),
]
Thickness = Annotated[
    float | None, typer.Option(help="Sheet thickness t >= 0.", rich_help_panel=_MAT)
]
BendRadius = Annotated[
    float | None, typer.Option(help="Inside bend radius r >= 0.", rich_help_panel=_MAT)
]
KFactor = Annotated[float | None, typer.Option(help="K-factor in [0, 1].", rich_help_panel=_MAT)]
Kerf = Annotated[float | None, typer.Option(help="Cutting kerf >= 0.", rich_help_panel=_MAT)]
ReliefHole = Annotated[
    float | None,
    typer.Option(
        "--relief-hole",
        metavar="DIAMETER",
        help="Relief hole diameter at the apex >= 0.",
        rich_help_panel=_MAT,
    ),
]
Density = Annotated[
    float | None, typer.Option(help="Density (mass / unit^3) > 0.", rich_help_panel=_MAT)
]


class Body(StrEnum):
    """What the STEP holds."""

    AUTO = "auto"
    SOLID = "solid"
    SHELL = "shell"


SheetSurfaceOpt = Annotated[
    SheetSurface | None,
    typer.Option(
        "--sheet-surface",
        help="Which face of the sheet the folded surface is: INSIDE (material below "
        "the top face), OUTSIDE (above it) or MID.",
        rich_help_panel=_MAT,
    ),
]
UnitsOpt = Annotated[Units | None, typer.Option("--units", help="Length unit of the design.")]

# Parameter name -> option, in the order the help lists them.
DESIGN_FLAGS: dict[str, Any] = {
    "model": ModelOpt,
    "alpha": Alpha,
    "beta": Beta,
    "hc": Hc,
    "radius": Radius,
    "divisions": Divisions,
    "x_plus": XPlus,
    "x_minus": XMinus,
    "y_plus": YPlus,
    "y_minus": YMinus,
    "polygon": Polygon,
    "rectangle": Rectangle,
    "apex_fraction": ApexFraction,
    "thickness": Thickness,
    "bend_radius": BendRadius,
    "k_factor": KFactor,
    "kerf": Kerf,
    "relief_hole": ReliefHole,
    "density": Density,
    "sheet_surface": SheetSurfaceOpt,
    "units": UnitsOpt,
}


def with_design_flags(command: Callable[..., None]) -> Callable[..., None]:
    """Give ``command`` the options of :data:`DESIGN_FLAGS` after its own ones.

    ``command`` declares a keyword-only parameter ``flags`` instead of one
    parameter per design flag; it receives ``{parameter name: value}`` for
    every flag (None where not given). Typer reads the command's parameters
    from ``__signature__``, so the flags are declared once for every command.
    """
    sig = inspect.signature(command, eval_str=True)
    if "flags" not in sig.parameters:
        raise TypeError(f"{command.__name__}() must take a keyword-only parameter 'flags'")
    own = [p for p in sig.parameters.values() if p.name != "flags"]
    added = [
        inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=None, annotation=opt)
        for name, opt in DESIGN_FLAGS.items()
    ]

    @functools.wraps(command)
    def wrapper(**kwargs: Any) -> None:
        flags = {name: kwargs.pop(name, None) for name in DESIGN_FLAGS}
        command(**kwargs, flags=flags)

    wrapper.__signature__ = sig.replace(parameters=[*own, *added])  # type: ignore[attr-defined]
    return wrapper


class Overrides:
    """Flag values that replace template values; None means "keep the template's"."""

    _FLAGS = {
        "frame.alpha": "--alpha",
        "frame.beta": "--beta",
        "frame.h_c": "--hc",
        "frame.radius": "--radius",
        "frame.divisions": "--divisions",
        "material.thickness": "--thickness",
        "material.bend_radius": "--bend-radius",
        "material.k_factor": "--k-factor",
        "material.kerf": "--kerf",
        "material.relief_hole": "--relief-hole",
        "material.density": "--density",
    }
    _QUAD = {
        "x_plus": "--x-plus",
        "x_minus": "--x-minus",
        "y_plus": "--y-plus",
        "y_minus": "--y-minus",
    }

    def __init__(self, **values: Any) -> None:
        self.values = {k: v for k, v in values.items() if v is not None}

    def apply(self, data: dict[str, Any]) -> tuple[dict[str, Any], dict[str, str]]:
        """Template data with the flags applied, and the flag name of each changed key."""
        out = copy.deepcopy(data)
        v = self.values
        names: dict[str, str] = {}
        for key, flag in self._FLAGS.items():
            arg = flag[2:].replace("-", "_")
            if arg in v:
                table, field = key.split(".")
                out.setdefault(table, {})[field] = v[arg]
                names[key] = flag
        if "model" in v:
            out["model"] = Model(v["model"]).value
        if "units" in v:
            out["units"] = Units(v["units"]).value
        if "sheet_surface" in v:
            out.setdefault("material", {})["sheet_surface"] = SheetSurface(v["sheet_surface"]).value
            names["material.sheet_surface"] = "--sheet-surface"
        if "name" in v:
            out["name"] = v["name"]
            names["name"] = "--name"
        self._apply_sheet(out, names)
        return out, names

    def _apply_sheet(self, out: dict[str, Any], names: dict[str, str]) -> None:
        v = self.values
        quad = {k: v[k] for k in self._QUAD if k in v}
        given = [
            f
            for f, on in (
                ("--polygon", "polygon" in v),
                ("--rectangle", "rectangle" in v),
                ("--x-plus/--x-minus/--y-plus/--y-minus", bool(quad)),
            )
            if on
        ]
        if len(given) > 1:
            raise InvalidParameterError(given[1], f"cannot be combined with {given[0]}")
        sheet = out.get("sheet") if isinstance(out.get("sheet"), dict) else {}
        if "polygon" in v:
            out["sheet"] = {"polygon": _parse_polygon(v["polygon"])}
            names["sheet.polygon"] = "--polygon"
        elif "rectangle" in v:
            w, h = _parse_rectangle(v["rectangle"])
            old = sheet.get("rectangle", {}) if isinstance(sheet.get("rectangle"), dict) else {}
            out["sheet"] = {"rectangle": {**old, "width": w, "height": h}}
            names["sheet.rectangle.width"] = names["sheet.rectangle.height"] = "--rectangle"
        elif quad:
            if "quadrilateral" in sheet:
                out["sheet"] = {"quadrilateral": {**sheet["quadrilateral"], **quad}}
            else:
                for key, flag in self._QUAD.items():
                    if key not in quad:
                        raise InvalidParameterError(
                            flag,
                            "missing: a quadrilateral sheet needs all of --x-plus, "
                            "--x-minus, --y-plus, --y-minus (each > 0)",
                        )
                out["sheet"] = {"quadrilateral": quad}
            for key, flag in self._QUAD.items():
                names[f"sheet.quadrilateral.{key}"] = flag
        if "apex_fraction" in v:
            rect = out.get("sheet", {}).get("rectangle")
            if not isinstance(rect, dict):
                raise InvalidParameterError(
                    "--apex-fraction", "applies to a rectangle sheet only (add --rectangle WxH)"
                )
            rect["apex_fraction"] = v["apex_fraction"]
            names["sheet.rectangle.apex_fraction"] = "--apex-fraction"


def _parse_number(text: str, flag: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise InvalidParameterError(flag, f"{text.strip()!r} is not a number") from None


def _parse_polygon(text: str) -> list[list[float]]:
    pts = []
    for i, pair in enumerate(p for p in text.split(";") if p.strip()):
        parts = pair.split(",")
        if len(parts) != 2:
            raise InvalidParameterError(
                "--polygon",
                f'vertex {i} must be "x,y", got {pair.strip()!r} (format "x,y;x,y;...")',
            )
        pts.append([_parse_number(parts[0], "--polygon"), _parse_number(parts[1], "--polygon")])
    return pts


def _parse_rectangle(text: str) -> tuple[float, float]:
    parts = text.lower().split("x")
    try:
        width, height = (float(p) for p in parts)
    except ValueError:
        raise InvalidParameterError(
            "--rectangle", f"must be WIDTHxHEIGHT (e.g. 3048x7315.2), got {text!r}"
        ) from None
    return width, height


def load_designs(templates: Sequence[str], overrides: Overrides) -> list[Design]:
    """The designs of the given templates (the default one if none) with flags applied."""
    refs = list(templates) or [DEFAULT_TEMPLATE]
    designs = []
    for ref in refs:
        path = find_template(ref)
        data, names = overrides.apply(read_template(path))
        try:
            designs.append(design_from_data(data, key_names=names))
        except InvalidParameterError as exc:
            if exc.parameter.startswith("--"):
                raise
            raise type(exc)(
                f"{path}: {exc.parameter}", str(exc)[len(exc.parameter) + 2 :]
            ) from None
    return designs


# -- output -------------------------------------------------------------------
def _summary(report: dict[str, Any]) -> str:
    u = report["units"]
    c = report["crease"]
    r = report["resting"]
    f = report["sheet"]
    t = report["timings_s"]
    lines = [
        f"{report['name']}  ({report['model']} model, {u})",
        f"  apex height              {report['apex_height']:.6g} {u}",
        f"  angle condition error    {report['angle_condition_error_deg']:.3g} deg",
    ]
    for half in ("plus_x", "minus_x"):
        h = c[half]
        lines.append(
            f"  crease {half:<8}  fold {h['fold_angle_deg']:.4g} deg {h['bend']:<4}  "
            f"length {h['length']:.6g}  BA {h['bend_allowance']:.4g}  BD {h['bend_deduction']:.4g}"
        )
    lines += [
        f"  relief hole diameter     {report['relief_hole_diameter']:.4g} {u}"
        + (
            f" (a STEP solid needs > {report['solid_min_relief_hole']:.4g} {u})"
            if report["solid_min_relief_hole"] is not None
            else ""
        ),
        f"  sheet size (designed)    {f['size'][0]:.6g} x {f['size'][1]:.6g} {u}, "
        f"area {f['area']:.6g} {u}^2",
        f"  flat pattern size        {report['flat_size'][0]:.6g} x {report['flat_size'][1]:.6g} "
        f"{u}, net area {report['flat_area']:.6g} {u}^2",
        f"  surface area (folded)    {report['surface_area']:.6g} {u}^2",
        f"  resting height           {r['height']:.6g} {u}, footprint "
        f"{r['footprint']['width']:.6g} x {r['footprint']['depth']:.6g} {u}",
        f"  timings                  direction-surface {t['direction_surface']:.3g} s, "
        f"final surface {t['final_surface']:.3g} s",
    ]
    return "\n".join(lines)


def _stage_design(
    design: Design, folded: FoldedSheet, stage: Path, body: str | None = None
) -> list[Path]:
    """Write all files of one design into the folder ``stage``; return them."""
    from onefold_cad.export.dxf import export_design_dxf
    from onefold_cad.export.dxf_preview import render_preview
    from onefold_cad.export.preview import render_folded_preview
    from onefold_cad.export.report import design_report, write_report
    from onefold_cad.export.step import export_design_step

    stem = design.name
    stage.mkdir()
    step = export_design_step(design, stage / f"{stem}.step", folded=folded, body=body)
    dxf = export_design_dxf(design, stage / f"{stem}.dxf", folded=folded)
    flat = render_preview(dxf, stage / f"{stem}-flat.svg")
    view = render_folded_preview(
        folded, stage / f"{stem}-3d.png", title=design.name, units=design.units.value
    )
    staged = [Path(p) for p in (step, dxf, flat, view)] + [stage / f"{stem}.json"]
    write_report(staged[-1], design_report(design, folded, files=staged))
    return staged


# -- commands -----------------------------------------------------------------
@app.command()
@with_design_flags
def build(
    templates: Annotated[
        list[str] | None,
        typer.Argument(
            metavar="[TEMPLATE.toml ...]",
            help=f"Template files or shipped template names (default: {DEFAULT_TEMPLATE}).",
            show_default=False,
        ),
    ] = None,
    outdir: Annotated[Path, typer.Option("-o", "--outdir", help="Output folder.")] = Path("out"),
    name: Annotated[
        str | None, typer.Option(help="File name stem (one template only; default: its name).")
    ] = None,
    body: Annotated[
        Body,
        typer.Option(
            help="STEP body: 'solid' (the sheet's thickness, exact model), 'shell' (the "
            "reference surface) or 'auto': solid when the design has thickness and a "
            "relief hole, else shell.",
        ),
    ] = Body.AUTO,
    *,
    flags: dict[str, Any],
) -> None:
    """Write NAME.step, NAME.dxf, NAME.json, NAME-3d.png and NAME-flat.svg per template.

    Flags override the templates' values (without a template they override
    the default template). Files are written under temporary names and moved
    into OUTDIR only when every design of the call succeeded.
    """
    refs = list(templates or [])
    step_body = None if Body(body) is Body.AUTO else Body(body).value
    if name is not None and len(refs) > 1:
        raise InvalidParameterError("--name", f"needs exactly one template, got {len(refs)}")
    designs = load_designs(refs, Overrides(**flags, name=name))
    stems = [d.name for d in designs]
    dup = sorted({s for s in stems if stems.count(s) > 1})
    if dup:
        raise InvalidParameterError(
            "templates", f"two templates share the name {dup[0]!r}; their files would collide"
        )
    from onefold_cad.export.flat_pattern import flat_pattern
    from onefold_cad.export.step import default_body

    # Every design solves and has a valid flat pattern before any file is written.
    solved = [(d, build_design(d)) for d in designs]
    for d, f in solved:
        flat_pattern(d, f)
    created = not outdir.exists()
    try:
        outdir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InvalidParameterError(
            "--outdir", f"cannot create {str(outdir)!r}: {exc.strerror}"
        ) from None
    n = len(solved)
    staging = Path(tempfile.mkdtemp(prefix=".onefold-", suffix=".partial", dir=outdir))
    try:
        staged: list[Path] = []
        for i, (design, folded) in enumerate(solved, 1):
            t0 = time.perf_counter()
            staged += _stage_design(design, folded, staging / str(i), step_body)
            kind = step_body or default_body(design)
            typer.echo(
                f"[{i}/{n}] {design.name} done in {time.perf_counter() - t0:.1f} s (STEP {kind})",
                err=True,
            )
        # Every file of every design exists: only now do they move into place.
        mode = 0o666 & ~_umask()
        for p in staged:
            os.chmod(p, mode)  # temp files are private (0600); give them the usual mode
            os.replace(p, outdir / p.name)
            typer.echo(str(outdir / p.name))
    finally:
        shutil.rmtree(staging, ignore_errors=True)
        if created and not any(outdir.iterdir()):
            outdir.rmdir()


@app.command()
@with_design_flags
def solve(
    template: Annotated[
        str | None,
        typer.Argument(
            metavar="[TEMPLATE.toml]",
            help=f"Template file or shipped template name (default: {DEFAULT_TEMPLATE}).",
            show_default=False,
        ),
    ] = None,
    json_: Annotated[bool, typer.Option("--json", help="Print the JSON report.")] = False,
    *,
    flags: dict[str, Any],
) -> None:
    """Solve a design and print the result (nothing is written)."""
    from onefold_cad.export.report import design_report, report_json

    (design,) = load_designs([template] if template else [], Overrides(**flags))
    report = design_report(design, build_design(design))
    typer.echo(report_json(report) if json_ else _summary(report), nl=not json_)


@app.command("templates")
def templates_cmd() -> None:
    """List the shipped templates, one line each: name and description."""
    infos = list_templates()
    width = max((len(t.name) for t in infos), default=0)
    for t in infos:
        typer.echo(f"{t.name:<{width}}  {t.description}")


@app.command()
def fit(
    template: Annotated[
        str,
        typer.Argument(
            metavar="TEMPLATE", help="Template file or shipped template name: sheet and material."
        ),
    ],
    height: Annotated[
        float, typer.Option(help="Height of the form as it rests on the ground, > 0.")
    ],
    span: Annotated[
        float,
        typer.Option(help="Footprint width of the resting form (along its x axis), > 0."),
    ],
    depth: Annotated[
        float | None,
        typer.Option(help="Footprint depth of the resting form (along its y axis), > 0."),
    ] = None,
    min_tipping_margin: Annotated[
        float | None,
        typer.Option(
            "--min-tipping-margin", metavar="DEG", help="Smallest tipping margin allowed, deg."
        ),
    ] = None,
    json_: Annotated[bool, typer.Option("--json", help="Print the result as JSON.")] = False,
    outdir: Annotated[
        Path | None,
        typer.Option("-o", "--outdir", help="Build the found design into this folder."),
    ] = None,
) -> None:
    """Find alpha, beta and h_c whose resting form has the target height and span.

    The template's sheet, material and model are kept; lengths are in its
    unit. Each target is met within 0.5 %; a target out of reach is an error
    that gives the ranges the template's sheet can reach.
    """
    import contextlib
    import json

    from onefold_cad.fit import fit_design

    (design,) = load_designs([template], Overrides())
    result = fit_design(design, height, span, depth, min_tipping_margin)
    f = result.design.frame
    if outdir is not None:  # the build's list of files goes to stderr under --json
        with contextlib.redirect_stdout(sys.stderr) if json_ else contextlib.nullcontext():
            build(templates=[template], outdir=outdir, alpha=f.alpha, beta=f.beta, hc=f.h_c)
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
    if json_:
        typer.echo(json.dumps(data, indent=2, allow_nan=False))
        return
    typer.echo(
        f"{design.name}: alpha {f.alpha:.6g} deg, beta {f.beta:.6g} deg, h_c {f.h_c:.6g} {u}"
    )
    for key, got in (("height", result.height), ("span", result.span), ("depth", result.depth)):
        want = result.targets.get(key)
        aim = f" (target {want:.6g}, {100 * abs(got - want) / want:.2g} %)" if want else ""
        typer.echo(f"  {key:<15} {got:.6g} {u}{aim}")
    typer.echo(f"  tipping margin  {result.tipping_margin_deg:.3g} deg ({result.body})")


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``onefold`` command with ``argv`` (default: ``sys.argv[1:]``).

    Returns:
        The exit status: 0 on success, 2 on bad input (one line on stderr).
    """
    args = list(sys.argv[1:] if argv is None else argv)
    command = typer.main.get_command(app)
    try:
        rv = command.main(args=args or ["--help"], prog_name="onefold", standalone_mode=False)
    except OneFoldError as exc:
        typer.echo(f"onefold: error: {_one_line(str(exc))}", err=True)
        return 2
    except typer.TyperException as exc:  # click usage errors: bad option, value, choice
        typer.echo(f"onefold: error: {_one_line(exc.format_message())}", err=True)
        return 2 if getattr(exc, "exit_code", 1) in (1, 2) else int(exc.exit_code)
    except typer.Abort:
        typer.echo("onefold: aborted", err=True)
        return 1
    except KeyboardInterrupt:
        return 130
    return rv if isinstance(rv, int) else 0
