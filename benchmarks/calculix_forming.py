"""The independent CalculiX benchmark of the forming and springback (issue 35,
"Against CalculiX"): a template's flat sheet formed in CalculiX into its
designed form, released on a statically determinate support, and measured the
way ``onefold simulate`` measures itself.

The model (SI units: m, Pa, N):

* **Mesh**: the flat sheet meshed with Triangle by ``kratos_shell.mesh_sheet``
  (the peer benchmark's mesh: relief hole as a polygon hole, the crease as
  constrained segments, welded), each triangle made an ``S6`` shell by its
  edge midpoints (:func:`quadratic`).
* **Section**: ``*SHELL SECTION, COMPOSITE`` of ``--layers`` equal layers of
  the template's steel (each layer has 2 Gauss points through the thickness
  in CalculiX's expansion to C3D15, so 2 * layers points; a plain S6 section
  has 3 and its fully plastic moment comes out 14 % low);
  ``*ELASTIC`` E, nu and ``*PLASTIC`` sigma_y, 0 (von Mises, perfectly
  plastic), the template's values; ``NLGEOM``.
* **Forming**: every node driven from the flat sheet to the designed form
  along forms that stay isometric to the flat sheet: the designs with the same
  alpha, h_c and sheet but beta scaled by s in (0, 1], each node mapped with
  ``FoldedSheet.map_points`` at ``--s-steps`` values of s; one ``*STEP`` per
  value, in which ccx ramps each node's ``*BOUNDARY`` linearly from the last
  form to the next (total time = s). A piecewise-linear ``*AMPLITUDE`` per
  node in one step does not work in ccx 2.20: every increment that crossed a
  knot of the amplitudes diverged.
* **Driving without locking the thickness**: CalculiX expands a shell into a
  solid layer, and a ``*BOUNDARY`` on a shell node is applied to all its
  expanded nodes (through-thickness strain and the normal's rotation there are
  locked: a strip's springback comes out far too large, see ``strip``). Each
  shell node is instead tied by ``*EQUATION`` (u_shell - u_driver = 0) to a
  driver node of its own that belongs to no element, and the driver nodes
  carry the ``*BOUNDARY``. ``--direct`` writes the ``*BOUNDARY`` on the shell
  nodes instead, to show the trap.
* **Release** (a restart from the forming's ``*RESTART, WRITE``):
  ``*BOUNDARY, OP=NEW`` keeps a 3-2-1 support (three driver
  nodes: both crease ends and the lifted corner; for the strip three nodes
  of the centre line) and every other driver node gets ``*CLOAD, OP=NEW`` equal
  to its reaction at the end of the forming, ramped to zero over the step (a
  removed boundary's force ramped down, not dropped). The reactions are those
  the forming run printed (two ccx runs per mesh, both timed).
* **Measures** (from the ``.dat`` file's ``*NODE PRINT`` / ``*EL PRINT``):
  the plastic area share after forming: the area share of in-plane
  integration points where either surface of the sheet has yielded: the
  outermost Gauss point has plastic strain, or the stress tensor linearly
  extrapolated from the two outermost points (both in the outer layer) to the
  surface has a von Mises stress >= sigma_y; the springback: the released
  shell nodes brought onto the designed nodes by ``deviation.best_fit``
  weighted by each node's share of the area (the quadratic triangle split in
  four), then ``deviation.surface_distance`` from the designed surface (the
  same measure as ``simulate._aligned_deviation``, which weights by the lumped
  mass rho t area); the share that yields again on release: points whose
  outermost plastic strain grows in the release.
* **Mesh convergence**: a sequence of ``--h``; with three meshes of a constant
  ratio, Richardson's extrapolation of each measure (order from the three, or
  the nominal order 2 when they are not monotone: then marked).

``strip`` validates the chain on a narrow strip (width^2 / (R t) < 0.3, so
uniaxial stress) bent to a cylinder of radius R by its centre line and
released: R_formed / R_released against Gardiner's 4 x^3 - 3 x + 1,
x = R sigma_y / (E t).

CalculiX (Debian's ``calculix-ccx``: ``apt-get install calculix-ccx``) and
``triangle`` are no dependency of the package. Run from the repository root,
one thread per ccx (``OMP_NUM_THREADS=1`` is set for the child)::

    .venv/bin/python benchmarks/calculix_forming.py strip [--x 0.1 0.3] [--direct]
    .venv/bin/python benchmarks/calculix_forming.py patkau-one-fold \\
        --h 0.4 0.28 0.2 [--layers 10] [--s-steps 20] [--json] [--keep DIR]
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

sys.path.insert(0, str(Path(__file__).resolve().parent))

from kratos_shell import mesh_sheet  # noqa: E402

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
        x0: ``(n, 3)`` the flat sheet's nodes (m).
        tri6: ``(m, 6)`` S6 connectivity (0-based).
        s: ``(k,)`` the step times of the driven forms, increasing to 1.
        u: ``(k, len(driven), 3)`` the driven nodes' displacements at each s (m).
        driven: the driven nodes (0-based).
        t, E, nu, sy: thickness (m), Young's modulus, Poisson's ratio, yield
            stress (Pa).
        layers: equal layers of the composite section.
        support: for the release, node -> fixed directions (1-based).
        loads: ``(len(driven), 3)`` the reactions to ramp down in the release;
            None: forming only.
        direct: ``*BOUNDARY`` on the shell nodes (the locking trap) instead of
            driver nodes tied by ``*EQUATION``.
        form_inc, release_inc: the largest increment of each step (step time).
        first_inc: each forming step's first increment as a fraction of its
            largest (ccx cuts the first increment of most steps back to about
            1/16 after 2 or 3 failed attempts: the driven motion turns there).
        controls: a ``*CONTROLS, PARAMETERS=TIME INCREMENTATION`` data line
            (I_0, I_R, I_P, I_C, ...) for both steps, or None (ccx's default).
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
    support: dict[int, list[int]] = field(default_factory=dict)
    loads: Array | None = None
    direct: bool = False
    form_inc: float = 0.025
    release_inc: float = 0.05
    controls: str | None = None
    first_inc: float = 1.0


def write_deck(deck: Deck, path: Path) -> None:
    """Write the ``.inp``: shell nodes 1..n, driver nodes n+1.. (one per driven
    node), elements 1..m, sets SH (shell nodes), DRV (driver nodes), E."""
    n = len(deck.x0)
    drv = {int(i): n + 1 + j for j, i in enumerate(deck.driven)}
    target = (lambda i: int(i) + 1) if deck.direct else (lambda i: drv[int(i)])
    out: list[str] = ["*HEADING", "onefold calculix_forming", "*NODE"]
    out += [f"{i + 1},{p[0]:.12g},{p[1]:.12g},{p[2]:.12g}" for i, p in enumerate(deck.x0)]
    if not deck.direct:
        out += [
            f"{drv[int(i)]},{deck.x0[i][0]:.12g},{deck.x0[i][1]:.12g},{deck.x0[i][2]:.12g}"
            for i in deck.driven
        ]
    out.append("*ELEMENT,TYPE=S6,ELSET=E")
    out += [f"{j + 1}," + ",".join(str(int(v) + 1) for v in e) for j, e in enumerate(deck.tri6)]
    out.append("*NSET,NSET=SH")
    out += _id_lines(range(1, n + 1))
    out.append("*NSET,NSET=DRV")
    out += _id_lines(target(i) for i in deck.driven)
    out += [
        "*MATERIAL,NAME=STEEL",
        "*ELASTIC",
        f"{deck.E:.10g},{deck.nu:.10g}",
        "*PLASTIC",
        f"{deck.sy:.10g},0.",
    ]
    out.append("*SHELL SECTION,ELSET=E,COMPOSITE")
    out += [f"{deck.t / deck.layers:.12g},,STEEL"] * deck.layers
    if not deck.direct:
        out.append("*EQUATION")
        for i in deck.driven:
            for d in (1, 2, 3):
                out += ["2", f"{int(i) + 1},{d},1.,{drv[int(i)]},{d},-1."]
    out.append("*AMPLITUDE,NAME=DOWN")
    out.append("0.,1.,1.,0.")
    # one step per driven form: ccx ramps each boundary linearly from the
    # last form to the next within the step (an increment that crosses a knot
    # of a piecewise-linear *AMPLITUDE diverges in ccx 2.20: every one did)
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
        out += _controls(deck)
        out.append("*BOUNDARY")
        for j, i in enumerate(deck.driven):
            for d in range(3):
                out.append(f"{target(i)},{d + 1},{d + 1},{deck.u[k, j, d]:.12g}")
        last = k == len(deck.s) - 1
        if last:
            out.append("*RESTART,WRITE,FREQUENCY=1")
            out += _prints(with_rf=False)
        out.append("*END STEP")
    path.write_text("\n".join(out) + "\n")


HOLD = 1e-3  # the hold step's length (step time)
HELD = round(1.0 + HOLD, 6)  # the total time at its end
RELEASED = round(2.0 + HOLD, 6)  # and at the release's end


def write_hold(deck: Deck, path: Path) -> None:
    """Write the hold deck: a restart from the forming that keeps every
    boundary for one short increment and prints the shell nodes' reactions
    (ccx reports no reaction at a driver node: it has no element; the shell
    node's reaction is the sum over its expanded nodes)."""
    del deck
    out = ["*RESTART,READ", "*STEP,NLGEOM,INC=100", "*STATIC"]
    out += [f"{HOLD:g},{HOLD:g},{HOLD * 1e-6:g},{HOLD:g}", "*RESTART,WRITE,FREQUENCY=1"]
    out += ["*NODE PRINT,NSET=SH,FREQUENCY=100000", "RF", "*END STEP"]
    path.write_text("\n".join(out) + "\n")


def write_release(deck: Deck, path: Path) -> None:
    """Write the release deck that restarts from the forming run's state
    (``*RESTART, READ``): the 3-2-1 support kept at its formed place, every
    other driven direction loaded by its reaction ramped to zero."""
    assert deck.loads is not None
    n = len(deck.x0)
    drv = {int(i): n + 1 + j for j, i in enumerate(deck.driven)}
    target = (lambda i: int(i) + 1) if deck.direct else (lambda i: drv[int(i)])
    u_end = deck.u[-1]
    row = {int(i): j for j, i in enumerate(deck.driven)}
    out = [
        "*RESTART,READ",
        "*STEP,NLGEOM,INC=10000",
        "*STATIC",
        f"{deck.release_inc:.6g},1.,1e-6,{deck.release_inc:.6g}",
    ]
    out += _controls(deck)
    out.append("*BOUNDARY,OP=NEW")
    for node, dirs in deck.support.items():
        for d in dirs:
            out.append(f"{target(node)},{d},{d},{u_end[row[node], d - 1]:.12g}")
    out.append("*CLOAD,OP=NEW,AMPLITUDE=DOWN")
    for j, i in enumerate(deck.driven):
        fixed = deck.support.get(int(i), [])
        for d in (1, 2, 3):
            if d not in fixed and deck.loads[j, d - 1] != 0.0:
                out.append(f"{int(i) + 1},{d},{deck.loads[j, d - 1]:.12g}")
    out += _prints(with_rf=False)
    out.append("*END STEP")
    path.write_text("\n".join(out) + "\n")


def _controls(deck: Deck) -> list[str]:
    if deck.controls is None:
        return []
    return ["*CONTROLS,PARAMETERS=TIME INCREMENTATION", deck.controls]


def _id_lines(ids: Any) -> list[str]:
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


def run_ccx(
    deck: Deck, workdir: Path, name: str, restart: str | None = None, hold: bool = False
) -> tuple[dict[str, Any], float]:
    """Write and run the deck (the forming; with ``restart``, the release
    from that run's restart file); ``(blocks, wall seconds)``. ``blocks``
    maps ``(kind, total time)`` to the rows of the ``.dat`` (the last of each)."""
    if restart is None:
        write_deck(deck, workdir / f"{name}.inp")
    else:
        (write_hold if hold else write_release)(deck, workdir / f"{name}.inp")
        shutil.copyfile(workdir / f"{restart}.rout", workdir / f"{name}.rin")
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_STIFFNESS="1", CCX_NPROC_RESULTS="1")
    t0 = time.perf_counter()
    proc = subprocess.run(
        [CCX, "-i", name], cwd=workdir, env=env, capture_output=True, text=True, check=False
    )
    wall = time.perf_counter() - t0
    (workdir / f"{name}.log").write_text(proc.stdout + proc.stderr)
    if proc.returncode != 0 or "*ERROR" in proc.stdout:
        err = [ln for ln in proc.stdout.splitlines() if "ERROR" in ln][:3]
        raise RuntimeError(f"ccx {name} failed (status {proc.returncode}): {' | '.join(err)}")
    return read_dat(workdir / f"{name}.dat"), wall


