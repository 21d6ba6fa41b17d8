"""Does the forming path change the formed plastic share?

``onefold simulate`` forms the sheet proportionally: at every point of every
face the curvature grows from zero straight to the designed one (the
"Limits" of docs/mechanics.md: monotonic and proportional). CalculiX's
forming (``calculix_forming.py``) follows instead the One-Fold forms of the
same flat sheet with beta scaled by s from 0 to 1: the sheet folded a little,
then more, as a fold is closed by hand or by a machine. Along that path the
cones change (their apex angles and rulings move over the material), so a
point's curvature changes in direction as well as in size, and a J2 section
may yield where the proportional path does not.

This script runs onefold's own J2 sections (``mechanics.j2``: the same law,
points through the thickness and surfaces as ``simulate``) on one mesh along
both paths, no equilibrium to solve (imposed forms, membrane strain 0):

* **proportional**: ``j2.stages.form`` (``simulate``'s forming);
* **fold path**: the forms of the design with beta scaled by s, at ``--steps``
  equal steps of s, each face's curvature at s (the second fundamental form
  of the same flat nodes mapped into the form at s, the directors along its
  normals) fed to the sections in turn.

It prints each path's formed plastic area share (surfaces yielded, as
``simulate`` reports it), its largest plastic strain and, for the fold path,
how the share grows with s. Pure numpy; seconds. Run from the repository
root::

    .venv/bin/python benchmarks/forming_path.py [TEMPLATE] [--mesh coarse|normal|fine]
        [--steps 24 48] [--json]
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import time
from typing import Any

import numpy as np

from onefold_cad.design import fold_design
from onefold_cad.mechanics.j2 import stages as j2_stages
from onefold_cad.mechanics.j2.measures import surfaces
from onefold_cad.mechanics.model import director_normals, sheet_model
from onefold_cad.mechanics.shell import director_angles, pack
from onefold_cad.mechanics.standing_measures import area_share
from onefold_cad.templates import find_template, load_template


def _curvature_at(model: Any, shell: Any, design: Any, s: float) -> np.ndarray:
    """``(m, 3)`` the faces' Cartesian curvatures of the form at ``s`` (beta
    times ``s``) of the model's flat nodes."""
    frame = dataclasses.replace(design.frame, beta=s * design.frame.beta)
    folded = fold_design(dataclasses.replace(design, frame=frame))
    mesh, scale = model.mesh, model.scale
    x = folded.map_points(mesh.nodes / scale) * scale
    normals = director_normals(folded, mesh, scale)
    return j2_stages.cartesian_curvatures(shell, pack(x, director_angles(shell, x, normals)))


def run(template: str, level: str, steps: list[int]) -> dict[str, Any]:
    """Both paths on ``template`` meshed at ``level``; the fold path at each
    number of ``steps``."""
    design = load_template(find_template(template))
    model = sheet_model(design, fold_design(design), level=level)
    zero = np.zeros((model.mesh.n_faces, 3))

    def measured(stage: j2_stages.J2Stage) -> dict[str, float]:
        peeq = surfaces(stage).face_plastic_strain
        return {
            "plastic_area_share": area_share(model, peeq > 0),
            "max_plastic_strain": float(peeq.max()),
        }

    t0 = time.process_time()
    shell = j2_stages.j2_shell(model)
    proportional = j2_stages.form(model, shell)
    out: dict[str, Any] = {
        "template": template,
        "mesh": level,
        "faces": int(model.mesh.n_faces),
        "proportional": {**measured(proportional), "cpu_s": time.process_time() - t0},
        "fold_path": [],
    }
    final = _curvature_at(model, shell, design, 1.0)
    designed = np.einsum("mij,mj->mi", shell.cartesian, model.shell.rest_curvature)
    out["final_curvature_vs_designed"] = float(
        np.abs(final - designed).max() / np.abs(designed).max()
    )
    for n in steps:
        t0 = time.process_time()
        p = shell.plasticity
        assert p is not None
        growth = []
        resp = None
        for i in range(1, n + 1):
            s = i / n
            resp = p.respond(zero, _curvature_at(model, shell, design, s))
            p = p.moved_on(resp.state)
            if i % max(1, n // 8) == 0 or i == n:
                stage = j2_stages.J2Stage(proportional.q, None, p, resp)
                growth.append((s, measured(stage)["plastic_area_share"]))
        assert resp is not None
        stage = j2_stages.J2Stage(proportional.q, None, p, resp)
        out["fold_path"].append(
            {"steps": n, **measured(stage), "share_by_s": growth, "cpu_s": time.process_time() - t0}
        )
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--mesh", default="normal")
    ap.add_argument("--steps", type=int, nargs="+", default=[24, 48])
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    out = run(args.template, args.mesh, args.steps)
    if args.json:
        print(json.dumps(out, indent=1))
        return 0
    p = out["proportional"]
    print(
        f"{out['template']}, {out['mesh']} mesh ({out['faces']} faces); the fold path's final "
        f"curvature against the designed: {out['final_curvature_vs_designed']:.2g} (relative)"
    )
    print(
        f"  proportional: plastic share {p['plastic_area_share']:.4f}, largest plastic strain "
        f"{p['max_plastic_strain']:.4f}"
    )
    for f in out["fold_path"]:
        grow = ", ".join(f"{s:.3g}: {v:.3f}" for s, v in f["share_by_s"])
        print(
            f"  fold path, {f['steps']} steps: plastic share {f['plastic_area_share']:.4f}, "
            f"largest plastic strain {f['max_plastic_strain']:.4f} ({f['cpu_s']:.1f} s CPU)\n"
            f"    share by s: {grow}"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
