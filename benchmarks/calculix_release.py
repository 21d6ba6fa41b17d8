"""The CalculiX peer of the springback, started from the formed state: a
template's designed sheet as solid quadratic wedges in CalculiX, carrying the
stress onefold's J2 forming leaves in it, released on a statically
determinate support, measured as ``onefold simulate`` measures itself;
onefold's own release (``--law j2`` and the moment law) beside it, timed in
the same run. No forming runs in ccx (its quadratic shells cannot follow the
cones without membrane strain on a mesh this machine can run: see
``calculix_forming.py``); what is checked is the release alone.

* **Model** (``ccx_release.py``): onefold's mesh of the sheet (``sheet_model``
  at ``--mesh``), each face a column of ``--layers`` ``C3D15`` wedges
  extruded along the designed normals (``--split 4``: four columns per
  face, on its curved patch as ``NAME.inp`` splits its facets), the crease
  welded (its nodes shared by both sides, moved along the mitre of their
  normals: ``ccx_release.node_moves``; it keeps its angle, as ``--crease held``);
  ``*ELASTIC`` E, nu, ``*PLASTIC`` sigma_y, 0 (the perfectly plastic
  variant of the template: ``--hardening-modulus 0`` on both sides),
  ``NLGEOM``.
* **Formed state**: at each of the 9 integration points of every wedge the
  stress of onefold's imposed forming at that point's height (the J2 law's
  response to the membrane-free strain ``h`` times the face's designed
  curvature, ``FORMING_STEPS`` return mappings), given to ccx as the
  eigenstrain ``-C^-1 sigma`` (``*INITIAL CONDITIONS, TYPE=PLASTIC
  STRAIN``; why not ``TYPE=STRESS``: ``ccx_release``'s docstring).
* **Or CalculiX's own formed state** (``--formed-by DIR``, a
  ``calculix_forming.py --keep`` folder whose forming finished, perfectly
  plastic: broken-vault's, or patkau-one-fold's formed with
  ``--perfectly-plastic``): the stress its ``S6`` shells left at their
  integration points, carried to the wedges' points by flat position
  (``ccx_handover.py``: per side of the crease, linear in the plane and
  through the thickness), its through-thickness stress taken out as a
  pressure (the deviator kept: a shell's plane stress), on one column of
  wedges a face or four. So CalculiX forms and CalculiX releases, the state moved
  between two meshes as Abaqus's ``*IMPORT`` moves a forming into its
  springback.
* **Held run**: every node fixed; the printed stresses must be the initial
  ones (``held_stress_error``, relative to sigma_y) and no point may yield
  (``held_peeq_max``); its reactions are the forming tool's forces.
* **Release**: a 3-2-1 support on three mid-surface nodes off the crease
  (next to its ends, and the highest), every other node loaded by its held
  reaction as ``*CLOAD`` ramped from 1 to 0 (``*AMPLITUDE``; ``ccx_deck``'s
  release); ``--field R_n C_n``: ccx's residual and correction bounds.
* **Measures**: the mid-surface's released nodes (the middle level of the
  corner columns, onefold's mesh nodes) after the best rigid fit
  (``standing_measures.aligned_deviation``: weighted by the nodes' mass, the
  distance from the designed surface), max and rms in the design's unit; the
  share of the area that yields again (a face where an outermost point's
  plastic strain grows, as onefold's ``reloaded_area_share``).

Run from the repository root (Debian's ``calculix-ccx``; one thread)::

    .venv/bin/python benchmarks/calculix_release.py patkau-one-fold \\
        [--mesh coarse|normal] [--layers 4] [--onefold] [--keep DIR] [--json]
    .venv/bin/python benchmarks/calculix_release.py broken-vault --mesh normal \\
        --layers 2 --linear --formed-by FORMING_KEEP_DIR
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from ccx_deck import CCX, displacements, finish, id_lines, run_inp, support_321  # noqa: E402
from ccx_handover import wedge_state  # noqa: E402
from ccx_onefold import onefold_side  # noqa: E402
from ccx_release import (  # noqa: E402
    face_frames,
    formed_stress,
    initial_strain,
    node_moves,
    point_heights,
    solid_mesh,
    to_frame,
    to_global,
    wedge_volumes,
)

#: The release's first and largest increment (shares of the ramp): ccx
#: grows an increment that converged fast up to the largest.
FIRST_INC, RELEASE_INC = 0.05, 0.25
#: The formed stresses are given to ccx times ``1 - MARGIN``: ccx's
#: finite-strain law turns the eigenstrain back into the stress within 0.36 %
#: of sigma_y (patkau, coarse), so about half the points on the yield surface
#: landed outside it, flowed in the held run (plastic strain 1.4e-6) and gave
#: the release's first iterations their plastic tangent: the first increment
#: (5 % of the ramp) took 8 iterations and was cut back, where the elastic
#: release took 2. Scaled by 0.995 every point starts inside the surface.
MARGIN = 5e-3


def setup(
    template: str,
    level: str,
    layers: int,
    split: int = 1,
    margin: float = 0.0,
    formed_by: Path | None = None,
) -> dict[str, Any]:
    """The pure-numpy part: the perfectly plastic variant's model, its solid
    mesh (each face one column, or with ``split`` 4 four, on the face's curved
    patch as ``NAME.inp`` splits it), the formed stresses at the integration
    points (global, Pa) and their eigenstrains (of the stresses times ``1 -
    margin``), the 3-2-1 support. ``formed_by``: a ``calculix_forming.py
    --keep`` folder whose forming's state is handed over
    (``ccx_handover``) in place of onefold's J2 forming."""
    from onefold_cad.design import fold_design
    from onefold_cad.export.simulation.inp_mesh import curved_midpoints, shell_mesh, unique_edges
    from onefold_cad.mechanics.energy import second_fundamental_form
    from onefold_cad.mechanics.j2.stages import FORMING_STEPS, j2_shell
    from onefold_cad.mechanics.model import sheet_model
    from onefold_cad.mechanics.shell import director_angles, pack
    from onefold_cad.templates import find_template, load_template

    design = load_template(find_template(template))
    design = dataclasses.replace(
        design,
        material=dataclasses.replace(
            design.material, hardening_modulus=0.0, kinematic_hardening=0.0
        ),
    )
    folded = fold_design(design)
    model = sheet_model(design, folded, level=level)
    mesh, x = model.mesh, model.designed
    tri, flat, n = mesh.triangles, mesh.nodes, len(model.designed)
    shell = j2_shell(model)
    q = pack(x, director_angles(shell, x, model.normals))
    curvature = np.einsum("mij,mj->mi", shell.cartesian, second_fundamental_form(shell, q))
    t = model.material.thickness
    if split == 4:
        sm = shell_mesh(x, tri, flat)
        pts, tri6, where = sm.nodes, sm.elements, sm.flat
    else:
        side = (flat[tri].mean(axis=1)[:, 1] > 0).astype(np.int64)
        edges, face_edge = unique_edges(tri)
        on = np.abs(flat[:, 1]) <= 1e-12 * float(np.ptp(flat, axis=0).max())
        mids = curved_midpoints(x, tri, side, on[edges[:, 0]] & on[edges[:, 1]])
        pts, tri6 = np.concatenate([x, mids]), np.concatenate([tri, n + face_edge], axis=1)
        where = np.concatenate([flat, 0.5 * (flat[edges[:, 0]] + flat[edges[:, 1]])])
    move, crease = node_moves(folded, where, model.scale, t)
    if split == 1:  # the midpoints along the mean of their ends' directions, normalised
        mean = move[edges[:, 0]] + move[edges[:, 1]]
        move[n:] = mean / np.linalg.norm(mean, axis=1)[:, None]
    corner, middle = np.unique(tri6[:, :3]), np.unique(tri6[:, 3:])
    assert np.array_equal(corner[:n], np.arange(n))  # onefold's nodes first
    solid = solid_mesh(
        pts[corner], np.searchsorted(corner, tri6[:, :3]), move[corner],
        pts[middle], move[middle], np.searchsorted(middle, tri6[:, 3:]), t, layers,
    )  # fmt: skip
    vol = wedge_volumes(solid)
    assert plastic_law(shell).hardening_iso == 0.0
    heights = point_heights(t, layers)  # (L, 9)
    frames = np.repeat(face_frames(x, tri), split, axis=0)
    handover: dict[str, Any] = {}
    if formed_by is None:
        plane, plastic = formed_stress(
            plastic_law(shell), curvature, heights.ravel(), FORMING_STEPS
        )
        plane = np.repeat(plane, split, axis=0) * (1.0 - margin)  # sub-element c of face c // split
        stress = to_global(plane, frames)  # (m split, L * 9, 6)
    else:  # each column's corners on the flat sheet: the wedges' points found there
        corners = where[tri6[:, :3]]
        plane, plastic, handover = wedge_state(
            formed_by, folded, model, corners, heights, frames, margin
        )
        stress = to_global(plane, frames)
        plastic = plastic.reshape(len(tri), split, -1).any(axis=1)  # per face, as onefold's
    mat = model.material
    # the support off the crease: next to its two ends, and the highest node
    on_crease = np.flatnonzero(crease[:n])
    free = np.flatnonzero(~crease[:n])
    tips = [x[on_crease[np.argmax(x[on_crease, 0])]], x[on_crease[np.argmin(x[on_crease, 0])]]]
    ends = [int(free[np.argmin(np.linalg.norm(x[free] - p, axis=1))]) for p in tips]
    top = int(free[np.argmax(x[free, 2])])
    return {
        "design": design,
        "folded": folded,
        "model": model,
        "solid": solid,
        "volume_min": float(vol.min()),
        "volume_sum": float(vol.sum()),
        "plane": plane,
        "plastic": plastic,
        "frames": frames,
        "stress": stress,
        "eigen": initial_strain(stress, mat.youngs_modulus, mat.poisson),
        "support": support_321(x, [ends[0], ends[1], top]),
        "layers": layers,
        "split": split,
        "margin": margin,
        "n": n,
        "handover": handover,
    }


