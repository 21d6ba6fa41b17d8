"""Would MKL PARDISO (through ``pypardiso``) pay in place of QDLDL?

Builds the free-free Hessian ``newton`` factors at patkau-one-fold's formed
state (the moment law's elastic shell, a 3-2-1 restraint's unknowns held)
on each mesh level, times ``newton.SymmetricFactor`` on it (the symbolic
analysis with the first factorisation, then numeric refactorisations, a
solve) and, in a second interpreter that has ``pypardiso`` installed
(``--pardiso-python``; it is no dependency of this package), PARDISO on the
same matrix: symmetric positive definite (``mtype`` 2), one thread, its
analysis (phase 11), numeric factorisation (22) and solve (33), and whether
a matrix that is not positive definite is refused (error -4, as
``SymmetricFactor.factor`` must report False). Best of ``--rounds``; prints
a table, asserts nothing.

Run from the repository root (a PARDISO interpreter made with
``python3 -m venv /tmp/pv && /tmp/pv/bin/pip install pypardiso``)::

    .venv/bin/python benchmarks/bench_factor_pardiso.py --pardiso-python /tmp/pv/bin/python
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import scipy.sparse as sp

_CHILD = r"""
import json, sys, time
import numpy as np, scipy.sparse as sp, pypardiso
out = {}
for name, rounds in json.loads(sys.argv[1]):
    a = sp.load_npz(name).tocsr()
    up = sp.triu(a, format="csr"); up.sort_indices()
    b = np.ones(a.shape[0])
    s = pypardiso.PyPardisoSolver(mtype=2)
    s.set_phase(11); t = time.perf_counter(); s._call_pardiso(up, b)
    analysis = time.perf_counter() - t
    fac, sol = [], []
    for _ in range(rounds):
        s.set_phase(22); t = time.perf_counter(); s._call_pardiso(up, b)
        fac.append(time.perf_counter() - t)
        s.set_phase(33); t = time.perf_counter(); x = s._call_pardiso(up, b)
        sol.append(time.perf_counter() - t)
    shift = sp.diags(np.full(a.shape[0], 2 * np.abs(a.diagonal()).mean()))
    bad = sp.triu((a - shift).tocsr(), format="csr"); bad.sort_indices()
    s.set_phase(22)
    try:
        s._call_pardiso(bad, b); refused = None
    except pypardiso.pardiso_wrapper.PyPardisoError as err:
        refused = err.value
    out[name] = {"analysis": analysis, "factor": min(fac), "solve": min(sol),
                 "residual": float(np.abs(a @ x - b).max()), "refused": refused}
print(json.dumps(out))
"""


def hessian(level: str) -> sp.csc_matrix:
    """The free-free Hessian of patkau-one-fold's elastic shell at the formed
    state on ``level``'s mesh, as ``newton.minimize`` factors it."""
    from onefold_cad.design import fold_design
    from onefold_cad.mechanics import newton
    from onefold_cad.mechanics.energy import evaluate
    from onefold_cad.mechanics.model import sheet_model
    from onefold_cad.mechanics.shell import rigid_dofs
    from onefold_cad.mechanics.stages import form
    from onefold_cad.templates import find_template, load_template

    design = load_template(find_template("patkau-one-fold"))
    model = sheet_model(design, fold_design(design), level=level)
    h = evaluate(model.shell, form(model).q, 2).hessian
    assert h is not None
    free = np.ones(h.shape[0], dtype=bool)
    free[np.asarray(rigid_dofs(model.designed))] = False
    return newton.restrict(h, free)[1](h)


def qdldl_times(a: sp.csc_matrix, rounds: int) -> dict[str, float]:
    """``SymmetricFactor``'s first factorisation (with its analysis), its best
    refactorisation and solve (s)."""
    from onefold_cad.mechanics.newton import SymmetricFactor

    t = time.perf_counter()
    f = SymmetricFactor(a)
    assert f.factor(a)
    first = time.perf_counter() - t
    fac, sol = [], []
    b = np.ones(a.shape[0])
    for _ in range(rounds):
        t = time.perf_counter()
        f.factor(a)
        fac.append(time.perf_counter() - t)
        t = time.perf_counter()
        f.solve(b)
        sol.append(time.perf_counter() - t)
    return {"first": first, "factor": min(fac), "solve": min(sol)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--levels", nargs="+", default=["coarse", "normal"])
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--pardiso-python", required=True, help="an interpreter with pypardiso")
    args = ap.parse_args()
    env = dict(os.environ, OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    with tempfile.TemporaryDirectory() as tmp:
        rows, files = {}, []
        for level in args.levels:
            a = hessian(level)
            name = str(Path(tmp) / f"{level}.npz")
            sp.save_npz(name, a)
            files.append([name, args.rounds])
            rows[level] = (a.shape[0], qdldl_times(a, args.rounds), name)
        child = subprocess.run(
            [args.pardiso_python, "-c", _CHILD, json.dumps(files)],
            capture_output=True, text=True, env=env, check=True,
        )  # fmt: skip
        pard = json.loads(child.stdout)
    print(
        "| mesh | free unknowns | QDLDL: first (analysis + factor) | QDLDL: factor | QDLDL: "
        "solve | PARDISO: analysis | PARDISO: factor | PARDISO: solve | not definite |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    for level, (n, q, name) in rows.items():
        p = pard[name]
        print(
            f"| {level} | {n} | {1e3 * q['first']:.1f} ms | {1e3 * q['factor']:.1f} ms | "
            f"{1e3 * q['solve']:.1f} ms | {1e3 * p['analysis']:.1f} ms | "
            f"{1e3 * p['factor']:.1f} ms | {1e3 * p['solve']:.1f} ms | "
            f"error {p['refused']} |"
        )
    print(f"one thread each; best of {args.rounds}; {sys.version.split()[0]}")


if __name__ == "__main__":
    main()
