"""The mechanics core's cost per Newton iteration on a patkau-sized sheet.

A 7.3 m x 3.05 m sheet with a 0.1 m hole at H and the fold line through it
(meshed by ``mesh_sheet``, graded from the hole), 304 stainless, t = 3.57 mm,
bent into a trough so every term is live. Per mesh size: the one-time pattern,
the energy with gradient and Hessian (``evaluate``), and the factorisation of
the free-free Hessian as ``newton`` does it (QDLDL's LDL^T, its symbolic
analysis once per structure: ``SymmetricFactor.factor``) beside SuperLU as
``newton`` did it before (symmetric mode, MMD on A + A^T, diagonal pivots),
interleaved (CPU medians with their spread) with the ratio. Prints only.

Run from the repository root::

    .venv/bin/python benchmarks/bench_mechanics_core.py [--rounds 5] [--sizes 0.08 0.05]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
import scipy.sparse.linalg as spla

sys.path.insert(0, str(Path(__file__).resolve().parent))

from interleave import interleave  # noqa: E402

from onefold_cad.mechanics import (  # noqa: E402
    Shell,
    ShellMaterial,
    evaluate,
    flat_positions,
    mesh_sheet,
    pack,
    rigid_dofs,
)
from onefold_cad.mechanics.assembly import pattern_of  # noqa: E402
from onefold_cad.mechanics.newton import SymmetricFactor, restrict  # noqa: E402

STEEL = ShellMaterial(youngs_modulus=193e9, poisson=0.29, thickness=3.57e-3, density=7900.0)


def case(h_max: float):
    half_l, half_w, hole = 3.65, 1.525, 0.1
    outline = [[-half_l, -half_w], [half_l, -half_w], [half_l, half_w], [-half_l, half_w]]
    creases = [[(hole, 0.0), (half_l, 0.0)], [(-hole, 0.0), (-half_l, 0.0)]]
    t = time.process_time()
    mesh = mesh_sheet(outline, size=(h_max / 4, 0.25, h_max), hole_radius=hole, creases=creases)
    t_mesh = time.process_time() - t
    shell = Shell.create(mesh, STEEL, crease_angle=0.3, gravity=(0, 0, -9.80665))
    x = flat_positions(mesh)
    x[:, 2] = 0.05 * x[:, 1] ** 2
    q = pack(x, np.zeros(mesh.n_directors))
    t = time.process_time()
    pattern_of(mesh)
    t_pattern = time.process_time() - t
    free = np.ones(mesh.n_dofs, dtype=bool)
    free[rigid_dofs(x)] = False
    ev = evaluate(shell, q)
    _, block = restrict(ev.hessian, free)
    hf = block(ev.hessian)
    return mesh, shell, q, hf, t_mesh, t_pattern


def superlu(a):
    """SuperLU as ``newton`` factored before QDLDL (the signs of U's diagonal read)."""
    lu = spla.splu(
        a, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True}
    )
    return bool(np.all(lu.U.diagonal() > 0))


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--sizes", type=float, nargs="*", default=[0.12, 0.08, 0.055])
    args = ap.parse_args(argv)
    print(
        "| nodes | unknowns | Hessian nnz | mesh s | pattern s | evaluate (E, g, H) s "
        "| factor: QDLDL s | SuperLU s | SuperLU / QDLDL |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    for h in args.sizes:
        mesh, shell, q, hf, t_mesh, t_pattern = case(h)
        factors = SymmetricFactor(hf)
        factors.factor(hf)  # the symbolic analysis, once per structure as in newton
        stats = interleave(
            {
                "evaluate": lambda shell=shell, q=q: evaluate(shell, q),
                "factor": lambda hf=hf, f=factors: f.factor(hf),
                "superlu": lambda hf=hf: superlu(hf),
            },
            rounds=args.rounds,
            batch_time=0.0,
        )
        print(
            f"| {mesh.n_nodes} | {mesh.n_dofs} | {hf.nnz} | {t_mesh:.2f} | {t_pattern:.2f} "
            f"| {stats['evaluate'].fmt()} | {stats['factor'].fmt()} | {stats['superlu'].fmt()} "
            f"| {stats['superlu'].median / stats['factor'].median:.2f} |"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
