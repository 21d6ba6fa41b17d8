"""What a simulation found, as frozen values and as the report's ``simulation``
section (plain JSON data).

Lengths are in the design's unit (``unit``), forces in N (``_N``), energies in
J (``_J``), stresses in MPa (``_MPa``), angles in degrees (``_deg``); shares
and ratios are plain numbers. Arrays of the forms themselves (``positions``)
are in metres and stay out of the JSON.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from onefold_cad.geometry.numeric import Array, Index

if TYPE_CHECKING:
    from onefold_cad.mechanics.reserve import ReserveCheck

__all__ = ["Designed", "FormedResult", "Released", "Simulation", "Standing"]


def _f(x: float | None) -> float | None:
    return None if x is None else float(x)


def _xy(x: Array | None) -> list[float] | None:
    return None if x is None else np.asarray(x, dtype=float).tolist()


@dataclass(frozen=True)
class FormedResult:
    """The sheet bent into the design.

    Attributes:
        bending_energy_J: the work of bending the flat sheet into the form
            (J): elastic energy where it stays elastic, plus plastic work.
        plastic_area_share: the share (0..1) of the sheet's area bent past yield.
        plastic_radius_max: the largest distance from H of a yielded face's
            centroid (length; 0 when nothing yields).
        max_plastic_strain: the largest equivalent plastic strain at the
            sheet's surfaces (J2 law; None for the moment law).
        max_plastic_strain_at: ``(2,)`` where it is on the flat sheet
            (length, fold frame; H at the origin), or None.
        max_stress_MPa: the largest von Mises stress at the surfaces (J2 law).
    """

    bending_energy_J: float
    plastic_area_share: float
    plastic_radius_max: float
    max_plastic_strain: float | None = None
    max_plastic_strain_at: Array | None = None
    max_stress_MPa: float | None = None


@dataclass(frozen=True)
class Released:
    """The sheet after springback (no gravity, no supports).

    Attributes:
        max_deviation, rms_deviation: distance of the mid-surface's nodes
            from the designed form after the best rigid alignment (length;
            rms weighted by the nodes' areas).
        height, span: the released form stood rigidly on the ground
            (length; span as the designed form's: its extent along the
            resting frame's x).
        iterations: Newton steps.
        reloaded_area_share: the share of the sheet's area that bent past
            its elastic range in springback (the release unloads it
            elastically: the springback there is underestimated).
    """

    max_deviation: float
    rms_deviation: float
    height: float
    span: float
    iterations: int
    reloaded_area_share: float


@dataclass(frozen=True)
class Standing:
    """The sheet on the ground under its own weight.

    Attributes:
        stands: it found an equilibrium under its full weight with its
            centre of mass over the contacts' support polygon (no contact
            pulls: the ground only pushes).
        reason: why it does not stand ('' when it does).
        load_factor: the share of its weight it carried in the last
            equilibrium found (1 when it stands).
        max_deviation, rms_deviation: distance of the nodes from the
            designed form as it stands (length); None without an equilibrium.
        max_displacement: the largest movement of a node from where it was
            set down (length).
        height, span: of the standing form (length).
        reactions_total_N: the ground's total vertical force (N).
        contacts: ``(k, 3)`` the nodes on the ground (length, resting frame).
        tipping_margin_deg: of the centre of mass over the contacts.
        max_stress_MPa, utilisation: the largest stress at the sheet's faces
            and its ratio to the yield stress.
        max_stress_at: ``(2,)`` where it is on the flat sheet (length, fold
            frame; H at the origin), None without an equilibrium.
        iterations: Newton steps.
        reloaded_area_share: the share of the sheet's area its weight makes
            yield again (J2 law; the moment law: bends past the elastic range,
            which it takes elastically).
        positions: ``(n, 3)`` the standing nodes (m), None without one.
        max_plastic_strain: the largest equivalent plastic strain at the
            surfaces standing (J2 law), its place ``max_plastic_strain_at``
            (flat sheet, fold frame) and ``plastic_area_share``, the share of
            the area whose surfaces have yielded at some stage.
        reserve: on the coarse preview mesh, the multiple of its weight the
            sheet was found to carry (up to :data:`COARSE_RESERVE`), else None.
        uncertain: why a coarse 'stands' is no yes ('' when it is).
    """

    stands: bool
    reason: str
    load_factor: float
    max_deviation: float | None
    rms_deviation: float | None
    max_displacement: float | None
    height: float | None
    span: float | None
    reactions_total_N: float | None
    contacts: Array
    tipping_margin_deg: float | None
    max_stress_MPa: float | None
    utilisation: float | None
    max_stress_at: Array | None
    iterations: int
    reloaded_area_share: float
    positions: Array | None = field(default=None, repr=False)
    max_plastic_strain: float | None = None
    max_plastic_strain_at: Array | None = None
    plastic_area_share: float | None = None
    reserve: float | None = None
    uncertain: str = ""

    @property
    def verdict(self) -> str:
        """'stands', 'uncertain' (a coarse preview near its limit) or 'does not stand'."""
        if not self.stands:
            return "does not stand"
        return "uncertain" if self.uncertain else "stands"

    @classmethod
    def stalled(
        cls, reason: str, load_factor: float, iterations: int, moved: float | None = None
    ) -> Standing:
        """No equilibrium under the full weight: it does not stand, and only what
        is known of the last equilibrium (the share of the weight carried,
        how far it had moved) is kept."""
        return cls(
            stands=False,
            reason=reason,
            load_factor=load_factor,
            max_deviation=None,
            rms_deviation=None,
            max_displacement=moved,
            height=None,
            span=None,
            reactions_total_N=None,
            contacts=np.zeros((0, 3)),
            tipping_margin_deg=None,
            max_stress_MPa=None,
            utilisation=None,
            max_stress_at=None,
            iterations=iterations,
            reloaded_area_share=0.0,
        )

    def to_data(self) -> dict[str, Any]:
        """The JSON data (the positions left out)."""
        return {
            "stands": bool(self.stands),
            "verdict": self.verdict,
            "uncertain": self.uncertain,
            "reserve": _f(self.reserve),
            "reason": self.reason,
            "load_factor": float(self.load_factor),
            "max_deviation": _f(self.max_deviation),
            "rms_deviation": _f(self.rms_deviation),
            "max_displacement": _f(self.max_displacement),
            "height": _f(self.height),
            "span": _f(self.span),
            "reactions_total_N": _f(self.reactions_total_N),
            "contacts": np.asarray(self.contacts, dtype=float).tolist(),
            "tipping_margin_deg": _f(self.tipping_margin_deg),
            "max_stress_MPa": _f(self.max_stress_MPa),
            "utilisation": _f(self.utilisation),
            "max_stress_at": _xy(self.max_stress_at),
            "iterations": int(self.iterations),
            "reloaded_area_share": float(self.reloaded_area_share),
            "max_plastic_strain": _f(self.max_plastic_strain),
            "max_plastic_strain_at": _xy(self.max_plastic_strain_at),
            "plastic_area_share": _f(self.plastic_area_share),
        }


@dataclass(frozen=True)
class Designed:
    """The structural check of the designed form taken as stress-free.

    Attributes:
        max_displacement: the largest movement under its weight (length).
        max_stress_MPa: the largest stress at the sheet's faces.
    """

    max_displacement: float | None
    max_stress_MPa: float | None


@dataclass(frozen=True)
class Simulation:
    """One simulation of a design.

    Attributes:
        unit: the design's length unit.
        supports: 'anchored' or 'frictionless'; ``reference``: 'flat' or
            'designed'; ``crease``: 'held' or 'elastic'; ``crease_overbend_deg``:
            how far past its fold angle the crease is set (deg);
            ``cone_forming``: 'compensated' where the cones were formed past
            their springback (J2, from the flat sheet), else 'design'.
        weight_N: the sheet's weight.
        nodes, triangles, h_max: the mesh (h_max in the design's unit).
        yield_stress_MPa, youngs_modulus_GPa, poisson, thickness: the values used.
        law: 'j2' (J2 plasticity through the thickness) or 'moment' (the 1D
            moment-curvature law of a rectangular section, elastic membrane).
        hardening_modulus_MPa, kinematic_hardening: the law's linear
            hardening and its kinematic share (J2).
        density_kg_m3: the sheet's density (kg/m^3).
        formed, released: the forming sequence (reference 'flat'), else None.
        standing: on the ground.
        designed: the structural check (reference 'designed'), else None.
        convergence: the same quantities on the next finer mesh and the
            relative change of the standing (or released) form's largest
            deviation (``max_deviation_change``), or None when not run.
        reverse_yield_faces: faces that unloaded past reverse yield (not modelled).
        warnings: one line each.
        timings_s: seconds per stage (CPU).
        face_stress_MPa, deviation: per-face stress and per-node standing
            deviation (design unit) for the pictures; arrays, not in the JSON.
        faces: ``(m, 3)`` the mesh's triangles (node indices).
        flat: ``(n, 2)`` the nodes on the flat sheet, fold frame (design unit).
        designed_positions: ``(n, 3)`` the nodes on the designed form as it
            stands (design unit, resting frame).
        standing_positions, released_positions: ``(n, 3)`` the simulated nodes
            (design unit; standing in the resting frame, released as the
            standing start placed it), None when there is none.
        fields: per stage (J2 law) the faces' surface stresses, plastic
            strains and resultants (:class:`~onefold_cad.mechanics.j2.measures.Surfaces`),
            and ``stage_positions`` its nodes (m), for the VTU file.
        pending_reserve: a coarse standing's reserve check left for later
            (``run(..., reserve=False)``; ``verdicts.settle_reserve``), else None.
    """

    unit: str
    supports: str
    reference: str
    crease: str
    weight_N: float
    nodes: int
    triangles: int
    h_max: float
    youngs_modulus_GPa: float
    poisson: float
    yield_stress_MPa: float
    thickness: float
    density_kg_m3: float
    formed: FormedResult | None
    released: Released | None
    standing: Standing
    designed: Designed | None
    convergence: dict[str, Any] | None
    reverse_yield_faces: int
    warnings: tuple[str, ...]
    timings_s: dict[str, float]
    face_stress_MPa: Array | None = field(default=None, repr=False)
    deviation: Array | None = field(default=None, repr=False)
    faces: Index | None = field(default=None, repr=False)
    flat: Array | None = field(default=None, repr=False)
    designed_positions: Array | None = field(default=None, repr=False)
    standing_positions: Array | None = field(default=None, repr=False)
    released_positions: Array | None = field(default=None, repr=False)
    law: str = "moment"
    hardening_modulus_MPa: float = 0.0
    kinematic_hardening: float = 0.0
    crease_overbend_deg: float = 0.0
    cone_forming: str = "design"
    fields: dict[str, Any] | None = field(default=None, repr=False)
    stage_positions: dict[str, Array] | None = field(default=None, repr=False)
    pending_reserve: ReserveCheck | None = field(default=None, repr=False)

    def to_data(self) -> dict[str, Any]:
        """The report's ``simulation`` section."""
        out: dict[str, Any] = {
            "units": self.unit,
            "supports": self.supports,
            "reference": self.reference,
            "crease": self.crease,
            "crease_overbend_deg": self.crease_overbend_deg,
            "cone_forming": self.cone_forming,
            "law": self.law,
            "material": {
                "youngs_modulus_GPa": self.youngs_modulus_GPa,
                "poisson": self.poisson,
                "yield_stress_MPa": self.yield_stress_MPa,
                "hardening_modulus_MPa": self.hardening_modulus_MPa,
                "kinematic_hardening": self.kinematic_hardening,
                "thickness": self.thickness,
            },
            "weight_N": self.weight_N,
            "mesh": {"nodes": self.nodes, "triangles": self.triangles, "h_max": self.h_max},
            "convergence": self.convergence,
        }
        if self.formed is not None:
            out["formed"] = {
                "bending_energy_J": self.formed.bending_energy_J,
                "plastic_area_share": self.formed.plastic_area_share,
                "plastic_radius_max": self.formed.plastic_radius_max,
                "max_plastic_strain": _f(self.formed.max_plastic_strain),
                "max_plastic_strain_at": _xy(self.formed.max_plastic_strain_at),
                "max_stress_MPa": _f(self.formed.max_stress_MPa),
            }
        if self.released is not None:
            r = self.released
            out["released"] = {
                "max_deviation": r.max_deviation,
                "rms_deviation": r.rms_deviation,
                "height": r.height,
                "span": r.span,
                "iterations": r.iterations,
                "reloaded_area_share": r.reloaded_area_share,
            }
        out["standing"] = self.standing.to_data()
        if self.designed is not None:
            out["designed"] = {
                "max_displacement": _f(self.designed.max_displacement),
                "max_stress_MPa": _f(self.designed.max_stress_MPa),
            }
        out["reverse_yield_faces"] = self.reverse_yield_faces
        out["warnings"] = list(self.warnings)
        out["timings_s"] = dict(self.timings_s)
        return out
