"""One site being built by ``onefold site``: its sheets as they stand and what
the site's writers share (:class:`SiteContext`).

Each sheet's part is the one its own STEP holds (built by
:func:`onefold_cad.export.part.build_part`, standing on the ground by
:func:`onefold_cad.fabrication.rules.resting_placement`); on the site it is
turned about the vertical and moved on the ground
(:class:`onefold_cad.site.placement.SitePlacement`). Lengths in the site's unit.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import build123d as bd

    from onefold_cad.design import Design
    from onefold_cad.geometry.folding import FoldedSheet
    from onefold_cad.geometry.placement import RestingPlacement
    from onefold_cad.site.clearance import Clearance
    from onefold_cad.site.placement import SitePlacement

__all__ = ["MESH_ANGLE", "MESH_DEFLECTION", "SiteContext", "SiteSheet", "place_on_site"]

#: The sheets' meshes: the largest distance of a triangle from the part,
#: relative to the sheet's size, and the largest turn from its surface (rad).
MESH_DEFLECTION = 1e-3
MESH_ANGLE = 0.1


def place_on_site(part: bd.Shape, site: SitePlacement, label: str) -> bd.Shape:
    """``part`` (standing in its resting frame) turned about z by
    ``site.rotation_deg`` and moved by ``(site.x, site.y)``: a new shape (the
    geometry transformed) labelled ``label``, with the part's fit numbers."""
    import build123d as bd
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from OCP.gp import gp_Trsf

    m = site.matrix
    trsf = gp_Trsf()
    trsf.SetValues(*m[0], *m[1], *m[2])
    out = bd.Shape.cast(BRepBuilderAPI_Transform(part.wrapped, trsf, True).Shape())
    out.label = label
    for name in ("fit_deviation", "fit_tolerance"):
        if hasattr(part, name):
            setattr(out, name, getattr(part, name))
    return out


@dataclass(eq=False)
class SiteSheet:
    """One sheet of the site, built.

    Attributes:
        name: the sheet's name (its part's label, its folder).
        design: its design (in the site's unit).
        folded: ``fold_design(design)``.
        part: the part its own STEP holds, standing in its resting frame.
        resting: how it stands (:func:`~onefold_cad.fabrication.rules.resting_placement`).
        report: its report (:func:`~onefold_cad.fabrication.report.design_report`),
            the one its NAME.json holds.
        site: where it stands on the site.
    """

    name: str
    design: Design
    folded: FoldedSheet
    part: Any
    resting: RestingPlacement
    report: dict[str, Any]
    site: SitePlacement

    @cached_property
    def placed(self) -> Any:
        """The part where it stands on the site (build123d shape)."""
        return place_on_site(self.part, self.site, self.name)

    @cached_property
    def mesh(self) -> tuple[Any, Any]:
        """The part's triangle mesh in its resting frame, ``(vertices (k, 3),
        triangles (m, 3))``, within :data:`MESH_DEFLECTION` of the sheet's size
        and :data:`MESH_ANGLE` rad of it (:func:`onefold_cad.export.site_mesh.mesh_shape`),
        made once (the IFC's face sets)."""
        from onefold_cad.export.site_mesh import mesh_shape

        return mesh_shape(self.part, MESH_DEFLECTION * float(self.design.sheet.size), MESH_ANGLE)


@dataclass(eq=False)
class SiteContext:
    """A site being built: its sheets, their clearance and the site's files.

    Attributes:
        name: the site's name (its files' stem).
        description: the site's one line.
        units: the site's unit ('mm', 'in', 'ft').
        sheets: the sheets, in the site file's order.
        clearance: every pair's distance (None until measured).
        files: the site's files, in writing order.
        sections: what writers report of their file (the IFC's geometry kind
            and deviation).
    """

    name: str
    description: str
    units: str
    sheets: list[SiteSheet]
    clearance: Clearance | None = None
    files: list[Path] = field(default_factory=list)
    sections: dict[str, dict[str, Any]] = field(default_factory=dict)

    @property
    def size(self) -> float:
        """The largest sheet's size (length)."""
        return max(float(s.design.sheet.size) for s in self.sheets)
