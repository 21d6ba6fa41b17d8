"""The CalculiX deck of the forming benchmark (``calculix_forming.py``): the S6
mesh with its crease as a hinge, the ``.inp`` of the forming and release in
one run, running ccx and reading its ``.dat`` (SI units: m, Pa, N).

* **Mesh**: linear triangles made ``S6`` by their edge midpoints
  (:func:`quadratic`); the crease split into a hinge (:func:`split_crease`):
  the elements on the -y side get their own copy (a *twin*) of every node on
  the crease, tied to the +y side's node in translation only. A welded crease
  (shared nodes) is one continuous shell in ccx: one director per crease node
  for both sides, so folding it forces the elements beside it to take the fold
  (the mid-plane within 0.15 m of patkau's crease had all yielded at s = 0.1,
  plastic strain 7e-3; the hinge is what ``onefold simulate``'s crease is).
* **Driving without locking the thickness**: a ``*BOUNDARY`` on a shell node
  goes to all its expanded nodes (thickness and normal locked there), so each
  shell node is tied by ``*EQUATION`` (u_shell - u_driver = 0) to a driver
  node of its own that has no element, and the drivers carry the
  ``*BOUNDARY``; a twin is tied to its partner's driver (the hinge, kept in
  the release). ``direct`` writes the trap for comparison.
* **Forming**: one ``*STEP`` per driven form, in which ccx ramps each driver
  linearly from the last form to the next (a piecewise-linear ``*AMPLITUDE``
  across an increment diverged in ccx 2.20).
* **Release in the same run** (a ``*RESTART`` of the formed state diverged at
  once): after the forming, ``*BOUNDARY, OP=NEW`` keeps a 3-2-1 support on
  three drivers and every other driver is loaded by its reaction at the end
  of the forming (summed over the shell nodes tied to it, taken from a first,
  forming-only run: ccx reports no reaction at a node without an element)
  as ``*CLOAD`` ramped to zero over the step (a removed boundary's force is
  ramped down, not dropped).
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
import re
import resource
import shutil
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]

CCX = shutil.which("ccx") or "/usr/bin/ccx"
GAUSS = 1.0 / math.sqrt(3.0)


# -- mesh -----------------------------------------------------------------------
def quadratic(points: Array, tris: IntArray) -> tuple[Array, IntArray]:
    """Linear triangles made quadratic: ``(points with the edge midpoints
    appended, (m, 6) S6 connectivity)``: corners 1-3 counterclockwise, then
    the midpoints of edges 1-2, 2-3, 3-1 (one node per edge, shared)."""
    pts = np.asarray(points, dtype=float)
    tris = np.asarray(tris, dtype=np.int64).copy()
    d = pts[tris]
    cross = (d[:, 1, 0] - d[:, 0, 0]) * (d[:, 2, 1] - d[:, 0, 1]) - (d[:, 1, 1] - d[:, 0, 1]) * (
        d[:, 2, 0] - d[:, 0, 0]
    )
    tris[cross < 0] = tris[cross < 0][:, [0, 2, 1]]
    edges = np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
    key = np.sort(edges, axis=1)
    uniq, inv = np.unique(key, axis=0, return_inverse=True)
    mids = 0.5 * (pts[uniq[:, 0]] + pts[uniq[:, 1]])
    m = len(tris)
    mid_id = len(pts) + inv.reshape(3, m).T
    return np.concatenate([pts, mids]), np.concatenate([tris, mid_id], axis=1)


def split_crease(
    flat: Array, tri6: IntArray, hole_radius: float, tol: float = 1e-9
) -> tuple[Array, IntArray, IntArray]:
    """The crease (the x axis outside the relief hole, fold frame) made a
    hinge: every node on it that an element below it (centroid y < 0) uses
    gets a twin, appended, which those elements use instead. Returns ``(nodes,
    tri6, partner)``: ``partner[k]`` is the original node of twin
    ``n_original + k``. ``tol`` is relative to the sheet's size."""
    flat = np.asarray(flat, dtype=float)
    tri6 = np.asarray(tri6, dtype=np.int64).copy()
    size = float(np.ptp(flat, axis=0).max())
    on = (np.abs(flat[:, 1]) <= tol * size) & (np.abs(flat[:, 0]) >= hole_radius * (1 - 1e-6))
    below = flat[tri6[:, :3], 1].mean(axis=1) < 0
    used = np.unique(tri6[below][on[tri6[below]]])
    new_id = np.full(len(flat), -1, dtype=np.int64)
    new_id[used] = len(flat) + np.arange(len(used))
    sub = tri6[below]
    sub[on[sub]] = new_id[sub[on[sub]]]
    tri6[below] = sub
    return np.concatenate([flat, flat[used]]), tri6, used


