"""The structural check's NAME.inp run in CalculiX beside ``onefold simulate
--reference designed`` on the same mesh: the largest movement of the designed
form standing under its weight, the feet's reactions, the time of each.

    .venv/bin/python benchmarks/calculix_structural.py [TEMPLATE] [--mesh coarse normal fine]

Needs Debian's ``calculix-ccx`` (``make test`` installs it). ccx runs on one
thread (OMP_NUM_THREADS=1), in a temporary folder. Prints one row per mesh.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

from onefold_cad.design import fold_design
from onefold_cad.export.simulation.inp import write_structural_inp
from onefold_cad.mechanics.simulate import simulate
from onefold_cad.templates import load_template


def read_dat(path: Path, n_nodes: int | None) -> tuple[np.ndarray, np.ndarray]:
    """The feet's reactions ``(k, 3)`` and the first ``n_nodes`` nodes'
    displacements ``(n, 3)`` (m; None: every node's) from ccx's .dat (the
    *NODE PRINT blocks NAME.inp asks for)."""
    forces, moves, block = [], [], None
    for line in path.read_text().splitlines():
        if "forces (fx,fy,fz)" in line:
            block = forces
        elif "displacements (vx,vy,vz)" in line:
            block = moves
        elif block is not None and line.strip():
            block.append([float(v) for v in line.split()[1:4]])
    return np.array(forces), np.array(moves)[:n_nodes]


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--mesh", nargs="+", default=["coarse", "normal"])
    args = ap.parse_args()
    ccx = shutil.which("ccx")
    if ccx is None:
        raise SystemExit("needs CalculiX: apt-get install calculix-ccx")
    design = load_template(args.template)
    folded = fold_design(design)
    print(f"{args.template}: designed form under its weight, anchored feet, largest movement (mm)")
    print("| mesh | nodes | onefold | s CPU | CalculiX S6 | s | ccx feet / weight |")
    print("|---|---|---|---|---|---|---|")
    for level in args.mesh:
        clock = time.process_time()
        sim = simulate(design, folded, level=level, reference="designed", convergence=False)
        ours_s = time.process_time() - clock
        assert sim.designed is not None
        with tempfile.TemporaryDirectory() as tmp:
            write_structural_inp(sim, Path(tmp) / "check.inp")
            start = time.perf_counter()
            subprocess.run([ccx, "-i", "check"], cwd=tmp, check=True, capture_output=True,
                           env={**os.environ, "OMP_NUM_THREADS": "1"})  # fmt: skip
            ccx_s = time.perf_counter() - start
            forces, moves = read_dat(Path(tmp) / "check.dat", sim.nodes)
        largest = 1000 * float(np.linalg.norm(moves, axis=1).max())
        carried = forces[:, 2].sum() / sim.weight_N
        print(f"| {level} | {sim.nodes} | {sim.designed.max_displacement:.2f} | {ours_s:.1f} | "
              f"{largest:.2f} | {ccx_s:.0f} | {carried:.5f} |")  # fmt: skip


if __name__ == "__main__":
    main()
