"""One evaluation of a candidate design: ``onefold simulate`` as a black box.

:func:`simulate_standing` is the task a worker runs (module-level, plain data
in and out, so a process pool pickles it and a Dask cluster ships it): it
calls :func:`onefold_cad.mechanics.simulate.simulate`, the function ``onefold
simulate`` calls, and keeps what compensation needs of its result: the
standing form's nodes on the flat sheet and as they stand, its height, span,
tipping margin and CPU time.

:func:`standing_measures` compares a standing form with a target design as it
stands on its feet (its resting placement): the residual vector the optimiser
drives to zero (the standing nodes' distance from the target's form at the
same material points, sampled at fixed points of the flat sheet) and the
report's mid-surface distance (max and rms, as ``simulate`` measures it).
Lengths are in the design's unit.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from onefold_cad.design import Design, fold_design, rest_once
from onefold_cad.errors import FabricationError
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.geometry.numeric import Array, Index
from onefold_cad.mechanics.deviation import surface_distance

__all__ = [
    "Standing",
    "StandingMeasures",
    "crease_springback",
    "designed_sizes",
    "node_weights",
    "simulate_standing",
    "standing_measures",
    "target_form",
]


@dataclass(frozen=True)
class Standing:
    """What one simulation of a candidate gave (plain data).

    Attributes:
        stands: it found a standing equilibrium with a positive tipping margin.
        reason: why not ('' when it stands).
        flat: ``(n, 2)`` the mesh's nodes on the flat sheet (design unit).
        faces: ``(m, 3)`` the mesh's triangles.
        positions: ``(n, 3)`` the standing nodes (resting frame, design unit),
            None when there is no standing equilibrium.
        height, span, depth: the standing form's height and extents along the
            resting frame's x and y (design unit), None without one.
        tipping_margin_deg: its tipping margin (deg), or None.
        self_max_deviation: ``simulate``'s own max deviation from the
            candidate's design (design unit), or None.
        convergence: the relative change of the largest deviation on the finer
            mesh (None: not checked).
        cpu_s: the CPU seconds the simulation took.
        warnings: the simulation's warnings.
    """

    stands: bool
    reason: str
    flat: Array
    faces: Index
    positions: Array | None
    height: float | None
    span: float | None
    depth: float | None
    tipping_margin_deg: float | None
    self_max_deviation: float | None
    convergence: float | None
    cpu_s: float
    warnings: tuple[str, ...]


def bend_problem(design: Design) -> FabricationError | None:
    """The error ``onefold build`` would refuse ``design``'s flat pattern with
    (its bends, :func:`~onefold_cad.fabrication.bend_checks.check_bends`,
    compensated sharp, as ``compensate -o`` writes them), or None."""
    from onefold_cad.fabrication.bend_checks import bend_error, check_bends

    return bend_error(check_bends(fold_design(design), design.material, design.units))


def bend_refusal(design: Design) -> str | None:
    """:func:`bend_problem`'s one line, as a refused candidate's answer."""
    error = bend_problem(design)
    return None if error is None else "not buildable: " + " ".join(str(error).split())


def simulate_standing(
    design: Design, level: str, check: bool = False, law: str = "moment"
) -> Standing:
    """Simulate ``design`` (forming, springback, standing; reference 'flat',
    anchored, held crease) on mesh ``level`` with the bending ``law``
    (``simulate``'s: 'moment' or 'j2'); with ``check`` also on the finer mesh
    (the convergence check). The worker's task.

    Raises:
        OneFoldError: the simulation refused or did not converge.
    """
    from onefold_cad.mechanics.simulate import simulate

    t0 = time.process_time()
    sim = simulate(design, fold_design(design), level=level, convergence=check, law=law)
    st = sim.standing
    x = sim.standing_positions
    conv = None if sim.convergence is None else sim.convergence.get("max_deviation_change")
    return Standing(
        stands=bool(st.stands),
        reason=st.reason,
        flat=np.asarray(sim.flat, dtype=float)[:, :2],
        faces=np.asarray(sim.faces),
        positions=None if x is None else np.asarray(x, dtype=float),
        height=st.height,
        span=st.span,
        depth=None if x is None else float(np.ptp(x[:, 1])),
        tipping_margin_deg=st.tipping_margin_deg,
        self_max_deviation=st.max_deviation,
        convergence=conv,
        cpu_s=time.process_time() - t0,
        warnings=tuple(sim.warnings),
    )


@dataclass(frozen=True)
class StandingMeasures:
    """A standing form against the target design as it stands.

    Attributes:
        residual: ``(k,)`` the standing form's distance from the target's
            mid-surface at the sample points, signed by the side it lies on,
            times the square root of their weights (design unit), after the
            best horizontal alignment (a turn about the vertical and a shift
            along the ground, fitted to the same material points of the
            target: where it stands is the builder's choice).
        max_deviation, rms_deviation: the aligned standing nodes' distance from
            the target's mid-surface (design unit).
        deviation: ``(n,)`` that distance at each node.
        aligned: ``(n, 3)`` the standing nodes after the alignment.
    """

    residual: Array
    max_deviation: float
    rms_deviation: float
    deviation: Array
    aligned: Array


def node_weights(flat: Array, faces: Index) -> Array:
    """``(n,)`` each node's share of the flat sheet's area (a third of its
    triangles'), normalised to sum 1."""
    p = flat[faces]
    u, v = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    a = 0.5 * np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
    w = np.zeros(len(flat))
    np.add.at(w, faces.ravel(), np.repeat(a / 3.0, 3))
    return w / w.sum()


def _interpolate(flat: Array, faces: Index, values: Array, at: Array) -> Array:
    """``values`` (n, 3) at the nodes ``flat`` (n, 2) of the triangles
    ``faces``, linearly interpolated at the points ``at`` (k, 2) (the nearest
    node's value outside the triangles). The same nodes: the values."""
    if flat.shape == at.shape and np.array_equal(flat, at):
        return values.copy()
    from scipy.spatial import cKDTree

    p = flat[faces]  # (m, 3, 2)
    e1, e2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    out = np.full((len(at), values.shape[1]), np.nan)
    for lo in range(0, len(at), 128):  # barycentric coordinates in every triangle
        q = at[lo : lo + 128, None, :] - p[None, :, 0]
        b1 = (q[..., 0] * e2[:, 1] - q[..., 1] * e2[:, 0]) / det
        b2 = (e1[:, 0] * q[..., 1] - e1[:, 1] * q[..., 0]) / det
        inside = np.minimum(np.minimum(b1, b2), 1.0 - b1 - b2)
        t = np.argmax(inside, axis=1)
        rows = np.arange(len(t))
        ok = inside[rows, t] >= -1e-9
        c1, c2 = b1[rows, t], b2[rows, t]
        v = values[faces[t]]
        val = (1 - c1 - c2)[:, None] * v[:, 0] + c1[:, None] * v[:, 1] + c2[:, None] * v[:, 2]
        out[lo : lo + 128][ok] = val[ok]
    bad = ~np.isfinite(out).all(axis=1)
    if bad.any():
        out[bad] = values[cKDTree(flat).query(at[bad])[1]]
    return out


def _planar_fit(x: Array, y: Array, w: Array) -> tuple[Array, Array]:
    """The turn about z and the shift in xy that bring ``x`` (k, 3) closest to
    ``y`` (k, 3) in the ``w``-weighted least-squares sense: (rotation, shift)."""
    xc, yc = w @ x, w @ y
    a, b = x[:, :2] - xc[:2], y[:, :2] - yc[:2]
    s = np.sum(w * (a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]))
    c = np.sum(w * (a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1]))
    phi = np.arctan2(s, c)
    rot = np.array([[np.cos(phi), -np.sin(phi), 0.0], [np.sin(phi), np.cos(phi), 0.0], [0, 0, 1]])
    shift = yc - rot @ xc
    shift[2] = 0.0  # it stands on the ground: no lift
    return rot, shift


def _vertex_normals(x: Array, faces: Index) -> Array:
    """``(n, 3)`` unit normals at the nodes of the triangles ``faces`` on ``x``
    (area-weighted mean of their triangles', oriented as the flat sheet's +z)."""
    p = x[faces]
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    out = np.zeros_like(x)
    for i in range(3):
        np.add.at(out, faces[:, i], n)
    return out / np.maximum(np.linalg.norm(out, axis=1), 1e-300)[:, None]


def designed_sizes(target: Design) -> dict[str, float]:
    """The target design's own height, span and depth as it rests (its
    resting placement; design unit): what a design target's standing steel
    is measured against."""
    rest = rest_once(fold_design(target))
    return {"height": rest.height, "span": rest.width, "depth": rest.depth}


def target_form(target: Design, flat: Array) -> Array:
    """``(k, 3)`` the target design's form at the flat points ``flat`` (k, 2),
    as it rests on the ground (its resting placement, design unit)."""
    folded = fold_design(target)
    return rest_once(folded).apply(folded.map_points(flat))


def standing_measures(
    target: Design, samples: Array, sample_weights: Array, standing: Standing
) -> StandingMeasures:
    """Compare ``standing`` (which must stand) with ``target`` as it stands.

    Args:
        target: the design whose form the steel should take.
        samples: ``(k, 2)`` the flat points the residual is sampled at (the
            same for every candidate of one compensation).
        sample_weights: ``(k,)`` their weights (sum 1: their share of the area).
        standing: a candidate's simulation.
    """
    if standing.positions is None:
        raise ValueError("no standing form to measure")
    folded = fold_design(target)
    rest = rest_once(folded)
    w = node_weights(standing.flat, standing.faces)
    goal = target_form(target, standing.flat)
    rot, shift = _planar_fit(standing.positions, goal, w)
    aligned = standing.positions @ rot.T + shift
    hole = 0.5 * relief_hole_diameter(target, folded)
    # to the target's fold frame, where its surface is measured from
    d = surface_distance(folded, (aligned - rest.translation) @ rest.rotation, hole)
    # signed by the side of the target's surface the node is on (a residual
    # smooth through zero): the side of the same material point's normal
    side = np.sign(np.einsum("ij,ij->i", aligned - goal, _vertex_normals(goal, standing.faces)))
    signed = np.where(side == 0.0, 1.0, side) * d
    at = _interpolate(standing.flat, standing.faces, signed[:, None].repeat(3, 1), samples)[:, 0]
    residual = np.sqrt(sample_weights) * at
    return StandingMeasures(
        residual=residual,
        max_deviation=float(d.max()),
        rms_deviation=float(np.sqrt(np.average(d**2, weights=w))),
        deviation=d,
        aligned=aligned,
    )


def _crease_dihedrals(flat: Array, faces: Index, x: Array) -> tuple[Array, Array]:
    """``(x-sign of each crease edge, its fold angle in deg)`` on the form ``x``
    (n, 3): the angle between the normals of the two triangles that meet at
    each mesh edge on the fold line (y = 0 on the flat sheet)."""
    on = np.abs(flat[:, 1]) <= 1e-9 * float(np.ptp(flat))
    edges: dict[tuple[int, int], list[int]] = {}
    for f, tri in enumerate(faces):
        for i in range(3):
            a, b = int(tri[i]), int(tri[(i + 1) % 3])
            if on[a] and on[b]:
                edges.setdefault((min(a, b), max(a, b)), []).append(f)
    p = x[faces]
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    n /= np.linalg.norm(n, axis=1)[:, None]
    side, angle = [], []
    for (a, b), fs in edges.items():
        if len(fs) != 2:
            continue
        c = float(np.clip(n[fs[0]] @ n[fs[1]], -1.0, 1.0))
        side.append(np.sign(flat[a, 0] + flat[b, 0]))
        angle.append(np.degrees(np.arccos(c)))
    return np.array(side), np.array(angle)


def crease_springback(design: Design, standing: Standing) -> dict[str, float]:
    """How far each crease half's fold angle (deg) changes from the designed
    form to the standing steel, measured on the mesh: the mean over the half's
    edges of the standing dihedral minus the designed one (the same mesh, so
    the triangles' own angle to the curved surface cancels). Keys '+x', '-x'."""
    if standing.positions is None:
        return {}
    folded = fold_design(design)
    designed = folded.map_points(standing.flat)
    s0, a0 = _crease_dihedrals(standing.flat, standing.faces, designed)
    _, a1 = _crease_dihedrals(standing.flat, standing.faces, standing.positions)
    return {
        key: float(np.mean(a1[s0 == sign] - a0[s0 == sign]))
        for key, sign in (("+x", 1.0), ("-x", -1.0))
        if (s0 == sign).any()
    }