def node_areas(flat: Array, tri6: IntArray) -> tuple[Array, Array]:
    """``(node weights (n,), element areas (m,))``: each quadratic triangle
    split in four by its midpoints, a third of each part's area to its nodes."""
    area = _tri_area(flat, tri6[:, :3])
    w = np.zeros(len(flat))
    for sub in ([0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]):
        np.add.at(w, tri6[:, sub].ravel(), np.repeat(area / 12.0, 3))
    return w, area


def _tri_area(p: Array, tri: IntArray) -> Array:
    a, b, c = p[tri[:, 0]], p[tri[:, 1]], p[tri[:, 2]]
    return 0.5 * np.abs(
        (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    )


def support_321(x: Array, nodes: list[int]) -> dict[int, list[int]]:
    """A statically determinate support at three nodes A, B, C of positions
    ``x``: A fixed in x, y, z; B in the two directions most across AB; C in
    the direction most along AB x AC (1-based directions)."""
    a, b, c = nodes
    ab = x[b] - x[a]
    n = np.cross(ab, x[c] - x[a])
    along = int(np.argmax(np.abs(ab)))
    return {
        a: [1, 2, 3],
        b: [d + 1 for d in range(3) if d != along],
        c: [int(np.argmax(np.abs(n))) + 1],
    }


# -- the deck -------------------------------------------------------------------
@dataclass
class Deck:
    """What one CalculiX forming (and release) run needs (SI units).

    Attributes:
        x0: ``(n, 3)`` the flat sheet's nodes (m), twins included.
        tri6: ``(m, 6)`` S6 connectivity (0-based).
        s: ``(k,)`` the step times of the driven forms, increasing.
        u: ``(k, len(driven), 3)`` the driven nodes' displacements at each s (m).
        driven: the driven nodes (0-based, sorted; no twin among them).
        t, E, nu, sy: thickness (m), Young's modulus, Poisson's ratio, yield
            stress (Pa).
        layers: equal layers of the composite section.
        twins: ``(k,)`` the partner of each twin (the twins are the nodes
            ``n - k .. n - 1``): tied to the partner's driver, or to the
            partner itself when it is not driven.
        support: for the release, driven node -> fixed directions (1-based).
        loads: ``(len(driven), 3)`` the drivers' reactions to ramp down in the
            release (N); None: forming only, the reactions printed.
        direct: ``*BOUNDARY`` on the shell nodes (the locking trap) instead of
            driver nodes tied by ``*EQUATION``.
        form_inc, release_inc: the largest increment of each step (step time).
        first_inc: each forming step's first increment as a share of its
            largest (ccx cut the first increment of every patkau step from 1
            to 1/4 after a failed attempt: the driven motion turns there).
        hardening: the linear isotropic hardening modulus (Pa): the flow
            stress sy + hardening * (equivalent plastic strain), the law of
            ``onefold simulate --law j2`` (0: perfectly plastic).
    """

    x0: Array
    tri6: IntArray
    s: Array
    u: Array
    driven: IntArray
    t: float
    E: float
    nu: float
    sy: float
    layers: int = 10
    twins: IntArray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    support: dict[int, list[int]] = field(default_factory=dict)
    loads: Array | None = None
    direct: bool = False
    form_inc: float = 0.025
    release_inc: float = 0.05
    first_inc: float = 1.0
    hardening: float = 0.0

    def carrier(self, i: int) -> int:
        """The 1-based node a twin of node ``i`` is tied to: ``i``'s driver
        when ``i`` is driven, else the shell node ``i`` itself."""
        k = int(np.searchsorted(self.driven, i))
        if k < len(self.driven) and self.driven[k] == i:
            return self.target(i)
        return int(i) + 1

    def target(self, i: int) -> int:
        """The 1-based node that carries node ``i``'s driven motion."""
        n = len(self.x0)
        if self.direct:
            return int(i) + 1
        return n + 1 + int(np.searchsorted(self.driven, i))


def write_deck(deck: Deck, path: Path) -> None:
    """Write the ``.inp``: shell nodes 1..n, driver nodes n+1.. (one per driven
    node, in ``driven``'s order, which must be sorted), elements 1..m, sets SH
    (shell nodes), E; the forming steps, then (with ``loads``) the release."""
    n = len(deck.x0)
    assert np.all(np.diff(deck.driven) > 0)
    n_tw = len(deck.twins)
    out: list[str] = ["*HEADING", "onefold calculix_forming", "*NODE"]
    out += [f"{i + 1},{p[0]:.12g},{p[1]:.12g},{p[2]:.12g}" for i, p in enumerate(deck.x0)]
    if not deck.direct:
        out += [f"{deck.target(i)},{_xyz(deck.x0[i])}" for i in deck.driven]
    out.append("*ELEMENT,TYPE=S6,ELSET=E")
    out += [f"{j + 1}," + ",".join(str(int(v) + 1) for v in e) for j, e in enumerate(deck.tri6)]
    out.append("*NSET,NSET=SH")
    out += id_lines(range(1, n + 1))
    out += ["*MATERIAL,NAME=STEEL", "*ELASTIC", f"{deck.E:.10g},{deck.nu:.10g}"]
    out += ["*PLASTIC", f"{deck.sy:.10g},0."]
    if deck.hardening > 0:  # linear: ccx interpolates between the two rows
        out.append(f"{deck.sy + deck.hardening:.10g},1.")
    out.append("*SHELL SECTION,ELSET=E,COMPOSITE")
    out += [f"{deck.t / deck.layers:.12g},,STEEL"] * deck.layers
    ties = [(n - n_tw + k + 1, deck.carrier(p)) for k, p in enumerate(deck.twins)]
    if not deck.direct:
        ties += [(int(i) + 1, deck.target(i)) for i in deck.driven]
    if ties:
        out.append("*EQUATION")
        for a, b in ties:
            for d in (1, 2, 3):
                out += ["2", f"{a},{d},1.,{b},{d},-1."]
    out += ["*AMPLITUDE,NAME=DOWN", "0.,1.,1.,0."]
    prev = 0.0
    for k, sk in enumerate(deck.s):
        dt = float(sk - prev)
        prev = float(sk)
        inc = min(dt, deck.form_inc)
        out += [
            "*STEP,NLGEOM,INC=10000",
            "*STATIC",
            f"{inc * deck.first_inc:.6g},{dt:.6g},{1e-6 * dt:.6g},{inc:.6g}",
        ]
        out.append("*BOUNDARY")
        for j, i in enumerate(deck.driven):
            for d in range(3):
                out.append(f"{deck.target(i)},{d + 1},{d + 1},{deck.u[k, j, d]:.12g}")
        if k == len(deck.s) - 1:
            out += _prints(with_rf=deck.loads is None)
        out.append("*END STEP")
    if deck.loads is not None:
        out += _release(deck)
    path.write_text("\n".join(out) + "\n")


def _release(deck: Deck) -> list[str]:
    """The release step: the 3-2-1 support kept at its formed place, every
    other driven direction loaded by its reaction, ramped to zero."""
    assert deck.loads is not None
    row = {int(i): j for j, i in enumerate(deck.driven)}
    u_end = deck.u[-1]
    inc = deck.release_inc
    out = ["*STEP,NLGEOM,INC=10000", "*STATIC", f"{inc:.6g},1.,1e-6,{inc:.6g}"]
    out.append("*BOUNDARY,OP=NEW")
    for node, dirs in deck.support.items():
        for d in dirs:
            out.append(f"{deck.target(node)},{d},{d},{u_end[row[node], d - 1]:.12g}")
    out.append("*CLOAD,OP=NEW,AMPLITUDE=DOWN")
    for j, i in enumerate(deck.driven):
        fixed = deck.support.get(int(i), [])
        for d in (1, 2, 3):
            if d not in fixed and deck.loads[j, d - 1] != 0.0:
                out.append(f"{deck.target(i)},{d},{deck.loads[j, d - 1]:.12g}")
    out += _prints(with_rf=False)
    out.append("*END STEP")
    return out


def driver_loads(deck: Deck, rf: Array) -> Array:
    """``(len(driven), 3)`` each driver's reaction: the shell nodes' printed
    reactions ``rf`` (rows: 1-based node, fx, fy, fz) summed over the shell
    nodes tied to it (its own node and its twin)."""
    n = len(deck.x0)
    n_tw = len(deck.twins)
    owner = np.full(n, -1, dtype=np.int64)
    owner[deck.driven] = np.arange(len(deck.driven))
    k = np.minimum(np.searchsorted(deck.driven, deck.twins), len(deck.driven) - 1)
    owner[n - n_tw :] = np.where(deck.driven[k] == deck.twins, k, -1)
    loads = np.zeros((len(deck.driven), 3))
    node = rf[:, 0].astype(np.int64) - 1
    ok = (node >= 0) & (node < n)
    ok[ok] = owner[node[ok]] >= 0
    np.add.at(loads, owner[node[ok]], rf[ok, 1:4])
    return loads


def _xyz(p: Array) -> str:
    return f"{p[0]:.12g},{p[1]:.12g},{p[2]:.12g}"


def id_lines(ids: Any) -> list[str]:
    """``*NSET`` data lines: the ids ``ids``, twelve to a line."""
    ids = [str(i) for i in ids]
    return [",".join(ids[k : k + 12]) for k in range(0, len(ids), 12)]


def _prints(with_rf: bool) -> list[str]:
    out = ["*NODE PRINT,NSET=SH,FREQUENCY=100000", "U"]
    if with_rf:
        out += ["*NODE PRINT,NSET=SH,FREQUENCY=100000", "RF"]
    out += ["*EL PRINT,ELSET=E,FREQUENCY=100000", "S,PEEQ"]
    return out


# -- running and reading ----------------------------------------------------------
_HEAD = re.compile(r"^\s*(displacements|forces|stresses|equivalent plastic strain).*time\s+(\S+)")


def run_ccx(deck: Deck, workdir: Path, name: str) -> tuple[dict[Any, Array], float, float]:
    """Write and run the deck with one thread; ``(blocks, wall seconds, CPU
    seconds)`` (:func:`read_dat`; CPU from ``getrusage`` of the children)."""
    write_deck(deck, workdir / f"{name}.inp")
    return run_inp(workdir, name)


def run_inp(workdir: Path, name: str) -> tuple[dict[Any, Array], float, float]:
    """Run the written ``workdir/name.inp`` with one thread: ``(blocks, wall
    seconds, CPU seconds)`` (:func:`read_dat`; CPU from ``getrusage`` of the
    children); its output in ``name.log``."""
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_STIFFNESS="1", CCX_NPROC_RESULTS="1")
    t0, c0 = time.perf_counter(), _child_cpu()
    proc = subprocess.run(
        [CCX, "-i", name], cwd=workdir, env=env, capture_output=True, text=True, check=False
    )
    wall, cpu = time.perf_counter() - t0, _child_cpu() - c0
    (workdir / f"{name}.log").write_text(proc.stdout + proc.stderr)
    if proc.returncode != 0 or "*ERROR" in proc.stdout:
        err = [ln for ln in proc.stdout.splitlines() if "ERROR" in ln][:3]
        raise RuntimeError(f"ccx {name} failed (status {proc.returncode}): {' | '.join(err)}")
    return read_dat(workdir / f"{name}.dat"), wall, cpu