def plastic_law(shell):
    """The J2 law of the shell's sections."""
    assert shell.plasticity is not None
    return shell.plasticity.law


def _model_lines(st: dict[str, Any]) -> list[str]:
    """Nodes, elements, material, section and the initial strains."""
    solid, mat = st["solid"], st["model"].material
    used = np.unique(solid.elements)  # not the edge midpoints' odd levels
    out = ["*HEADING", "onefold calculix_release", "*NODE"]
    xs = solid.nodes
    out += [f"{i + 1},{xs[i, 0]:.12g},{xs[i, 1]:.12g},{xs[i, 2]:.12g}" for i in used]
    out.append("*ELEMENT,TYPE=C3D15,ELSET=E")
    out += [
        f"{j + 1}," + ",".join(str(int(v) + 1) for v in e) for j, e in enumerate(solid.elements)
    ]
    out.append("*NSET,NSET=ALL")
    out += id_lines(used + 1)
    mid = solid.layers * solid.n_corners
    out.append("*NSET,NSET=MID")
    out += id_lines(range(mid + 1, mid + st["n"] + 1))
    out += ["*MATERIAL,NAME=STEEL", "*ELASTIC", f"{mat.youngs_modulus:.10g},{mat.poisson:.10g}"]
    if not st.get("elastic"):
        out += ["*PLASTIC", f"{mat.yield_stress:.10g},0."]
    # small strains (no NLGEOM): ccx's small-strain plasticity reads the stress itself
    kind, values = ("STRESS", st["stress"]) if st.get("linear") else ("PLASTIC STRAIN", st["eigen"])
    out += ["*SOLID SECTION,ELSET=E,MATERIAL=STEEL", f"*INITIAL CONDITIONS,TYPE={kind}"]
    eigen = values.reshape(-1, solid.layers, 9, 6)  # column, layer, point
    for f in range(len(eigen)):
        for k in range(solid.layers):
            elem = f * solid.layers + k + 1
            for p in range(9):
                vals = ",".join(f"{v:.10g}" for v in eigen[f, k, p])
                out.append(f"{elem},{p + 1},{vals}")
    return out


