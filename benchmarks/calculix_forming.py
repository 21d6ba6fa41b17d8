"""The independent CalculiX benchmark of the forming and springback: a
template's flat sheet formed in CalculiX into its designed form, released on
a statically determinate support, and measured the way ``onefold simulate``
measures itself; onefold's numbers beside it, timed in the same run.

The model (SI units; the deck in ``ccx_deck.py``, the driven path in
``ccx_path.py``):

* **Mesh**: the flat sheet meshed with Triangle by ``kratos_shell.mesh_sheet``
  (relief hole as a polygon hole, the crease as constrained segments), each
  triangle made an ``S6`` shell by its edge midpoints, the crease split into a
  hinge (each side its own nodes, tied in translation).
* **Section**: ``*SHELL SECTION, COMPOSITE`` of ``--layers`` equal layers of
  the template's steel (2 Gauss points through each layer), ``*ELASTIC`` E,
  nu and ``*PLASTIC`` sigma_y, 0 (von Mises, perfectly plastic), ``NLGEOM``.
* **Forming**: every node driven from the flat sheet to the designed form
  along forms that stay isometric to the flat sheet (the designs with beta
  scaled by s, ``FoldedSheet.map_points`` of the same flat nodes), each form
  moved rigidly onto the one before (the rigid motion between forms taken out
  of the path), the steps graded (halved where needed) until ccx's linear ramp
  between two forms changes no chord by more than ``--bound`` (default a tenth
  of the yield strain: :func:`ccx_path.graded_steps`). ``--s-max`` stops the
  forming early (the check that the mid-plane stays elastic).
* **Release** in the same ccx run after the forming: a 3-2-1 support (both
  crease ends and the lifted corner) and every other driver's reaction (from
  a first, forming-only run) ramped down to zero as ``*CLOAD``.
* **Measures** (from the ``.dat``): the plastic area share after forming (the
  area share of in-plane integration points where either surface has yielded:
  the outermost Gauss point has plastic strain, or the stress extrapolated
  from the outer layer's two points to the surface reaches sigma_y), the
  mid-plane's yielded share (the two innermost levels: membrane yielding,
  which an isometric forming should not cause), the springback (the released
  nodes brought onto the designed ones by ``deviation.best_fit``, weighted by
  area, then ``deviation.surface_distance``, as ``simulate`` measures it), the
  share that yields again on release; the share the bending alone yields
  (the membrane stress of the S6's own stretching taken out: ``ccx_split``).
* **Mesh convergence**: several ``--h`` of a constant ratio, Richardson's
  extrapolation of each measure.
* **onefold's side** (``--onefold``): ``onefold simulate TEMPLATE --json``
  (the public command) for each ``--onefold-mesh``, ``--onefold-crease`` and
  ``--onefold-law``, as child processes, CPU time from ``getrusage`` of the
  children.

``strip`` validates the chain on a wide strip bent to a cylinder of radius R
and released, against Gardiner's springback in plane strain.

CalculiX (Debian's ``calculix-ccx``) and ``triangle`` are no dependency of the
package. Run from the repository root, one thread per ccx::

    .venv/bin/python benchmarks/calculix_forming.py strip [--x 0.1 0.3] [--direct]
    .venv/bin/python benchmarks/calculix_forming.py patkau-one-fold --path-only --h 0.4
    .venv/bin/python benchmarks/calculix_forming.py patkau-one-fold \\
        --h 0.4 0.28 0.2 [--layers 4] [--bound 1.1e-4] [--s-max 0.1] [--onefold] \\
        [--json] [--keep DIR]
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from ccx_deck import (  # noqa: E402
    CCX,
    Array,
    Deck,
    displacements,
    finish,
    form_and_release,
    node_areas,
    quadratic,
    split_crease,
    support_321,
    surface_state,
)
from ccx_mesh import graded_sheet  # noqa: E402
from ccx_onefold import onefold_side  # noqa: E402
from ccx_path import corner_edges, graded_steps, half_edges, s6_membrane_strain  # noqa: E402
from ccx_split import formed_split, level_heights  # noqa: E402
from ccx_strip import strip  # noqa: E402
from kratos_shell import mesh_sheet  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def free_edge_midpoints(tri6: Any, n1: int) -> Any:
    """The sorted midpoints (below ``n1``: no crease twin) of the S6 edges that
    one element alone uses: the outline, the relief hole and the hinge's +y
    side (its -y twins are tied to those)."""
    t = np.asarray(tri6, dtype=np.int64)
    mids = np.concatenate([t[:, 3], t[:, 4], t[:, 5]])
    ids, count = np.unique(mids, return_counts=True)
    return ids[(count == 1) & (ids < n1)]


# -- the template ---------------------------------------------------------------
def template_setup(
    template: str,
    h: float,
    *,
    bound: float | None,
    start: int,
    s_max: float,
    align: bool = True,
    drive: str = "corners",
    growth: float | None = None,
) -> dict[str, Any]:
    """The pure-numpy part of a template's run at edge length ``h`` (m): the
    mesh (crease split), the graded driven path, the material, the 3-2-1
    support; ``bound`` None: a tenth of the yield strain sigma_y / E;
    ``growth``: the mesh graded toward H (``ccx_mesh.graded_sheet``), None:
    Triangle's uniform mesh of ``kratos_shell``."""
    from onefold_cad.design import fold_design
    from onefold_cad.fabrication.relief_hole import relief_hole_diameter
    from onefold_cad.templates import find_template, load_template

    design = load_template(find_template(template))
    scale = {"mm": 1e-3, "in": 0.0254, "m": 1.0}[design.units.value]
    folded = fold_design(design)
    hole = relief_hole_diameter(design, folded)
    polygon = np.asarray(design.sheet.vertices, dtype=float)
    if growth is None:
        pts, tris, info = mesh_sheet(polygon, hole, h / scale)
    else:
        pts, tris, info = graded_sheet(polygon, hole, h / scale, growth)
    flat1, tri1 = quadratic(pts, tris)
    flat, tri6, partner = split_crease(flat1, tri1, 0.5 * hole)
    n1, n = len(flat1), len(flat)
    m = design.material
    E, nu, sy, t = m.youngs_modulus * 1e9, m.poisson, m.yield_stress * 1e6, m.thickness * scale
    hardening = (m.hardening_modulus or 0.0) * 1e6  # Pa, isotropic (as simulate's J2 law)
    if m.kinematic_hardening:
        raise SystemExit("calculix_forming: a kinematic hardening share is not modelled here")
    bound = 0.1 * sy / E if bound is None else bound
    weights, area = node_areas(flat, tri6)

    def form(sigma: float) -> Array:
        frame = dataclasses.replace(design.frame, beta=sigma * s_max * design.frame.beta)
        return fold_design(dataclasses.replace(design, frame=frame)).map_points(flat) * scale

    x0 = np.column_stack([flat * scale, np.zeros(n)])
    edges = half_edges(tri6) if drive == "all" else corner_edges(tri6)
    path = graded_steps(form, x0, edges, weights, bound=bound, start=start, align=align)
    ends = info["crease_ends"]
    corners = [int(v) for v in info["vertices"] if int(v) not in ends]
    final = path.forms[-1]
    corner = max(corners, key=lambda v: form(1.0)[v, 2])
    support = support_321(final, [int(ends[0]), int(ends[1]), corner])
    driven = np.arange(n1 if drive == "all" else len(pts))
    if drive == "crease":  # and the crease's midpoints: on its straight rulings, exactly
        size = float(np.ptp(flat1, axis=0).max())
        mids = np.arange(len(pts), n1)
        on = (np.abs(flat1[mids, 1]) <= 1e-9 * size) & (np.abs(flat1[mids, 0]) >= 0.5 * hole)
        driven = np.concatenate([driven, mids[on]])
    elif drive == "edges":  # and the midpoint of every free edge (outline, hole, hinge)
        driven = np.concatenate([driven, free_edge_midpoints(tri6, n1)])
    deck = Deck(
        x0,
        tri6,
        np.round(path.s * s_max, 9),
        (path.forms - x0[None])[:, driven],  # the midpoints follow the corners
        driven,
        t,
        E,
        nu,
        sy,
        hardening=hardening,
        twins=partner,
        support=support,
        form_inc=1.0,
        first_inc=0.25,
    )
    return {
        "design": design,
        "folded": folded,
        "scale": scale,
        "hole": hole,
        "flat": flat,
        "deck": deck,
        "path": path,
        "bound": bound,
        "weights": weights,
        "area": area,
        "designed": form(1.0) if s_max == 1.0 else None,
    }


