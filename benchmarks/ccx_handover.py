"""CalculiX's own formed state handed to its release: the stress a finished
``calculix_forming.py`` run leaves at its shells' integration points, at the
integration points of ``calculix_release.py``'s wedges (pure numpy and
scipy; ``calculix_release.py --formed-by DIR`` uses it).

The industry's way to release a formed part in another model (Abaqus's
``*IMPORT`` of an explicit forming into an implicit springback): the state
moves, the forming's mesh does not. Here both meshes are of one flat sheet,
so a material point is found by its flat coordinates.

* **The forming** (:func:`read_forming`): its ``.inp`` gives the flat shell
  nodes (m), the ``S6`` elements, the composite section's layers and the
  thickness, and whether the law is perfectly plastic (one ``*PLASTIC``
  row: the stress is the whole state, nothing else to hand over); its
  ``.dat`` the displacements and, per element, level (two Gauss points
  through each layer, bottom up along the element's own normal) and
  in-plane point (the 3-point rule of :data:`ccx_release.GAUSS_WEDGE`), the
  global stress and the equivalent plastic strain at the end.
* **Up, as the wedges mean it** (:func:`levels_up`): each element's levels
  are ordered along the designed top normal at its centroid (the wedges'
  height axis, ``ccx_release.node_moves``): reversed where the element's
  formed normal points the other way.
* **In the plane** (:func:`handed_over`): per side of the crease (flat
  ``y`` > 0 and < 0, never across it), the fields at every level
  interpolated linearly over the forming's points (Delaunay, ``scipy``),
  the nearest point outside their hull; **through the thickness** linear
  between the two levels around the wedge point's height. A linear
  combination of stresses inside the von Mises surface lies inside it, so
  nothing is pushed past the yield stress but for the thin rim the outer
  Gauss points do not reach; :func:`within_yield` scales those back and
  counts them.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from ccx_deck import GAUSS, displacements, level_fields, mises, read_dat
from numpy.typing import NDArray

__all__ = [
    "Forming",
    "forming_file",
    "handed_over",
    "level_heights",
    "levels_up",
    "point_flat",
    "read_forming",
    "wedge_state",
    "within_yield",
]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True)
class Forming:
    """A finished CalculiX forming (SI units).

    Attributes:
        flat: ``(n, 2)`` the shell nodes on the flat sheet (m).
        tri6: ``(m, 6)`` the ``S6`` elements (0-based).
        formed: ``(n, 3)`` the shell nodes at the forming's end (m).
        layers: equal layers of the composite section.
        thickness: m.
        stress: ``(m, 2 layers, 3, 6)`` global stress (Pa): element, level
            bottom up along the element's normal, in-plane point.
        peeq: ``(m, 2 layers, 3)`` equivalent plastic strain.
        perfectly_plastic: one ``*PLASTIC`` row.
        yield_stress: Pa.
    """

    flat: Array
    tri6: IntArray
    formed: Array
    layers: int
    thickness: float
    stress: Array
    peeq: Array
    perfectly_plastic: bool
    yield_stress: float


def _block(lines: list[str], head: str) -> list[str]:
    """The data lines after the keyword line starting with ``head``."""
    start = next(i for i, ln in enumerate(lines) if ln.upper().startswith(head))
    out = []
    for ln in lines[start + 1 :]:
        if ln.startswith("*"):
            break
        out.append(ln)
    return out


def read_forming(inp: Path) -> Forming:
    """The forming of ``inp`` (``NAME_form.inp``) and its ``.dat``."""
    lines = inp.read_text().splitlines()
    tri6 = np.array([[int(v) for v in ln.split(",")[1:]] for ln in _block(lines, "*ELEMENT")]) - 1
    n = int(tri6.max()) + 1  # the shell nodes come first; the drivers follow
    nodes = np.array([[float(v) for v in ln.split(",")[1:]] for ln in _block(lines, "*NODE")])
    section = _block(lines, "*SHELL SECTION")
    plastic = _block(lines, "*PLASTIC")
    blocks = read_dat(inp.with_suffix(".dat"))
    end = max(k[1] for k in blocks if k[0] == "stresses")
    stress, peeq = level_fields(blocks, end, len(section), len(tri6))
    return Forming(
        flat=nodes[:n, :2],
        tri6=tri6,
        formed=nodes[:n] + displacements(blocks, end, n),
        layers=len(section),
        thickness=sum(float(ln.split(",")[0]) for ln in section),
        stress=stress,
        peeq=peeq,
        perfectly_plastic=len(plastic) == 1,
        yield_stress=float(plastic[0].split(",")[0]),
    )


def level_heights(thickness: float, layers: int) -> Array:
    """``(2 layers,)`` the Gauss levels' heights (m) from the mid-surface,
    bottom up: two points at ``+-1/sqrt(3)`` of each layer's half depth."""
    d = thickness / layers
    mid = -0.5 * thickness + (np.arange(layers) + 0.5) * d
    return (mid[:, None] + 0.5 * d * np.array([-GAUSS, GAUSS])[None, :]).ravel()


