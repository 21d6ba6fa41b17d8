"""How far CalculiX's own formed state, handed to the release's wedges, is from
onefold's: the resultants of the two states on the same release mesh.

``calculix_release.py --formed-by DIR`` releases the state a CalculiX
forming leaves (``ccx_handover.py``); without it, onefold's J2 forming of
the same perfectly plastic sheet. This compares the two where they are
given to ccx (``calculix_release.setup``: plane stresses on the faces'
frames at every wedge integration point), face by face:

* the membrane force ``N`` and the moment ``M`` per unit length (N/m, N),
  the least-squares line of each stress component through the points'
  heights (:func:`resultants`: exact for a stress linear through the
  thickness);
* the moment's ratio to onefold's, projected on it (:func:`projected_ratio`:
  1 where the two are equal, 0.9 where CalculiX's is onefold's times 0.9);
* in bands of the distance from H on the flat sheet, the medians of the
  larger principal moment over ``M_y = sigma_y t^2 / 4``, of the ratio, of
  the membrane force over ``sigma_y t``, and the share of faces a point of
  which yielded in the forming; and the stress along onefold's bending
  direction at the points' heights (``--profile``).

One line per forming sums it: the ratio averaged with the weight of
onefold's moment times the face's area, and the area's mean membrane force.
Reads the kept files only (no ccx run); prints only.

Run from the repository root::

    .venv/bin/python benchmarks/ccx_handed_moments.py TEMPLATE FORMING_KEEP_DIR...
        [--mesh normal] [--layers 2] [--profile]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

sys.path.insert(0, str(Path(__file__).resolve().parent))

from calculix_release import MARGIN, setup  # noqa: E402
from ccx_release import point_heights  # noqa: E402

Array = NDArray[np.float64]

__all__ = ["larger_principal", "projected_ratio", "resultants"]

#: Bands of the distance from H (m on the flat sheet), as fractions of the
#: largest: ten of equal face counts.
BANDS = 10


def resultants(plane: Array, heights: Array, thickness: float) -> tuple[Array, Array]:
    """``(N, M)``, each ``(m, 3)`` ``(xx, yy, xy)``: the membrane force (N/m)
    and the moment (N m/m) of the plane stresses ``plane`` ``(m, k, 3)`` (Pa)
    at the points' ``heights`` ``(k,)`` (m, from the mid-surface), from the
    least-squares line ``s(z) = N / t + 12 M z / t^3`` of each component."""
    a = np.stack([np.ones_like(heights), heights], axis=1)
    c = np.einsum("jk,mkc->mjc", np.linalg.pinv(a), plane)
    return c[:, 0] * thickness, c[:, 1] * thickness**3 / 12


def _inner(a: Array, b: Array) -> Array:
    """The tensors' inner product of ``(xx, yy, xy)`` rows."""
    return a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1] + 2 * a[:, 2] * b[:, 2]


def projected_ratio(other: Array, ref: Array) -> Array:
    """``(m,)`` ``<other, ref> / <ref, ref>`` per row of ``(xx, yy, xy)``
    tensors: how much of ``ref`` ``other`` carries."""
    return _inner(other, ref) / _inner(ref, ref)


def _principal(t: Array) -> tuple[Array, Array]:
    """Principal values ``(m, 2)`` (ascending) and directions ``(m, 2, 2)``
    (columns) of ``(xx, yy, xy)`` rows."""
    tens = np.stack([np.stack([t[:, 0], t[:, 2]], 1), np.stack([t[:, 2], t[:, 1]], 1)], 1)
    values, vectors = np.linalg.eigh(tens)
    return values, vectors


def larger_principal(t: Array) -> Array:
    """``(m,)`` the larger principal value's magnitude of ``(xx, yy, xy)`` rows."""
    return np.abs(_principal(t)[0]).max(axis=1)


def _along(plane: Array, ref: Array) -> tuple[Array, Array]:
    """``(m, k)`` twice: the stress along each face's principal direction of
    ``ref`` whose value is the larger in magnitude, and across it."""
    values, vectors = _principal(ref)
    d = vectors[np.arange(len(ref)), :, np.argmax(np.abs(values), axis=1)]  # (m, 2)
    c, s = d[:, None, 0], d[:, None, 1]
    along = plane[..., 0] * c**2 + plane[..., 1] * s**2 + 2 * plane[..., 2] * c * s
    across = plane[..., 0] * s**2 + plane[..., 1] * c**2 - 2 * plane[..., 2] * c * s
    return along, across