def template_run(
    template: str,
    h: float,
    *,
    layers: int,
    bound: float | None,
    start: int,
    s_max: float,
    workdir: Path,
    drive: str = "corners",
    release: bool = True,
    reuse: bool = False,
    growth: float | None = None,
    perfectly_plastic: bool = False,
) -> dict[str, Any]:
    """Form (to ``s_max``) and, when the forming is complete and ``release``,
    release ``template`` meshed at edge length ``h`` (m); the measures.
    ``reuse``: a finished forming run in ``workdir`` is read, not rerun;
    ``perfectly_plastic``: the template's law without its hardening (a state
    ``calculix_release.py --formed-by`` can hand over)."""
    from onefold_cad.mechanics.deviation import best_fit, surface_distance

    st = template_setup(
        template, h, bound=bound, start=start, s_max=s_max, drive=drive, growth=growth
    )
    deck: Deck = dataclasses.replace(st["deck"], layers=layers)
    if perfectly_plastic:
        deck = dataclasses.replace(deck, hardening=0.0)
    scale, path = st["scale"], st["path"]
    full = s_max == 1.0 and release
    name = f"{template}_h{h:g}_{drive}" + ("" if growth is None else f"_g{growth:g}")
    name += "_pp" if perfectly_plastic and st["deck"].hardening > 0 else ""
    name += "" if s_max == 1.0 else f"_s{s_max:g}"
    res = form_and_release(deck, workdir, name, release=full, reuse=reuse)
    n, ne = len(deck.x0), len(deck.tri6)
    end = round(float(deck.s[-1]), 6)
    formed = surface_state(res["form"], end, layers, deck.t, deck.sy, ne)
    sp = formed_split(res["form"], end, layers, deck.t, ne)  # membrane taken out
    outer = float(level_heights(deck.t, layers)[-1])
    w_pt = np.repeat(st["area"][:, None] / 3.0, 3, axis=1)
    share = lambda mask: float(w_pt[mask].sum() / w_pt.sum())  # noqa: E731
    xf = deck.x0 + displacements(res["form"], end, n)
    out: dict[str, Any] = {
        "template": template,
        "h_m": h,
        "nodes": n,
        "elements": ne,
        "layers": layers,
        "s_max": s_max,
        "steps": len(deck.s),
        "ramp_strain_max": float(path.worst.max()),
        "bound": st["bound"],
        "plastic_share": share(formed["yielded"]),
        "plastic_share_outer_point": share((formed["peeq_bottom"] > 0) | (formed["peeq_top"] > 0)),
        "mid_plane_yielded_share": share(formed["mid_yielded"]),
        "bending_share": share(sp.bending_yielded(0.5 * deck.t, deck.sy)),
        "bending_share_outer_point": share(sp.bending_yielded(outer, deck.sy)),
        "membrane_at_yield_edge_mpa": sp.membrane_at_edge(deck.t, deck.sy) / 1e6,
        "peeq_max_formed": float(formed["peeq"].max()),
        "drive": drive,
        "formed_vs_driven_max": float(
            np.abs(xf[deck.driven] - path.forms[-1][deck.driven]).max() / scale
        ),
        "unit": st["design"].units.value,
        "wall_form_s": res["wall_form_s"],
        "wall_release_s": res["wall_release_s"],
        "cpu_form_s": res["cpu_form_s"],
        "cpu_release_s": res["cpu_release_s"],
    }
    if full:
        released = surface_state(res["release"], end + 1.0, layers, deck.t, deck.sy, ne)
        grew = (released["peeq_bottom"] > formed["peeq_bottom"] * (1 + 1e-9) + 1e-12) | (
            released["peeq_top"] > formed["peeq_top"] * (1 + 1e-9) + 1e-12
        )
        xr = deck.x0 + displacements(res["release"], end + 1.0, n)
        fit = best_fit(xr, st["designed"], st["weights"])
        dev = surface_distance(st["folded"], fit.apply(xr) / scale, 0.5 * st["hole"])
        out.update(
            springback_max=float(dev.max()),
            springback_rms=float(np.sqrt(np.average(dev**2, weights=st["weights"]))),
            yields_again_share=share(grew),
        )
    return out


