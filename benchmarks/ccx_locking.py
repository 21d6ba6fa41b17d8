"""Do ``calculix_release.py``'s thin ``C3D15`` wedges lock? A closed-form
check meshed like the sheet: a cylindrical panel (patkau-one-fold's
thickness, a radius of its median curvature) carrying the elastic stress of
its own bend, released on a 3-2-1 support as ``calculix_release.py``
releases the sheet (held run, reactions ramped down, ``write_held`` and
``write_release``). The stress is the whole bend's (curvature ``1 / R``
across the rulings, none along them, no membrane strain), so the exact
release takes every bit of it back: with ``NLGEOM`` the panel unrolls flat,
without it (``--linear``) it moves by the linear inextensional field of the
curvature change ``-1 / R`` (:func:`linear_unbend`). The springback measured
as ``simulate`` measures it (max and rms deviation from the formed panel
after the best rigid fit, here node to node) divided by the exact one is
the share of the springback the wedges give: 1 without locking.

* **Mesh** (:func:`panel`): Triangle's quality mesh of the flat panel
  (longest edges about ``--h``, as onefold's faces), mapped onto the
  cylinder, edge midpoints on it, each face a column of ``--layers`` wedges
  along the cylinder's normals (``ccx_release.solid_mesh``).
* **Stress** (:func:`bend_stress`): at each integration point the plane
  strain bend ``s_ss = E' eps``, ``s_yy = nu E' eps``, ``eps = -h / R`` (h
  along the top normal, towards the axis), along the cylinder's tangent at
  the point (``--frame point``) or, as ``calculix_release.py`` does, one
  tangent per face at its centroid (``--frame face``); with ``--jumps A``
  each face's stress scaled by its own factor in ``1 +- A``, constant on
  the face as onefold's formed state is (no closed form then: compared
  between ``--splits``, each face split into four so often, the factors
  kept).

Run from the repository root (one ccx at a time, one thread)::

    .venv/bin/python benchmarks/ccx_locking.py [--h 0.386 0.193 0.156 0.078] \\
        [--layers 2] [--linear] [--frame point|face] [--splits 0 1 2] \\
        [--jumps 0.2] [--json]
"""

from __future__ import annotations

import argparse
import itertools
import math
import sys
import tempfile
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from calculix_release import write_held, write_release  # noqa: E402
from ccx_deck import CCX, Array, displacements, finish, run_inp, support_321  # noqa: E402
from ccx_release import GAUSS_WEDGE, initial_strain, point_heights, solid_mesh, to_global  # noqa: E402

#: patkau-one-fold's sheet (m, Pa) and the area-weighted median radius of
#: its designed curvature (m; 0.95 and 3.85 at the 10th and 90th percentiles).
THICKNESS, YOUNGS, POISSON, RADIUS = 3.57e-3, 193e9, 0.29, 2.3
#: The panel: arc length across the rulings, width along them (m).
LENGTH, WIDTH = 2.0, 1.0
#: The seed of ``--jumps``' factors.
JUMP_SEED = 7


