"""The cost of one Newton iteration of ``onefold simulate`` on a template's
own sheet, part by part: the order-2 energy (``evaluate(shell, q, 2)``) with
the J2 sections (after forming, at the formed state: every face's section
mixed elastic and plastic through the thickness) and with the moment law
(the model's elastic shell), and the factorisation of the free-free
Hessian as ``newton`` does it (``SymmetricFactor.factor``, the symbolic
analysis once per structure), with the factor's fill (QDLDL's ``L`` against
the matrix's upper triangle, and whether its ordering permutes: AMD). With
``--baseline COMMIT`` the same calls of
that commit's package (``git_baseline.py``) run interleaved beside today's
on the same inputs (CPU medians [quartiles] and the paired ratio). BLAS runs
on one thread, as ``simulate`` runs it. ``--chunks N ...`` times the J2
evaluation with ``energy.CHUNK`` (faces per run of the face terms) set to each.

Run from the repository root::

    .venv/bin/python benchmarks/bench_iteration.py [TEMPLATE] [--levels coarse normal]
        [--rounds 7] [--baseline main] [--chunks 256 512 1024 2048]

Prints only.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from pathlib import Path

import numpy as np
import qdldl
import scipy.sparse as sp
from threadpoolctl import threadpool_limits

sys.path.insert(0, str(Path(__file__).resolve().parent))

from git_baseline import load  # noqa: E402
from interleave import interleave, paired_ratio  # noqa: E402

from onefold_cad.design import fold_design  # noqa: E402
from onefold_cad.mechanics import energy  # noqa: E402
from onefold_cad.mechanics.energy import evaluate  # noqa: E402
from onefold_cad.mechanics.j2.simulate import form_j2  # noqa: E402
from onefold_cad.mechanics.model import sheet_model  # noqa: E402
from onefold_cad.mechanics.newton import SymmetricFactor, restrict  # noqa: E402
from onefold_cad.mechanics.shell import rigid_dofs, unpack  # noqa: E402
from onefold_cad.templates import find_template, load_template  # noqa: E402


def _cases(template: str, level: str):
    """The J2 shell and state after forming, the moment law's shell there,
    and the free-free Hessian ``newton`` factors."""
    design = load_template(find_template(template))
    folded = fold_design(design)
    model = sheet_model(design, folded, level=level)
    formed = form_j2(model)
    q = formed.stage.q
    j2 = formed.shell.with_changes(plasticity=formed.stage.plasticity)
    free = np.ones(model.mesh.n_dofs, dtype=bool)
    free[rigid_dofs(unpack(model.mesh, q)[0])] = False
    h = evaluate(j2, q, 2).hessian
    assert h is not None
    hf = restrict(h, free)[1](h)
    return model, j2, q, hf


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--levels", nargs="*", default=["coarse", "normal"])
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--baseline", default=None)
    ap.add_argument("--chunks", type=int, nargs="*", default=[])
    args = ap.parse_args(argv)
    with threadpool_limits(limits=1, user_api="blas"):
        _run(args)
    return 0


def _chunked(shell, q, chunk: int) -> None:
    energy.CHUNK, was = chunk, energy.CHUNK
    try:
        evaluate(shell, q, 2)
    finally:
        energy.CHUNK = was


def _run(args: argparse.Namespace) -> None:
    old_evaluate = old_factor = None
    if args.baseline:
        old, why = load(args.baseline)
        if old is None:
            print(f"no baseline: {why}")
        else:
            old_evaluate = importlib.import_module(old.__name__ + ".mechanics.energy").evaluate
            old_newton = importlib.import_module(old.__name__ + ".mechanics.newton")
            old_factor = old_newton.SymmetricFactor
    for level in args.levels:
        model, j2, q, hf = _cases(args.template, level)
        moment = model.shell
        factors = SymmetricFactor(hf)
        factors.factor(hf)  # the symbolic analysis, once per structure as in newton
        calls = {
            "evaluate J2": lambda s=j2, q=q: evaluate(s, q, 2),
            "evaluate moment": lambda s=moment, q=q: evaluate(s, q, 2),
            "factor": lambda f=factors, hf=hf: f.factor(hf),
        }
        if old_evaluate is not None and old_factor is not None:
            old_factors = old_factor(hf)
            old_factors.factor(hf)
            calls["old evaluate J2"] = lambda s=j2, q=q: old_evaluate(s, q, 2)
            calls["old evaluate moment"] = lambda s=moment, q=q: old_evaluate(s, q, 2)
            calls["old factor"] = lambda f=old_factors, hf=hf: f.factor(hf)
        for n in args.chunks:
            calls[f"evaluate J2 CHUNK={n}"] = lambda s=j2, q=q, n=n: _chunked(s, q, n)
        stats = interleave(calls, rounds=args.rounds, batch_time=0.0)
        upper = sp.triu(hf, format="csc")
        lower, _, perm = qdldl.Solver(upper, upper=True).factors()
        print(
            f"{args.template} {level}: {model.mesh.n_faces} faces, {hf.shape[0]} free "
            f"unknowns, Hessian nnz {hf.nnz}; LDL^T: nnz(L) {lower.nnz} against "
            f"{upper.nnz} in the upper triangle ({lower.nnz / upper.nnz:.2f} x), "
            f"ordering {'permuted (AMD)' if np.any(perm != np.arange(len(perm))) else 'natural'}"
        )
        for name, s in stats.items():
            line = f"  {name:20s} {s.fmt(1e3, ' ms')}"
            if name.startswith("old "):
                ratio = paired_ratio(stats, name, name[4:])
                line += f"   old / new {ratio.fmt()}"
            print(line)


if __name__ == "__main__":
    raise SystemExit(main())
