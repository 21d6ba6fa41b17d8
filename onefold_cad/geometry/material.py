"""Sheet material and fabrication inputs, and where the sheet's faces lie.

Lengths are in the design's unit; angles in degrees at the API edge. The
names follow build123d's sheet-metal vocabulary: ``thickness``,
``bend_radius``, ``k_factor`` and the reference surface ``sheet_surface``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

from onefold_cad.choices import ConeForming, SheetSurface
from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.checks import closed_interval, finite, shown

__all__ = [
    "DENSITY_RANGE",
    "MAX_MODULUS_GPA",
    "MIN_MODULUS_GPA",
    "MIN_YIELD_MPA",
    "OVERBEND_MAX",
    "Material",
    "default_relief_hole",
    "sheet_offsets",
]

#: The largest Young's modulus a material may have (GPa): ten times diamond's
#: (about 1 050-1 220 GPa), so no real sheet is refused.
MAX_MODULUS_GPA = 10_000.0
#: The smallest Young's modulus (GPa) and yield stress (MPa), both 1 kPa: a
#: thousandth of a soft rubber's modulus and of lead's yield stress, so no
#: real sheet is refused and the plastic moment (sigma_y t^2 / 4, in SI)
#: stays far from underflow (1e-320 MPa gave simulate a division by zero).
MIN_MODULUS_GPA, MIN_YIELD_MPA = 1e-6, 1e-3
#: The densities a material may have (kg/m^3): wide enough that one given in
#: another unit (7.85e-9 t/mm^3, 7.85e6 g/m^3) is only warned about
#: (:data:`onefold_cad.fabrication.rules.PLAUSIBLE_DENSITY`), narrow enough that
#: a sheet's mass and weight neither underflow nor overflow.
DENSITY_RANGE = (1e-15, 1e15)
#: The largest crease overbend either way (deg): a crease set half a right
#: angle past the cones it joins is a different fold, not an overbend.
OVERBEND_MAX = 45.0


@dataclass(frozen=True)
class Material:
    """Fabrication inputs (lengths in the design unit).

    Attributes:
        thickness: sheet thickness t >= 0; 0 means a zero-thickness surface.
        bend_radius: inside bend radius r >= 0.
        k_factor: neutral-axis position K in [0, 1].
        kerf: cutting kerf >= 0; cut contours are offset by kerf/2.
        relief_hole: diameter of the relief hole at the apex >= 0 (0 = none);
            None chooses the default: none for t = 0, 2 * t + 2 * r otherwise
            (at least 3 * t).
        density: kg/m^3 within :data:`DENSITY_RANGE` (e.g. 7850 for steel), or
            None; independent of the design's length unit (see
            :func:`onefold_cad.fabrication.mass.design_mass`).
        name: a material description for the notes (e.g. '304 stainless').
        sheet_surface: the reference surface (INSIDE, OUTSIDE, MID).
        youngs_modulus: Young's modulus E in GPa (1e-6 <= E <= 10 000), or None;
            independent of the design's length unit, like the density.
        poisson: Poisson's ratio nu, -1 < nu < 0.5, or None.
        yield_stress: the yield stress sigma_y in MPa, 1e-3 <= sigma_y <= E (a
            yield stress as high as the modulus itself never yields: a check
            of the elastic model), or None.
        hardening_modulus: the linear hardening modulus H in MPa, 0 <= H < E
            (the flow stress grows by H times the equivalent plastic strain:
            sigma = sigma_y + H eps_p in uniaxial tension; 0: perfectly
            plastic), or None (perfectly plastic).
        kinematic_hardening: the share of H that is kinematic (moves the yield
            surface: the Bauschinger effect), in [0, 1], or None (0: isotropic).
        crease_overbend: how much further than the design's fold angle each
            crease half is set (deg, in [-OVERBEND_MAX, OVERBEND_MAX]; > 0
            folds it more), or None (0: set to the fold angle). The cones are
            formed as designed; the crease alone is set past them (a press
            brake on the crease line), so the steel stands between the two:
            ``onefold compensate``'s fourth knob.
        cone_forming: the curvature the cones are formed to
            (:class:`~onefold_cad.choices.ConeForming`: the design's, or past
            its springback at every point), or None (the design's).

    The elastic-plastic values are what ``onefold simulate`` needs
    (:mod:`onefold_cad.mechanics`); nothing else reads them.
    """

    thickness: float = 0.0
    bend_radius: float = 0.0
    k_factor: float = 0.44
    kerf: float = 0.0
    relief_hole: float | None = None
    density: float | None = None
    name: str = ""
    sheet_surface: SheetSurface = SheetSurface.MID
    youngs_modulus: float | None = None
    poisson: float | None = None
    yield_stress: float | None = None
    hardening_modulus: float | None = None
    kinematic_hardening: float | None = None
    crease_overbend: float | None = None
    cone_forming: ConeForming | None = None

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        for key in ("thickness", "bend_radius", "kerf"):
            v = finite(key, getattr(self, key))
            if v < 0.0:
                raise InvalidParameterError(key, f"must be >= 0, got {shown(v)}")
            set_(self, key, v)
        set_(self, "k_factor", closed_interval("k_factor", self.k_factor, 0.0, 1.0))
        if self.relief_hole is not None:
            v = finite("relief_hole", self.relief_hole)
            if v < 0.0:
                raise InvalidParameterError(
                    "relief_hole", f"must be >= 0 (0 = no hole), got {shown(v)}"
                )
            set_(self, "relief_hole", v)
        if self.density is not None:
            v = finite("density", self.density)
            lo, hi = DENSITY_RANGE
            if not lo <= v <= hi:
                raise InvalidParameterError(
                    "density", f"must be in [{lo:g}, {hi:g}] kg/m^3, got {shown(v)}"
                )
            set_(self, "density", v)
        set_(self, "sheet_surface", SheetSurface.parse(self.sheet_surface))
        set_(self, "name", str(self.name))
        if self.crease_overbend is not None:
            set_(self, "crease_overbend", closed_interval(
                "crease_overbend", self.crease_overbend, -OVERBEND_MAX, OVERBEND_MAX, " deg"
            ))  # fmt: skip
        if self.cone_forming is not None:
            set_(self, "cone_forming", ConeForming.parse(self.cone_forming))
        self._check_elastic_plastic()

    @property
    def cones_compensated(self) -> bool:
        """Whether the cones are formed past their springback."""
        return self.cone_forming is ConeForming.COMPENSATED

    @property
    def cones_formed(self) -> str:
        """:attr:`cone_forming`'s name ('design' when none is given)."""
        return (self.cone_forming or ConeForming.DESIGN).value

    @property
    def overbend_deg(self) -> float:
        """:attr:`crease_overbend` as a number (deg; 0 when none is given)."""
        return 0.0 if self.crease_overbend is None else float(self.crease_overbend)

    def crease_set_angle(self, fold_angle_deg: float) -> float:
        """The angle (deg) a crease half of fold angle ``fold_angle_deg`` is set
        to: the fold angle plus :attr:`overbend_deg`."""
        return fold_angle_deg + self.overbend_deg

    def _check_elastic_plastic(self) -> None:
        """Validate Young's modulus, Poisson's ratio and the yield stress (each
        may be None)."""
        set_ = object.__setattr__
        if self.youngs_modulus is not None:
            e = finite("youngs_modulus", self.youngs_modulus)
            if not MIN_MODULUS_GPA <= e <= MAX_MODULUS_GPA:
                raise InvalidParameterError(
                    "youngs_modulus",
                    f"must be in [{MIN_MODULUS_GPA:g}, {MAX_MODULUS_GPA:g}] GPa, got {shown(e)}",
                )
            set_(self, "youngs_modulus", e)
        if self.poisson is not None:
            nu = finite("poisson", self.poisson)
            if not -1.0 < nu < 0.5:
                raise InvalidParameterError("poisson", f"must be > -1 and < 0.5, got {shown(nu)}")
            set_(self, "poisson", nu)
        if self.yield_stress is not None:
            sy = finite("yield_stress", self.yield_stress)
            top = (MAX_MODULUS_GPA if self.youngs_modulus is None else self.youngs_modulus) * 1e3
            what = "Young's modulus" if self.youngs_modulus is not None else "the largest modulus"
            if not MIN_YIELD_MPA <= sy <= top:
                raise InvalidParameterError(
                    "yield_stress",
                    f"must be in [{MIN_YIELD_MPA:g}, {top:g}] MPa (up to {what}), got {shown(sy)}",
                )
            set_(self, "yield_stress", sy)
        self._check_hardening()

    def _check_hardening(self) -> None:
        """Validate the hardening modulus and its kinematic share (each may be None)."""
        set_ = object.__setattr__
        if self.hardening_modulus is not None:
            h = finite("hardening_modulus", self.hardening_modulus)
            top = (MAX_MODULUS_GPA if self.youngs_modulus is None else self.youngs_modulus) * 1e3
            if not 0.0 <= h < top:
                raise InvalidParameterError(
                    "hardening_modulus",
                    f"must be >= 0 and below Young's modulus ({top:g} MPa), got {shown(h)} MPa",
                )
            set_(self, "hardening_modulus", h)
        if self.kinematic_hardening is not None:
            share = closed_interval("kinematic_hardening", self.kinematic_hardening, 0.0, 1.0)
            set_(self, "kinematic_hardening", share)

    @property
    def relief_hole_diameter(self) -> float:
        """The relief hole's diameter after applying the default (length)."""
        if self.relief_hole is not None:
            return self.relief_hole
        return default_relief_hole(self.thickness, self.bend_radius)

    def with_changes(self, **changes: Any) -> Material:
        """A copy with some fields replaced (validated again)."""
        return replace(self, **changes)


#: Where the sheet's faces lie for each reference surface, in thicknesses
#: along the top normal from the reference surface.
_S_RANGE = {
    SheetSurface.INSIDE: (-1.0, 0.0),
    SheetSurface.OUTSIDE: (0.0, 1.0),
    SheetSurface.MID: (-0.5, 0.5),
}


def sheet_offsets(material: Material) -> tuple[float, float]:
    """The sheet's two faces as signed distances from the reference surface
    along its top normal (length): INSIDE (-t, 0), OUTSIDE (0, t), MID (-t/2, t/2)."""
    lo, hi = _S_RANGE[material.sheet_surface]
    return lo * material.thickness, hi * material.thickness


def default_relief_hole(thickness: float, bend_radius: float) -> float:
    """The default relief hole's diameter before a solid's needs (length):
    none for a zero-thickness sheet, else max(3 t, 2 (t + r)). The one home of
    that rule (:attr:`Material.relief_hole_diameter`, the fabrication checks)."""
    if thickness == 0.0:
        return 0.0
    return max(3.0 * thickness, 2.0 * (thickness + bend_radius))