def point_flat(corners: Array, natural: Array) -> Array:
    """``(m, k, 2)`` the flat points at natural coordinates ``natural``
    ``(k, 2)`` (xi, eta) of triangles with ``corners`` ``(m, 3, 2)``."""
    xi, eta = natural[:, 0], natural[:, 1]
    shape = np.stack([1.0 - xi - eta, xi, eta], axis=1)  # (k, 3)
    return np.einsum("kc,mcd->mkd", shape, corners)


def levels_up(forming: Forming, up: Array) -> tuple[Array, Array]:
    """The forming's stress and plastic strain with each element's levels
    ordered along ``up`` ``(m, 3)``, the designed top normal at its centroid."""
    x = forming.formed[forming.tri6[:, :3]]
    normal = np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0])
    down = np.einsum("ij,ij->i", normal, up) < 0
    stress, peeq = forming.stress.copy(), forming.peeq.copy()
    stress[down] = stress[down, ::-1]
    peeq[down] = peeq[down, ::-1]
    return stress, peeq


def _in_plane(src: Array, values: Array, dst: Array) -> Array:
    """``values`` ``(P, c)`` at flat points ``src`` ``(P, 2)``, at ``dst``
    ``(Q, 2)``: linear over the Delaunay triangles, the nearest outside."""
    from scipy.interpolate import LinearNDInterpolator, NearestNDInterpolator

    out = LinearNDInterpolator(src, values)(dst)
    gone = np.isnan(out).any(axis=1)
    if gone.any():
        out[gone] = NearestNDInterpolator(src, values)(dst[gone])
    return out


def handed_over(forming: Forming, up: Array, dst: Array, heights: Array) -> tuple[Array, Array]:
    """The forming's global stress ``(Q, 6)`` (Pa) and equivalent plastic
    strain ``(Q,)`` at flat points ``dst`` ``(Q, 2)`` (m) and heights
    ``heights`` ``(Q,)`` (m, along the designed top normal); ``up``: the top
    normal at each forming element's centroid ``(m, 3)``."""
    natural = np.array([(1 / 6, 1 / 6), (2 / 3, 1 / 6), (1 / 6, 2 / 3)])
    src = point_flat(forming.flat[forming.tri6[:, :3]], natural).reshape(-1, 2)  # (m 3, 2)
    stress, peeq = levels_up(forming, up)
    lv = 2 * forming.layers
    fields = np.concatenate(
        [stress.transpose(0, 2, 1, 3).reshape(-1, lv * 6), peeq.transpose(0, 2, 1).reshape(-1, lv)],
        axis=1,
    )  # per source point: every level's stress, then every level's plastic strain
    side_src = np.repeat(forming.flat[forming.tri6[:, :3]].mean(axis=1)[:, 1] > 0, 3)
    at = np.empty((len(dst), fields.shape[1]))
    for side in (True, False):
        pick = (dst[:, 1] > 0) == side
        at[pick] = _in_plane(src[side_src == side], fields[side_src == side], dst[pick])
    z = level_heights(forming.thickness, forming.layers)
    k = np.clip(np.searchsorted(z, heights) - 1, 0, lv - 2)
    w = ((heights - z[k]) / (z[k + 1] - z[k]))[:, None]
    s = at[:, : lv * 6].reshape(-1, lv, 6)
    e = at[:, lv * 6 :]
    rows = np.arange(len(dst))
    out_s = (1 - w) * s[rows, k] + w * s[rows, k + 1]
    out_e = (1 - w[:, 0]) * e[rows, k] + w[:, 0] * e[rows, k + 1]
    return out_s, out_e


