"""What the writers would refuse, raised before any file of a build exists
(:func:`check_before_writing`, for ``onefold build`` and the other commands
that write a design's files)."""

from __future__ import annotations

from collections.abc import Sequence

from onefold_cad.export.build_context import BuildContext

__all__ = ["check_before_writing"]


def check_before_writing(ctx: BuildContext, formats: Sequence[str]) -> None:
    """Raise what a writer of ``formats`` would refuse, before any file exists:
    a relief hole that does not fit
    (:func:`~onefold_cad.fabrication.relief_hole.relief_hole_problem`),
    the flat pattern (FabricationError or InvalidParameterError), a STEP
    shell the kernel cannot be given and, with ``--compensation sharp``, a
    STEP solid past the bend model's limits."""
    from onefold_cad.export.writers import WRITERS

    part = any(WRITERS[n].builds_part for n in formats)
    if part or any(WRITERS[n].cuts_sheet for n in formats):
        from onefold_cad.fabrication.relief_hole import relief_hole_problem

        problem = relief_hole_problem(ctx.design, ctx.folded)
        if problem is not None:
            raise problem
    if any(WRITERS[n].needs_flat_pattern for n in formats):
        ctx.pattern  # noqa: B018 - computed (and cached) to raise now
    if "cones" in formats:
        from onefold_cad.mechanics.cone_forming import check_cone_sheet

        check_cone_sheet(ctx.design)
    if part:
        _check_part(ctx)


def _check_part(ctx: BuildContext) -> None:
    """The refusals the part's builder gives before any kernel call
    (:func:`onefold_cad.export.brep.part.build_part`), raised before anything is
    written: a shell's H too close to the sheet's boundary or a relief hole
    below the kernel's resolution
    (:func:`~onefold_cad.export.brep.step_checks.shell_problem`), a solid past
    the bend model's limits
    (:func:`~onefold_cad.fabrication.rules.solid_bend_problem`)."""
    from onefold_cad.fabrication.rules import default_body

    if (ctx.body or default_body(ctx.design)) != "solid":
        from onefold_cad.export.brep.step_checks import shell_problem
        from onefold_cad.fabrication.relief_hole import relief_hole_diameter

        shell = shell_problem(ctx.folded, relief_hole_diameter(ctx.design, ctx.folded))
        if shell is not None:
            raise shell
        return
    from onefold_cad.fabrication.rules import solid_bend_problem

    problem = solid_bend_problem(ctx.design, ctx.folded, ctx.compensation)
    if problem is not None:
        raise problem
