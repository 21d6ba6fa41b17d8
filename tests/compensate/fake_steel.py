"""A stand-in for ``onefold simulate`` whose answer is known: the "steel"
stands as the designed form of the fold with alpha and beta less by
:data:`SPRING` (degrees) and more by :data:`PER_OVERBEND` times the crease
overbend (degrees), at the nodes of a small triangulation of the flat sheet.
Compensating for it must form the fold :data:`SPRING` more, or (the
overbend alone) set the crease :data:`OVERBEND` degrees past the fold; no
simulation runs (the tests stay fast)."""

from __future__ import annotations

import numpy as np
from matplotlib.path import Path
from scipy.spatial import Delaunay

from onefold_cad.compensate.evaluate import Standing
from onefold_cad.design import Design, fold_design, rest_once

#: How much the fake steel opens the fold (alpha, beta), deg.
SPRING = (3.0, 2.0)
#: How much a degree of crease overbend closes the fold (alpha, beta), deg.
PER_OVERBEND = (0.5, 1.0 / 3.0)
#: The overbend that alone undoes :data:`SPRING`.
OVERBEND = 6.0


def flat_mesh(design: Design, n: int = 12) -> tuple[np.ndarray, np.ndarray]:
    """``(nodes (k, 2), faces (m, 3))``: the points of a grid over the sheet's
    bounding box inside the sheet, its corners and ``n`` points along the fold
    line (none in the relief hole), triangulated on each side of the fold line apart (Delaunay: each
    side of a convex sheet is convex), so the fold line is a chain of edges."""
    v = design.sheet.vertices
    lo, hi = v.min(axis=0), v.max(axis=0)
    gx, gy = np.meshgrid(np.linspace(lo[0], hi[0], n), np.linspace(lo[1], hi[1], n))
    p = np.column_stack([gx.ravel(), gy.ravel()])
    p = p[Path(v).contains_points(p, radius=-1e-9 * design.sheet.size)]
    ends = v[np.abs(v[:, 1]) <= 1e-12 * design.sheet.size, 0]
    crease = np.column_stack([np.linspace(ends.min(), ends.max(), n + 1), np.zeros(n + 1)])
    p = np.concatenate([p[np.abs(p[:, 1]) > 1e-9], v[np.abs(v[:, 1]) > 1e-12], crease])
    p = p[np.hypot(p[:, 0], p[:, 1]) > 0.02 * design.sheet.size]  # the relief hole
    faces = []
    for side in (1.0, -1.0):
        idx = np.flatnonzero(side * p[:, 1] >= 0.0)
        tri = idx[Delaunay(p[idx]).simplices]
        e1, e2 = p[tri[:, 1]] - p[tri[:, 0]], p[tri[:, 2]] - p[tri[:, 0]]
        flip = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0] < 0  # counter-clockwise
        tri[flip] = tri[flip][:, [0, 2, 1]]
        faces.append(tri)
    return p, np.concatenate(faces)


#: The bending law of every fake simulation, in order (a test may clear it).
LAWS: list[str] = []


def fake_standing(design: Design, level: str, check: bool = False, law: str = "moment") -> Standing:
    """The known "steel" of ``design`` (see the module docstring); ``law``
    is recorded in :data:`LAWS` and changes nothing."""
    LAWS.append(law)
    f = design.frame
    ob = design.material.overbend_deg
    opened = design.with_changes(
        frame=f.with_changes(
            alpha=f.alpha - SPRING[0] + PER_OVERBEND[0] * ob,
            beta=f.beta - SPRING[1] + PER_OVERBEND[1] * ob,
        )
    )
    folded = fold_design(opened)
    rest = rest_once(folded)
    flat, faces = flat_mesh(design)
    x = rest.apply(folded.map_points(flat))
    return Standing(
        stands=True, reason="", flat=flat, faces=faces, positions=x,
        height=rest.height, span=rest.width, depth=rest.depth,
        tipping_margin_deg=10.0, self_max_deviation=None,
        convergence=0.01 if check else None, cpu_s=0.0, warnings=(fake_warning(law),),
    )  # fmt: skip


def fake_warning(law: str) -> str:
    """The one warning the fake steel's simulation gives (as ``simulate``
    gives its own), naming its law."""
    return f"the fake steel of the {law} law springs back as it is told"