def _child_cpu() -> float:
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def read_dat(path: Path) -> dict[tuple[str, float], Array]:
    """The ``.dat`` blocks: ``(kind, total time) -> (rows, columns)`` numeric
    table (first columns: node, or element and integration point; the last
    block of each kind and time)."""
    blocks: dict[tuple[str, float], list[list[float]]] = {}
    key = None
    for line in path.read_text().splitlines():
        m = _HEAD.match(line)
        if m:
            key = (m.group(1), round(float(m.group(2)), 6))
            blocks[key] = []
            continue
        parts = line.split()
        if key is None or not parts:
            continue
        try:
            blocks[key].append([float(v) for v in parts if not v.startswith("_")])
        except ValueError:
            key = None
    return {k: np.array(v) for k, v in blocks.items() if v}


def level_fields(blocks: dict, when: float, layers: int, n_elem: int) -> tuple[Array, Array]:
    """The stresses ``(m, levels, 3, 6)`` and equivalent plastic strains
    ``(m, levels, 3)`` ``read_dat`` read at total time ``when``: element,
    level through the thickness (bottom up), in-plane point."""
    levels = 2 * layers
    sig = blocks[("stresses", when)][:, 2:8].reshape(n_elem, levels, 3, 6)
    peeq = blocks[("equivalent plastic strain", when)][:, 2].reshape(n_elem, levels, 3)
    return sig, peeq


