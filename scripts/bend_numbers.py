"""The bend model's numbers for a template, read back from the written DXF.

For each reference surface (INSIDE, MID, OUTSIDE) and crease half: the set-back
SB = (r + s t) tan(psi/2), BA, BD and the shift SB - BA/2 from the formula
(computed here, by hand), and the shift per side measured on the DXF blank
written by onefold_cad and read back with ezdxf (every sheet corner off the
fold line: its designed distance from the fold line minus the blank's).

    .venv/bin/python scripts/bend_numbers.py [TEMPLATE] [--surfaces INSIDE,MID,OUTSIDE]
"""

from __future__ import annotations

import argparse
import math
import tempfile
from pathlib import Path

import ezdxf  # noqa: TID251 (a script: reads the DXF back)
import numpy as np

from onefold_cad import fold_design
from onefold_cad.export.dxf import export_design_dxf
from onefold_cad.templates import load_template

S = {("INSIDE", "UP"): 0.0, ("INSIDE", "DOWN"): 1.0, ("OUTSIDE", "UP"): 1.0,
     ("OUTSIDE", "DOWN"): 0.0, ("MID", "UP"): 0.5, ("MID", "DOWN"): 0.5}  # fmt: skip


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--surfaces", default="INSIDE,MID,OUTSIDE")
    args = ap.parse_args(argv)
    base = load_template(args.template)
    folded = fold_design(base)
    m, u = base.material, base.units.value
    t, r, k = m.thickness, m.bend_radius, m.k_factor
    print(f"{args.template}: t = {t:g} {u}, r = {r:g} {u}, K = {k:g}")
    print("surface  half     bend  psi [deg]   s    SB        BA        BD        shift     "
          "mean shift  DXF shift  DXF - formula")  # fmt: skip
    for surface in args.surfaces.split(","):
        design = base.with_changes(material=m.with_changes(sheet_surface=surface))
        rows = []
        for half in folded.crease:
            psi = math.radians(half.fold_angle_deg)
            s = S[(surface, half.bend)]
            sb = (r + s * t) * math.tan(psi / 2)
            ba = psi * (r + k * t)
            rows.append((half, s, sb, ba, 2 * sb - ba, sb - ba / 2))
        mean = (rows[0][5] + rows[1][5]) / 2
        with tempfile.TemporaryDirectory() as tmp:
            path = export_design_dxf(design, Path(tmp) / "b.dxf", folded)
            poly = ezdxf.readfile(path).modelspace().query("LWPOLYLINE[layer=='CUT']")[0]
            blank = design.sheet.to_sheet.inverse(np.array(poly.get_points("xy"))[:, :2])
        v = np.asarray(design.sheet.vertices)
        corners = [p for i, p in enumerate(v) if i not in (0, design.sheet.minus_x_index)]
        measured = [abs(c[1]) - abs(blank[np.argmin(np.linalg.norm(blank - c, axis=1))][1])
                    for c in corners]  # fmt: skip
        shift = float(np.median(measured))
        for half, s, sb, ba, bd, own in rows:
            print(f"{surface:8s} {half.name:8s} {half.bend:5s} {half.fold_angle_deg:9.4f}  "
                  f"{s:3.1f}  {sb:8.4f}  {ba:8.4f}  {bd:8.4f}  {own:8.4f}  {mean:10.4f}  "
                  f"{shift:9.4f}  {shift - mean:+.1e}")  # fmt: skip
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
