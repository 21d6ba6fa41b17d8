"""The peer check of the sheet's mechanics: a KratosMultiphysics shell model of
the designed form standing under its own weight (the structural check of issue 23).

The designed form of a template (the exact model's fold, taken as stress-free)
is meshed flat with Shewchuk's Triangle (the ``triangle`` package): the sheet
polygon as outline, the relief hole as a polygon hole, the crease (the x axis
from the hole to the boundary, both halves) as constrained segments, so no
triangle crosses the crease; the two sides share the crease nodes (a welded
crease). Every node is folded with :meth:`FoldedSheet.map_points` and stood
with the zero-thickness shell's resting placement (``rest_once(folded)``: z up,
ground z = 0), in metres.

Kratos solves it with ``ShellThinElementCorotational3D3N`` (nonlinear:
Newton-Raphson on the corotational element, displacement criterion) or
``ShellThinElement3D3N`` (``--linear``: one linear solve, small displacement),
a linear elastic plane-stress law, gravity as the nodal ``VOLUME_ACCELERATION``
the element integrates with its mass per unit area rho t, and Eigen's sparse LU
(``LinearSolversApplication.sparse_lu``). Supports at the three resting
contacts (both crease ends and one sheet corner): ``anchored`` fixes x, y, z
at each (rotations free); ``frictionless`` fixes z at each, and only x, y at
the first and the component across the first two at the second (no in-plane
rigid-body motion, no other horizontal restraint).

:func:`mesh_sheet` (flat mesh) and :func:`standing_mesh` (a template's mesh
on the ground) need only numpy and ``triangle``; :func:`solve_shell` takes
plain arrays and returns plain data, and imports KratosMultiphysics inside
itself, so this module imports without Kratos. Kratos is no dependency of the
package; install it in a separate environment::

    python3 -m venv /work/kratos-venv
    /work/kratos-venv/bin/pip install KratosMultiphysics \\
        KratosStructuralMechanicsApplication KratosLinearSolversApplication triangle
    /work/kratos-venv/bin/pip install -e .

Run from the repository root (h in metres; several h and ``--repeat`` for a
convergence table with median timings)::

    /work/kratos-venv/bin/python benchmarks/kratos_shell.py patkau-one-fold --h 0.05 \\
        [--supports anchored|frictionless] [--linear] [--json] [--repeat 3]
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import statistics
import sys
import time
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: 304 stainless steel (the template gives the density and thickness).
YOUNG_MODULUS = 193.0e9  # Pa
POISSON_RATIO = 0.29
GRAVITY = 9.81  # m/s^2

INSTALL_HINT = (
    "this needs KratosMultiphysics, KratosStructuralMechanicsApplication and "
    "KratosLinearSolversApplication (and `triangle` for the mesh), which are no "
    "dependency of onefold_cad: install them in a separate environment, e.g. "
    "`python3 -m venv /work/kratos-venv && /work/kratos-venv/bin/pip install "
    "KratosMultiphysics KratosStructuralMechanicsApplication "
    "KratosLinearSolversApplication triangle && /work/kratos-venv/bin/pip install -e .`"
)


# -- timing -------------------------------------------------------------------
@contextlib.contextmanager
def _timed(into: dict[str, float], name: str) -> Iterator[None]:
    """Adds the CPU (``time.process_time``, all threads) and wall time of the
    block to ``into[name + '_cpu_s']`` and ``into[name + '_wall_s']``."""
    c0, w0 = time.process_time(), time.perf_counter()
    try:
        yield
    finally:
        into[name + "_cpu_s"] = into.get(name + "_cpu_s", 0.0) + time.process_time() - c0
        into[name + "_wall_s"] = into.get(name + "_wall_s", 0.0) + time.perf_counter() - w0


# -- the flat mesh ------------------------------------------------------------
def _axis_crossings(polygon: Array) -> tuple[Array, list[int]]:
    """The polygon with its crossings of the x axis inserted as vertices (where
    they are not vertices already), and the indices of the +x and -x crossing."""
    out: list[Array] = []
    k = len(polygon)
    for i in range(k):
        p, q = polygon[i], polygon[(i + 1) % k]
        out.append(p)
        if (p[1] < 0.0 < q[1]) or (q[1] < 0.0 < p[1]):
            s = p[1] / (p[1] - q[1])
            out.append(np.array([p[0] + s * (q[0] - p[0]), 0.0]))
    poly = np.array(out, dtype=float)
    on_axis = np.flatnonzero(np.abs(poly[:, 1]) <= 1e-12 * np.abs(poly).max())
    poly[on_axis, 1] = 0.0
    plus = [int(i) for i in on_axis if poly[i, 0] > 0.0]
    minus = [int(i) for i in on_axis if poly[i, 0] < 0.0]
    if len(plus) != 1 or len(minus) != 1:
        raise ValueError("the sheet must cross the x axis (the crease) once on each side of H")
    return poly, [plus[0], minus[0]]


def mesh_sheet(
    polygon: Array,
    hole_diameter: float,
    h: float,
    *,
    hole_segments: int = 16,
    min_angle: float = 30.0,
) -> tuple[Array, IntArray, dict[str, Any]]:
    """Triangulate the flat sheet (fold frame: crease on the x axis, H at the
    origin) with Triangle: quality mesh ``pq{min_angle}a{A}``, A the area of the
    equilateral triangle of edge ``h`` (the unit of ``polygon``).

    The relief hole is a regular ``hole_segments``-gon inscribed in the circle
    of ``hole_diameter`` about H, with vertices on the x axis; the crease halves
    run from those vertices to the boundary's crossings of the x axis as
    constrained segments, so every triangle lies on one side of the crease.
    Triangle grades the mesh finer toward the hole by itself.

    Returns ``(points (n, 2), triangles (m, 3) int, info)``; ``info`` names the
    nodes of the polygon's vertices (``'vertices'``: one node per vertex of the
    input polygon, in order), the crease ends on the boundary (``'crease_ends'``:
    +x, -x), and every node on the crease (``'crease'``).
    """
    try:
        import triangle
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError(INSTALL_HINT) from exc
    if hole_segments % 2:
        raise ValueError("hole_segments must be even (a vertex on each crease half)")
    outline, (i_plus, i_minus) = _axis_crossings(np.asarray(polygon, dtype=float))
    k = len(outline)
    r = 0.5 * hole_diameter
    a = 2.0 * np.pi * np.arange(hole_segments) / hole_segments
    hole = np.stack([r * np.cos(a), r * np.sin(a)], axis=-1)
    hole[[0, hole_segments // 2], 1] = 0.0
    verts = np.concatenate([outline, hole])
    ring = np.arange(k)
    hring = k + np.arange(hole_segments)
    segs = np.concatenate(
        [
            np.stack([ring, np.roll(ring, -1)], axis=-1),
            np.stack([hring, np.roll(hring, -1)], axis=-1),
            [[k, i_plus], [k + hole_segments // 2, i_minus]],
        ]
    )
    area = math.sqrt(3.0) / 4.0 * h * h
    tri = triangle.triangulate(
        {"vertices": verts, "segments": segs, "holes": [[0.0, 0.0]]},
        f"pq{min_angle:g}a{area:.10g}",
    )
    pts = np.asarray(tri["vertices"], dtype=float)
    tris = np.asarray(tri["triangles"], dtype=np.int64)
    scale = float(np.abs(outline).max())
    crease = np.flatnonzero((np.abs(pts[:, 1]) <= 1e-9 * scale) & (np.abs(pts[:, 0]) >= 0.99 * r))
    pts[crease, 1] = 0.0

    def node_of(p: Array) -> int:
        d = np.hypot(*(pts - p).T)
        i = int(np.argmin(d))
        if d[i] > 1e-9 * scale:
            raise RuntimeError("Triangle moved an input vertex")
        return i

    vertices = [node_of(np.asarray(p, dtype=float)) for p in polygon]
    ends = [node_of(outline[i_plus]), node_of(outline[i_minus])]
    # no triangle may have nodes strictly on both sides of the crease
    side = np.sign(pts[tris, 1])
    crossing = int(np.sum((side.max(axis=1) > 0) & (side.min(axis=1) < 0)))
    if crossing:
        raise RuntimeError(f"{crossing} triangles cross the crease")
    info = {"vertices": vertices, "crease_ends": ends, "crease": crease, "options": tri}
    return pts, tris, info


# -- the designed form on the ground -----------------------------------------------
@dataclass
class StandingMesh:
    """A template's shell mesh, folded and stood on the ground (SI units).

    Attributes:
        name: the template.
        h: the target edge length (m).
        flat: ``(n, 2)`` the nodes on the flat sheet (fold frame, mm).
        nodes: ``(n, 3)`` the nodes of the designed form standing (m; z up,
            ground z = 0).
        triangles: ``(m, 3)`` node indices.
        contacts: ``(3,)`` the nodes nearest to ``rest_once(folded).contacts``.
        contact_gap: ``(3,)`` their distances from those contacts (m).
        corners: ``(k,)`` the nodes of the sheet's vertices, in order.
        lifted_corner: the index into ``corners`` of the vertex that is no contact.
        thickness: t (m); density: rho (kg/m^3); hole_diameter: (m).
        flat_area: the meshed flat area (m^2); the polygon area less the hole polygon's.
        timings: CPU and wall time (s) of Triangle (``triangle_*``) and of the
            whole mesh (``mesh_*``: Triangle, folding and standing the nodes,
            finding the contacts; the design's solve and placement excluded).
    """

    name: str
    h: float
    flat: Array
    nodes: Array
    triangles: IntArray
    contacts: IntArray
    contact_gap: Array
    corners: IntArray
    lifted_corner: int
    thickness: float
    density: float
    hole_diameter: float
    flat_area: float
    timings: dict[str, float] = field(default_factory=dict)


def standing_mesh(template: str, h: float, *, hole_segments: int = 16) -> StandingMesh:
    """Mesh the template's flat sheet at edge length ``h`` (m) and stand its
    designed form on the ground (:func:`mesh_sheet`, ``folded.map_points``,
    ``rest_once(folded).apply``). The design must be in millimetres."""
    from onefold_cad.design import fold_design, rest_once
    from onefold_cad.fabrication.relief_hole import relief_hole_diameter
    from onefold_cad.templates import find_template, load_template

    timings: dict[str, float] = {}
    design = load_template(find_template(template))
    if design.units.value != "mm":
        raise ValueError(f"{template}: the check expects a millimetre design")
    folded = fold_design(design)
    rest = rest_once(folded)  # the package's own work: not timed as the mesh's
    hole = relief_hole_diameter(design, folded)
    polygon = np.asarray(design.sheet.vertices, dtype=float)
    with _timed(timings, "mesh"), _timed(timings, "triangle"):
        flat, tris, info = mesh_sheet(polygon, hole, 1000.0 * h, hole_segments=hole_segments)
    with _timed(timings, "mesh"):
        nodes = rest.apply(folded.map_points(flat)) / 1000.0
        contacts_m = np.asarray(rest.contacts, dtype=float) / 1000.0
        d = np.linalg.norm(nodes[None, :, :] - contacts_m[:, None, :], axis=-1)
        contacts = np.argmin(d, axis=1)
    corners = np.asarray(info["vertices"], dtype=np.int64)
    lifted = [i for i, n in enumerate(corners) if n not in set(contacts.tolist())]
    e1 = flat[tris[:, 1]] - flat[tris[:, 0]]
    e2 = flat[tris[:, 2]] - flat[tris[:, 0]]
    area = 0.5 * float(np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]).sum()) / 1e6
    m = design.material
    return StandingMesh(
        name=template,
        h=h,
        flat=flat,
        nodes=nodes,
        triangles=tris,
        contacts=contacts.astype(np.int64),
        contact_gap=d[np.arange(len(contacts)), contacts],
        corners=corners,
        lifted_corner=lifted[0] if len(lifted) == 1 else -1,
        thickness=m.thickness / 1000.0,
        density=float(m.density) if m.density is not None else 8000.0,
        hole_diameter=hole / 1000.0,
        flat_area=area,
        timings=timings,
    )


def support_sets(contacts: Sequence[int], nodes: Array, supports: str) -> dict[str, list[int]]:
    """The fixed nodes per direction ('x', 'y', 'z') for ``anchored`` (x, y, z
    at every contact) or ``frictionless`` (z at every contact; x and y at the
    first; at the second the horizontal component most across the line
    between the two, so no in-plane rigid-body motion is left)."""
    c = [int(i) for i in contacts]
    if supports == "anchored":
        return {"x": c, "y": c, "z": c}
    if supports == "frictionless":
        d = nodes[c[1], :2] - nodes[c[0], :2]
        across = "y" if abs(d[0]) >= abs(d[1]) else "x"
        fixed: dict[str, list[int]] = {"x": [c[0]], "y": [c[0]], "z": c}
        fixed[across].append(c[1])
        return fixed
    raise ValueError(f"unknown supports {supports!r} (anchored or frictionless)")


# -- Kratos ---------------------------------------------------------------------
@contextlib.contextmanager
def _quiet(enabled: bool) -> Iterator[None]:
    """Silence the C++ side's stdout (Kratos's banner and per-iteration log)."""
    if not enabled:
        yield
        return
    sys.stdout.flush()
    saved = os.dup(1)
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), 1)
        try:
            yield
        finally:
            sys.stdout.flush()
            os.dup2(saved, 1)
            os.close(saved)


def _import_kratos() -> tuple[Any, Any, Any]:
    try:
        import KratosMultiphysics as km
        import KratosMultiphysics.LinearSolversApplication  # noqa: F401
        import KratosMultiphysics.StructuralMechanicsApplication  # noqa: F401
        from KratosMultiphysics import python_linear_solver_factory
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError(INSTALL_HINT) from exc
    return km, km.StructuralMechanicsApplication, python_linear_solver_factory


def solve_shell(
    nodes: Array,
    triangles: IntArray,
    fixed: Mapping[str, Sequence[int]],
    *,
    E: float = YOUNG_MODULUS,
    nu: float = POISSON_RATIO,
    rho: float = 8000.0,
    t: float = 3.57e-3,
    g: float = GRAVITY,
    nonlinear: bool = True,
    load_steps: int = 1,
    rel_tol: float = 1e-9,
    abs_tol: float = 1e-14,
    max_iterations: int = 50,
    linear_solver: str = "LinearSolversApplication.sparse_lu",
    threads: int | None = 1,
    quiet: bool = True,
) -> dict[str, Any]:
    """Solve a thin triangular shell under its own weight with Kratos.

    Args:
        nodes: ``(n, 3)`` the stress-free form (m), gravity along -z.
        triangles: ``(m, 3)`` node indices (0-based).
        fixed: node indices whose displacement is fixed, per direction
            ``'x'``, ``'y'``, ``'z'`` (rotations are free everywhere).
        E, nu, rho, t, g: Young's modulus (Pa), Poisson's ratio, density
            (kg/m^3), thickness (m), gravity (m/s^2).
        nonlinear: ``ShellThinElementCorotational3D3N`` with Newton-Raphson in
            ``load_steps`` equal increments of gravity (displacement criterion
            ``rel_tol`` relative or ``abs_tol`` absolute, at most
            ``max_iterations`` per step); else ``ShellThinElement3D3N`` and one
            linear solve.
        linear_solver: the Kratos linear solver's ``solver_type``.
        threads: OpenMP threads for Kratos (None: Kratos's default).
        quiet: silence Kratos's own output.

    Returns:
        plain data: ``displacement`` ``(n, 3)`` (m), ``reaction`` ``(n, 3)``
        (N; the force the supports exert on the shell, zero at free
        directions), ``weight`` (N; rho g t times the area of the flat
        triangles is the caller's, here the triangles as meshed in 3D),
        ``converged``, ``steps`` (per load step: iterations, converged), the
        element, linear solver and Kratos version, and ``timings`` (CPU and
        wall s: ``build`` (model part), ``solve`` (initialisation, assembly,
        factorisation, iterations, reactions)).
    """
    nodes = np.asarray(nodes, dtype=float)
    triangles = np.asarray(triangles, dtype=np.int64)
    timings: dict[str, float] = {}
    with _quiet(quiet):
        km, sma, solver_factory = _import_kratos()
    if threads is not None:
        km.ParallelUtilities.SetNumThreads(int(threads))
    km.Logger.GetDefaultOutput().SetSeverity(
        km.Logger.Severity.WARNING if quiet else km.Logger.Severity.INFO
    )
    element = "ShellThinElementCorotational3D3N" if nonlinear else "ShellThinElement3D3N"
    with _quiet(quiet), _timed(timings, "build"):
        model = km.Model()
        mp = model.CreateModelPart("Shell")
        mp.SetBufferSize(2)
        mp.ProcessInfo[km.DOMAIN_SIZE] = 3
        for var in (
            km.DISPLACEMENT,
            km.ROTATION,
            km.REACTION,
            km.REACTION_MOMENT,
            km.VOLUME_ACCELERATION,
        ):
            mp.AddNodalSolutionStepVariable(var)
        for i, (x, y, z) in enumerate(nodes):
            mp.CreateNewNode(i + 1, float(x), float(y), float(z))
        prop = mp.GetProperties()[1]
        prop[km.YOUNG_MODULUS] = E
        prop[km.POISSON_RATIO] = nu
        prop[km.DENSITY] = rho
        prop[km.THICKNESS] = t
        prop[km.CONSTITUTIVE_LAW] = sma.LinearElasticPlaneStress2DLaw()
        for j, (a, b, c) in enumerate(triangles):
            mp.CreateNewElement(element, j + 1, [int(a) + 1, int(b) + 1, int(c) + 1], prop)
        for comp in ("X", "Y", "Z"):
            d = getattr(km, "DISPLACEMENT_" + comp)
            r = getattr(km, "REACTION_" + comp)
            km.VariableUtils().AddDof(d, r, mp)
            km.VariableUtils().AddDof(
                getattr(km, "ROTATION_" + comp), getattr(km, "REACTION_MOMENT_" + comp), mp
            )
        for comp in ("x", "y", "z"):
            d = getattr(km, "DISPLACEMENT_" + comp.upper())
            for i in fixed.get(comp, ()):
                mp.GetNode(int(i) + 1).Fix(d)
        lin = solver_factory.ConstructSolver(
            km.Parameters(json.dumps({"solver_type": linear_solver}))
        )
        scheme = km.ResidualBasedIncrementalUpdateStaticScheme()
        bns = km.ResidualBasedBlockBuilderAndSolver(lin)
        if nonlinear:
            crit = km.DisplacementCriteria(rel_tol, abs_tol)
            crit.SetEchoLevel(0 if quiet else 1)
            strategy = km.ResidualBasedNewtonRaphsonStrategy(
                mp, scheme, crit, bns, max_iterations, True, False, True
            )
        else:
            strategy = km.ResidualBasedLinearStrategy(mp, scheme, bns, True, False, False, False)
        strategy.SetEchoLevel(0 if quiet else 1)

    def nodal(var: Any) -> Array:
        return np.array([list(nd.GetSolutionStepValue(var)) for nd in mp.Nodes], dtype=float)

    steps: list[dict[str, Any]] = []
    history: list[dict[str, Any]] = []
    n_steps = load_steps if nonlinear else 1
    last: tuple[float, Array, Array] | None = None
    with _quiet(quiet), _timed(timings, "solve"):
        strategy.Initialize()
        for k in range(1, n_steps + 1):
            mp.CloneTimeStep(float(k))
            mp.ProcessInfo[km.STEP] = k
            acc = km.Vector([0.0, 0.0, -g * k / n_steps])
            km.VariableUtils().SetVectorVar(km.VOLUME_ACCELERATION, acc, mp.Nodes)
            strategy.InitializeSolutionStep()
            strategy.Predict()
            ok = bool(strategy.SolveSolutionStep())
            strategy.FinalizeSolutionStep()
            it = int(mp.ProcessInfo[km.NL_ITERATION_NUMBER]) if nonlinear else 1
            steps.append({"step": k, "load_factor": k / n_steps, "iterations": it, "converged": ok})
            if not ok:
                break
            if n_steps > 1:  # keep the converged state (a later step may fail)
                last = (k / n_steps, nodal(km.DISPLACEMENT), nodal(km.REACTION))
                history.append({"load_factor": k / n_steps, "displacement": last[1]})
    converged = all(st["converged"] for st in steps) and len(steps) == n_steps
    if converged or last is None:
        load_factor = 1.0 if converged else 0.0
        disp, reac = nodal(km.DISPLACEMENT), nodal(km.REACTION)
    else:  # report the last converged increment, not the diverged iterate
        load_factor, disp, reac = last
    # Kratos's REACTION at a fixed dof is the force the support exerts on the
    # shell (its sum balances the weight: upward positive here).
    mask = np.zeros_like(reac, dtype=bool)
    for col, comp in enumerate("xyz"):
        mask[np.asarray(list(fixed.get(comp, ())), dtype=np.int64), col] = True
    reac[~mask] = 0.0
    e1 = nodes[triangles[:, 1]] - nodes[triangles[:, 0]]
    e2 = nodes[triangles[:, 2]] - nodes[triangles[:, 0]]
    area_3d = 0.5 * float(np.linalg.norm(np.cross(e1, e2), axis=1).sum())
    return {
        "element": element,
        "constitutive_law": "LinearElasticPlaneStress2DLaw",
        "linear_solver": linear_solver,
        "kratos_version": km.KratosGlobals.Kernel.Version(),
        "threads": km.ParallelUtilities.GetNumThreads(),
        "nonlinear": nonlinear,
        "converged": converged,
        "load_factor": load_factor,
        "steps": steps,
        "history": history,
        "displacement": disp,
        "reaction": reac,
        "area_3d": area_3d,
        "weight": rho * g * t * area_3d,
        "timings": timings,
    }


# -- a case: mesh, solve, summarise --------------------------------------------------
def run_case(
    template: str,
    h: float,
    *,
    supports: str = "anchored",
    nonlinear: bool = True,
    load_steps: int = 1,
    threads: int | None = 1,
    quiet: bool = True,
) -> dict[str, Any]:
    """Mesh the template at ``h`` (m), solve it in Kratos, and summarise
    (lengths in mm, forces in N, times in s)."""
    sm = standing_mesh(template, h)
    timings = dict(sm.timings)
    fixed = support_sets(sm.contacts, sm.nodes, supports)
    res = solve_shell(
        sm.nodes,
        sm.triangles,
        fixed,
        rho=sm.density,
        t=sm.thickness,
        nonlinear=nonlinear,
        load_steps=load_steps,
        threads=threads,
        quiet=quiet,
    )
    timings.update(res["timings"])
    for kind in ("cpu", "wall"):
        timings[f"kratos_{kind}_s"] = timings[f"build_{kind}_s"] + timings[f"solve_{kind}_s"]
        timings[f"total_{kind}_s"] = timings[f"mesh_{kind}_s"] + timings[f"kratos_{kind}_s"]
    u = res["displacement"]
    mag = np.linalg.norm(u, axis=1)
    imax = int(np.argmax(mag))
    label: dict[int, str] = {}
    for n in sm.corners:
        x, y = sm.flat[n]
        on_axis = abs(y) <= 1e-9 * abs(x)
        label[int(n)] = (
            f"crease end {'+' if x > 0 else '-'}x" if on_axis else (f"corner ({x:.1f}, {y:.1f})")
        )
    corners = []
    for i, n in enumerate(sm.corners):
        corners.append(
            {
                "name": label[int(n)],
                "flat_mm": sm.flat[n].tolist(),
                "standing_mm": (1000.0 * sm.nodes[n]).tolist(),
                "displacement_mm": (1000.0 * u[n]).tolist(),
                "magnitude_mm": 1000.0 * float(mag[n]),
                "lifted": i == sm.lifted_corner,
            }
        )
    r = res["reaction"]
    sup = []
    for n in sm.contacts:
        sup.append(
            {
                "name": label.get(int(n), f"node {int(n)}"),
                "node": int(n),
                "standing_mm": (1000.0 * sm.nodes[n]).tolist(),
                "reaction_N": r[n].tolist(),
                "vertical_N": float(r[n, 2]),
                "horizontal_N": float(np.hypot(r[n, 0], r[n, 1])),
                "displacement_mm": (1000.0 * u[n]).tolist(),
            }
        )
    feet = sm.nodes[sm.contacts]
    moved = feet + u[sm.contacts]
    pairs = [(0, 1), (0, 2), (1, 2)]
    spread = [
        {
            "feet": [sup[a]["name"], sup[b]["name"]],
            "distance_mm": 1000.0 * float(np.linalg.norm(feet[a] - feet[b])),
            "change_mm": 1000.0
            * float(np.linalg.norm(moved[a] - moved[b]) - np.linalg.norm(feet[a] - feet[b])),
        }
        for a, b in pairs
    ]
    weight_flat = sm.density * GRAVITY * sm.thickness * sm.flat_area
    z = sm.nodes[:, 2] + u[:, 2]
    free = np.setdiff1d(np.arange(len(z)), sm.contacts)
    ilow = int(free[np.argmin(z[free])])
    return {
        "template": template,
        "h_m": h,
        "supports": supports,
        "fixed": {k: [int(i) for i in v] for k, v in fixed.items()},
        "nodes": len(sm.nodes),
        "elements": len(sm.triangles),
        "dofs": 6 * len(sm.nodes),
        "hole_diameter_mm": 1000.0 * sm.hole_diameter,
        "contact_gap_mm": (1000.0 * sm.contact_gap).tolist(),
        "element": res["element"],
        "linear_solver": res["linear_solver"],
        "kratos_version": res["kratos_version"],
        "threads": res["threads"],
        "nonlinear": nonlinear,
        "converged": res["converged"],
        "steps": res["steps"],
        "load_factor": res["load_factor"],
        "history": [
            {
                "load_factor": hs["load_factor"],
                "max_displacement_mm": 1000.0
                * float(np.linalg.norm(hs["displacement"], axis=1).max()),
                "lifted_corner_mm": (
                    (1000.0 * hs["displacement"][sm.corners[sm.lifted_corner]]).tolist()
                    if sm.lifted_corner >= 0
                    else None
                ),
                "feet_change_mm": [
                    1000.0
                    * float(
                        np.linalg.norm(
                            feet[a]
                            + hs["displacement"][sm.contacts[a]]
                            - feet[b]
                            - hs["displacement"][sm.contacts[b]]
                        )
                        - np.linalg.norm(feet[a] - feet[b])
                    )
                    for a, b in pairs
                ],
            }
            for hs in res["history"]
        ],
        "max_displacement_mm": 1000.0 * float(mag[imax]),
        "max_displacement_at_mm": (1000.0 * sm.nodes[imax]).tolist(),
        "max_displacement_at_flat_mm": sm.flat[imax].tolist(),
        "max_displacement_vector_mm": (1000.0 * u[imax]).tolist(),
        "corners": corners,
        "supports_out": sup,
        "feet_spread": spread,
        "lowest_free_node_z_mm": 1000.0 * float(z[ilow]),
        "lowest_free_node_flat_mm": sm.flat[ilow].tolist(),
        "sum_reaction_N": r.sum(axis=0).tolist(),
        "weight_N": res["weight"],
        "weight_flat_N": weight_flat,
        "flat_area_m2": sm.flat_area,
        "area_3d_m2": res["area_3d"],
        "timings": timings,
    }


def _median_timings(runs: list[dict[str, Any]]) -> dict[str, float]:
    keys = runs[0]["timings"].keys()
    return {k: statistics.median(r["timings"][k] for r in runs) for k in keys}


def _print_case(res: dict[str, Any]) -> None:
    t = res["timings"]
    kind = "nonlinear" if res["nonlinear"] else "linear"
    print(
        f"{res['template']}  h = {res['h_m']:g} m  {res['supports']}  {kind}  "
        f"{res['element']}  {res['linear_solver']}  Kratos {res['kratos_version']}  "
        f"threads {res['threads']}"
    )
    print(
        f"  nodes {res['nodes']}  elements {res['elements']}  dofs {res['dofs']}  "
        f"converged {res['converged']}  load factor {res['load_factor']:g}  steps "
        + ", ".join(f"{s['load_factor']:g}:{s['iterations']}it" for s in res["steps"])
    )
    at = res["max_displacement_at_mm"]
    fl = res["max_displacement_at_flat_mm"]
    print(
        f"  largest displacement {res['max_displacement_mm']:.3f} mm at "
        f"({at[0]:.1f}, {at[1]:.1f}, {at[2]:.1f}) mm standing, flat "
        f"({fl[0]:.1f}, {fl[1]:.1f})"
    )
    for c in res["corners"]:
        u = c["displacement_mm"]
        tag = "  (lifted)" if c["lifted"] else ""
        print(
            f"  {c['name']:<24} |u| {c['magnitude_mm']:9.3f} mm  "
            f"u = ({u[0]:8.3f}, {u[1]:8.3f}, {u[2]:8.3f}) mm{tag}"
        )
    for s in res["supports_out"]:
        r = s["reaction_N"]
        print(
            f"  support {s['name']:<16} R = ({r[0]:9.2f}, {r[1]:9.2f}, {r[2]:9.2f}) N  "
            f"vertical {s['vertical_N']:8.2f}  horizontal {s['horizontal_N']:8.2f}"
        )
    for sp in res["feet_spread"]:
        print(
            f"  feet {sp['feet'][0]} - {sp['feet'][1]}: {sp['distance_mm']:.1f} mm, "
            f"change {sp['change_mm']:+.3f} mm"
        )
    lo = res["lowest_free_node_flat_mm"]
    print(
        f"  lowest node but the supports after the load: z = {res['lowest_free_node_z_mm']:.3f} mm "
        f"(flat ({lo[0]:.1f}, {lo[1]:.1f}))"
    )
    for hs in res["history"]:
        ch = ", ".join(f"{c:+.1f}" for c in hs["feet_change_mm"])
        lc = hs["lifted_corner_mm"]
        lc_txt = "" if lc is None else f"  lifted corner u_z {lc[2]:+.1f} mm"
        print(
            f"    load {hs['load_factor']:.3f}: max |u| {hs['max_displacement_mm']:9.1f} mm  "
            f"feet distance change ({ch}) mm{lc_txt}"
        )
    sr = res["sum_reaction_N"]
    print(
        f"  sum of reactions ({sr[0]:.4f}, {sr[1]:.4f}, {sr[2]:.4f}) N at load factor "
        f"{res['load_factor']:g}; full weight rho g t A: "
        f"{res['weight_N']:.4f} N (3D triangles, {res['area_3d_m2']:.6f} m^2), "
        f"{res['weight_flat_N']:.4f} N (flat, {res['flat_area_m2']:.6f} m^2)"
    )
    print(
        "  time (s, cpu / wall): mesh {:.3f} / {:.3f}  build {:.3f} / {:.3f}  "
        "solve {:.3f} / {:.3f}  kratos {:.3f} / {:.3f}  total {:.3f} / {:.3f}".format(
            t["mesh_cpu_s"],
            t["mesh_wall_s"],
            t["build_cpu_s"],
            t["build_wall_s"],
            t["solve_cpu_s"],
            t["solve_wall_s"],
            t["kratos_cpu_s"],
            t["kratos_wall_s"],
            t["total_cpu_s"],
            t["total_wall_s"],
        )
    )


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--h", type=float, nargs="+", default=[0.05], help="edge length(s), m")
    ap.add_argument("--supports", choices=["anchored", "frictionless"], default="anchored")
    ap.add_argument("--linear", action="store_true", help="one linear solve (ShellThinElement3D3N)")
    ap.add_argument("--steps", type=int, default=1, help="load increments (nonlinear)")
    ap.add_argument("--repeat", type=int, default=1, help="runs per h; timings are medians")
    ap.add_argument("--threads", type=int, default=1, help="Kratos OpenMP threads")
    ap.add_argument("--json", action="store_true", help="print JSON (no displacement field)")
    ap.add_argument("--verbose", action="store_true", help="keep Kratos's own output")
    args = ap.parse_args(argv)
    out = []
    for h in args.h:
        runs = [
            run_case(
                args.template,
                h,
                supports=args.supports,
                nonlinear=not args.linear,
                load_steps=args.steps,
                threads=args.threads,
                quiet=not args.verbose,
            )
            for _ in range(args.repeat)
        ]
        res = dict(runs[-1])
        res["timings"] = _median_timings(runs)
        res["repeat"] = args.repeat
        res["timings_each"] = [r["timings"] for r in runs]
        out.append(res)
        if not args.json:
            _print_case(res)
            sys.stdout.flush()
    if args.json:
        print(json.dumps(out if len(out) > 1 else out[0], indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
