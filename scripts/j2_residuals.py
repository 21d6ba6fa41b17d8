"""Every Newton residual of the J2 release and stand, solve by solve: how
many iterations each load step takes and how its residual falls (the
numbers docs/mechanics.md's "Why not yet the default" quotes).

    .venv/bin/python scripts/j2_residuals.py [TEMPLATE] [--mesh coarse|normal]
        [--moment]

One line per solve (a load step, or a failed attempt that the path then
halved): its index, its Newton iterations and the largest residual (N)
before each step; then the stage's iterations and CPU seconds.
``--moment`` prints the moment law's release the same way, for comparison.
"""

from __future__ import annotations

import argparse
import time

from onefold_cad.design import fold_design
from onefold_cad.mechanics import stages
from onefold_cad.mechanics.j2 import stages as j2_stages
from onefold_cad.mechanics.model import sheet_model
from onefold_cad.mechanics.simulate import aligned_deviation
from onefold_cad.templates import load_template


class Log:
    """A Newton progress callback that keeps each solve's residuals."""

    def __init__(self) -> None:
        self.solves: list[list[float]] = []

    def __call__(self, iteration: int, residual: float, energy: float) -> None:
        if iteration == 0:
            self.solves.append([])
        self.solves[-1].append(residual)

    def show(self, stage: str, iterations: int, seconds: float) -> None:
        for i, seq in enumerate(self.solves):
            print(f"  {i:2d} {len(seq) - 1:3d} " + " ".join(f"{r:.2e}" for r in seq))
        print(f"{stage}: {len(self.solves)} solves, {iterations} Newton iterations, "
              f"{seconds:.2f} s CPU")  # fmt: skip
        self.solves = []


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--mesh", default="coarse")
    ap.add_argument("--moment", action="store_true")
    args = ap.parse_args()
    design = load_template(args.template)
    folded = fold_design(design)
    model = sheet_model(design, folded, level=args.mesh)
    print(f"{args.template}, mesh {args.mesh}: {model.mesh.n_nodes} nodes")
    log = Log()
    if args.moment:
        t = time.process_time()
        rel = stages.release(model, stages.form(model), log)
        log.show("moment law's release", rel.equilibrium.iterations, time.process_time() - t)
        return
    shell = j2_stages.j2_shell(model)
    formed = j2_stages.form(model, shell)
    t = time.process_time()
    released = j2_stages.release(model, shell, formed, log)
    assert released.equilibrium is not None
    log.show("J2 release", released.equilibrium.iterations, time.process_time() - t)
    n = model.mesh.n_nodes
    dev = aligned_deviation(model, folded, released.q[: 3 * n].reshape(n, 3))[0]
    print(f"springback max {dev:.6g} {design.units.value}")
    t = time.process_time()
    placed = stages.place(model, released.q)
    standing = j2_stages.stand(model, shell, placed, released.plasticity, "anchored", log)
    assert standing.equilibrium is not None
    log.show("J2 stand (anchored)", standing.equilibrium.iterations, time.process_time() - t)


if __name__ == "__main__":
    main()