def write_held(st: dict[str, Any], path: Path) -> None:
    """Every node held: the stresses printed (the initial ones?) and the
    reactions (the forming tool's forces)."""
    step = "*STEP" if st.get("linear") else "*STEP,NLGEOM"
    out = _model_lines(st) + ["*BOUNDARY", "ALL,1,3", step, "*STATIC", "1.,1."]
    out += ["*NODE PRINT,NSET=ALL", "RF", "*EL PRINT,ELSET=E", "S,PEEQ", "*END STEP"]
    path.write_text("\n".join(out) + "\n")


def write_release(
    st: dict[str, Any],
    rf: np.ndarray,
    path: Path,
    inc: float,
    field: tuple[float, ...] = (),
    iterations: tuple[int, ...] = (),
) -> None:
    """The 3-2-1 support on the mid-surface, every other node's held reaction
    ``rf`` ``(N, 3)`` ramped from 1 to 0 over the step; ``field``: ccx's
    ``*CONTROLS, PARAMETERS=FIELD`` (R_n, C_n: the residual's and the
    correction's bounds, defaults 0.005 and 0.01), none: ccx's;
    ``iterations``: its ``TIME INCREMENTATION`` (I_0, I_R: the iterations
    before it checks for divergence and at most, defaults 4 and 8)."""
    solid = st["solid"]
    mid = solid.layers * solid.n_corners
    fixed = {mid + node: dirs for node, dirs in st["support"].items()}
    out = _model_lines(st)
    out += ["*AMPLITUDE,NAME=DOWN", "0.,1.,1.,0.", "*BOUNDARY"]
    for node, dirs in fixed.items():
        out += [f"{node + 1},{d},{d},0." for d in dirs]
    first = min(inc, FIRST_INC)
    step = "*STEP,INC=10000" if st.get("linear") else "*STEP,NLGEOM,INC=10000"
    out += [step, "*STATIC", f"{first:.6g},1.,1e-7,{inc:.6g}"]
    if field:
        out += ["*CONTROLS,PARAMETERS=FIELD", ",".join(f"{v:g}" for v in field)]
    if iterations:
        out += ["*CONTROLS,PARAMETERS=TIME INCREMENTATION", ",".join(map(str, iterations))]
    out.append("*CLOAD,AMPLITUDE=DOWN")
    for i, f in enumerate(rf):
        for d in (1, 2, 3):
            if d not in fixed.get(i, []) and f[d - 1] != 0.0:
                out.append(f"{i + 1},{d},{f[d - 1]:.12g}")
    out += ["*NODE PRINT,NSET=MID,FREQUENCY=100000", "U"]
    out += ["*EL PRINT,ELSET=E,FREQUENCY=100000", "PEEQ", "*END STEP"]
    path.write_text("\n".join(out) + "\n")


