"""What makes CalculiX's run of NAME.inp converge: the structural check's deck
with other meshes and options, its largest movement against ours
(docs/mechanics.md, "The structural check in CalculiX").

    .venv/bin/python benchmarks/ccx_inp_variants.py --mesh coarse \\
        --variants flat normal pinned s8r flat4 curved now

Variants (the rest of the deck is NAME.inp's): ``flat``, the facets as flat
S6 (midpoints on the chords: the file as written before); ``normal``, that
with one ``*NORMAL`` per node and side of the crease (ccx makes no knot off
the crease); ``pinned``, that with the feet held through ``*EQUATION`` to
nodes of their own (rotations free); ``s8r``, each facet three S8R quads;
``flat4``, each flat S6 split in four; ``curved``, the S6 with curved
midpoints (``inp_mesh.curved_midpoints``), not split; ``now``, NAME.inp as
written. ccx on one thread; CPU from ``getrusage`` of the children.
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np
from calculix_structural import read_dat  # the .dat blocks NAME.inp asks for

from onefold_cad.design import fold_design
from onefold_cad.export.simulation.inp import inp_text, structural_model
from onefold_cad.export.simulation.inp_mesh import curved_midpoints, unique_edges
from onefold_cad.mechanics.simulate import simulate
from onefold_cad.templates import load_template


def _flat_s6(x, faces, mids):
    edges, fe = unique_edges(faces)
    return np.vstack([x, mids]), np.column_stack([faces, len(x) + fe])


def _split(x, faces, mid):
    """The node list (the corners first) and a function that adds a node once
    per key (``mid`` holds the keys): new nodes are linear in the facet."""
    pts = list(x)

    def node(key, p):
        if key not in mid:
            mid[key] = len(pts)
            pts.append(p)
        return mid[key]

    return pts, node


def _quads(x, faces):
    mid: dict = {}
    pts, node = _split(x, faces, mid)
    els = []
    for f, (a, b, c) in enumerate(faces):
        m = {k: node(("m", *sorted(k)), (x[k[0]] + x[k[1]]) / 2) for k in ((a, b), (b, c), (c, a))}
        g = node(("g", f), (x[a] + x[b] + x[c]) / 3)
        for q in ((a, m[a, b], g, m[c, a]), (b, m[b, c], g, m[a, b]), (c, m[c, a], g, m[b, c])):
            sides = [(q[k], q[(k + 1) % 4]) for k in range(4)]
            els.append(
                list(q) + [node(("h", *sorted(s)), (pts[s[0]] + pts[s[1]]) / 2) for s in sides]
            )
    return np.array(pts), np.array(els)


def _four(x, faces):
    mid: dict = {}
    pts, node = _split(x, faces, mid)

    def m(i, j):
        return node(tuple(sorted((i, j))), (pts[i] + pts[j]) / 2)

    els = []
    for a, b, c in faces:
        ab, bc, ca = m(a, b), m(b, c), m(c, a)
        for t in ((a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)):
            els.append(list(t) + [m(t[0], t[1]), m(t[1], t[2]), m(t[2], t[0])])
    return np.array(pts), np.array(els)


def deck(sim, variant: str) -> str:
    """NAME.inp's text with the variant's mesh and options."""
    text = inp_text(sim, "check")
    if variant == "now":
        return text
    model = structural_model(sim)
    x = np.asarray(sim.designed_positions) / 1000.0
    faces, flat = np.asarray(sim.faces), np.asarray(sim.flat)
    side = (flat[faces, 1].mean(axis=1) > 0).astype(np.int64)
    edges, _ = unique_edges(faces)
    chords = 0.5 * (x[edges[:, 0]] + x[edges[:, 1]])
    etype, extra, pins = "S6", [], []
    if variant in ("flat", "normal", "pinned"):
        nodes, els = _flat_s6(x, faces, chords)
    elif variant == "curved":
        straight = np.zeros(len(edges), dtype=bool)
        nodes, els = _flat_s6(x, faces, curved_midpoints(x, faces, side, straight))
    elif variant == "s8r":
        (nodes, els), etype = _quads(x, faces), "S8R"
    elif variant == "flat4":
        nodes, els = _four(x, faces)
    else:
        raise SystemExit(f"unknown variant {variant}")
    if variant == "normal":  # one normal per node and side: the facets' mean
        normal = np.cross(x[faces[:, 1]] - x[faces[:, 0]], x[faces[:, 2]] - x[faces[:, 0]])
        acc = np.zeros((len(nodes), 2, 3))
        for k in range(6):
            np.add.at(acc, (els[:, k], side), normal)
        unit = acc / np.linalg.norm(acc, axis=2, keepdims=True).clip(1e-300)
        extra = ["*NORMAL"] + [
            f"{e + 1}, {v + 1}, " + ", ".join(f"{c:.12g}" for c in unit[v, side[e]])
            for e in range(len(els))
            for v in els[e]
        ]
    if variant == "pinned":  # a node of its own per foot, tied in x, y, z
        base = len(nodes)
        pins = [f"{base + k + 1}, " + ", ".join(f"{c:.12g}" for c in x[f])
                for k, f in enumerate(model["feet"])]  # fmt: skip
        extra = ["*NSET, NSET=PINS", ", ".join(str(base + k + 1) for k in range(len(pins)))]
        extra.append("*EQUATION")
        for k, f in enumerate(model["feet"]):
            extra += [
                line
                for d in (1, 2, 3)
                for line in ("2", f"{f + 1}, {d}, 1., {base + k + 1}, {d}, -1.")
            ]
    lines = text.splitlines()
    i0 = lines.index("*NODE, NSET=EVERY")
    i2 = lines.index("*NSET, NSET=FEET")
    new = ["*NODE, NSET=EVERY"]
    new += [f"{i + 1}, {p[0]:.12g}, {p[1]:.12g}, {p[2]:.12g}" for i, p in enumerate(nodes)] + pins
    new.append(f"*ELEMENT, TYPE={etype}, ELSET=SHEET")
    new += [f"{k + 1}, " + ", ".join(str(v + 1) for v in e) for k, e in enumerate(els)]
    rest = lines[i2:]
    if variant == "pinned":
        rest[rest.index("FEET, 1, 3")] = "PINS, 1, 3"
    return "\n".join(lines[:i0] + new + extra + rest) + "\n"


def run(text: str, n: int) -> tuple[float, float, float]:
    """ccx on ``text``: ``(largest movement of the first n nodes in mm, feet
    / weight numerator (N), CPU s)``."""
    ccx = shutil.which("ccx")
    assert ccx, "needs CalculiX: apt-get install calculix-ccx"
    with tempfile.TemporaryDirectory() as tmp:
        Path(tmp, "check.inp").write_text(text)
        ru0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run([ccx, "-i", "check"], cwd=tmp, check=True, capture_output=True,
                       env={**os.environ, "OMP_NUM_THREADS": "1"})  # fmt: skip
        ru1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        forces, u = read_dat(Path(tmp, "check.dat"), n)
    cpu = ru1.ru_utime + ru1.ru_stime - ru0.ru_utime - ru0.ru_stime
    return 1000 * float(np.linalg.norm(u, axis=1).max()), float(forces[:, 2].sum()), cpu


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--mesh", nargs="+", default=["coarse"])
    ap.add_argument("--variants", nargs="+", default=["flat", "now"])
    args = ap.parse_args()
    design = load_template(args.template)
    folded = fold_design(design)
    print("| mesh | variant | nodes | onefold (mm) | CalculiX (mm) | ccx s CPU | feet / weight |")
    print("|---|---|---|---|---|---|---|")
    for level in args.mesh:
        sim = simulate(design, folded, level=level, reference="designed", convergence=False)
        assert sim.designed is not None
        for v in args.variants:
            big, fz, cpu = run(deck(sim, v), sim.nodes)
            print(f"| {level} | {v} | {sim.nodes} | {sim.designed.max_displacement:.2f} | "
                  f"{big:.2f} | {cpu:.0f} | {fz / sim.weight_N:.5f} |", flush=True)  # fmt: skip


if __name__ == "__main__":
    main()
