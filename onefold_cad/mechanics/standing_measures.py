"""The measures of a simulated form, whatever its law: the deviation from the
design after the best rigid alignment, and of a sheet standing on the ground
its deviation from the designed form as it stands, the contacts, the tipping
margin, height, span and movement (:class:`~onefold_cad.mechanics.results.Standing`).
"""

from __future__ import annotations

import numpy as np

from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.hull import convex_hull_2d
from onefold_cad.geometry.numeric import Array
from onefold_cad.geometry.placement import tipping_margin
from onefold_cad.mechanics.deviation import best_fit, surface_distance
from onefold_cad.mechanics.equilibrium import Equilibrium, PathStalled
from onefold_cad.mechanics.model import SheetModel
from onefold_cad.mechanics.results import Standing
from onefold_cad.mechanics.shell import unpack
from onefold_cad.mechanics.stages import Placed

__all__ = ["aligned_deviation", "area_share", "stalled", "standing_deviation", "standing_result"]


def aligned_deviation(model: SheetModel, folded: FoldedSheet, x: Array) -> tuple[float, float]:
    """Max and rms distance (design unit) of nodes ``x`` (m) from the designed
    form after the best rigid alignment."""
    mass = model.shell.node_mass
    fit = best_fit(x, model.designed, mass)
    d = surface_distance(folded, fit.apply(x) / model.scale, model.hole_radius / model.scale)
    return float(d.max()), float(np.sqrt(np.average(d**2, weights=mass)))


def area_share(model: SheetModel, faces: np.ndarray) -> float:
    """The share of the sheet's area on ``faces`` (m,) bool."""
    area = model.shell.ref_area
    return float(area[faces].sum() / area.sum())


def standing_deviation(model: SheetModel, folded: FoldedSheet, x: Array) -> Array:
    """``(n,)`` distance (design unit) of standing nodes ``x`` (m, resting frame)
    from the designed form as it stands."""
    rot, shift = model.standing_frame()
    back = (x - shift) @ rot  # to the fold frame
    return surface_distance(folded, back / model.scale, model.hole_radius / model.scale)


def stalled(model: SheetModel, placed: Placed, err: PathStalled, supports: str, unit: str
            ) -> Standing:  # fmt: skip
    """The answer when the weight's path stalls: it does not stand, and how
    much of the weight it carried and how far it had moved."""
    reason = (
        f"no equilibrium under its full weight on {supports} supports: the load path ends at "
        f"{err.reached:.3g} of the weight (Newton's residual there {err.residual:.3g} N)"
    )
    spread = None
    if err.last is not None:
        x0 = unpack(model.mesh, placed.q)[0]
        spread = float(np.max(np.linalg.norm(err.last.positions - x0, axis=1)) / model.scale)
        reason += f"; at that load it had moved by up to {spread:.4g} {unit}"
    return Standing.stalled(reason, err.reached, err.iterations, spread)


def standing_result(
    model: SheetModel,
    folded: FoldedSheet,
    placed: Placed,
    eq: Equilibrium,
    stress_MPa: Array,
    flow_MPa: float,
    **extra: object,
) -> tuple[Standing, Array]:
    """The standing measures of equilibrium ``eq`` from ``placed``, with the
    faces' stress ``stress_MPa`` (m,) (its largest, where, and its ratio to
    ``flow_MPa``); ``extra`` fields of :class:`Standing` as given. Returns
    the standing and the nodes' deviation (design unit)."""
    s = model.scale
    x = eq.positions
    dev = standing_deviation(model, folded, x)
    mass = model.shell.node_mass
    contacts = x[eq.contacts] / s
    com = mass @ x / mass.sum() / s
    margin = None
    if len(contacts) >= 1:
        hull = contacts[convex_hull_2d(contacts[:, :2], 1e-9 * float(np.ptp(x)) / s), :2]
        margin = float(tipping_margin(hull, com, 1e-9 * float(np.ptp(x)) / s)[0])
    stands = margin is not None and margin > 0.0
    reason = "" if stands else "its centre of mass is not over its contacts' support polygon"
    x0 = unpack(model.mesh, placed.q)[0]
    worst = int(np.argmax(stress_MPa))
    standing = Standing(
        stands=stands,
        reason=reason,
        load_factor=1.0,
        max_deviation=float(dev.max()),
        rms_deviation=float(np.sqrt(np.average(dev**2, weights=mass))),
        max_displacement=float(np.max(np.linalg.norm(x - x0, axis=1)) / s),
        height=float(x[:, 2].max() / s),
        span=float(np.ptp(x[:, 0]) / s),
        reactions_total_N=float(eq.reactions[:, 2].sum()),
        contacts=contacts,
        tipping_margin_deg=margin,
        max_stress_MPa=float(stress_MPa[worst]),
        utilisation=float(stress_MPa[worst] / flow_MPa),
        max_stress_at=model.mesh.nodes[model.mesh.triangles[worst]].mean(axis=0) / s,
        iterations=eq.iterations,
        positions=x,
        **extra,  # type: ignore[arg-type]
    )
    return standing, dev