def read_dat(path: Path) -> dict[tuple[str, float], Array]:
    """The ``.dat`` blocks: ``(kind, time) -> (rows, columns)`` numeric table
    (first columns: node, or element and integration point)."""
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


def surface_state(
    blocks: dict, when: float, layers: int, t: float, sy: float, n_elem: int
) -> dict[str, Array]:
    """Per element and in-plane point ``(m, 3)``: the outermost Gauss points'
    plastic strain (bottom, top) and whether each surface has yielded (plastic
    strain at the outermost point, or the stress extrapolated linearly from
    the outer layer's two points to the surface at or above the yield stress)."""
    st = blocks[("stresses", when)]
    pe = blocks[("equivalent plastic strain", when)]
    levels = 2 * layers
    sig = st[:, 2:8].reshape(n_elem, levels, 3, 6)  # element, level (bottom up), in-plane point
    peeq = pe[:, 2].reshape(n_elem, levels, 3)
    h = t / layers
    z0, z1 = -0.5 * t + 0.5 * h * (1 - GAUSS), -0.5 * t + 0.5 * h * (1 + GAUSS)
    f = (-0.5 * t - z0) / (z1 - z0)  # extrapolation to the bottom surface; the top mirrors it
    bottom = sig[:, 0] + f * (sig[:, 1] - sig[:, 0])
    top = sig[:, -1] + f * (sig[:, -2] - sig[:, -1])
    yielded = (peeq[:, 0] > 0) | (peeq[:, -1] > 0) | (_mises(bottom) >= sy) | (_mises(top) >= sy)
    return {"peeq_bottom": peeq[:, 0], "peeq_top": peeq[:, -1], "yielded": yielded, "peeq": peeq}


