"""The files ``onefold site`` writes for the site as a whole: one
:class:`SiteWriter` per file, the registry :data:`SITE_WRITERS` behind its
``--formats``. Each sheet's own files are ``onefold build``'s
(:data:`onefold_cad.export.writers.WRITERS`), in DIR/NAME/.

Every writer reads the :class:`~onefold_cad.export.site.context.SiteContext`
(the sheets' parts, placements and reports) and imports its library only
when it runs; none re-derives a sheet's geometry.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from importlib.util import find_spec
from pathlib import Path
from typing import Any

from onefold_cad.export.site.context import SiteContext

__all__ = ["SITE_WRITERS", "SiteWriter", "site_file_names", "site_files_help", "site_report"]


@dataclass(frozen=True)
class SiteWriter:
    """One file of the site.

    Attributes:
        name: the ``--formats`` name.
        suffix: what follows the site's name in the file name.
        stage: the progress label.
        write: ``write(context, path)`` writes the file at ``path``.
        what: what the file is for, one line.
        requires: the module it needs from an optional extra ('' for none).
        extra: the optional extra that brings it (``pip install
            'onefold_cad[EXTRA]'``).
    """

    name: str
    suffix: str
    stage: str
    write: Callable[[SiteContext, Path], Any]
    what: str = ""
    requires: str = ""
    extra: str = ""

    @property
    def available(self) -> bool:
        """Its required module is installed (found, not imported)."""
        return not self.requires or find_spec(self.requires) is not None


def _step(ctx: SiteContext, path: Path) -> Any:
    from onefold_cad.choices import Units
    from onefold_cad.export.brep.step import export_site_step

    return export_site_step([s.placed for s in ctx.sheets], Units.parse(ctx.units), path, ctx.name)


def _glb(ctx: SiteContext, path: Path) -> Any:
    from onefold_cad.choices import Units
    from onefold_cad.export.glb import write_site_glb

    parts = [s.placed for s in ctx.sheets]
    return write_site_glb(parts, Units.parse(ctx.units), path, ctx.size, ctx.name)


def _ifc(ctx: SiteContext, path: Path) -> Any:
    from onefold_cad.export.site.ifc import write_site_ifc

    result = write_site_ifc(ctx, path)
    ctx.sections["ifc"] = result.to_data()
    return result


def _plan(ctx: SiteContext, path: Path) -> Any:
    from onefold_cad.export.site.plan import write_site_plan

    return write_site_plan(ctx, path)


def _order(ctx: SiteContext, path: Path) -> Any:
    from onefold_cad.export.site.order import write_order_csv

    return write_order_csv([(s.name, s.report) for s in ctx.sheets], path)


def _json(ctx: SiteContext, path: Path) -> Any:
    import json

    from onefold_cad.export.atomic import atomic_output

    text = json.dumps(site_report(ctx), indent=2, allow_nan=False) + "\n"
    with atomic_output(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return path


def site_report(ctx: SiteContext) -> dict[str, Any]:
    """The site's report (SITE.json): its sheets where they stand (the site
    file's placement, height, footprint size, mass from each report), every
    pair's clearance (length, in the site's unit) and what the writers said
    of their files (the IFC's geometry and deviation)."""
    c = ctx.clearance
    pairs = [] if c is None else c.pairs
    smallest = None if c is None else c.smallest
    return {
        "name": ctx.name,
        "description": ctx.description,
        "units": ctx.units,
        "sheets": [
            {
                "name": s.name,
                "x": s.site.x,
                "y": s.site.y,
                "rotation_deg": s.site.rotation_deg,
                "height": s.report["resting"]["height"],
                "mass": s.report["mass"],
                "files": [f"{s.name}/{f}" for f in s.report["files"]],
            }
            for s in ctx.sheets
        ],
        "clearance": {
            "pairs": [
                {
                    "a": p.a,
                    "b": p.b,
                    "distance": p.distance,
                    "point_a": [float(v) for v in p.point_a],
                    "point_b": [float(v) for v in p.point_b],
                    "touching": p.touching,
                    "footprint_overlap": p.footprint_overlap,
                }
                for p in pairs
            ],
            "smallest": None
            if smallest is None
            else {"a": smallest.a, "b": smallest.b, "distance": smallest.distance},
            "accuracy": None if c is None else c.accuracy,
        },
        **ctx.sections,
        "files": [p.name for p in ctx.files],
    }


def _png(ctx: SiteContext, path: Path) -> Any:
    from onefold_cad.export.site.picture import render_site_picture

    return render_site_picture(ctx, path)


#: name -> writer, in writing order.
SITE_WRITERS: dict[str, SiteWriter] = {
    w.name: w
    for w in (
        SiteWriter("step", ".step", "site STEP", _step,
                   "one STEP assembly, each sheet a named part where it stands"),
        SiteWriter("glb", ".glb", "site GLB", _glb,
                   "one glTF scene, a node per sheet (metres, y up)"),
        SiteWriter("ifc", ".ifc", "site IFC", _ifc,
                   "IFC4 for BIM: project, site, each sheet an IfcPlate with its material",
                   requires="ifcopenshell", extra="bim"),
        SiteWriter("plan", "-plan.dxf", "site plan", _plan,
                   "the plan: footprints, ground contacts, names, distances to neighbours"),
        SiteWriter("order", "-order.csv", "order", _order,
                   "the bill of materials: stock, gauge, blank, mass, cut length, bends"),
        SiteWriter("png", ".png", "site picture", _png, "a picture of every sheet as it stands"),
        SiteWriter("json", ".json", "site report", _json,
                   "the site's report: placements, clearances, the IFC's deviation"),
    )
}  # fmt: skip


def site_file_names(stem: str, formats: Sequence[str]) -> list[str]:
    """The site's file names for ``formats``."""
    return [f"{stem}{SITE_WRITERS[n].suffix}" for n in formats]


def site_files_help() -> str:
    """The site's files, one line each (``onefold site --help``)."""
    width = max(len(f"SITE{w.suffix}") for w in SITE_WRITERS.values())
    return "\n".join(
        f"  {w.name:<6} SITE{w.suffix:<{width - 4}}  {w.what}" for w in SITE_WRITERS.values()
    )
