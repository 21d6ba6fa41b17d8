"""The files ``onefold build`` can write: one :class:`Writer` per format.

``WRITERS`` is the registry behind ``--formats``: a name (``step``), the
file's suffix after the design name (``.step``), the progress label and a
function ``write(context, path)``. A new output format registers a writer
here; the CLI needs no change. Each writer imports its adapter (build123d,
ezdxf, matplotlib) only when it runs.

The JSON report is written last (it lists the other files and their
timings). Writers marked ``needs_flat_pattern`` refuse, before anything is
written, a design whose flat pattern cannot be made. What the writers share
is computed once: the flat pattern and the resting placement through the
package's one cache of a fold's results (:func:`onefold_cad.design.derived`),
and the CAD products of this build, the STEP's part (shared with the GLB,
``builds_part``) and the flat pattern's ezdxf drawing, held by the
:class:`BuildContext` while the design's files are written (they are freed
with it).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any

from onefold_cad.choices import Compensation, Placement
from onefold_cad.errors import InvalidParameterError, OneFoldError

if TYPE_CHECKING:  # the parser reads the registry: no numpy before a writer runs
    from onefold_cad.design import Design
    from onefold_cad.fabrication.flat_pattern import FlatPattern
    from onefold_cad.geometry.folding import FoldedSheet
    from onefold_cad.geometry.placement import RestingPlacement

__all__ = [
    "WRITERS",
    "BuildContext",
    "Writer",
    "files_help",
    "parse_formats",
    "register",
    "write_design",
]


@dataclass
class BuildContext:
    """One design being built: its fold, options and what writers share.

    Attributes:
        design: the design.
        folded: ``build_design(design)``.
        body: the STEP body ('solid', 'shell') or None for the default.
        compensation: 'sharp' (bend compensation) or 'none'.
        sources: where each input came from (for the report).
        warnings: warnings found before writing (for the report).
        files: every file of the design, in writing order (the report lists them).
        timings: seconds per stage, filled in as the writers finish.
        placement: where the STEP, the GLB and the 3D preview put the form:
            'rest' (standing on the ground) or 'frame' (the fold frame).
    """

    design: Design
    folded: FoldedSheet
    body: str | None = None
    compensation: str = Compensation.SHARP.value
    sources: Mapping[str, str] = field(default_factory=dict)
    warnings: Sequence[str] = ()
    files: list[Path] = field(default_factory=list)
    timings: dict[str, float] = field(default_factory=dict)
    placement: str = Placement.REST.value

    @property
    def pattern(self) -> FlatPattern:
        """The flat pattern (raises when it cannot be made;
        :func:`~onefold_cad.fabrication.flat_pattern.flat_pattern_once`)."""
        from onefold_cad.fabrication.flat_pattern import flat_pattern_once

        return flat_pattern_once(self.design, self.folded, self.compensation)

    @property
    def resting(self) -> RestingPlacement:
        """How the STEP's body stands (:func:`onefold_cad.fabrication.rules.resting_placement`)."""
        from onefold_cad.fabrication.rules import resting_placement

        return resting_placement(self.design, self.folded, self.body)

    @cached_property
    def part(self) -> Any:
        """The STEP's part (build123d shape, :func:`onefold_cad.export.part.build_part`
        with this body, placement and compensation), built once for this
        build: the STEP and the GLB writers write this one part."""
        from onefold_cad.export.part import build_part

        return build_part(
            self.design,
            self.folded,
            body=self.body,
            placement=self.placement,
            compensation=self.compensation,
        )

    @property
    def built_part(self) -> Any | None:
        """:attr:`part` if a writer has built it already, else None (never builds)."""
        return self.__dict__.get("part")

    @cached_property
    def drawing(self) -> Any:
        """The flat pattern as an ezdxf document (for the flat preview), drawn once
        for this build."""
        from onefold_cad.export.dxf import draw_flat_pattern

        return draw_flat_pattern(self.pattern)


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
    """

    name: str
    suffix: str
    stage: str
    write: Callable[[BuildContext, Path], Any]
    cuts_sheet: bool = False
    needs_flat_pattern: bool = False
    builds_part: bool = False
    what: str = ""


#: name -> writer, in writing order (the report, 'json', is always written last).
WRITERS: dict[str, Writer] = {}


def register(writer: Writer) -> Writer:
    """Add ``writer`` to :data:`WRITERS` (replacing one of the same name)."""
    WRITERS[writer.name] = writer
    return writer


def _step(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export import step

    return step.export_design_step(ctx.design, path, folded=ctx.folded, part=ctx.part)


def _dxf(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export import dxf

    return dxf.export_design_dxf(ctx.design, path, folded=ctx.folded, compensation=ctx.compensation)


def _cut(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export import cut_dxf

    return cut_dxf.export_design_cut_dxf(
        ctx.design, path, folded=ctx.folded, compensation=ctx.compensation
    )


def _bends(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export import bend_csv

    return bend_csv.write_bend_csv(ctx.pattern, path)


def _fold(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export import fold_file

    return fold_file.write_fold(ctx.design, ctx.folded, path)


def _glb(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export import glb

    return glb.write_glb(ctx.design, ctx.folded, path, part=ctx.part)


def _png(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export import preview

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
    from onefold_cad.export import dxf_preview

    return dxf_preview.render_preview(ctx.drawing, path)


def _json(ctx: BuildContext, path: Path) -> Any:
    from onefold_cad.export.report_file import write_report
    from onefold_cad.fabrication.report import design_report

    try:
        pattern = ctx.pattern
    except OneFoldError:  # the report says why (a warning); it does not refuse
        pattern = None
    report = design_report(
        ctx.design,
        ctx.folded,
        files=ctx.files,
        pattern=pattern,
        sources=ctx.sources,
        timings=ctx.timings,
        warnings=ctx.warnings,
        compensation=ctx.compensation,
        body=ctx.body,
        step=_part_numbers(ctx),
    )
    return write_report(path, report)


def _part_numbers(ctx: BuildContext) -> dict[str, Any] | None:
    """The report's ``step`` section when a writer built the part (else None:
    the report never runs the CAD kernel)."""
    part = ctx.built_part
    if part is None:
        return None
    return {
        "body": ctx.body or _default_body(ctx.design),
        "placement": ctx.placement,
        "fit_deviation": float(part.fit_deviation),
        "fit_tolerance": float(part.fit_tolerance),
    }


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


def parse_formats(text: str | None) -> tuple[str, ...]:
    """The writers named by ``--formats`` ('step,dxf,...'; None or 'all' for
    every one), in writing order with the report last.

    Raises:
        InvalidParameterError: an unknown or repeated name (the message lists
            the allowed ones).
    """
    allowed = ", ".join(WRITERS)
    if text is None or text.strip().lower() == "all":
        names = list(WRITERS)
    else:
        names = [n.strip().lower() for n in text.split(",") if n.strip()]
        if not names:
            raise InvalidParameterError("--formats", f"names no format (allowed: {allowed})")
        for n in names:
            if n not in WRITERS:
                raise InvalidParameterError(
                    "--formats", f"unknown format {n!r} (allowed: {allowed}, or all)"
                )
            if names.count(n) > 1:
                raise InvalidParameterError("--formats", f"{n!r} is named twice")
    order = [n for n in WRITERS if n in names and n != "json"]
    return (*order, "json") if "json" in names else tuple(order)


def file_names(stem: str, formats: Sequence[str]) -> list[str]:
    """The file names ``formats`` give for the design named ``stem``."""
    return [f"{stem}{WRITERS[n].suffix}" for n in formats]


def check_before_writing(ctx: BuildContext, formats: Sequence[str]) -> None:
    """Raise what a writer of ``formats`` would refuse, before any file exists:
    a relief hole that does not fit
    (:func:`~onefold_cad.fabrication.relief_hole.relief_hole_problem`),
    the flat pattern (FabricationError or InvalidParameterError) and, with
    ``--compensation sharp``, a STEP solid past the bend model's limits."""
    part = any(WRITERS[n].builds_part for n in formats)
    if part or any(WRITERS[n].cuts_sheet for n in formats):
        from onefold_cad.fabrication.relief_hole import relief_hole_problem

        problem = relief_hole_problem(ctx.design, ctx.folded)
        if problem is not None:
            raise problem
    if any(WRITERS[n].needs_flat_pattern for n in formats):
        ctx.pattern  # noqa: B018 - computed (and cached) to raise now
    if part:
        _check_solid_bends(ctx)


def _check_solid_bends(ctx: BuildContext) -> None:
    """The refusal the part's builder gives a solid past the bend model's
    limits (:func:`onefold_cad.export.part.build_part`, through
    :func:`~onefold_cad.fabrication.rules.solid_bend_problem`), raised before anything
    is written; a shell, the designed surface, is always written."""
    if (ctx.body or _default_body(ctx.design)) != "solid":
        return
    from onefold_cad.fabrication.rules import solid_bend_problem

    problem = solid_bend_problem(ctx.design, ctx.folded, ctx.compensation)
    if problem is not None:
        raise problem


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
