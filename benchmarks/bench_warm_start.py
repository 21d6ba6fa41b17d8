"""Would a warm start from the last design's form shorten the Steel view's Newton
solves? Counts the Newton iterations of the coarse springback and standing of
patkau-one-fold at a new alpha, started as ``simulate`` starts them (cold: the
formed state, the placed form) and from the last design's converged states
carried onto the new design:

* **frames**: each node's displacement (last formed -> released, last placed ->
  standing) carried in the surface's frame at that node (the rotation of the
  flat-to-form map there), the director angles' changes added;
* **fit**: the displacements turned by the rigid best fit of the last form onto
  the new one;
* **last form**: the last released (standing) form itself, rigidly fitted onto
  the new formed (placed) form, its directors turned with it and measured in
  the new shell, every crease's two directors set to the new design's crease
  angle (an equilibrium of the last design, no hinge moment).

Each start is solved as the cold path's first step: the same shell, held
unknowns, contacts and tolerance (``stages.RTOL`` times the weight), at most
25 (springback) or 12 (standing) Newton steps. A 3-2-1 restraint carries
nothing, so the springback's fixed unknowns take the start's values. Prints a
table; asserts nothing.

Run from the repository root::

    .venv/bin/python benchmarks/bench_warm_start.py [--pairs 30:31 30:35]
"""

from __future__ import annotations

import argparse
from dataclasses import replace

import numpy as np

from onefold_cad.design import fold_design
from onefold_cad.errors import ConvergenceError
from onefold_cad.mechanics.deviation import best_fit
from onefold_cad.mechanics.equilibrium import solve_equilibrium
from onefold_cad.mechanics.model import GRAVITY, sheet_model
from onefold_cad.mechanics.shell import director_angles, directors, rigid_dofs, unpack
from onefold_cad.mechanics.stages import RTOL, form, place, release, stand, standing_path
from onefold_cad.templates import load_template


def _frames(flat, faces, x):
    """``(n, 3, 3)`` each node's frame on ``x``: the rotation of the flat-to-form map."""
    e0 = np.stack([flat[faces[:, 1]] - flat[faces[:, 0]], flat[faces[:, 2]] - flat[faces[:, 0]]], 2)
    e1 = np.stack([x[faces[:, 1]] - x[faces[:, 0]], x[faces[:, 2]] - x[faces[:, 0]]], 2)
    grad = e1 @ np.linalg.inv(e0)
    area = 0.5 * np.abs(np.linalg.det(e0))
    node = np.zeros((len(x), 3, 2))
    for k in range(3):
        np.add.at(node, faces[:, k], area[:, None, None] * grad)
    u, _, vt = np.linalg.svd(node, full_matrices=False)
    rot = u @ vt
    return np.concatenate([rot, np.cross(rot[:, :, 0], rot[:, :, 1])[:, :, None]], 2)


def _creased(shell, angles):
    """The director angles with every crease at the shell's set angle."""
    mesh = shell.mesh
    ce = mesh.crease_edges
    delta = angles[ce] - angles[mesh.n_edges :] - shell.crease_angle
    out = angles.copy()
    out[ce] -= delta / 2
    out[mesh.n_edges :] += delta / 2
    return out


def _start(mode, model, shell, old_shell, before, after, base):
    """The new start from the last design's ``before`` -> ``after`` and the new ``base``."""
    mesh = model.mesh
    (x0, a0), (x1, a1), (xb, ab) = (unpack(mesh, q) for q in (before, after, base))
    fit = best_fit(x0, xb, model.shell.node_mass)
    if mode == "frames":
        f0, fb = _frames(mesh.nodes, mesh.triangles, x0), _frames(mesh.nodes, mesh.triangles, xb)
        local = np.einsum("nji,nj->ni", f0, x1 - x0)
        return np.concatenate([(xb + np.einsum("nij,nj->ni", fb, local)).ravel(), ab + a1 - a0])
    if mode == "fit":
        return np.concatenate([(xb + (x1 - x0) @ fit.rotation.T).ravel(), ab + a1 - a0])
    x = fit.apply(x1)
    turned = directors(old_shell, after) @ fit.rotation.T
    return np.concatenate([x.ravel(), _creased(shell, director_angles(shell, x, turned))])


def _iterations(shell, start, **options) -> str:
    try:
        return str(solve_equilibrium(shell, start, start_scales=False, **options).iterations)
    except ConvergenceError as err:
        return f"> {err.iterations} (no convergence)"


def _states(design):
    """The model and its cold stages' states: formed, released, placed, standing."""
    model = sheet_model(design, fold_design(design), level="coarse")
    formed = form(model)
    rel = release(model, formed)
    placed = place(model, rel.equilibrium.q)
    stood = stand(model, placed, rel.state.rest, rel.state, "anchored")
    return model, formed, rel, placed, stood


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--pairs", nargs="+", default=["30:31", "30:35"], help="alpha FROM:TO (deg)")
    args = ap.parse_args(argv)
    base = load_template("patkau-one-fold")
    print("| alpha | start | springback Newton steps | standing Newton steps |")
    print("|---|---|---|---|")
    for pair in args.pairs:
        a, b = (float(v) for v in pair.split(":"))
        old = _states(base.with_changes(frame=replace(base.frame, alpha=a)))
        new = _states(base.with_changes(frame=replace(base.frame, alpha=b)))
        model, formed, rel, placed, stood = new
        o_model, o_formed, o_rel, o_placed, o_stood = old
        if o_model.mesh.n_nodes != model.mesh.n_nodes:
            print(f"| {pair} | – | the mesh differs: cold | |")
            continue
        spring = model.shell.with_changes(rest_curvature=formed.curvature + 1.0 * (
            formed.state.rest - formed.curvature))  # fmt: skip
        fixed = rigid_dofs(model.designed)
        stand_opts = dict(standing_path(model, placed, "anchored"))
        standing_shell = placed.shell.with_changes(
            rest_curvature=rel.state.rest, gravity=np.array([0.0, 0.0, -GRAVITY])
        )
        n = model.mesh.n_nodes
        held = np.zeros(len(placed.q), dtype=bool)
        held[: 3 * n] = np.repeat(placed.contacts, 3)
        opts = {
            "fixed": stand_opts["fixed"], "ground": stand_opts["ground"],
            "contacts": stand_opts["contacts"], "force_scale": model.weight_N, "rtol": RTOL,
            "max_iter": stand_opts["step_iter"],
        }  # fmt: skip
        rows = [("cold (as simulate)", formed.q, placed.q)]
        for mode in ("frames", "fit", "last form"):
            s1 = _start(
                mode, model, spring, o_model.shell, o_formed.q, o_rel.equilibrium.q, formed.q
            )
            s2 = _start(
                mode, model, placed.shell, o_placed.shell, o_placed.q, o_stood.equilibrium.q,
                placed.q,
            )  # fmt: skip
            s2[held] = placed.q[held]
            rows.append((mode, s1, s2))
        for name, s1, s2 in rows:
            first = _iterations(spring, s1, fixed=fixed, force_scale=model.weight_N,
                                rtol=RTOL, max_iter=25)  # fmt: skip
            second = _iterations(standing_shell, s2, **opts)
            print(f"| {a:g} -> {b:g} | {name} | {first} | {second} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