def surface_state(
    blocks: dict, when: float, layers: int, t: float, sy: float, n_elem: int
) -> dict[str, Array]:
    """Per element and in-plane point ``(m, 3)``: the outermost Gauss points'
    plastic strain (bottom, top), whether each surface has yielded (plastic
    strain at the outermost point, or the stress extrapolated linearly from
    the outer layer's two points to the surface at or above the yield
    stress), and whether the mid-plane has (a point of the two innermost
    levels with plastic strain: membrane yielding)."""
    sig, peeq = level_fields(blocks, when, layers, n_elem)
    h = t / layers
    z0, z1 = -0.5 * t + 0.5 * h * (1 - GAUSS), -0.5 * t + 0.5 * h * (1 + GAUSS)
    f = (-0.5 * t - z0) / (z1 - z0)  # extrapolation to the bottom surface; the top mirrors it
    bottom = sig[:, 0] + f * (sig[:, 1] - sig[:, 0])
    top = sig[:, -1] + f * (sig[:, -2] - sig[:, -1])
    yielded = (peeq[:, 0] > 0) | (peeq[:, -1] > 0) | (mises(bottom) >= sy) | (mises(top) >= sy)
    mid = (peeq[:, layers - 1] > 0) | (peeq[:, layers] > 0)
    return {
        "peeq_bottom": peeq[:, 0],
        "peeq_top": peeq[:, -1],
        "yielded": yielded,
        "mid_yielded": mid,
        "peeq": peeq,
    }