def richardson(h: list[float], v: list[float]) -> tuple[float | None, float | None]:
    """``(extrapolated value, observed order)`` from the last three of a
    sequence with a constant ratio of h; the order from the three values, or 2
    (nominal, for S6) when they do not converge monotonically (order None)."""
    if len(h) < 3:
        return None, None
    (h1, h2, h3), (v1, v2, v3) = h[-3:], v[-3:]
    r = h1 / h2
    if abs(h2 / h3 - r) > 0.05 * r:
        return None, None
    d1, d2 = v2 - v1, v3 - v2
    if d1 != 0 and d2 / d1 > 0 and abs(d2) < abs(d1):
        p = math.log(d1 / d2) / math.log(r)
        return v3 + d2 / (r**p - 1.0), p
    return v3 + d2 / (r**2 - 1.0), None


# -- the command ------------------------------------------------------------------
def _path_only(args: argparse.Namespace) -> dict[str, Any]:
    rows = []
    for h in args.h:
        for align in (False, True):
            st = template_setup(
                args.case,
                h,
                bound=args.bound,
                start=args.start,
                s_max=args.s_max,
                align=align,
                drive=args.drive,
                growth=args.growth,
            )
            p = st["path"]
            mem = s6_membrane_strain(st["deck"].x0[:, :2], p.forms[-1], st["deck"].tri6)
            rows.append(
                {
                    "h_m": h,
                    "aligned": align,
                    "nodes": len(st["flat"]),
                    "steps": len(p.s),
                    "bound": st["bound"],
                    "ramp_strain_max": float(p.worst.max()),
                    "first_steps_s": [round(float(v), 6) for v in p.s[:4]],
                    "every_node_s6_strain": [float(np.quantile(mem, q)) for q in (0.5, 0.95, 1)],
                }
            )
            if not args.json:
                r = rows[-1]
                print(
                    f"h {h:g} m, {'aligned' if align else 'as mapped'}: {r['nodes']} nodes, "
                    f"{r['steps']} steps (first {r['first_steps_s']}), largest ramp strain "
                    f"{r['ramp_strain_max']:.3g} (bound {r['bound']:.3g}); every node on the "
                    "designed form would strain the S6 by (median, 95 %, max) "
                    + ", ".join(f"{v:.2g}" for v in r["every_node_s6_strain"])
                )
    return {"paths": rows}


