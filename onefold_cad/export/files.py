"""A design's files from a script: one file by its suffix, or a set of them
committed at once as ``onefold build`` commits its own.

:func:`stage_files` is the one way a build's files reach an output folder:
a dead run's leftovers recovered, the targets checked, the files written
into a private staging folder, then moved in all together
(:class:`~onefold_cad.export.atomic.Staging`, the journal of
:mod:`~onefold_cad.export.commit_steps`). ``onefold build`` and
:func:`write_files` both call it; :func:`export_file` writes one file
atomically, through the same writers.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from pathlib import Path

from onefold_cad.choices import Body, Compensation, Placement
from onefold_cad.design import Design, fold_design
from onefold_cad.errors import InvalidParameterError
from onefold_cad.export.atomic import Staging, check_targets, recover
from onefold_cad.export.build_context import BuildContext
from onefold_cad.export.commit_steps import FileSet, pause_point
from onefold_cad.export.write_checks import check_before_writing
from onefold_cad.export.writers import WRITERS, file_names, parse_formats, write_design

__all__ = ["SUFFIXES", "export_file", "stage_files", "write_files"]

#: The writer :func:`export_file` picks for a path's suffix.
SUFFIXES = {
    ".step": "step",
    ".dxf": "dxf",
    ".csv": "bends",
    ".fold": "fold",
    ".glb": "glb",
    ".3dm": "3dm",
    ".json": "json",
    ".svg": "svg",
    ".png": "png",
}


def stage_files(
    outdir: Path,
    stems: Sequence[str],
    formats: Sequence[str],
    write: Callable[[Staging], list[Path]],
    say: Callable[[str], None] | None = None,
    staged: Callable[[Staging], None] | None = None,
) -> tuple[list[Path], list[Path]]:
    """Write the files of the designs named ``stems`` into ``outdir`` (it
    exists) all at once.

    Args:
        outdir: the output folder.
        stems: the designs' names (their files' stems).
        formats: the writers' names (:data:`~onefold_cad.export.writers.WRITERS`).
        write: writes the files under ``staging.path`` and returns them.
        say: called with one line per leftover of a dead run that is cleaned.
        staged: called with the staging area before anything is written (the
            command line keeps it to say what an interruption left).

    Returns:
        The paths written, and the files of earlier runs of these designs
        that the commit removed and nothing replaced.

    Raises:
        ExportError: a target is blocked (nothing is written) or a step failed.
    """
    recover(outdir, say=say)
    check_targets(outdir, [f for s in stems for f in file_names(s, formats)])
    with Staging(outdir, say=say) as staging:
        if staged is not None:
            staged(staging)
        files = write(staging)
        pause_point("staged")
        sets = [FileSet(s, tuple(file_names(s, list(WRITERS)))) for s in stems]
        done = staging.commit(files, sets=sets)
        return done, list(staging.removed)


def _context(
    design: Design,
    body: Body | str | None,
    compensation: Compensation | str,
    placement: Placement | str,
) -> BuildContext:
    return BuildContext(
        design,
        fold_design(design),
        None if body is None else Body.parse(body),
        Compensation.parse(compensation),
        placement=Placement.parse(placement),
    )


def write_files(
    design: Design,
    folder: str | os.PathLike[str],
    formats: Sequence[str] | str | None = None,
    *,
    body: Body | str | None = None,
    compensation: Compensation | str = Compensation.SHARP,
    placement: Placement | str = Placement.REST,
) -> list[Path]:
    """Write the files of ``design`` into ``folder``, all or nothing, as
    ``onefold build DESIGN -o FOLDER --formats ...`` does.

    Args:
        design: the design (its name is the files' stem).
        folder: the output folder (made with its parents when missing).
        formats: writer names (``["step", "dxf"]`` or ``"step,dxf"``); None:
            every format whose library is installed.
        body: 'shell' or 'solid' for the STEP and GLB; None: the default
            (the solid when the design has thickness and a relief hole).
        compensation: 'sharp' (the blank compensates the bends) or 'none'.
        placement: 'rest' (standing on the ground) or 'frame' (fold frame).

    Returns:
        The files written, the report last.

    Raises:
        InvalidParameterError: an unknown format or option, or a design a
            writer refuses (named before anything is written).
        FabricationError: the flat pattern passes the bend model's limits.
        ExportError: a file could not be written (the folder is as it was).
    """
    names = formats if formats is None or isinstance(formats, str) else ",".join(formats)
    chosen = parse_formats(names, flag="formats", designs=[design])
    ctx = _context(design, body, compensation, placement)
    check_before_writing(ctx, chosen)
    out = Path(folder)
    out.mkdir(parents=True, exist_ok=True)
    written, _ = stage_files(
        out, [design.name], chosen, lambda staging: write_design(ctx, staging.path / "1", chosen)
    )
    return written


def export_file(
    design: Design,
    path: str | os.PathLike[str],
    *,
    body: Body | str | None = None,
    compensation: Compensation | str = Compensation.SHARP,
    placement: Placement | str = Placement.REST,
) -> Path:
    """Write one file of ``design``, its writer chosen by the suffix of ``path``.

    The file holds what ``onefold build`` writes for that format (a ``.dxf``
    is the annotated flat pattern, a ``.csv`` the bend sheet, a ``.png`` the
    3D picture, a ``.svg`` the flat pattern at true size).

    Args:
        design: the design.
        path: the file to write (atomically; its folder must exist).
        body, compensation, placement: as :func:`write_files`'s.

    Returns:
        The path written.

    Raises:
        InvalidParameterError: ('path') a suffix no writer has, naming the
            allowed ones; or a design the writer refuses.
        ExportError: the file could not be written.
    """
    target = Path(path)
    name = SUFFIXES.get(target.suffix.lower())
    if name is None:
        allowed = ", ".join(SUFFIXES)
        raise InvalidParameterError(
            "path", f"{str(target)!r}: no writer for the suffix {target.suffix!r} ({allowed})"
        )
    (name,) = parse_formats(name, flag="path")  # refused by name if its library is missing
    ctx = _context(design, body, compensation, placement)
    check_before_writing(ctx, [name])
    ctx.files = [target]
    WRITERS[name].write(ctx, target)
    return target
