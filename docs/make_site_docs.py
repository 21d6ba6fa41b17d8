"""Fill docs/site.md's generated block ``site-patkau`` from a build of the
shipped site: ``.venv/bin/python docs/make_site_docs.py [DIR]`` builds
``onefold site site-patkau-three -o DIR -j 2`` (DIR defaults to a temporary
folder; an existing build in DIR is read as it is with ``--read``) and writes
the block from the files it wrote (SITE.json, SITE-order.csv).
tests/cli/test_site.py checks the block against its own build.
"""

from __future__ import annotations

import argparse
import csv
import json
import sys
import tempfile
from pathlib import Path

DOCS = Path(__file__).resolve().parent
sys.path.insert(0, str(DOCS))

from make_reference import read_block, write_block  # noqa: E402, F401  (read_block: the test reads the block)

SITE = "site-patkau-three"


def site_block(outdir: Path, stem: str = "patkau-three") -> str:
    """The block's Markdown, from a built site in ``outdir``."""
    rep = json.loads((outdir / f"{stem}.json").read_text(encoding="utf-8"))
    rows = list(csv.DictReader((outdir / f"{stem}-order.csv").open(encoding="utf-8")))
    u = rep["units"]
    out = [
        "| sheet | x, y (mm) | turn (deg) | height (mm) | blank area (m^2) | mass (kg) "
        "| cut length (m) | bends (deg) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    by_name = {s["name"]: s for s in rep["sheets"]}
    for r in rows:
        name = r["sheet"]
        s = by_name.get(name)
        where = f"{s['x']:g}, {s['y']:g}" if s else ""
        turn = f"{s['rotation_deg']:g}" if s else ""
        height = f"{s['height']:.0f}" if s else ""
        angles = r["bend_angles_deg"].replace(";", ", ")
        out.append(
            f"| {name} | {where} | {turn} | {height} | {float(r['blank_area']):.3f} "
            f"| {float(r['mass']):.1f} | {float(r['cut_length']) / 1e3:.3f} | "
            f"{r['bends']}: {angles} |"
        )
    out.append("")
    out.append(f"Clearances (smallest distance between the solids as they stand, {u}):")
    out.append("")
    for p in rep["clearance"]["pairs"]:
        out.append(f"- {p['a']} - {p['b']}: {p['distance']:.1f}")
    c = rep["clearance"]
    out.append("")
    out.append(
        f"Smallest: {c['smallest']['distance']:.1f} {u} ({c['smallest']['a']} - "
        f"{c['smallest']['b']}); the B-reps lie within {c['accuracy']:.2g} {u} of the designed "
        "sheets."
    )
    ifc = rep.get("ifc")
    if ifc:
        tris = ", ".join(f"{k} {v}" for k, v in ifc["triangles"].items())
        out.append("")
        out.append(
            f"IFC plates: {ifc['geometry']} ({ifc['why']}); every triangle within "
            f"{ifc['deviation']:.3g} {u} and {ifc['angular_deflection']:g} rad of the solid; "
            f"largest area difference from the B-rep {100 * ifc['max_area_error']:.3f} %; "
            f"triangles: {tris}."
        )
    return "\n".join(out) + "\n"


def site_images(outdir: Path, stem: str = "patkau-three") -> list[Path]:
    """docs/images/site-patkau-three.png (the site's picture, as written) and
    docs/images/site-patkau-three-plan.png (the plan DXF drawn by ezdxf's
    matplotlib back-end)."""
    import shutil

    import ezdxf
    from ezdxf.addons.drawing import matplotlib as dxf_matplotlib

    images = DOCS / "images"
    picture = images / "site-patkau-three.png"
    shutil.copyfile(outdir / f"{stem}.png", picture)
    plan = images / "site-patkau-three-plan.png"
    doc = ezdxf.readfile(outdir / f"{stem}-plan.dxf")
    dxf_matplotlib.qsave(doc.modelspace(), str(plan), bg="#FFFFFF", size_inches=(10, 5), dpi=100)
    return [picture, plan]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("outdir", nargs="?", type=Path, help="where to build (default: a temp folder)")
    ap.add_argument("--read", action="store_true", help="read an existing build in OUTDIR")
    args = ap.parse_args(argv)
    from onefold_cad.cli.main import main as onefold

    with tempfile.TemporaryDirectory() as tmp:
        outdir = args.outdir or Path(tmp) / "site"
        if not args.read and onefold(["site", SITE, "-o", str(outdir), "-j", "2", "-q"]) != 0:
            return 1
        write_block(DOCS / "site.md", "site-patkau", site_block(outdir))
        for p in site_images(outdir):
            print(p)
    print(f"{DOCS / 'site.md'}: block 'site-patkau' updated")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
