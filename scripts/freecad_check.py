#!/usr/bin/env python3
"""Open STEP files with FreeCAD's own reader and print one line of checks per file.

A manual check, not part of the test suite (CI does not have FreeCAD). Run it
with a system Python that has FreeCAD's modules, not the project's venv::

    apt-get install -y freecad-python3          # Debian / Ubuntu
    .venv/bin/onefold build patkau-one-fold -o /tmp/fc_out
    /usr/bin/python3 scripts/freecad_check.py /tmp/fc_out/*.step

Each file becomes one row: isValid(), the number of solids, shells and faces,
free edges (edges bounding only one face: the sheet's outline and the relief
hole for an open shell, 0 for a closed solid), area, volume of the solids ("-"
when there are none: an open shell has no volume) and the bounding box size.
FreeCAD converts every STEP to millimetres, so the lengths are in mm whatever
the design's unit.

Exit status: 0 when every shape read, is valid and has faces; 1 otherwise;
2 when FreeCAD cannot be imported or no file is given. Set FREECAD_LIB to the
folder holding FreeCAD.so if it is not in one of the usual places.
"""

from __future__ import annotations

import importlib
import os
import sys
from pathlib import Path
from types import ModuleType

# Where distributions put FreeCAD.so / Part.so (Debian's freecad-python3 first).
FREECAD_LIBS = [
    "/usr/lib/freecad-python3/lib",
    "/usr/lib/freecad/lib",
    "/usr/lib64/freecad/lib",
    "/usr/local/lib/freecad/lib",
    "/usr/share/freecad/lib",
]

HEADER = (
    f"{'file':<24} {'valid':<5} {'solids':>6} {'shells':>6} {'faces':>5} {'free_edges':>10} "
    f"{'area_mm2':>14} {'volume_mm3':>14}  bbox_mm (x y z)"
)


def import_freecad() -> tuple[ModuleType, ModuleType]:
    """FreeCAD and Part, adding FreeCAD's library folder to sys.path if needed."""
    extra = [os.environ["FREECAD_LIB"]] if os.environ.get("FREECAD_LIB") else []
    for lib in [None, *extra, *FREECAD_LIBS]:
        if lib is not None:
            if not Path(lib, "FreeCAD.so").exists() or lib in sys.path:
                continue
            sys.path.append(lib)
        try:
            return importlib.import_module("FreeCAD"), importlib.import_module("Part")
        except ImportError:
            continue
    raise ImportError(
        "FreeCAD's Python module not found (apt-get install freecad-python3, "
        "or set FREECAD_LIB to the folder with FreeCAD.so)"
    )


def free_edge_count(shape) -> int:
    """Edges used by exactly one face (degenerate edges, e.g. at a cone apex, skipped)."""
    uses: dict[int, int] = {}
    for face in shape.Faces:
        seen = set()
        for edge in face.Edges:
            if edge.Degenerated:
                continue
            key = edge.hashCode()
            if key not in seen:  # a seam edge stands twice in one face
                seen.add(key)
                uses[key] = uses.get(key, 0) + 1
    return sum(1 for n in uses.values() if n == 1)


def check(part: ModuleType, path: str) -> tuple[str, bool]:
    """The table row for ``path`` and whether the shape passed."""
    name = Path(path).name
    try:
        shape = part.read(path)
    except Exception as exc:  # FreeCAD raises Part.OCCError / FreeCAD.Base.FreeCADError
        return f"{name:<24} ERROR  {' '.join(str(exc).split())}", False
    if shape.isNull() or not shape.Faces:
        return f"{name:<24} EMPTY  (no faces read)", False
    valid = shape.isValid()
    solids = shape.Solids
    volume = f"{sum(s.Volume for s in solids):14.6g}" if solids else f"{'-':>14}"
    box = shape.BoundBox
    row = (
        f"{name:<24} {str(valid):<5} {len(solids):>6} {len(shape.Shells):>6} "
        f"{len(shape.Faces):>5} {free_edge_count(shape):>10} {shape.Area:14.6g} {volume}  "
        f"{box.XLength:.6g} x {box.YLength:.6g} x {box.ZLength:.6g}"
    )
    return row, valid


def main(argv: list[str]) -> int:
    if argv and argv[0] in ("-h", "--help"):
        print(__doc__.strip())
        return 0
    if not argv:
        print("usage: freecad_check.py FILE.step [FILE.step ...]", file=sys.stderr)
        return 2
    try:
        freecad, part = import_freecad()
    except ImportError as exc:
        print(f"freecad_check: {exc}", file=sys.stderr)
        return 2
    version = ".".join(v for v in freecad.Version()[:3] if v)
    print(f"FreeCAD {version}, OCC {part.OCC_VERSION}, Python {sys.version.split()[0]}")
    print(HEADER)
    ok = True
    for path in argv:
        row, passed = check(part, path)
        print(row)
        ok &= passed
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
