"""One design being built by ``onefold build``: its fold, its options and
what its writers share (:class:`BuildContext`).

What the writers share is computed once: the flat pattern and the resting
placement through the package's one cache of a fold's results
(:func:`onefold_cad.design.derived`), and the CAD products of this build,
the STEP's part (shared with the GLB, ``builds_part``) and the flat
pattern's ezdxf drawing, held by the context while the design's files are
written (they are freed with it). The writers themselves are in
:mod:`onefold_cad.export.writers`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any

from onefold_cad.choices import Body, Compensation, Placement

if TYPE_CHECKING:  # the parser reads the registry: no numpy before a writer runs
    from onefold_cad.design import Design
    from onefold_cad.fabrication.flat_pattern import FlatPattern
    from onefold_cad.geometry.folding import FoldedSheet
    from onefold_cad.geometry.placement import RestingPlacement

__all__ = ["BuildContext"]


@dataclass
class BuildContext:
    """One design being built: its fold, options and what writers share.

    Attributes:
        design: the design.
        folded: ``fold_design(design)``.
        body: the STEP body ('solid', 'shell') or None for the default.
        compensation: 'sharp' (bend compensation) or 'none'.
        sources: where each input came from (for the report).
        warnings: warnings found before writing (for the report).
        files: every file of the design, in writing order (the report lists them).
        timings: seconds per stage, filled in as the writers finish.
        sections: what writers report of their file, by report section
            (the .3dm writer's ``rhino``).
        placement: where the STEP, the GLB, the 3DM and the 3D preview put the form:
            'rest' (standing on the ground) or 'frame' (the fold frame).
    """

    design: Design
    folded: FoldedSheet
    body: Body | None = None
    compensation: Compensation = Compensation.SHARP
    sources: Mapping[str, str] = field(default_factory=dict)
    warnings: Sequence[str] = ()
    files: list[Path] = field(default_factory=list)
    timings: dict[str, float] = field(default_factory=dict)
    placement: Placement = Placement.REST
    sections: dict[str, dict[str, Any]] = field(default_factory=dict)

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
