"""What an outdoors check found, as frozen values and as the report's
``outdoors`` section (plain JSON data).

Forces in N (``_N``), masses in kg (``_kg``), pressures in kPa (``_kPa``),
stresses in MPa; lengths in the design's unit (``unit``) but where a key
says ``_m``. Arrays of the forms (m) stay out of the JSON.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from onefold_cad.geometry.numeric import Array, Index

__all__ = ["CaseResult", "Foot", "Outdoors", "StrengthCheck"]


def _f(x: float | None) -> float | None:
    return None if x is None else float(x)


@dataclass(frozen=True)
class StrengthCheck:
    """One STR case's J2 load path.

    Attributes:
        case: its name.
        ratio: ``r_R``, the largest ratio of the case's design actions the
            sheet carries (``R_MAX`` or more when ``capped``).
        capped: the path reached ``R_MAX`` without a limit.
        limit: what ended the path (``plastic_limit.LoadRatio.limit``).
        stands: ``r_R >= gamma_M1``.
        plastic_at: the ratio the plastic strain is reported at (1, or the
            last step below ``r_R`` when that is below 1).
        max_plastic_strain: the largest equivalent plastic strain there (the
            sheet's surfaces; the increment from the stress-free form).
        max_plastic_strain_at: ``(2,)`` where (the flat sheet, design unit), or
            None when nothing yields.
        plastic_area_share: the share of the sheet's area yielded there.
        cpu_s: the path's CPU time (s).
    """

    case: str
    ratio: float
    capped: bool
    limit: str
    stands: bool
    plastic_at: float
    max_plastic_strain: float
    max_plastic_strain_at: Array | None
    plastic_area_share: float
    cpu_s: float

    def to_data(self) -> dict[str, Any]:
        """The JSON data."""
        at = self.max_plastic_strain_at
        return {
            "case": self.case,
            "load_ratio": float(self.ratio),
            "load_ratio_capped": bool(self.capped),
            "limit": self.limit,
            "stands": bool(self.stands),
            "plastic_at_ratio": float(self.plastic_at),
            "max_plastic_strain": float(self.max_plastic_strain),
            "max_plastic_strain_at": None if at is None else np.asarray(at).tolist(),
            "plastic_area_share": float(self.plastic_area_share),
            "cpu_s": float(self.cpu_s),
        }


@dataclass(frozen=True)
class CaseResult:
    """One load case.

    Attributes:
        name, kind: the case (``EQU``, ``STR``, ``SLS``; see ``combinations``).
        stands: it passes its checks (EQU: the rigid body on its supports;
            STR: its J2 load path carries ``gamma_M1`` times its design
            actions, ``strength``, or its elastic stresses stay below the
            yield stress; SLS: always, reported).
        reason: why not ('' when it stands).
        reactions_N: ``(k, 3)`` each foot's reaction on the sheet (N, up > 0).
        uplift_N, slide_ratio, tip_margin: the rigid-body checks (the net
            vertical reaction, ``|H| / (mu V)``, the centre of pressure's
            distance inside the feet's polygon in the design's unit).
        max_deflection: the variable loads' largest movement of a node from
            the standing form (design unit).
        utilisation: the peak linear elastic von Mises stress over
            ``f_y / gamma_M0`` (information: singular at the relief hole's rim
            and near H; not the STR verdict), ``utilisation_at`` ``(2,)`` its
            face on the flat sheet (design unit).
        ballast_kg: ``(k,)`` the ballast each foot needs (EQU; zeros else).
        strength: STR: the J2 load path's answer, or None (not run: the
            elastic stresses stay below the yield stress, or the case was not
            among those checked).
    """

    name: str
    kind: str
    stands: bool
    reason: str
    reactions_N: Array
    vertical_N: float
    horizontal_N: float
    slide_ratio: float
    tip_margin: float | None
    max_deflection: float
    utilisation: float
    ballast_kg: Array
    utilisation_at: Array | None = None
    strength: StrengthCheck | None = None

    def to_data(self) -> dict[str, Any]:
        """The JSON data."""
        ratio = self.slide_ratio
        return {
            "name": self.name,
            "kind": self.kind,
            "stands": bool(self.stands),
            "reason": self.reason,
            "reactions_N": np.asarray(self.reactions_N, dtype=float).tolist(),
            "vertical_N": float(self.vertical_N),
            "horizontal_N": float(self.horizontal_N),
            "slide_ratio": None if not np.isfinite(ratio) else float(ratio),
            "tip_margin": _f(self.tip_margin),
            "max_deflection": float(self.max_deflection),
            "utilisation": float(self.utilisation),
            "utilisation_at": None
            if self.utilisation_at is None
            else np.asarray(self.utilisation_at, dtype=float).tolist(),
            "ballast_kg": np.asarray(self.ballast_kg, dtype=float).tolist(),
            "strength": None if self.strength is None else self.strength.to_data(),
        }


@dataclass(frozen=True)
class Foot:
    """What one foot must take over every ultimate (EQU and STR) case.

    Attributes:
        at: ``(2,)`` where it stands (design unit, resting frame).
        nodes: how many mesh nodes it has on the ground.
        tension_N: the largest upward pull its anchor takes (N; 0: none).
        shear_N: the largest horizontal force (N).
        compression_N: the largest downward push (N).
        ballast_kg: the ballast it needs (kg; supports 'ballast', else the
            ballast that would replace an anchor).
    """

    at: Array
    nodes: int
    tension_N: float
    shear_N: float
    compression_N: float
    ballast_kg: float

    def to_data(self) -> dict[str, Any]:
        """The JSON data."""
        return {
            "at": np.asarray(self.at, dtype=float).tolist(),
            "nodes": int(self.nodes),
            "tension_N": float(self.tension_N),
            "shear_N": float(self.shear_N),
            "compression_N": float(self.compression_N),
            "ballast_kg": float(self.ballast_kg),
        }


@dataclass(frozen=True)
class Outdoors:
    """An outdoors check of a design.

    Attributes:
        unit: the design's length unit.
        inputs: the loads and supports asked for (``LoadSpec`` as data).
        assumptions: one sentence each, with its source.
        weight_N: the sheet's weight.
        reference_height_m, peak_velocity_pressure_kPa: the wind's ``z_e``, ``q_p``.
        mesh: nodes and triangles.
        feet: per foot, the demands.
        cases: every case.
        governing: the name of the case that governs the supports
            (anchored: the largest pull; friction: the worst sliding or a
            failing case; ballast: the most ballast), and ``governing_strength``
            the STR case of the largest utilisation.
        stands: every case stands.
        person_at: ``(2,)`` where the person stands (flat sheet, design unit), or None.
        nonlinear: the governing cases solved again with the full model
            (``nonlinear.NonlinearCheck``).
        strength: the STR cases' J2 load paths: ``cases_checked``,
            ``cases_not_checked`` (past first yield), ``screened_by``, ``cpu_s``.
        warnings: one line each.
        faces, positions, moves, face_utilisation: for the picture: ``(m, 3)``,
            ``(n, 3)`` the standing form (m), the governing case's movement
            ``(n, 3)`` (m), ``(m,)`` its faces' utilisation.
    """

    unit: str
    inputs: dict[str, Any]
    assumptions: tuple[str, ...]
    weight_N: float
    reference_height_m: float
    peak_velocity_pressure_kPa: float
    mesh: dict[str, int]
    feet: tuple[Foot, ...]
    cases: tuple[CaseResult, ...]
    governing: str
    governing_strength: str
    stands: bool
    person_at: Array | None
    nonlinear: tuple[Any, ...]
    warnings: tuple[str, ...]
    strength: dict[str, Any] = field(default_factory=dict)
    faces: Index | None = field(default=None, repr=False)
    positions: Array | None = field(default=None, repr=False)
    moves: Array | None = field(default=None, repr=False)
    face_utilisation: Array | None = field(default=None, repr=False)

    def case(self, name: str) -> CaseResult:
        """The case named ``name``."""
        return next(c for c in self.cases if c.name == name)

    def to_data(self) -> dict[str, Any]:
        """The report's ``outdoors`` section."""
        tension = sum(f.tension_N for f in self.feet)
        return {
            "units": self.unit,
            "inputs": dict(self.inputs),
            "assumptions": list(self.assumptions),
            "weight_N": float(self.weight_N),
            "reference_height_m": float(self.reference_height_m),
            "peak_velocity_pressure_kPa": float(self.peak_velocity_pressure_kPa),
            "mesh": dict(self.mesh),
            "stands": bool(self.stands),
            "governing": self.governing,
            "governing_strength": self.governing_strength,
            "person_at": None if self.person_at is None else np.asarray(self.person_at).tolist(),
            "feet": [f.to_data() for f in self.feet],
            "totals": {
                "feet": len(self.feet),
                "anchored_feet": sum(1 for f in self.feet if f.tension_N > 0.0),
                "tension_N": float(tension),
                "shear_N": float(sum(f.shear_N for f in self.feet)),
                "ballast_kg": float(sum(f.ballast_kg for f in self.feet)),
            },
            "nonlinear": [c.to_data() for c in self.nonlinear],
            "strength": dict(self.strength),
            "cases": [c.to_data() for c in self.cases],
            "warnings": list(self.warnings),
        }