def panel(h: float, radius: float = RADIUS, splits: int = 0) -> dict[str, Array]:
    """The panel's mesh: ``flat`` ``(n, 2)`` (s across the rulings, y along),
    ``x`` ``(n, 3)`` on the cylinder ``(R sin(s/R), y, R (1 - cos(s/R)))``,
    ``normals`` (top, towards the axis), ``triangles`` ``(m, 3)``
    counterclockwise about them, ``edges`` ``(E, 2)``, ``face_edge`` ``(m,
    3)``, ``mids`` ``(E, 3)`` and ``mid_normals`` on the cylinder; each face
    of Triangle's mesh split ``splits`` times into four (:func:`split4`),
    ``parent`` ``(m,)`` the face of Triangle's mesh it lies in."""
    import triangle

    from onefold_cad.export.simulation.inp_mesh import unique_edges

    box = np.array([[-0.5 * LENGTH, -0.5 * WIDTH], [0.5 * LENGTH, -0.5 * WIDTH]])
    box = np.concatenate([box, -box])
    seg = np.array([[0, 1], [1, 2], [2, 3], [3, 0]])
    area = 0.5 * h * h  # (Triangle keeps under it: longest edges about h)
    out = triangle.triangulate({"vertices": box, "segments": seg}, f"pq30a{area:.10f}")
    flat, tri = np.asarray(out["vertices"], float), np.asarray(out["triangles"], np.int64)
    d = flat[tri]
    cross = (d[:, 1, 0] - d[:, 0, 0]) * (d[:, 2, 1] - d[:, 0, 1]) - (d[:, 1, 1] - d[:, 0, 1]) * (
        d[:, 2, 0] - d[:, 0, 0]
    )
    tri[cross < 0] = tri[cross < 0][:, [0, 2, 1]]
    parent = np.arange(len(tri))
    for _ in range(splits):
        flat, tri, up = split4(flat, tri)
        parent = parent[up]
    edges, face_edge = unique_edges(tri)
    mid_flat = 0.5 * (flat[edges[:, 0]] + flat[edges[:, 1]])
    x, normals = on_cylinder(flat, radius)
    mids, mid_normals = on_cylinder(mid_flat, radius)
    return {
        "flat": flat, "x": x, "normals": normals, "triangles": tri, "edges": edges,
        "face_edge": face_edge, "mids": mids, "mid_normals": mid_normals, "parent": parent,
    }  # fmt: skip


def split4(flat: Array, triangles: Array) -> tuple[Array, Array, Array]:
    """``(flat, triangles, parent)``: each face split at its edge midpoints
    into four (corners first, then the middle one), counterclockwise as it
    was; the children of face ``f`` are ``4 f .. 4 f + 3``."""
    from onefold_cad.export.simulation.inp_mesh import unique_edges

    edges, fe = unique_edges(triangles)
    mid = len(flat) + fe  # (m, 3): the midpoints of edges 01, 12, 20
    pts = np.concatenate([flat, 0.5 * (flat[edges[:, 0]] + flat[edges[:, 1]])])
    a, b, c = triangles.T
    ab, bc, ca = mid.T
    kids = np.stack(
        [np.stack(k, axis=1) for k in ((a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca))],
        axis=1,
    )
    return pts, kids.reshape(-1, 3), np.repeat(np.arange(len(triangles)), 4)


def on_cylinder(flat: Array, radius: float) -> tuple[Array, Array]:
    """``(positions, top normals)`` of flat points ``(k, 2)`` rolled onto the
    cylinder of ``radius`` (axis along y at height ``radius``)."""
    a = flat[:, 0] / radius
    x = np.column_stack([radius * np.sin(a), flat[:, 1], radius * (1.0 - np.cos(a))])
    return x, np.column_stack([-np.sin(a), np.zeros_like(a), np.cos(a)])


def longest_edges(x: Array, triangles: Array) -> Array:
    """``(m,)`` each face's longest edge (m)."""
    p = x[triangles]
    return np.linalg.norm(p[:, [1, 2, 0]] - p, axis=2).max(axis=1)


