"""SITE-plan.dxf: the site plan seen from above, in the site's unit.

Layers:

- ``FOOTPRINT``: each sheet's footprint (the convex hull of its shadow on
  the ground, :attr:`RestingPlacement.footprint`), closed polylines;
- ``CONTACT``: where it touches the ground (:attr:`RestingPlacement.contacts`,
  small circles) and its support polygon (their convex hull);
- ``NAMES``: each sheet's name at its footprint's centre, and the site's
  name and unit;
- ``CLEARANCE``: for each sheet its nearest neighbour, a line between the
  ground projections of the two points where their smallest distance (3D,
  between the solids) is reached, and that distance.

The placements are the site's (:mod:`onefold_cad.site.placement`) applied to
each sheet's resting placement; nothing is re-derived here.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from onefold_cad.choices import Units
from onefold_cad.errors import ExportError
from onefold_cad.export.dxf.pattern import new_document, set_units, write_dxf_atomic
from onefold_cad.export.site.context import SiteContext
from onefold_cad.site.clearance import nearest_neighbours

__all__ = ["PLAN_LAYERS", "draw_site_plan", "write_site_plan"]

#: layer -> AutoCAD colour index.
PLAN_LAYERS = {"FOOTPRINT": 7, "CONTACT": 3, "NAMES": 5, "CLEARANCE": 1}


def draw_site_plan(ctx: SiteContext) -> object:
    """The plan as an ezdxf document (audited)."""
    doc = new_document("R2010")
    set_units(doc, Units.parse(ctx.units))
    for name, colour in PLAN_LAYERS.items():
        doc.layers.add(name, color=colour)
    msp = doc.modelspace()
    h = ctx.size / 25.0  # text height
    for s in ctx.sheets:
        foot = s.site.apply(np.asarray(s.resting.footprint, dtype=float))
        msp.add_lwpolyline(foot.tolist(), close=True, dxfattribs={"layer": "FOOTPRINT"})
        contacts = s.site.apply(np.asarray(s.resting.contacts, dtype=float)[:, :2])
        for c in contacts:
            msp.add_circle(tuple(c.tolist()), h / 4.0, dxfattribs={"layer": "CONTACT"})
        support = s.site.apply(np.asarray(s.resting.support_polygon, dtype=float).reshape(-1, 2))
        if len(support) > 1:
            msp.add_lwpolyline(
                support.tolist(), close=len(support) > 2, dxfattribs={"layer": "CONTACT"}
            )
        centre = foot.mean(axis=0)
        msp.add_text(s.name, height=h, dxfattribs={"layer": "NAMES"}).set_placement(
            tuple(centre.tolist())
        )
    if ctx.clearance is not None:
        for p in nearest_neighbours(ctx.clearance, [s.name for s in ctx.sheets]):
            a, b = np.asarray(p.point_a)[:2], np.asarray(p.point_b)[:2]
            msp.add_line(tuple(a.tolist()), tuple(b.tolist()), dxfattribs={"layer": "CLEARANCE"})
            label = f"{p.a} - {p.b}: {p.distance:.0f} {ctx.units}"
            msp.add_text(label, height=h * 0.6, dxfattribs={"layer": "CLEARANCE"}).set_placement(
                tuple(((a + b) / 2.0).tolist())
            )
    lo = np.min([s.site.apply(np.asarray(s.resting.footprint)).min(axis=0) for s in ctx.sheets], 0)
    title = f"site {ctx.name} ({len(ctx.sheets)} sheets; lengths in {ctx.units})"
    msp.add_text(title, height=h, dxfattribs={"layer": "NAMES"}).set_placement(
        (float(lo[0]), float(lo[1] - 3 * h))
    )
    auditor = doc.audit()
    if auditor.has_errors:
        raise ExportError(f"the site plan failed its audit: {auditor.errors}")
    return doc


def write_site_plan(ctx: SiteContext, path: str | os.PathLike[str]) -> Path:
    """Write SITE-plan.dxf (atomically, deterministic bytes)."""
    doc = draw_site_plan(ctx)
    return write_dxf_atomic(doc, path)  # type: ignore[arg-type]
