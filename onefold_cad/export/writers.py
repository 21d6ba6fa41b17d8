"""The files ``onefold build`` can write: one :class:`Writer` per format.

``WRITERS`` is the registry behind ``--formats``: a name (``step``), the
file's suffix after the design name (``.step``), the progress label and a
function ``write(context, path)``. A new output format registers a writer
here; the CLI needs no change. Each writer imports its adapter (build123d,
ezdxf, matplotlib) only when it runs.

The JSON report is written last (it lists the other files and their
timings). Writers marked ``needs_flat_pattern`` refuse, before anything is
written, a design whose flat pattern cannot be made. What the writers share
is computed once, held by the build's
:class:`~onefold_cad.export.build_context.BuildContext`. A writer whose
library is an optional extra (``requires``, rhino3dm for the .3dm) is left
out of the default (all) when the library is not installed, and refused by
name.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from importlib.util import find_spec
from pathlib import Path
from typing import TYPE_CHECKING, Any

from onefold_cad.errors import InvalidParameterError, OneFoldError, not_installed
from onefold_cad.export.brep.part_numbers import part_numbers
from onefold_cad.export.build_context import BuildContext

if TYPE_CHECKING:  # the parser reads the registry: no numpy before a writer runs
    from onefold_cad.design import Design

__all__ = [
    "WRITERS",
    "BuildContext",
    "context_report",
    "Writer",
    "files_help",
    "parse_formats",
    "register",
    "write_design",
]


@dataclass(frozen=True)
class Writer:
    """One output format.

    Attributes:
        name: the ``--formats`` name.
        suffix: what follows the design name in the file name.
        stage: the progress label.
        write: ``write(context, path)`` writes the file at ``path``.
        cuts_sheet: the file describes the part to make (STEP, DXF, FOLD,
            flat preview): refuse (before anything is written) a relief hole that
            does not fit the sheet.
        needs_flat_pattern: refuse (before anything is written) when the
            flat pattern cannot be made.
        builds_part: the file holds the STEP's part (:attr:`BuildContext.part`):
            refuse (before anything is written) what the part's builder
            refuses for fabrication (a relief hole that does not fit, a solid
            past the bend model's limits).
        what: what the file is for, one line (``onefold build --help``).
        requires: the module the writer needs from an optional extra ('' for
            none): without it the default (all) leaves the writer out and
            naming it is refused.
        extra: the package's optional extra that brings ``requires``
            (``pip install 'onefold_cad[EXTRA]'``).
        in_all: whether ``--formats all`` (the default) names it; one that
            is not is written when named (and ``cones`` where the cones are
            formed past their springback: :func:`parse_formats`).
    """

    name: str
    suffix: str
    stage: str
    write: Callable[[BuildContext, Path], Any]
    cuts_sheet: bool = False
    needs_flat_pattern: bool = False
    builds_part: bool = False
    what: str = ""
    requires: str = ""
    extra: str = ""
    in_all: bool = True

    @property
    def available(self) -> bool:
        """Its required module is installed (found, not imported)."""
        return not self.requires or find_spec(self.requires) is not None


#: name -> writer, in writing order (the report, 'json', is always written last).
WRITERS: dict[str, Writer] = {}


def register(writer: Writer) -> Writer:
    """Add ``writer`` to :data:`WRITERS` (replacing one of the same name)."""
    WRITERS[writer.name] = writer
    return writer


def _step(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export.brep import step

    return step.export_design_step(ctx.design, path, folded=ctx.folded, part=ctx.part)


def _dxf(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export.dxf import pattern as dxf

    return dxf.export_design_dxf(ctx.design, path, folded=ctx.folded, compensation=ctx.compensation)


def _cut(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export.dxf import cut as cut_dxf

    return cut_dxf.export_design_cut_dxf(
        ctx.design, path, folded=ctx.folded, compensation=ctx.compensation
    )


def _bends(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export import bend_csv

    return bend_csv.write_bend_csv(ctx.pattern, path)


def _cones(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export import cone_csv

    return cone_csv.write_cone_csv(ctx.design, path, ctx.folded)


def _fold(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export.fold import file as fold_file

    return fold_file.write_fold(ctx.design, ctx.folded, path)


def _glb(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export import glb

    return glb.write_glb(ctx.design, ctx.folded, path, part=ctx.part)


def _rhino(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export.rhino import file as rhino3dm_file

    model = rhino3dm_file.write_3dm(
        ctx.design,
        ctx.folded,
        path,
        pattern=ctx.pattern,
        placement=ctx.placement,
        body=ctx.body,
        compensation=ctx.compensation,
    )
    ctx.sections["rhino"] = {
        "placement": ctx.placement,
        "faces": model.faces,
        "fit_deviation": float(model.fit_deviation),
        "fit_tolerance": float(model.fit_tolerance),
    }
    return model


def _png(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export.pictures import preview

    d = ctx.design
    return preview.render_folded_preview(
        ctx.folded,
        path,
        placement=ctx.resting,
        frame=ctx.placement == "frame",
        title=d.name,
        units=d.units.value,
    )


def _svg(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export.dxf import preview as dxf_preview

    return dxf_preview.render_preview(ctx.drawing, path)


def _json(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export.report_file import write_report

    return write_report(path, context_report(ctx))


def context_report(ctx: BuildContext) -> dict[str, Any]:
    """The design's report as its NAME.json holds it
    (:func:`~onefold_cad.fabrication.report.design_report` with what this
    build wrote and measured)."""
    from onefold_cad.fabrication.report import design_report

    try:
        pattern = ctx.pattern
    except OneFoldError:  # the report says why (a warning); it does not refuse
        pattern = None
    return design_report(
        ctx.design,
        ctx.folded,
        files=ctx.files,
        pattern=pattern,
        sources=ctx.sources,
        timings=ctx.timings,
        warnings=ctx.warnings,
        compensation=ctx.compensation,
        body=ctx.body,
        step=part_numbers(ctx),
        rhino=ctx.sections.get("rhino"),
    )


register(
    Writer(
        "step",
        ".step",
        "STEP",
        _step,
        cuts_sheet=True,
        builds_part=True,
        what="the folded part for CAD: the sheet's solid, or its surface (--body)",
    )
)
register(
    Writer(
        "dxf",
        ".dxf",
        "DXF",
        _dxf,
        cuts_sheet=True,
        needs_flat_pattern=True,
        what="the flat pattern with bend lines (angle, direction), zones and notes",
    )
)
register(
    Writer(
        "cut",
        "-cut.dxf",
        "cut DXF",
        _cut,
        cuts_sheet=True,
        needs_flat_pattern=True,
        what="the blank alone for the laser: outline and relief hole, layer CUT",
    )
)
register(
    Writer(
        "bends",
        "-bends.csv",
        "bend sheet",
        _bends,
        needs_flat_pattern=True,
        what="the bend sheet for the press brake: angle, direction, BA, BD per bend",
    )
)
register(
    Writer(
        "cones",
        "-cones.csv",
        "cone forming sheet",
        _cones,
        what="the cones' radii, designed and to form to (all: if formed past springback)",
        in_all=False,
    )
)
register(
    Writer(
        "fold",
        ".fold",
        "FOLD",
        _fold,
        cuts_sheet=True,
        what="crease pattern and folded form for origami tools (Origami Simulator)",
    )
)
register(
    Writer(
        "glb",
        ".glb",
        "GLB",
        _glb,
        builds_part=True,
        what="the folded form for web viewers and Blender (glTF, metres, y up)",
    )
)
register(
    Writer(
        "3dm",
        ".3dm",
        "Rhino 3DM",
        _rhino,
        cuts_sheet=True,
        needs_flat_pattern=True,
        what="the exact folded faces and the flat pattern in layers, for Rhino 8",
        requires="rhino3dm",
        extra="rhino",
    )
)
register(
    Writer(
        "png",
        "-3d.png",
        "3D preview",
        _png,
        what="a picture of the form as it stands, with a legend",
    )
)
register(
    Writer(
        "svg",
        "-flat.svg",
        "flat preview",
        _svg,
        cuts_sheet=True,
        needs_flat_pattern=True,
        what="a picture of the flat pattern at true size",
    )
)
register(
    Writer(
        "json",
        ".json",
        "report",
        _json,
        what="the report: material and sources, angles, bends, sizes, mass, warnings",
    )
)


def files_help() -> str:
    """The files ``build`` writes, one line each: the ``--formats`` name, the
    file name and what it is for (from :data:`WRITERS`)."""
    width = max(len(f"NAME{w.suffix}") for w in WRITERS.values())
    return "\n".join(
        f"  {w.name:<6} NAME{w.suffix:<{width - 4}}  {w.what}" for w in WRITERS.values()
    )


def parse_formats(
    text: str | None,
    registry: Mapping[str, Any] | None = None,
    flag: str = "--formats",
    designs: Sequence[Design] = (),
) -> tuple[str, ...]:
    """The writers named by ``--formats`` ('step,dxf,...'; None or 'all' for
    every one whose required package is installed), in writing order with
    the report last; all leaves out the writers not ``in_all``, but names
    ``cones`` where one of ``designs`` has its cones formed past their
    springback. ``registry``: the writers to pick from (default
    :data:`WRITERS`; ``onefold site`` passes its own), each with ``available``
    and ``requires``; ``flag`` names the option in errors.

    Raises:
        InvalidParameterError: an unknown or repeated name (the message lists
            the allowed ones), or one whose required package is missing.
    """
    writers: Mapping[str, Any] = WRITERS if registry is None else registry
    allowed = ", ".join(writers)
    if text is None or text.strip().lower() == "all":
        cones = any(d.material.cones_compensated for d in designs)
        names = [
            n
            for n, w in writers.items()
            if w.available and (getattr(w, "in_all", True) or (n == "cones" and cones))
        ]
    else:
        names = [n.strip().lower() for n in text.split(",") if n.strip()]
        if not names:
            raise InvalidParameterError(flag, f"names no format (allowed: {allowed})")
        for n in names:
            if n not in writers:
                raise InvalidParameterError(
                    flag, f"unknown format {n!r} (allowed: {allowed}, or all)"
                )
            if names.count(n) > 1:
                raise InvalidParameterError(flag, f"{n!r} is named twice")
            if not writers[n].available:
                w = writers[n]
                raise InvalidParameterError(flag, not_installed(repr(n), [w.requires], w.extra))
    order = [n for n in writers if n in names and n != "json"]
    return (*order, "json") if "json" in names else tuple(order)


def file_names(stem: str, formats: Sequence[str]) -> list[str]:
    """The file names ``formats`` give for the design named ``stem``."""
    return [f"{stem}{WRITERS[n].suffix}" for n in formats]


def write_design(
    ctx: BuildContext,
    folder: Path,
    formats: Sequence[str],
    progress: Callable[[str, float], None] | None = None,
) -> list[Path]:
    """Write the files of ``formats`` for ``ctx.design`` into ``folder`` (created
    here); call ``progress(stage, seconds)`` as each finishes; return the files."""
    folder.mkdir()
    ctx.files = [folder / name for name in file_names(ctx.design.name, formats)]
    for name, path in zip(formats, ctx.files, strict=True):
        writer = WRITERS[name]
        t0 = time.perf_counter()
        writer.write(ctx, path)
        ctx.timings[name] = time.perf_counter() - t0
        if progress is not None:
            label = writer.stage
            if name == "step":
                label += f" ({ctx.body or _default_body(ctx.design)})"
            progress(label, ctx.timings[name])
    return ctx.files


def _default_body(design: Design) -> str:
    from onefold_cad.fabrication.rules import default_body

    return default_body(design)