def _outer(values: np.ndarray, layers: int) -> np.ndarray:
    """``(m, 6)`` the values at each face's outermost points (the bottom
    layer's three lowest, the top layer's three highest) of per-point
    ``values`` ``(m * layers * 9,)`` in ccx's order."""
    v = values.reshape(-1, layers, 9)
    return np.concatenate([v[:, 0, :3], v[:, -1, 6:]], axis=1)


def run(
    template: str,
    level: str,
    layers: int,
    workdir: Path,
    inc: float,
    elastic: bool = False,
    linear: bool = False,
    split: int = 1,
    margin: float = 0.0,
    field: tuple[float, ...] = (),
    iterations: tuple[int, ...] = (),
    formed_by: Path | None = None,
) -> dict[str, Any]:
    """The held and the released runs and their measures; ``elastic``: the
    release without ``*PLASTIC`` (the formed stresses unloaded elastically);
    ``linear``: no ``NLGEOM`` (the stresses as ``TYPE=STRESS``);
    ``formed_by``: CalculiX's own forming kept there, handed over."""
    from onefold_cad.mechanics.standing_measures import aligned_deviation, area_share

    st = setup(template, level, layers, split, margin, formed_by)
    st |= {"elastic": elastic, "linear": linear}
    solid, model, mat = st["solid"], st["model"], st["model"].material
    m, n_pts = len(model.mesh.triangles), layers * 9
    cols = m * split
    name = f"{template}_{level}_L{layers}_x{split}" + ("_elastic" if elastic else "")
    name += "_linear" if linear else ""
    name += "" if formed_by is None else "_ccxformed"
    write_held(st, workdir / f"{name}_held.inp")
    held, wall1, cpu1 = run_inp(workdir, f"{name}_held")
    s_ccx = held[("stresses", 1.0)][:, 2:8].reshape(cols, n_pts, 6)
    none = np.zeros((cols * n_pts, 3))  # an elastic run prints no PEEQ
    peeq1 = held.get(("equivalent plastic strain", 1.0), none)[:, 2]
    rf = np.zeros((len(solid.nodes), 3))
    f = held[("forces", 1.0)]
    rf[f[:, 0].astype(int) - 1] = f[:, 1:4]
    write_release(st, rf, workdir / f"{name}.inp", inc, field, iterations)
    out: dict[str, Any] = {
        "template": template,
        "mesh": level,
        "layers": layers,
        "law": "elastic" if elastic else "perfectly plastic",
        "nlgeom": not linear,
        "columns_per_face": split,
        "controls_field": list(field),
        "controls_iterations": list(iterations),
        "margin": margin,
        "formed": "onefold" if formed_by is None else "calculix",
        **st["handover"],
        "faces": m,
        "nodes": len(solid.nodes),
        "elements": len(solid.elements),
        "wedge_volume_min": st["volume_min"],
        "volume_vs_area_t": st["volume_sum"] / (model.shell.ref_area.sum() * mat.thickness),
        "formed_outer_plastic_share": area_share(
            model, _outer(st["plastic"].ravel(), layers).any(1)
        ),
        "held_stress_error": float(np.abs(s_ccx - st["stress"]).max() / mat.yield_stress),
        "held_in_plane_error": float(
            np.abs(to_frame(s_ccx, st["frames"]) - st["plane"]).max() / mat.yield_stress
        ),
        "held_peeq_max": float(peeq1.max()),
        "reaction_sum_N": float(np.abs(rf.sum(axis=0)).max()),
        "reaction_max_N": float(np.abs(rf).max()),
        "unit": st["design"].units.value,
        "wall_held_s": wall1,
        "cpu_held_s": cpu1,
    }
    try:
        rel, wall2, cpu2 = run_inp(workdir, name)
    except RuntimeError as err:
        out["release_error"] = str(err)
        return out
    end = max(k[1] for k in rel if k[0] == "displacements")
    mid = solid.layers * solid.n_corners
    u = displacements(rel, end, len(solid.nodes))[mid : mid + st["n"]]
    dmax, drms = aligned_deviation(model, st["folded"], model.designed + u)
    peeq2 = rel.get(("equivalent plastic strain", end), none)[:, 2]
    grew = (_outer(peeq2, layers) > _outer(peeq1, layers) + 1e-9).reshape(m, -1)
    out.update(
        released_to=end,
        springback_max=dmax,
        springback_rms=drms,
        yields_again_share=area_share(model, grew.any(axis=1)),
        wall_release_s=wall2,
        cpu_release_s=cpu2,
    )
    return out