def _profiles(ours: tuple[Array, Array], theirs: tuple[Array, Array], heights: Array,
              r: Array, edges: Array, t: float, sy: float) -> None:  # fmt: skip
    """Print the mean stress along and across onefold's bending direction at
    each height (over sigma_y, the bending's tension side positive), onefold's
    and CalculiX's (:func:`_along` of each), in bands of two of ``edges``."""
    levels = np.unique(np.round(heights / t, 9))
    at = [np.flatnonzero(np.isclose(heights / t, z)) for z in levels]
    pairs = [ours, theirs]
    for lo, hi in zip(edges[:-1:2], edges[2::2], strict=True):
        k = (r >= lo) & (r <= hi)
        sign = np.sign(np.einsum("mk,k->m", pairs[0][0][k], heights))[:, None]
        print(f"  r {lo:.3g} to {hi:.3g} m, z / t: " + " ".join(f"{z:+.3f}" for z in levels))
        for who, (along, across) in zip(("onefold", "CalculiX"), pairs, strict=True):
            for name, v in (("along", along), ("across", across)):
                mean = np.mean(v[k] * sign, axis=0) / sy
                print(f"    {who:8s} {name:6s} " + " ".join(f"{mean[i].mean():+.3f}" for i in at))


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("template")
    ap.add_argument("formings", nargs="+", type=Path, help="calculix_forming.py --keep folders")
    ap.add_argument("--mesh", default="normal")
    ap.add_argument("--layers", type=int, default=2)
    ap.add_argument("--profile", action="store_true")
    args = ap.parse_args(argv)
    ours = setup(args.template, args.mesh, args.layers, 1, MARGIN, None)
    model = ours["model"]
    mat, mesh = model.material, model.mesh
    t, sy = mat.thickness, mat.yield_stress
    heights = point_heights(t, args.layers).ravel()
    n_ref, m_ref = resultants(ours["plane"], heights, t)
    p = mesh.nodes[mesh.triangles]
    e1, e2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    r = np.linalg.norm(p.mean(axis=1), axis=1)  # the flat sheet's origin is H
    edges = np.quantile(r, np.linspace(0, 1, BANDS + 1))
    my = sy * t**2 / 4
    big = larger_principal(m_ref)
    ours_along = _along(ours["plane"], m_ref) if args.profile else None
    for keep in args.formings:
        theirs = setup(args.template, args.mesh, args.layers, 1, MARGIN, keep)
        n, m = resultants(theirs["plane"], heights, t)
        ratio = projected_ratio(m, m_ref)
        print(f"\n{args.template}: {keep}")
        print("| r from H (m) | M / M_y onefold | M / M_y CalculiX | ratio | N / (sigma_y t) "
              "CalculiX | yielded in forming: CalculiX, onefold |")  # fmt: skip
        print("|---|---|---|---|---|---|")
        for lo, hi in zip(edges[:-1], edges[1:], strict=True):
            k = (r >= lo) & (r <= hi)
            print(f"| {lo:.3g} to {hi:.3g} | {np.median(big[k]) / my:.3f} | "
                  f"{np.median(larger_principal(m[k])) / my:.3f} | {np.median(ratio[k]):.3f} | "
                  f"{np.median(larger_principal(n[k])) / (sy * t):.4f} | "
                  f"{theirs['plastic'][k].any(axis=1).mean():.3f}, "
                  f"{ours['plastic'][k].any(axis=1).mean():.3f} |")  # fmt: skip
        w = area * big
        print(f"SUMMARY {keep}: moment ratio {np.sum(w * ratio) / np.sum(w):.4f} "
              f"(weighted by onefold's moment and the area), membrane force "
              f"{np.sum(area * larger_principal(n)) / area.sum() / (sy * t):.4f} sigma_y t "
              f"(area mean; onefold's largest {np.max(larger_principal(n_ref)) / (sy * t):.1g})"
              )  # fmt: skip
        if ours_along is not None:
            _profiles(ours_along, _along(theirs["plane"], m_ref), heights, r, edges, t, sy)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