def within_yield(stress: Array, yield_stress: float) -> tuple[Array, int]:
    """``stress`` ``(Q, 6)`` with every point past ``yield_stress`` (von
    Mises) scaled back onto it, and how many were."""
    vm = mises(stress)
    over = vm > yield_stress
    out = stress.copy()
    out[over] *= (yield_stress / vm[over])[:, None]
    return out, int(over.sum())


def forming_file(keep: Path) -> Path:
    """The forming's ``.inp`` in a ``--keep`` folder of ``calculix_forming.py``."""
    found = sorted(keep.glob("*_form.inp"))
    if len(found) != 1:
        raise SystemExit(f"ccx_handover: {keep} holds {len(found)} *_form.inp, not one")
    return found[0]


def plane_stress(stress: Array, frames: Array) -> tuple[Array, Array]:
    """``(plane (m, k, 3), normal (m, k))``: the in-plane ``(s11, s22, s12)``
    on the faces' ``frames`` ``(m, 3, 3)`` of the global ``stress``
    ``(m, k, 6)`` less its normal stress ``s33`` as a pressure, and that
    ``s33``. CalculiX's expanded shells carry a through-thickness stress
    (on broken-vault's finest forming up to 9 sigma_y near H, where the
    sheet yields far): a hydrostatic part, which the von Mises law does not
    see, so taking it out of all three normal stresses leaves the deviator
    and the yield state as they were and gives the plane stress a shell
    has; the transverse shears are dropped."""
    from ccx_release import tensor, to_frame

    e3 = np.broadcast_to(frames[:, None, 2], stress.shape[:-1] + (3,))
    normal = np.einsum("mki,mkij,mkj->mk", e3, tensor(stress), e3)
    plane = to_frame(stress, frames)
    plane[..., :2] -= normal[..., None]
    return plane, normal


def wedge_state(
    keep: Path,
    folded: Any,
    model: Any,
    corners: Array,
    heights: Array,
    frames: Array,
    margin: float,
) -> tuple[Array, Array, dict[str, Any]]:
    """The plane stress ``(m, L * 9, 3)`` on the columns' ``frames`` and the
    plastic flags ``(m, L * 9)`` of the forming kept in ``keep`` at the
    integration points of wedge columns with flat ``corners`` ``(m, 3, 2)``
    (m) and ``heights`` ``(L, 9)`` (times ``1 - margin``), and what the
    handover did: the points scaled back to yield, the normal stress taken
    out (median and largest, over sigma_y)."""
    from ccx_release import GAUSS_WEDGE, node_moves, to_frame, to_global

    forming = read_forming(forming_file(keep))
    mat = model.material
    if not forming.perfectly_plastic:
        raise SystemExit("calculix_release: --formed-by needs a perfectly plastic forming")
    if not np.isclose(forming.thickness, mat.thickness, rtol=1e-6):
        raise SystemExit("calculix_release: the forming's thickness is not the template's")
    centroid = forming.flat[forming.tri6[:, :3]].mean(axis=1)
    up = node_moves(folded, centroid, model.scale, mat.thickness)[0]
    dst = point_flat(corners, GAUSS_WEDGE[:, :2])  # (m, 9, 2): the wedge's points
    m, layers = len(corners), heights.shape[0]
    dst = np.broadcast_to(dst[:, None], (m, layers, 9, 2)).reshape(-1, 2)
    h = np.broadcast_to(heights[None], (m, layers, 9)).ravel()
    stress, peeq = handed_over(forming, up, dst, h)
    plane, normal = plane_stress(stress.reshape(m, layers * 9, 6), frames)
    flat_stress, clipped = within_yield(to_global(plane, frames).reshape(-1, 6), mat.yield_stress)
    sy = mat.yield_stress
    info = {
        "formed_by": str(forming_file(keep)),
        "forming_elements": len(forming.tri6),
        "points_scaled_to_yield": clipped,
        "normal_stress_median_vs_sy": float(np.median(np.abs(normal)) / sy),
        "normal_stress_max_vs_sy": float(np.abs(normal).max() / sy),
    }
    plane = to_frame(flat_stress.reshape(m, layers * 9, 6), frames) * (1.0 - margin)
    return plane, (peeq > 0).reshape(m, layers * 9), info
