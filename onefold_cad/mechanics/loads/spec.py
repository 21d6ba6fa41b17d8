"""The outdoor loads and the supports asked for, checked on construction.

Every bad value raises :class:`~onefold_cad.errors.InvalidParameterError`
naming the field (its ``onefold loads`` flag is the name with dashes) and
its allowed range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from onefold_cad.errors import InvalidParameterError
from onefold_cad.mechanics.loads.wind import CANOPY_CF, terrain

__all__ = ["FLAGS", "SUPPORT_MODES", "LoadSpec"]

#: How the feet meet the ground: bolted or screwed (``anchored``), standing
#: free on friction (``friction``), or held down by ballast (``ballast``).
SUPPORT_MODES = ("anchored", "friction", "ballast")


#: The ``onefold loads`` flag of each field.
FLAGS = {
    "wind_speed": "--wind-speed",
    "velocity_pressure_kPa": "--velocity-pressure",
    "height": "--height",
    "cf_down": "--cf-down",
    "cf_up": "--cf-up",
    "directions": "--directions",
    "snow_kPa": "--snow",
    "exposure": "--exposure",
    "thermal": "--thermal",
    "person_kN": "--person",
    "person_at": "--person-at",
    "person_grid": "--person-grid",
    "terrain": "--terrain",
    "supports": "--supports",
    "friction": "--friction",
}


def _range(name: str, value: float | None, lo: float, hi: float, unit: str) -> None:
    if value is None:
        return
    ok = isinstance(value, (int, float)) and not isinstance(value, bool)
    if not (ok and math.isfinite(value) and lo <= value <= hi):
        raise InvalidParameterError(
            name, f"must be {lo:g} to {hi:g}{unit} ({FLAGS[name]}), got {value!r}"
        )


@dataclass(frozen=True)
class LoadSpec:
    """The loads and supports of an outdoors check.

    Attributes:
        wind_speed: EN 1991-1-4's basic wind velocity ``v_b`` (m/s; the site's
            national annex), or None with ``velocity_pressure_kPa``.
        terrain: the terrain category ('0', 'I', 'II', 'III', 'IV').
        velocity_pressure_kPa: the peak velocity pressure ``q_p`` given
            directly (kPa), instead of from ``wind_speed``.
        height: the reference height ``z_e`` (m); None: the standing form's height.
        cf_down, cf_up: the net pressure coefficients, down (>= 0) and up
            (<= 0) (defaults: EN 1991-1-4 Table 7.6, :data:`~.wind.CANOPY_CF`).
        directions: how many wind directions, evenly over 360 deg.
        snow_kPa: the characteristic ground snow load ``s_k`` (kPa; 0: none).
        exposure, thermal: EN 1991-1-3's ``C_e`` and ``C_t``.
        person_kN: the point load (kN; 0: none).
        person_at: ``(x, y)`` where it stands on the flat sheet (design
            unit, fold frame), or None: the worst point of a grid.
        person_grid: the grid's points per side.
        supports: one of :data:`SUPPORT_MODES`.
        friction: the feet's friction coefficient on the ground ``mu``.
    """

    wind_speed: float | None = None
    terrain: str = "II"
    velocity_pressure_kPa: float | None = None
    height: float | None = None
    cf_down: float = CANOPY_CF["down"]
    cf_up: float = CANOPY_CF["up"]
    directions: int = 8
    snow_kPa: float = 0.0
    exposure: float = 1.0
    thermal: float = 1.0
    person_kN: float = 1.0
    person_at: tuple[float, float] | None = None
    person_grid: int = 6
    supports: str = "anchored"
    friction: float = 0.3

    def __post_init__(self) -> None:
        if self.wind_speed is None and self.velocity_pressure_kPa is None:
            raise InvalidParameterError(
                "wind_speed",
                "give the site's basic wind velocity v_b, 0 to 100 m/s (--wind-speed; EN "
                "1991-1-4 and its national annex), or its peak velocity pressure "
                "(--velocity-pressure KPA)",
            )
        if self.wind_speed is not None and self.velocity_pressure_kPa is not None:
            raise InvalidParameterError(
                "velocity_pressure_kPa",
                "give the basic wind velocity (--wind-speed) or the peak velocity pressure "
                "(--velocity-pressure), not both",
            )
        _range("wind_speed", self.wind_speed, 0.0, 100.0, " m/s")
        _range("velocity_pressure_kPa", self.velocity_pressure_kPa, 0.0, 20.0, " kPa")
        _range("height", self.height, 0.1, 200.0, " m")
        _range("cf_down", self.cf_down, 0.0, 5.0, "")
        _range("cf_up", self.cf_up, -5.0, 0.0, "")
        _range("directions", self.directions, 1, 72, "")
        if int(self.directions) != self.directions:
            raise InvalidParameterError(
                "directions", f"must be a whole number 1 to 72, got {self.directions!r}"
            )
        _range("snow_kPa", self.snow_kPa, 0.0, 20.0, " kPa")
        _range("exposure", self.exposure, 0.5, 2.0, "")
        _range("thermal", self.thermal, 0.1, 1.0, "")
        _range("person_kN", self.person_kN, 0.0, 100.0, " kN")
        _range("person_grid", self.person_grid, 1, 40, "")
        _range("friction", self.friction, 0.01, 2.0, "")
        terrain(self.terrain)  # raises for an unknown category
        if self.supports not in SUPPORT_MODES:
            raise InvalidParameterError(
                "supports", f"must be one of {', '.join(SUPPORT_MODES)}, got {self.supports!r}"
            )
        if self.person_at is not None:
            for v in self.person_at:
                if not math.isfinite(v):
                    raise InvalidParameterError(
                        "person_at", f"must be finite, got {self.person_at!r}"
                    )

    @property
    def direction_list(self) -> list[float]:
        """The wind directions (deg, towards which it blows, from +x of the
        resting frame counter-clockwise)."""
        return [360.0 * k / self.directions for k in range(int(self.directions))]