def mises(s: Array) -> Array:
    """The von Mises stress of ``(..., 6)`` tensors (xx, yy, zz, xy, xz, yz)."""
    xx, yy, zz, xy, xz, yz = (s[..., k] for k in range(6))
    return np.sqrt(
        0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2) + 3.0 * (xy**2 + xz**2 + yz**2)
    )


def displacements(blocks: dict, when: float, n: int) -> Array:
    """``(n, 3)`` the shell nodes' displacements at total time ``when``."""
    u = blocks[("displacements", when)]
    out = np.zeros((n, 3))
    keep = u[:, 0].astype(int) <= n
    out[u[keep, 0].astype(int) - 1] = u[keep, 1:4]
    return out


def form_and_release(
    deck: Deck, workdir: Path, name: str, release: bool, reuse: bool = False
) -> dict[str, Any]:
    """The forming alone (its reactions printed), then with ``release`` the
    forming and release in one run, the first run's reactions ramped down:
    the ``.dat`` blocks of each and their wall and CPU times (s). ``reuse``:
    read a forming run that finished in ``workdir`` instead (its times None)."""
    form = dataclasses.replace(deck, loads=None)
    end = round(float(deck.s[-1]), 6)
    dat = workdir / f"{name}_form.dat"
    b1 = read_dat(dat) if reuse and dat.exists() else {}
    if ("displacements", end) in b1:
        wall1 = cpu1 = None
    else:
        b1, wall1, cpu1 = run_ccx(form, workdir, name + "_form")
    out: dict[str, Any] = {"form": b1, "wall_form_s": wall1, "cpu_form_s": cpu1}
    out.update(wall_release_s=None, cpu_release_s=None)
    if release:
        loads = driver_loads(deck, b1[("forces", end)])
        b2, wall2, cpu2 = run_ccx(dataclasses.replace(deck, loads=loads), workdir, name)
        out.update(release=b2, wall_release_s=wall2, cpu_release_s=cpu2, loads=loads)
    return out


def finish(out: dict[str, Any], as_json: bool, keep: bool, workdir: Path) -> int:
    """A command's end: ``out`` printed as JSON when asked, ``workdir``
    removed unless kept; the exit status (0)."""
    if as_json:
        print(json.dumps(out, indent=1))
    if not keep:
        shutil.rmtree(workdir, ignore_errors=True)
    return 0
