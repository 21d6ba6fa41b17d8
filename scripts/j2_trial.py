"""A shipped template formed, released and stood with J2 sections through the
thickness (``onefold_cad.mechanics.j2_stages``), beside ``onefold simulate``'s
moment law on the same mesh: the numbers docs/mechanics.md quotes for the J2
work in progress.

    .venv/bin/python scripts/j2_trial.py [TEMPLATE] [--mesh coarse|normal] [--points N]

Prints the formed plastic share (surfaces yielded) and largest equivalent
plastic strain, the springback's deviation after the best rigid fit, the
share of the sheet that yields again on release, the largest surface stress
of each stage (never above the flow stress), Newton's iterations and the CPU
time of each stage, then the moment law's numbers.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from onefold_cad.design import fold_design
from onefold_cad.mechanics import j2_stages
from onefold_cad.mechanics.model import sheet_model
from onefold_cad.mechanics.simulate import aligned_deviation, run
from onefold_cad.mechanics.stages import place
from onefold_cad.templates import load_template


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--mesh", default="coarse")
    ap.add_argument("--points", type=int, default=9)
    args = ap.parse_args()
    design = load_template(args.template)
    folded = fold_design(design)
    clock = time.process_time()
    model = sheet_model(design, folded, level=args.mesh)
    shell = j2_stages.j2_shell(model, args.points)
    area = shell.ref_area
    share = lambda faces: float(area[faces].sum() / area.sum())  # noqa: E731
    print(f"{args.template}, mesh {args.mesh}: {model.mesh.n_nodes} nodes, "
          f"{model.mesh.n_faces} faces, {args.points} points through the thickness")  # fmt: skip
    formed = j2_stages.form(model, shell)
    t = time.process_time()
    peeq = formed.surface_plastic_strain()
    print(f"formed: plastic share {share(peeq > 0):.4f}, largest equivalent plastic strain "
          f"{peeq.max():.4g}, largest stress {formed.surface_stress().max() / 1e6:.5g} MPa "
          f"({t - clock:.2f} s)")  # fmt: skip
    clock = t
    released = j2_stages.release(model, shell, formed)
    t = time.process_time()
    n = model.mesh.n_nodes
    dev_max, dev_rms = aligned_deviation(model, folded, released.q[: 3 * n].reshape(n, 3))
    again = released.surface_plastic_strain() > peeq + 1e-12
    print(f"released: deviation max {dev_max:.4g} rms {dev_rms:.4g} {design.units.value}, "
          f"yields again {share(again):.4f}, largest stress "
          f"{released.surface_stress().max() / 1e6:.5g} MPa, "
          f"{released.equilibrium.iterations} Newton iterations ({t - clock:.2f} s)")  # fmt: skip
    clock = t
    placed = place(model, released.q)
    standing = j2_stages.stand(model, shell, placed, released.plasticity, "anchored")
    t = time.process_time()
    x = standing.equilibrium.positions / model.scale
    print(f"standing (anchored): height {x[:, 2].max():.5g}, span {np.ptp(x[:, 0]):.5g}, "
          f"largest stress {standing.surface_stress().max() / 1e6:.5g} MPa, "
          f"{standing.equilibrium.iterations} Newton iterations ({t - clock:.2f} s)")  # fmt: skip
    clock = time.process_time()
    sim = run(design, folded, level=args.mesh)
    t = time.process_time()
    assert sim.formed is not None and sim.released is not None
    print(f"moment law: formed plastic share {sim.formed.plastic_area_share:.4f}, released "
          f"deviation max {sim.released.max_deviation:.4g}, standing height "
          f"{sim.standing.height:.5g} span {sim.standing.span:.5g}, largest stress "
          f"{sim.standing.max_stress_MPa:.5g} MPa ({t - clock:.2f} s)")  # fmt: skip


if __name__ == "__main__":
    main()
