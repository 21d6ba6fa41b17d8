"""patkau-one-fold anchored at its feet under a uniform normal pressure: our
linear response (``onefold_cad.mechanics.loads.response``) beside CalculiX's
linear static S6 shells on the same mesh (issue 40's peer check).

    .venv/bin/python benchmarks/calculix_loads.py [TEMPLATE] [--mesh coarse normal fine]
        [--pressure PA]

The designed form is stress-free and weightless, set in its resting frame,
every node of its designed feet held in x, y and z; the pressure pushes on the
sheet's upper side. The deck is NAME.inp's (``export.simulation_inp``) with
the weight replaced by ``*DLOAD ... P``, no ``*PLASTIC`` and no ``NLGEOM``
(a linear step). Prints one row per mesh: the feet's reactions (kN) and the
largest movement (mm) of each, and their differences (of the reactions:
relative to the total load). Needs Debian's ``calculix-ccx``; ccx runs on one
thread in a temporary folder.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import tempfile
import time
from pathlib import Path
from types import SimpleNamespace

import numpy as np
from calculix_structural import read_dat  # the .dat blocks NAME.inp asks for

from onefold_cad.design import fold_design
from onefold_cad.export.simulation.inp import inp_text
from onefold_cad.mechanics.loads.response import linear_response, node_dofs
from onefold_cad.mechanics.loads.surface import face_vectors, pressure_load
from onefold_cad.mechanics.model import sheet_model
from onefold_cad.mechanics.shell import director_angles, moved, pack, unpack
from onefold_cad.templates import load_template


def ours(design, folded, level: str, pressure: float):
    """Our model on ``level``'s mesh: the stand-in simulation the deck is written
    from, the feet, their reactions (k, 3) and every node's movement (n, 3)."""
    model = sheet_model(design, folded, level=level)
    s = model.scale
    q0 = pack(model.designed, director_angles(model.shell, model.designed, model.normals))
    rot, shift = model.standing_frame()
    shell, q = moved(model.shell, q0, rot, shift)
    x = unpack(model.mesh, q)[0]
    size = float(np.ptp(x, axis=0).max())
    feet = np.flatnonzero(x[:, 2] <= x[:, 2].min() + 1e-9 * size)
    tri = model.mesh.triangles
    load = pressure_load(x, tri, np.full(model.mesh.n_faces, pressure))
    clock = time.process_time()
    resp = linear_response(shell, q, node_dofs(feet), load[None])
    seconds = time.process_time() - clock
    n = model.mesh.n_nodes
    mat = model.material
    sim = SimpleNamespace(
        unit=design.units.value,
        flat=model.mesh.nodes / s,
        faces=tri,
        designed_positions=x / s,
        supports="anchored",
        thickness=mat.thickness / s,
        youngs_modulus_GPa=mat.youngs_modulus / 1e9,
        poisson=mat.poisson,
        density_kg_m3=mat.density,
        yield_stress_MPa=mat.yield_stress / 1e6,
    )
    # ccx's P on these S6 elements pushes along their own normal (their corners'
    # order; measured: with the other sign every reaction is reversed): towards
    # our upper side unless face_vectors had to turn the sheet over
    c = np.cross(x[tri[:, 1]] - x[tri[:, 0]], x[tri[:, 2]] - x[tri[:, 0]])
    sign = -1.0 if c[:, 2].sum() >= 0.0 else 1.0
    assert np.allclose(-face_vectors(x, tri)[1][:, 2] * sign, c[:, 2] / np.linalg.norm(c, axis=1))
    return sim, feet, resp.reactions[0][feet], resp.moves[0, : 3 * n].reshape(n, 3), sign, seconds


def deck(sim, name: str, pressure: float) -> str:
    """NAME.inp's deck with the weight replaced by the pressure, linear."""
    lines = inp_text(sim, name).splitlines()
    out, skip = [], 0
    for line in lines:
        if skip:
            skip -= 1
            continue
        if line == "*PLASTIC":
            skip = 1
            continue
        if line == "*STEP, NLGEOM":
            line = "*STEP"
        if line.startswith("SHEET, GRAV"):
            line = f"SHEET, P, {pressure:.12g}"
        out.append(line)
    return "\n".join(out) + "\n"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--mesh", nargs="+", default=["coarse", "normal"])
    ap.add_argument("--pressure", type=float, default=500.0, help="Pa (default 500)")
    args = ap.parse_args()
    ccx = shutil.which("ccx")
    if ccx is None:
        raise SystemExit("needs CalculiX: apt-get install calculix-ccx")
    design = load_template(args.template)
    folded = fold_design(design)
    print(f"{args.template}: designed form, anchored feet, uniform normal pressure "
          f"{args.pressure:g} Pa on its upper side, linear")  # fmt: skip
    print("| mesh | nodes | foot | onefold (kN) | CalculiX S6 (kN) | largest movement onefold "
          "(mm) | CalculiX (mm) | s onefold / ccx |")  # fmt: skip
    print("|---|---|---|---|---|---|---|---|")
    for level in args.mesh:
        sim, feet, ours_r, ours_u, sign, ours_s = ours(design, folded, level, args.pressure)
        with tempfile.TemporaryDirectory() as tmp:
            Path(tmp, "load.inp").write_text(deck(sim, "load", sign * args.pressure))
            start = time.perf_counter()
            subprocess.run([ccx, "-i", "load"], cwd=tmp, check=True, capture_output=True,
                           env={**os.environ, "OMP_NUM_THREADS": "1"})  # fmt: skip
            ccx_s = time.perf_counter() - start
            forces, moves = read_dat(Path(tmp) / "load.dat", len(sim.flat))
        # ccx prints the support's force on the structure's node as RF: the same sign as ours
        total = float(np.linalg.norm(ours_r.sum(axis=0)))
        a = 1000 * float(np.linalg.norm(ours_u, axis=1).max())
        b = 1000 * float(np.linalg.norm(moves, axis=1).max())
        for k, (r1, r2) in enumerate(zip(ours_r, forces, strict=True)):
            first = k == 0
            print(f"| {level if first else ''} | {len(sim.flat) if first else ''} | {k + 1} | "
                  f"{', '.join(f'{v / 1e3:.3f}' for v in r1)} | "
                  f"{', '.join(f'{v / 1e3:.3f}' for v in r2)} "
                  f"({100 * np.linalg.norm(r1 - r2) / total:.2g} %) | "
                  f"{f'{a:.2f}' if first else ''} | "
                  f"{f'{b:.2f} ({100 * (a / b - 1):+.2g} %)' if first else ''} | "
                  f"{f'{ours_s:.1f} / {ccx_s:.0f}' if first else ''} |")  # fmt: skip


if __name__ == "__main__":
    main()
