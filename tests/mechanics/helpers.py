"""Shared set-ups for the mechanics tests: finite differences, strips and fits."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from onefold_cad.mechanics import (
    BOUNDARY,
    SheetMesh,
    Shell,
    ShellMaterial,
    flat_positions,
    mesh_sheet,
)

F = np.ndarray


def central_difference(fun: Callable[[F], F], x: F, step: float) -> F:
    """d fun / d x by the fourth-order central difference; (len(x), *fun(x).shape)."""
    out = []
    for j in range(len(x)):
        e = np.zeros_like(x)
        e[j] = step
        out.append(
            (8 * (fun(x + e) - fun(x - e)) - (fun(x + 2 * e) - fun(x - 2 * e))) / (12 * step)
        )
    return np.array(out)


def rectangle(length: float, width: float, h: float, creases=()) -> SheetMesh:
    """A uniform (size h) mesh of [0, length] x [0, width]."""
    outline = [[0, 0], [length, 0], [length, width], [0, width]]
    return mesh_sheet(outline, size=(h, 0.0, h), creases=creases)


def clamped_edge(mesh: SheetMesh, x0: float = 0.0):
    """Boundary edges and nodes on the line x = x0 (a clamp): (edges, nodes)."""
    on = np.abs(mesh.nodes[:, 0] - x0) < 1e-12
    edges = np.flatnonzero((mesh.edge_kind == BOUNDARY) & on[mesh.edges].all(axis=1))
    return edges, np.flatnonzero(on)


def cantilever(mesh: SheetMesh, material: ShellMaterial, gravity: float, height: float = 0.0):
    """A strip clamped level along x = 0 at z = height under gravity (m/s^2): the shell
    and its fixed DOFs (the clamped nodes, and the clamped edges' director angles at 0,
    their reference directors being the flat sheet's normal)."""
    edges, nodes = clamped_edge(mesh)
    ref = flat_positions(mesh) + [0.0, 0.0, height]
    shell = Shell.create(mesh, material, reference=ref, gravity=(0.0, 0.0, -gravity))
    fixed = np.concatenate([(3 * nodes[:, None] + np.arange(3)).ravel(), 3 * mesh.n_nodes + edges])
    return shell, fixed


def circle_radius(x: F, z: F) -> float:
    """Radius of the least-squares (Kasa) circle through points (x, z)."""
    a = np.column_stack([x, z, np.ones_like(x)])
    d, e, f = np.linalg.lstsq(a, -(x**2 + z**2), rcond=None)[0]
    return float(np.sqrt(d**2 / 4 + e**2 / 4 - f))


def cylinder(mesh: SheetMesh, radius: float):
    """Roll the flat mesh about the line z = radius (x -> arc length): positions (n, 3)
    and the cylinder's normals at the directors' edge midpoints (n_dir, 3)."""
    x, y = mesh.nodes.T
    pos = np.column_stack([radius * np.sin(x / radius), y, radius * (1 - np.cos(x / radius))])
    edges = np.concatenate([np.arange(mesh.n_edges), mesh.crease_edges])
    mid = (pos[mesh.edges[edges, 0]] + pos[mesh.edges[edges, 1]]) / 2
    normal = np.column_stack([-mid[:, 0], np.zeros(len(mid)), radius - mid[:, 2]])
    return pos, normal / np.linalg.norm(normal, axis=1)[:, None]