def _print_template(r: dict[str, Any]) -> None:
    line = (
        f"h {r['h_m']:g} m: {r['nodes']} nodes, {r['elements']} S6, {r['steps']} steps to "
        f"s = {r['s_max']:g} (ramp strain <= {r['ramp_strain_max']:.2g}); plastic share "
        f"{r['plastic_share']:.4f} (outermost point {r['plastic_share_outer_point']:.4f}, "
        f"mid-plane {r['mid_plane_yielded_share']:.4f}), peeq max {r['peeq_max_formed']:.3g}; "
        f"the bending alone {r['bending_share']:.4f} (outermost point "
        f"{r['bending_share_outer_point']:.4f}; membrane at its yield edge "
        f"{r['membrane_at_yield_edge_mpa']:.3g} MPa)"
    )
    if "springback_max" in r:
        line += (
            f"; springback max {r['springback_max']:.4g} {r['unit']} (rms "
            f"{r['springback_rms']:.4g}), yields again {r['yields_again_share']:.4f}"
        )
    if r["wall_form_s"] is not None:
        line += f"; ccx forming {r['wall_form_s']:.0f} s wall, {r['cpu_form_s']:.0f} s CPU"
    if r["wall_release_s"] is not None:
        line += f", forming + release {r['wall_release_s']:.0f} s wall {r['cpu_release_s']:.0f} CPU"
    print(line, flush=True)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("case", help="'strip' or a template name (patkau-one-fold, broken-vault)")
    ap.add_argument("--h", type=float, nargs="*", default=[0.4, 0.28, 0.2], help="edge lengths (m)")
    ap.add_argument("--x", type=float, nargs="+", default=[0.1, 0.3], help="strip: R sy / (E t)")
    ap.add_argument("--direct", action="store_true", help="strip: *BOUNDARY on the shell nodes")
    ap.add_argument("--layers", type=int, default=4)
    ap.add_argument("--bound", type=float, help="largest ramp strain (default sigma_y / E / 10)")
    ap.add_argument("--start", type=int, default=10, help="equal steps before the grading")
    ap.add_argument("--s-max", type=float, default=1.0, help="form only to this s (no release)")
    ap.add_argument(
        "--drive",
        choices=["corners", "crease", "edges", "all"],
        default="corners",
        help="drive the S6 corners (the midpoints follow), the corners and the crease's "
        "midpoints (the hinge's edges, straight), the corners and every free edge's "
        "midpoint (outline, hole, hinge: no free edge left to buckle), or every node",
    )
    ap.add_argument("--growth", type=float, help="grade the mesh toward H: size = growth * r")
    ap.add_argument("--no-release", action="store_true", help="form only")
    ap.add_argument(
        "--perfectly-plastic", action="store_true", help="the template's law without hardening"
    )
    ap.add_argument("--reuse", action="store_true", help="read a finished forming in --keep DIR")
    ap.add_argument("--path-only", action="store_true", help="the driven path's check, no ccx")
    ap.add_argument("--onefold", action="store_true", help="onefold's side, timed in this run")
    ap.add_argument("--onefold-mesh", nargs="+", default=["coarse", "normal"])
    ap.add_argument("--onefold-crease", nargs="+", default=["held", "elastic"])
    ap.add_argument("--onefold-law", nargs="+", default=["moment", "j2"])
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--keep", type=Path, help="keep the ccx files in this directory")
    args = ap.parse_args(argv)
    if args.path_only:
        out = _path_only(args)
        if args.json:
            print(json.dumps(out, indent=1))
        return 0
    if not Path(CCX).exists():
        print("calculix_forming: needs ccx (apt-get install calculix-ccx)", file=sys.stderr)
        return 2
    workdir = args.keep or Path(tempfile.mkdtemp(prefix="ccx_forming_"))
    workdir.mkdir(parents=True, exist_ok=True)
    if args.case == "strip":
        rows = [strip(x, direct=args.direct, layers=args.layers, workdir=workdir) for x in args.x]
        for r in rows if not args.json else []:
            print(
                f"strip x={r['x']:g} {'direct' if r['direct'] else 'drivers'}: R_formed/R_released "
                f"{r['ratio']:.4f} (whole length {r['ratio_whole_length']:.4f}), plane strain "
                f"{r['gardiner_plane_strain'][0]:.4f}..{r['gardiner_plane_strain'][1]:.4f}, "
                f"ccx {r['wall_s']:.0f} s"
            )
        out: dict[str, Any] = {"strip": rows}
    else:
        out = {"runs": [], "onefold": []}
        if args.onefold:
            out["onefold"] = onefold_side(
                args.case, args.onefold_mesh, args.onefold_crease, tuple(args.onefold_law)
            )
            for r in out["onefold"] if not args.json else []:
                print(
                    f"{r['what']}: plastic share {r['plastic_share']}, springback max "
                    f"{r['springback_max']}, yields again {r['yields_again_share']}, "
                    f"{r['wall_s']:.1f} s wall, {r['cpu_s']:.1f} s CPU",
                    flush=True,
                )
        for h in args.h:
            r = template_run(
                args.case,
                h,
                layers=args.layers,
                bound=args.bound,
                start=args.start,
                s_max=args.s_max,
                workdir=workdir,
                drive=args.drive,
                release=not args.no_release,
                reuse=args.reuse,
                growth=args.growth,
                perfectly_plastic=args.perfectly_plastic,
            )
            out["runs"].append(r)
            if not args.json:
                _print_template(r)
        hs = [r["h_m"] for r in out["runs"]]
        for key in ("plastic_share", "bending_share", "springback_max", "yields_again_share"):
            vals = [r.get(key) for r in out["runs"]]
            if None not in vals:
                val, p = richardson(hs, vals)
                out[key + "_richardson"] = {"value": val, "order": p}
                if val is not None and not args.json:
                    order = f"order {p:.2g}" if p else "order 2 assumed"
                    print(f"Richardson {key}: {val:.4g} ({order})")
    return finish(out, args.json, bool(args.keep), workdir)


if __name__ == "__main__":
    sys.exit(main())
