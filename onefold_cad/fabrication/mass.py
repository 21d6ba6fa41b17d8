"""The mass of the cut part: the one mass formula (numpy-free).

Density (kg/m^3) x thickness x area, the volume converted to m^3 with the
design unit's length in metres; reported in kg for mm designs and in lb for
inch and foot designs.
"""

from __future__ import annotations

from dataclasses import dataclass

from onefold_cad.choices import Units
from onefold_cad.design import Design
from onefold_cad.geometry.material import Material

__all__ = ["KG_PER_LB", "Mass", "design_mass", "part_mass"]

#: Kilograms per pound (the international avoirdupois pound, exact by definition).
KG_PER_LB = 0.45359237


@dataclass(frozen=True)
class Mass:
    """The mass of the cut part.

    Attributes:
        value: the mass, in ``unit``.
        unit: 'kg' (mm designs) or 'lb' (inch and foot designs).
        density: the density used, kg/m^3.
    """

    value: float
    unit: str
    density: float

    def __str__(self) -> str:
        return f"{self.value:.6g} {self.unit} (density {self.density:g} kg/m^3)"


def part_mass(material: Material, units: Units, net_area: float) -> Mass | None:
    """The mass of a part of ``net_area`` (``units``^2) cut from a sheet of
    ``material``, or None without a density or thickness: see
    :func:`design_mass`."""
    m = material
    if m.density is None or m.thickness <= 0.0:
        return None
    metres = units.mm / 1000.0
    kg = m.density * m.thickness * net_area * metres**3
    unit = units.mass_unit
    return Mass(kg if unit == "kg" else kg / KG_PER_LB, unit, m.density)


def design_mass(design: Design, net_area: float) -> Mass | None:
    """The mass of a part of ``net_area`` (design unit^2) cut from the design's
    sheet, or None without a density or thickness. The one mass formula:
    density (kg/m^3) x thickness x area, the volume converted to m^3 with the
    design unit's length in metres; reported in kg for mm designs and in lb
    (1 lb = 0.45359237 kg) for inch and foot designs."""
    return part_mass(design.material, design.units, net_area)