def _mises(s: Array) -> Array:
    xx, yy, zz, xy, xz, yz = (s[..., k] for k in range(6))
    return np.sqrt(
        0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2) + 3.0 * (xy**2 + xz**2 + yz**2)
    )


def _disp(blocks: dict, when: float, n: int) -> Array:
    u = blocks[("displacements", when)]
    out = np.zeros((n, 3))
    out[u[:, 0].astype(int) - 1] = u[:, 1:4]
    return out


def form_and_release(deck: Deck, workdir: Path, name: str, resume: bool = False) -> dict[str, Any]:
    """Run the forming (writing a restart file), hold it one short increment
    for the shell nodes' reactions, then release (restarts of the forming):
    the ``.dat`` blocks at the end of the forming and of the release and the
    wall times. ``resume``: take a finished forming run in ``workdir`` (its
    wall time from its files' times)."""
    form = dataclasses.replace(deck, loads=None)
    done = workdir / f"{name}_form.rout"
    b1 = read_dat(workdir / f"{name}_form.dat") if resume and done.exists() else {}
    if ("displacements", 1.0) in b1:
        wall1 = (workdir / f"{name}_form.sta").stat().st_mtime - (
            workdir / f"{name}_form.inp"
        ).stat().st_mtime
    else:
        b1, wall1 = run_ccx(form, workdir, name + "_form")
    bh, wallh = run_ccx(form, workdir, name + "_hold", restart=name + "_form", hold=True)
    rf = bh[("forces", HELD)]
    loads = np.zeros((len(deck.driven), 3))
    pos = {int(i) + 1: j for j, i in enumerate(deck.driven)}
    for row in rf:
        if int(row[0]) in pos:
            loads[pos[int(row[0])]] = row[1:4]
    b2, wall2 = run_ccx(
        dataclasses.replace(deck, loads=loads), workdir, name, restart=name + "_hold"
    )
    return {
        "form": b1,
        "release": b2,
        "wall_form_s": wall1,
        "wall_release_s": wallh + wall2,
        "loads": loads,
    }