def bend_stress(
    flat: Array, triangles: Array, heights: Array, radius: float, frame: str = "point"
) -> Array:
    """``(m, k, 6)`` ccx's stresses at the ``C3D15`` points (``heights``
    ``(layers, 9)``, ccx's order) of the panel bent from flat: plane strain
    across the rulings, ``eps = -h / radius``, ``s_ss = E' eps``, ``s_yy =
    nu E' eps``; along the cylinder's tangent at each point's ``s``
    (``frame="point"``) or at its face's centroid (``"face"``)."""
    ep = YOUNGS / (1.0 - POISSON**2)
    eps = -np.asarray(heights).ravel() / radius  # (k,)
    plane = np.zeros((len(triangles), eps.size, 3))
    plane[..., 0] = ep * eps
    plane[..., 1] = POISSON * ep * eps
    s = flat[triangles, 0]  # (m, 3)
    if frame == "face":
        s_at = np.repeat(s.mean(axis=1)[:, None], eps.size, axis=1)
    else:
        xi, eta = GAUSS_WEDGE[:, 0], GAUSS_WEDGE[:, 1]
        w = np.column_stack([1.0 - xi - eta, xi, eta])  # (9, 3)
        s_at = np.tile(s @ w.T, (1, eps.size // 9))
    a = s_at / radius
    e1 = np.stack([np.cos(a), np.zeros_like(a), np.sin(a)], axis=-1)
    e2 = np.broadcast_to([0.0, 1.0, 0.0], e1.shape)
    out = np.empty(plane.shape[:2] + (6,))
    for k in range(eps.size):  # one frame per point
        frames = np.stack([e1[:, k], e2[:, k], np.cross(e1[:, k], e2[:, k])], axis=1)
        out[:, k] = to_global(plane[:, k : k + 1], frames)[:, 0]
    return out


def linear_unbend(flat: Array, radius: float, steps: int = 400) -> Array:
    """``(n, 3)`` the linear displacement that takes the bend back: the
    rotation ``-s / R`` about the rulings, integrated along the tangent
    (``u' = -(s / R) n(s)``, no membrane strain: ``t . u' = 0``), y-independent."""
    s = flat[:, 0]
    out = np.zeros((len(s), 3))
    for i, si in enumerate(s):
        q = np.linspace(0.0, si, steps + 1)
        a = q / radius
        du = -(q / radius)[:, None] * np.column_stack([-np.sin(a), 0 * a, np.cos(a)])
        out[i] = np.trapezoid(du, q, axis=0)
    return out


def rigid_deviation(moved: Array, target: Array) -> tuple[float, float]:
    """``(max, rms)`` node distance of ``moved`` ``(n, 3)`` from ``target``
    after the best rigid fit (Kabsch, equal weights)."""
    a, b = moved - moved.mean(axis=0), target - target.mean(axis=0)
    u, _, vt = np.linalg.svd(a.T @ b)
    d = np.sign(np.linalg.det(u @ vt))
    rot = u @ np.diag([1.0, 1.0, d]) @ vt
    dist = np.linalg.norm(a @ rot - b, axis=1)
    return float(dist.max()), float(np.sqrt((dist**2).mean()))


def run(
    h: float,
    layers: int,
    linear: bool,
    frame: str,
    workdir: Path,
    splits: int = 0,
    jumps: float = 0.0,
) -> dict[str, Any]:
    """One panel: the held and the released ccx runs, the springback against
    the exact one; ``splits``: each face of Triangle's mesh split so often
    into four; ``jumps``: each of Triangle's faces' stress scaled by its own
    factor in ``1 +- jumps`` (seeded: the same on every split), the formed
    stress piecewise constant as onefold's faces give it (then the exact
    release is not known in closed form: the springback over the uniform
    bend's is only compared between splits)."""
    p = panel(h, splits=splits)
    solid = solid_mesh(
        p["x"], p["triangles"], p["normals"], p["mids"], p["mid_normals"], p["face_edge"],
        THICKNESS, layers,
    )  # fmt: skip
    stress = bend_stress(p["flat"], p["triangles"], point_heights(THICKNESS, layers), RADIUS, frame)
    if jumps:
        rng = np.random.default_rng(JUMP_SEED)
        stress *= (1.0 + jumps * rng.uniform(-1.0, 1.0, p["parent"].max() + 1))[p["parent"]][
            :, None, None
        ]
    x, flat, n = p["x"], p["flat"], len(p["x"])
    ends = [
        int(np.argmin(np.linalg.norm(flat - q, axis=1))) for q in ([-0.4, 0], [0.4, 0], [0, 0.3])
    ]
    mat = SimpleNamespace(youngs_modulus=YOUNGS, poisson=POISSON, yield_stress=math.inf)
    eps = np.zeros_like(stress)
    if not linear:
        eps = initial_strain(stress, YOUNGS, POISSON)
    st = {
        "solid": solid, "model": SimpleNamespace(material=mat), "n": n, "stress": stress,
        "eigen": eps, "support": support_321(x, ends), "elastic": True, "linear": linear,
    }  # fmt: skip
    name = f"panel_h{h:g}_s{splits}_j{jumps:g}_L{layers}_{frame}" + ("_linear" if linear else "")
    write_held(st, workdir / f"{name}_held.inp")
    held, _, cpu1 = run_inp(workdir, f"{name}_held")
    rf = np.zeros((len(solid.nodes), 3))
    f = held[("forces", 1.0)]
    rf[f[:, 0].astype(int) - 1] = f[:, 1:4]
    write_release(st, rf, workdir / f"{name}.inp", 0.25)
    rel, _, cpu2 = run_inp(workdir, name)
    end = max(k[1] for k in rel if k[0] == "displacements")
    mid = layers * n
    u = displacements(rel, end, len(solid.nodes))[mid : mid + n]
    exact = x + linear_unbend(flat, RADIUS) if linear else np.column_stack([flat, 0 * flat[:, 0]])
    got, want = rigid_deviation(x + u, x), rigid_deviation(exact, x)
    hmax = longest_edges(x, p["triangles"])
    return {
        "h_target_m": h,
        "splits": splits,
        "jumps": jumps,
        "faces": len(p["triangles"]),
        "nodes": len(solid.nodes),
        "layers": layers,
        "linear": linear,
        "frame": frame,
        "h_max_median_m": float(np.median(hmax)),
        "h2_over_Rt_median": float(np.median(hmax**2 / (RADIUS * THICKNESS))),
        "springback_max_m": got[0],
        "springback_rms_m": got[1],
        "exact_max_m": want[0],
        "exact_rms_m": want[1],
        "share_max": got[0] / want[0],
        "share_rms": got[1] / want[1],
        "cpu_s": cpu1 + cpu2,
    }


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--h", type=float, nargs="+", default=[0.386, 0.193, 0.156, 0.078])
    ap.add_argument("--layers", type=int, nargs="+", default=[2])
    ap.add_argument("--linear", action="store_true", help="no NLGEOM (TYPE=STRESS)")
    ap.add_argument("--frame", choices=["point", "face"], default="point")
    ap.add_argument(
        "--splits", type=int, nargs="+", default=[0], help="each face split so often into four"
    )
    ap.add_argument(
        "--jumps", type=float, default=0.0, help="each face's stress times 1 +- JUMPS (seeded)"
    )
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--keep", type=Path, help="keep the ccx files in this directory")
    args = ap.parse_args(argv)
    if not Path(CCX).exists():
        print("ccx_locking: needs ccx (apt-get install calculix-ccx)", file=sys.stderr)
        return 2
    workdir = args.keep or Path(tempfile.mkdtemp(prefix="ccx_locking_"))
    workdir.mkdir(parents=True, exist_ok=True)
    out: dict[str, Any] = {"radius_m": RADIUS, "thickness_m": THICKNESS, "runs": []}
    for layers, h, splits in itertools.product(args.layers, args.h, args.splits):
        r = run(h, layers, args.linear, args.frame, workdir, splits, args.jumps)
        out["runs"].append(r)
        if not args.json:
            print(
                f"h {r['h_max_median_m']:.3f} m (h^2/(R t) {r['h2_over_Rt_median']:.2f}), "
                f"splits {splits}, L={layers}, {r['faces']} faces, {r['nodes']} nodes: "
                f"springback max {1e3 * r['springback_max_m']:.2f} mm of "
                f"{1e3 * r['exact_max_m']:.2f} ({r['share_max']:.4f}), rms share "
                f"{r['share_rms']:.4f}, ccx {r['cpu_s']:.1f} s CPU",
                flush=True,
            )
    return finish(out, args.json, bool(args.keep), workdir)


if __name__ == "__main__":
    sys.exit(main())