def _print(r: dict[str, Any]) -> None:
    u = r["unit"]
    line = (
        f"{r['template']} {r['mesh']} x{r['columns_per_face']} L={r['layers']} {r['law']}: "
        f"{r['faces']} faces, {r['nodes']} nodes, {r['elements']} C3D15; held: stress error "
        f"{r['held_stress_error']:.2g} sigma_y "
        f"(in plane {r['held_in_plane_error']:.2g}), peeq {r['held_peeq_max']:.2g}, "
        f"ccx {r['cpu_held_s']:.0f} s CPU"
    )
    if "release_error" in r:
        line += f"; release FAILED: {r['release_error']}"
    else:
        line += (
            f"; released to {r['released_to']:g}: springback max {r['springback_max']:.4g} {u}"
            f" rms {r['springback_rms']:.4g}, yields again {r['yields_again_share']:.4f}, "
            f"ccx {r['cpu_release_s']:.0f} s CPU ({r['wall_release_s']:.0f} s wall)"
        )
    print(line, flush=True)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("template", help="a template name (patkau-one-fold, broken-vault)")
    ap.add_argument("--mesh", nargs="+", default=["coarse"], choices=["coarse", "normal"])
    ap.add_argument("--layers", type=int, nargs="+", default=[4], help="wedges through t")
    ap.add_argument("--inc", type=float, default=RELEASE_INC, help="largest release increment")
    ap.add_argument("--elastic", action="store_true", help="ccx without *PLASTIC")
    ap.add_argument(
        "--linear", action="store_true", help="no NLGEOM: small strains, TYPE=STRESS read as is"
    )
    ap.add_argument(
        "--margin",
        type=float,
        default=MARGIN,
        help="the formed stresses scaled by 1 - MARGIN (points on the yield surface inside it)",
    )
    ap.add_argument(
        "--field",
        type=float,
        nargs="+",
        default=[],
        help="ccx's *CONTROLS, PARAMETERS=FIELD for the release (R_n C_n ...)",
    )
    ap.add_argument(
        "--iterations",
        type=int,
        nargs="+",
        default=[],
        help="ccx's *CONTROLS, PARAMETERS=TIME INCREMENTATION for the release (I_0 I_R ...)",
    )
    ap.add_argument(
        "--split", type=int, choices=[1, 4], default=1, help="columns of wedges per face"
    )
    ap.add_argument(
        "--formed-by",
        type=Path,
        help="a calculix_forming.py --keep folder: release CalculiX's own (perfectly plastic) "
        "formed state instead of onefold's (ccx_handover.py)",
    )
    ap.add_argument("--onefold", action="store_true", help="onefold's side, timed in this run")
    ap.add_argument("--no-ccx", action="store_true", help="onefold's side only")
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--keep", type=Path, help="keep the ccx files in this directory")
    args = ap.parse_args(argv)
    if not args.no_ccx and not Path(CCX).exists():
        print("calculix_release: needs ccx (apt-get install calculix-ccx)", file=sys.stderr)
        return 2
    workdir = args.keep or Path(tempfile.mkdtemp(prefix="ccx_release_"))
    workdir.mkdir(parents=True, exist_ok=True)
    out: dict[str, Any] = {"runs": [], "onefold": []}
    if args.onefold:
        out["onefold"] = onefold_side(
            args.template, args.mesh, ["held"], ("j2", "moment"),
            extra=("--hardening-modulus", "0", "--no-check"),
        )  # fmt: skip
        for r in out["onefold"] if not args.json else []:
            print(
                f"{r['what']}: springback max {r['springback_max']:.4g} rms "
                f"{r['springback_rms']:.4g}, yields again {r['yields_again_share']}, formed "
                f"plastic share {r['plastic_share']}, {r['cpu_s']:.1f} s CPU "
                f"({r['wall_s']:.1f} s wall)",
                flush=True,
            )
    for level in [] if args.no_ccx else args.mesh:
        for layers in args.layers:
            r = run(
                args.template, level, layers, workdir, args.inc, args.elastic, args.linear,
                args.split, args.margin, tuple(args.field), tuple(args.iterations),
                args.formed_by,
            )  # fmt: skip
            out["runs"].append(r)
            if not args.json:
                _print(r)
    return finish(out, args.json, bool(args.keep), workdir)


if __name__ == "__main__":
    sys.exit(main())