# -- the strip ------------------------------------------------------------------
def gardiner(x: float) -> float:
    """R_formed / R_released for a rectangular section in uniaxial bending,
    elastic-perfectly plastic (Gardiner 1957), x = R sigma_y / (E t)."""
    return 4.0 * x**3 - 3.0 * x + 1.0


def _circle_radius(p: Array) -> float:
    """Least-squares circle through points ``(k, 2)`` (Kasa's fit)."""
    a = np.column_stack([2 * p[:, 0], 2 * p[:, 1], np.ones(len(p))])
    b = (p**2).sum(axis=1)
    cx, cy, c = np.linalg.lstsq(a, b, rcond=None)[0]
    return float(math.sqrt(c + cx * cx + cy * cy))


def strip(x: float, *, direct: bool, layers: int, workdir: Path, t: float = 1e-3) -> dict[str, Any]:
    """A wide strip (E 200 GPa, nu 0.3, t 1 mm, width 0.2 m, R = 1 m, so
    width^2 / (R t) = 40: a plate in cylindrical bending; sigma_y = x E t / R)
    bent through 30 degrees to radius R with every node driven along the
    isometric cylinders of curvature s / R (as the template's forming drives
    every node), released on three centre-line nodes; the radii fitted to the
    centre line's nodes of its central half. Gardiner's ratio for plane strain lies between the
    values with E' = E / (1 - nu^2) and sigma_y / sqrt(1 - nu + nu^2) (first
    yield) or 2 sigma_y / sqrt(3) (fully plastic) in place of sigma_y."""
    E, nu, R, b = 200e9, 0.3, 1.0, 0.2
    sy = x * E * t / R
    L = math.pi / 6.0 * R
    nx, ny = 20, 4
    xs = np.linspace(-0.5 * L, 0.5 * L, nx + 1)
    ys = np.linspace(-0.5 * b, 0.5 * b, ny + 1)
    grid = np.array([[xx, yy] for yy in ys for xx in xs])
    tris = []
    for r in range(ny):
        for c in range(nx):
            a0, a1 = r * (nx + 1) + c, r * (nx + 1) + c + 1
            b0, b1 = a0 + nx + 1, a1 + nx + 1
            tris += [[a0, a1, b1], [a0, b1, b0]]
    flat, tri6 = quadratic(grid, np.array(tris))
    driven = np.arange(len(flat))
    s = np.linspace(0.05, 1.0, 20)
    X = flat[:, 0]
    u = np.zeros((len(s), len(driven), 3))
    for k, sk in enumerate(s):
        kap = sk / R
        u[k, :, 0] = np.sin(kap * X) / kap - X
        u[k, :, 2] = (1 - np.cos(kap * X)) / kap
    x0 = np.column_stack([flat, np.zeros(len(flat))])
    centre = np.flatnonzero(np.abs(flat[:, 1]) < 1e-12 * b)
    centre = centre[np.argsort(flat[centre, 0])]
    a, c, bb = centre[len(centre) // 2], centre[len(centre) // 4], centre[-1]
    support = support_321(x0 + u[-1], [int(a), int(bb), int(c)])
    deck = Deck(x0, tri6, s, u, driven, t, E, nu, sy, layers, support, direct=direct, form_inc=0.05)
    name = f"strip_x{x:g}" + ("_direct" if direct else "")
    res = form_and_release(deck, workdir, name)
    xf = x0 + _disp(res["form"], 1.0, len(x0))
    xr = x0 + _disp(res["release"], RELEASED, len(x0))
    # the central half: the ends' boundary layer (M = 0 at a free end after
    # the release) bends back differently; the whole length beside it
    mid = centre[np.abs(flat[centre, 0]) <= 0.25 * L + 1e-12]
    r_form = _circle_radius(xf[mid][:, [0, 2]])
    r_rel = _circle_radius(xr[mid][:, [0, 2]])
    full = _circle_radius(xf[centre][:, [0, 2]]) / _circle_radius(xr[centre][:, [0, 2]])
    e_plate = E / (1 - nu * nu)
    lo = gardiner(R * sy / math.sqrt(1 - nu + nu * nu) / (e_plate * t))
    hi = gardiner(R * 2 * sy / math.sqrt(3) / (e_plate * t))
    ratio = r_form / r_rel
    return {
        "x": x,
        "direct": direct,
        "R_m": R,
        "R_formed_m": r_form,
        "R_released_m": r_rel,
        "ratio": ratio,
        "ratio_whole_length": full,
        "gardiner_uniaxial": gardiner(x),
        "gardiner_plane_strain": sorted([lo, hi]),
        "within": min(lo, hi) <= ratio <= max(lo, hi),
        "wall_s": res["wall_form_s"] + res["wall_release_s"],
    }


def _full(u: Array, driven: IntArray, n: int) -> Array:
    out = np.zeros((n, 3))
    out[driven] = u
    return out


# -- the template ---------------------------------------------------------------
def template_run(
    template: str,
    h: float,
    *,
    layers: int,
    s_steps: int,
    workdir: Path,
    controls: str | None = None,
    resume: bool = False,
) -> dict[str, Any]:
    """Form and release ``template`` meshed at edge length ``h`` (m)."""
    from onefold_cad.design import fold_design
    from onefold_cad.fabrication.relief_hole import relief_hole_diameter
    from onefold_cad.mechanics.deviation import best_fit, surface_distance
    from onefold_cad.templates import find_template, load_template

    design = load_template(find_template(template))
    scale = {"mm": 1e-3, "in": 0.0254, "m": 1.0}[design.units.value]
    folded = fold_design(design)
    hole = relief_hole_diameter(design, folded)
    polygon = np.asarray(design.sheet.vertices, dtype=float)
    pts, tris, info = mesh_sheet(polygon, hole, h / scale)
    flat, tri6 = quadratic(pts, tris)
    n = len(flat)
    s = np.linspace(1.0 / s_steps, 1.0, s_steps)
    forms = []
    for sk in s:
        frame = dataclasses.replace(design.frame, beta=sk * design.frame.beta)
        forms.append(fold_design(dataclasses.replace(design, frame=frame)).map_points(flat))
    forms_m = np.array(forms) * scale
    x0 = np.column_stack([flat * scale, np.zeros(n)])
    u = forms_m - x0[None]
    designed = forms_m[-1]
    m = design.material
    E, nu, sy, t = m.youngs_modulus * 1e9, m.poisson, m.yield_stress * 1e6, m.thickness * scale
    ends = info["crease_ends"]
    corners = [int(v) for v in info["vertices"] if int(v) not in ends]
    corner = max(corners, key=lambda v: designed[v, 2])
    support = support_321(designed, [int(ends[0]), int(ends[1]), corner])
    deck = Deck(
        x0,
        tri6,
        s,
        u,
        np.arange(n),
        t,
        E,
        nu,
        sy,
        layers,
        support,
        form_inc=1.0 / s_steps,
        controls=controls,
    )
    res = form_and_release(deck, workdir, f"{template}_h{h:g}", resume=resume)
    weights, area = node_areas(flat, tri6)
    ne = len(tri6)
    formed = surface_state(res["form"], 1.0, layers, t, sy, ne)
    released = surface_state(res["release"], RELEASED, layers, t, sy, ne)
    w_pt = np.repeat(area[:, None] / 3.0, 3, axis=1)
    share = lambda mask: float(w_pt[mask].sum() / w_pt.sum())  # noqa: E731
    outer_formed = (formed["peeq_bottom"] > 0) | (formed["peeq_top"] > 0)
    grew = (released["peeq_bottom"] > formed["peeq_bottom"] * (1 + 1e-9) + 1e-12) | (
        released["peeq_top"] > formed["peeq_top"] * (1 + 1e-9) + 1e-12
    )
    xr = x0 + _disp(res["release"], RELEASED, n)
    xf = x0 + _disp(res["form"], 1.0, n)
    fit = best_fit(xr, designed, weights)
    dev = surface_distance(folded, fit.apply(xr) / scale, 0.5 * hole)
    form_err = float(np.abs(xf - designed).max() / scale)
    return {
        "template": template,
        "h_m": h,
        "nodes": n,
        "elements": ne,
        "layers": layers,
        "s_steps": s_steps,
        "plastic_share": share(formed["yielded"]),
        "plastic_share_outer_point": share(outer_formed),
        "peeq_max_formed": float(formed["peeq"].max()),
        "springback_max": float(dev.max()),
        "springback_rms": float(np.sqrt(np.average(dev**2, weights=weights))),
        "unit": design.units.value,
        "yields_again_share": share(grew),
        "formed_vs_designed_max": form_err,
        "wall_form_s": res["wall_form_s"],
        "wall_release_s": res["wall_release_s"],
    }


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


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("case", help="'strip' or a template name (patkau-one-fold, broken-vault)")
    ap.add_argument("--h", type=float, nargs="+", default=[0.4, 0.28, 0.2], help="edge lengths (m)")
    ap.add_argument(
        "--x", type=float, nargs="+", default=[0.1, 0.3], help="strip: R sigma_y / (E t)"
    )
    ap.add_argument(
        "--direct", action="store_true", help="strip: *BOUNDARY on the shell nodes (the trap)"
    )
    ap.add_argument("--layers", type=int, default=10)
    ap.add_argument("--s-steps", type=int, default=20)
    ap.add_argument(
        "--controls",
        help="a *CONTROLS, PARAMETERS=TIME INCREMENTATION line, e.g. 8,16,9,40,10,4,12,5",
    )
    ap.add_argument(
        "--resume", action="store_true", help="reuse a finished forming run in --keep DIR"
    )
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--keep", type=Path, help="keep the ccx files in this directory")
    args = ap.parse_args(argv)
    if not Path(CCX).exists():
        print("calculix_forming: needs ccx (apt-get install calculix-ccx)", file=sys.stderr)
        return 2
    workdir = args.keep or Path(tempfile.mkdtemp(prefix="ccx_forming_"))
    workdir.mkdir(parents=True, exist_ok=True)
    rows: list[dict[str, Any]] = []
    if args.case == "strip":
        for x in args.x:
            rows.append(strip(x, direct=args.direct, layers=args.layers, workdir=workdir))
            if not args.json:
                r = rows[-1]
                print(
                    f"strip x={x:g} {'direct *BOUNDARY' if args.direct else '*EQUATION drivers'}: "
                    f"R_formed/R_released {r['ratio']:.4f}, Gardiner plane strain "
                    f"{r['gardiner_plane_strain'][0]:.4f}..{r['gardiner_plane_strain'][1]:.4f} "
                    f"(uniaxial {r['gardiner_uniaxial']:.4f}), "
                    f"R formed {r['R_formed_m']:.5g} m of {r['R_m']:.5g}, "
                    f"ccx {r['wall_s']:.1f} s",
                    flush=True,
                )
        out: dict[str, Any] = {"strip": rows}
    else:
        for h in args.h:
            rows.append(
                template_run(
                    args.case, h, layers=args.layers, s_steps=args.s_steps, workdir=workdir
                )
            )
            if not args.json:
                r = rows[-1]
                print(
                    f"h {h:g} m: {r['nodes']} nodes, {r['elements']} S6; "
                    f"plastic share {r['plastic_share']:.4f} "
                    f"(outermost point {r['plastic_share_outer_point']:.4f}), springback max "
                    f"{r['springback_max']:.4g} {r['unit']} (rms {r['springback_rms']:.4g}), "
                    "yields again "
                    f"{r['yields_again_share']:.4f}, peeq max {r['peeq_max_formed']:.3g}; "
                    "ccx forming "
                    f"{r['wall_form_s']:.1f} s, release {r['wall_release_s']:.1f} s",
                    flush=True,
                )
        out = {"runs": rows}
        hs = [r["h_m"] for r in rows]
        for key in ("plastic_share", "springback_max", "yields_again_share"):
            val, p = richardson(hs, [r[key] for r in rows])
            out[key + "_richardson"] = {"value": val, "order": p}
        if not args.json:
            print()
            print(
                "| h (m) | nodes | plastic share | springback max | yields again | ccx wall (s) |"
            )
            print("|---|---|---|---|---|---|")
            for r in rows:
                print(
                    f"| {r['h_m']:g} | {r['nodes']} | {r['plastic_share']:.4f} | "
                    f"{r['springback_max']:.1f} "
                    f"{r['unit']} | {r['yields_again_share']:.4f} | {r['wall_form_s']:.0f} + "
                    f"{r['wall_release_s']:.0f} |"
                )
            rich = [
                out[k + "_richardson"]
                for k in ("plastic_share", "springback_max", "yields_again_share")
            ]
            if rich[0]["value"] is not None:
                cells = [
                    f"{v['value']:.4g}"
                    + (f" (order {v['order']:.2g})" if v["order"] else " (order 2 assumed)")
                    for v in rich
                ]
                print(f"| Richardson | | {cells[0]} | {cells[1]} | {cells[2]} | |")
    if args.json:
        print(json.dumps(out, indent=1))
    if not args.keep:
        shutil.rmtree(workdir, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
