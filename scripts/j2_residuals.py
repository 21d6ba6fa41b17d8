"""Every Newton residual of the J2 release and stand, solve by solve: how
many iterations each load step takes and how its residual falls (the
numbers docs/mechanics.md's "Why not yet the default" quotes).

    .venv/bin/python scripts/j2_residuals.py [TEMPLATE] [--mesh coarse|normal]
        [--moment] [--first-step 0.125] [--step-iterations 16] [--flips]
        [--elastic-on-flip]

One line per solve (a load step, or a failed attempt that the path then
halved): its index, its Newton iterations and the largest residual (N)
before each step; then the stage's iterations and CPU seconds.
``--moment`` prints the moment law's release the same way, for comparison.
``--first-step`` and ``--step-iterations`` set the J2 release's first step
and its iterations per step (``j2.stages.RELEASE_STEP``,
``RELEASE_ITERATIONS``) for this run. ``--flips`` prints the release's
iterations one a line instead: the residual (N), the energy (J), and how
many material points changed between flowing and unloading since the
iteration before, of how many flow. ``--elastic-on-flip`` tries a modified
Newton (Crisfield's remedy for points that oscillate between loading and
unloading): a point that flows but did not at the evaluation before gets
the elastic tangent in the Hessian; the energy and its gradient stay the
law's.
"""

from __future__ import annotations

import argparse
import dataclasses
import time

import numpy as np

from onefold_cad.design import fold_design
from onefold_cad.mechanics import stages
from onefold_cad.mechanics.j2 import section
from onefold_cad.mechanics.j2 import stages as j2_stages
from onefold_cad.mechanics.j2.law import elastic_matrix
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
            FLOWED.clear()
        self.solves[-1].append(residual)

    def show(self, stage: str, iterations: int, seconds: float) -> None:
        for i, seq in enumerate(self.solves):
            print(f"  {i:2d} {len(seq) - 1:3d} " + " ".join(f"{r:.2e}" for r in seq))
        print(f"{stage}: {len(self.solves)} solves, {iterations} Newton iterations, "
              f"{seconds:.2f} s CPU")  # fmt: skip
        self.solves = []


class Flips:
    """A Newton progress callback that prints each iteration's residual,
    energy and the material points that changed between flowing and
    unloading (``j2.section.update`` wrapped while it lives)."""

    def __init__(self, points: int) -> None:
        self.points = points
        self.seen: list[np.ndarray] = []
        self.last: np.ndarray | None = None
        self._update = section.update

        def update(law, strain, state):
            r = self._update(law, strain, state)
            self.seen.append(r.plastic.ravel().copy())
            return r

        section.update = update  # type: ignore[assignment]

    def __call__(self, iteration: int, residual: float, energy: float) -> None:
        if iteration == 0:
            FLOWED.clear()
        flowing = np.concatenate(self.seen)[-self.points :] if self.seen else None
        self.seen = []
        change = "-"
        if flowing is not None and len(flowing) == self.points:
            if self.last is not None and iteration > 0:
                change = f"{int(np.sum(flowing != self.last))} of {int(flowing.sum())}"
            self.last = flowing
        print(f"  {iteration:3d} residual {residual:9.3g} energy {energy:.10g} changed {change}")


#: ``--elastic-on-flip``'s flags of the last evaluation, per section block
#: (keyed by its state's address and shape; emptied when a solve reports its start).
FLOWED: dict[tuple[int, tuple[int, ...]], np.ndarray] = {}


def elastic_on_flip() -> None:
    """Wrap ``j2.section.update`` so that points that flow now but did not at
    the last evaluation of the same section block get the elastic tangent."""
    update = section.update
    before = FLOWED

    def held(law, strain, state):
        r = update(law, strain, state)
        key = (state.equivalent.__array_interface__["data"][0], state.equivalent.shape)
        last = before.get(key)
        before[key] = r.plastic.copy()
        if last is not None and last.shape == r.plastic.shape:
            started = r.plastic & ~last
            if started.any():
                tangent = r.tangent.copy()
                tangent[started] = elastic_matrix(law)
                r = dataclasses.replace(r, tangent=tangent)
        return r

    section.update = held  # type: ignore[assignment]


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--mesh", default="coarse")
    ap.add_argument("--moment", action="store_true")
    ap.add_argument("--first-step", type=float, default=j2_stages.RELEASE_STEP)
    ap.add_argument("--step-iterations", type=int, default=j2_stages.RELEASE_ITERATIONS)
    ap.add_argument("--flips", action="store_true")
    ap.add_argument("--elastic-on-flip", action="store_true")
    args = ap.parse_args()
    if args.elastic_on_flip:
        elastic_on_flip()
    j2_stages.RELEASE_STEP = args.first_step
    j2_stages.RELEASE_ITERATIONS = args.step_iterations
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
    if args.flips:
        j2_stages.release(model, shell, formed, Flips(formed.plasticity.state.equivalent.size))
        return
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
