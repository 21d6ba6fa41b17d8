"""NAME.inp's shell mesh: curved midpoints that land on a cylinder the facets
only chord, the crease's edges kept straight, and the split in four: shared
nodes, orientation, area and the flat places of every node."""

from __future__ import annotations

import numpy as np

from onefold_cad.export.simulation.inp_mesh import shell_mesh


def _cylinder(radius: float, phi: float, rows: int, cols: int, width: float, crease=True):
    """A strip of a cylinder of axis x: ``rows`` facets of angle ``phi``
    around, ``cols`` of ``width`` along; the flat sheet it unrolls to
    (``(x, radius * angle)``), whose crease (flat y = 0) is the generator at
    angle 0, the strip's middle (``crease`` False: the flat sheet shifted to
    y > 0, no crease)."""
    u = (np.arange(cols + 1) - cols / 2) * width
    ang = (np.arange(rows + 1) - rows / 2) * phi
    a, x = np.meshgrid(ang, u, indexing="ij")
    x3 = np.column_stack([x.ravel(), radius * np.sin(a.ravel()), radius * np.cos(a.ravel())])
    flat = np.column_stack([x.ravel(), radius * a.ravel()])
    if not crease:
        flat[:, 1] += radius * rows * phi
    faces = []
    for r in range(rows):
        for c in range(cols):
            i = r * (cols + 1) + c
            faces += [(i, i + 1, i + cols + 2), (i, i + cols + 2, i + cols + 1)]
    return x3, np.array(faces), flat


def test_new_nodes_land_on_the_cylinder_the_chords_cut():
    """The chords' midpoints lie a sagitta R (1 - cos(phi / 2)) inside the
    arc; the curved edges' (Hermite) and the split's nodes (on the quadratic
    patch) within a quarter of it (the corners' normals are the area-weighted
    means of a fan that is not symmetric: 18 % at most here)."""
    R, phi, rows = 2.0, 0.3, 6
    x, faces, flat = _cylinder(R, phi, rows=rows, cols=4, width=0.2, crease=False)
    mesh = shell_mesh(x, faces, flat)
    n = len(x)
    assert np.allclose(mesh.nodes[:n], x)
    err = np.abs(np.hypot(mesh.nodes[:, 1], mesh.nodes[:, 2]) - R)
    # away from the strip's two outer rows (their corners' normals see one row of facets)
    angle = np.abs(np.arctan2(mesh.nodes[:, 1], mesh.nodes[:, 2]))
    inner = (np.arange(len(err)) >= n) & (angle <= (rows / 2 - 1) * phi + 1e-9)
    sagitta = R * (1 - np.cos(phi / 2))
    assert inner.sum() > 50 and err[inner].max() < 0.25 * sagitta
    chord = 0.5 * (x[faces[:, 0]] + x[faces[:, 2]])  # a facet edge across the rows
    assert np.abs(np.hypot(chord[:, 1], chord[:, 2]) - R).max() > 0.9 * sagitta


def test_the_crease_keeps_its_straight_edges():
    x, faces, flat = _cylinder(2.0, 0.3, rows=4, cols=6, width=0.2)
    mesh = shell_mesh(x, faces, flat)
    on = np.abs(mesh.flat[:, 1]) < 1e-12
    pts = mesh.nodes[on]  # the generator at angle 0: y = 0, z = R
    assert len(pts) == 7 + 6 + 12  # its corners, edge midpoints and quarter points
    assert np.allclose(pts[:, 1:], [0.0, 2.0], atol=1e-12)


def test_four_elements_per_facet_share_their_nodes_and_keep_the_orientation():
    x, faces, flat = _cylinder(2.0, 0.3, rows=3, cols=5, width=0.25)
    mesh = shell_mesh(x, faces, flat)
    m = len(faces)
    edges = {tuple(sorted(e)) for f in faces for e in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0]))}
    assert len(mesh.elements) == 4 * m
    assert len(mesh.nodes) == len(x) + 3 * len(edges) + 3 * m
    # every node used; each S6 edge (corner, midpoint, corner) used by at most two elements
    assert np.array_equal(np.unique(mesh.elements), np.arange(len(mesh.nodes)))
    halves = {}
    for e in mesh.elements:
        for k in range(3):
            key = (min(e[k], e[(k + 1) % 3]), e[3 + k], max(e[k], e[(k + 1) % 3]))
            halves[key] = halves.get(key, 0) + 1
    assert max(halves.values()) == 2

    # flat places: each sub-element's area a quarter of its facet's, same turning sense
    def area(p, tri):
        a, b, c = p[tri[:, 0]], p[tri[:, 1]], p[tri[:, 2]]
        return 0.5 * ((b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0])

    parent = np.repeat(area(flat, faces), 4)
    assert np.allclose(area(mesh.flat, mesh.elements[:, :3]), parent / 4)
    # midpoints on the flat sheet halfway between their corners
    for k in range(3):
        a, b = mesh.elements[:, k], mesh.elements[:, (k + 1) % 3]
        assert np.allclose(mesh.flat[mesh.elements[:, 3 + k]], (mesh.flat[a] + mesh.flat[b]) / 2)
