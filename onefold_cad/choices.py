"""The design's named options, one enum each: the vocabulary every layer uses.

No numpy here: the command's parser (:mod:`onefold_cad.flags`) reads its
choices from these enums and starts in milliseconds. One way to read a name
from text (:meth:`Choice.parse`, any case) and one error for a name that is
not one.
"""

from __future__ import annotations

import re
from enum import StrEnum
from typing import Self

from onefold_cad.errors import InvalidParameterError

__all__ = [
    "Body",
    "CheckMesh",
    "Choice",
    "Compensation",
    "ConeForming",
    "Crease",
    "Knob",
    "Law",
    "MeshLevel",
    "Model",
    "Placement",
    "Reference",
    "SheetSurface",
    "Supports",
    "Units",
]


class Choice(StrEnum):
    """A string enum whose members a user names in any case.

    The parameter a bad name is reported against is the class name in
    snake case: ``Model`` -> ``model``, ``SheetSurface`` -> ``sheet_surface``.
    """

    @classmethod
    def parse(cls, value: object) -> Self:
        """The member named by ``value`` (a member, or its value in any case).

        Raises:
            InvalidParameterError: naming the parameter and the allowed names.
        """
        if isinstance(value, cls):
            return value
        text = str(value).casefold()
        for member in cls:
            if member.value.casefold() == text:
                return member
        names = ", ".join(member.value for member in cls)
        parameter = re.sub(r"(?<!^)(?=[A-Z])", "_", cls.__name__).lower()
        raise InvalidParameterError(parameter, f"must be one of {names}, got {value!r}")


class Model(Choice):
    """Which direction-surface the solver uses.

    PAPER: the fan of ``divisions`` planar triangles over the division points
    of the frame curve, exactly as in the paper.
    EXACT: the continuous cone over the circular arc (the limit of infinitely
    many divisions); independent of ``divisions``.
    """

    PAPER = "paper"
    EXACT = "exact"


class SheetSurface(Choice):
    """Which face of the sheet the designed (reference) surface is.

    INSIDE: the top (+z) face; the material lies below it.
    OUTSIDE: the bottom face; the material lies above it.
    MID: the mid-surface; half the thickness each way.
    """

    INSIDE = "INSIDE"
    OUTSIDE = "OUTSIDE"
    MID = "MID"


class Units(Choice):
    """Length unit of a design."""

    MM = "mm"
    M = "m"
    IN = "in"
    FT = "ft"

    @property
    def mm(self) -> float:
        """Millimetres per unit (exact: 1 m = 1000 mm, 1 in = 25.4 mm, 1 ft = 304.8 mm)."""
        return {"mm": 1.0, "m": 1000.0, "in": 25.4, "ft": 304.8}[self.value]

    def factor_to(self, other: Units | str) -> float:
        """The factor that turns a length in this unit into one in ``other``."""
        return self.mm / Units.parse(other).mm

    @property
    def mass_unit(self) -> str:
        """The unit masses are reported in: 'kg' for mm and metre designs, 'lb'
        for inch and foot designs."""
        return "kg" if self in (Units.MM, Units.M) else "lb"


class Compensation(Choice):
    """How the flat blank accounts for the bends.

    SHARP: each side moves by the bend model's shift (refused past the limits).
    NONE: the blank is the designed reference surface's outline, uncompensated.
    """

    SHARP = "sharp"
    NONE = "none"


class Body(Choice):
    """The body a form is written as (STEP, GLB) and stood on the ground with.

    SHELL: the folded reference surface (zero thickness).
    SOLID: the sheet of the material's thickness (exact model).
    """

    SHELL = "shell"
    SOLID = "solid"


class Placement(Choice):
    """Where the STEP, the GLB and the 3D preview put the form.

    REST: as it stands on the ground z = 0 (the resting placement).
    FRAME: the fold frame (H at the origin, the fold line on x, the apex above H).
    """

    REST = "rest"
    FRAME = "frame"


class Supports(Choice):
    """How the ground holds a simulated sheet where it touches.

    ANCHORED: a touching point does not slide (it is held in x, y and z).
    FRICTIONLESS: a touching point slides freely on the ground (held in z only).
    """

    ANCHORED = "anchored"
    FRICTIONLESS = "frictionless"


class Reference(Choice):
    """The stress-free form of a simulated sheet.

    FLAT: the flat-cut sheet, bent into the design (forming, springback, standing).
    DESIGNED: the designed form (a structural check of it under its weight).
    """

    FLAT = "flat"
    DESIGNED = "designed"


class Crease(Choice):
    """How a simulated sheet's crease behaves.

    HELD: each crease half keeps its set angle (a welded fold line).
    ELASTIC: the bend zone's own stiffness, D / (psi (r + t / 2)) per length.
    """

    HELD = "held"
    ELASTIC = "elastic"


class Law(Choice):
    """How ``onefold simulate``'s steel bends and yields.

    J2: von Mises plasticity with linear hardening at points through the
    thickness, membrane and bending together: unloading and reverse yield
    follow the law, no stress passes the flow stress (the default; its
    springback is CalculiX's within 5 %).
    MOMENT: the 1D moment-curvature law of a rectangular section in uniaxial
    stress with an elastic membrane and elastic unloading (the faster
    estimate, a fifth to a half of J2's CPU: the explorer's previews; its
    springback a third to two fifths short, its stresses past yield not a
    state steel can be in, and it says so in warnings).
    """

    J2 = "j2"
    MOMENT = "moment"


class ConeForming(Choice):
    """What curvature the machine forms the cones to.

    DESIGN: the design's own; the sheet then springs back from it.
    COMPENSATED: at every point, the curvature whose springback leaves the
    design's (the J2 section bent in plane strain and released:
    :mod:`onefold_cad.mechanics.j2.springback`); ``onefold build`` writes
    the radii per ruling station, ``NAME-cones.csv``.
    """

    DESIGN = "design"
    COMPENSATED = "compensated"


class Knob(Choice):
    """What ``onefold compensate`` may change in the fold it forms.

    ALPHA, BETA: the frame curve's angles (deg). H_C: its height h_c.
    OVERBEND: the crease set past the fold angle (``crease_overbend``, deg).
    CONES: the cones formed past their springback (``cone_forming =
    "compensated"``) instead of to the design's curvature.
    """

    ALPHA = "alpha"
    BETA = "beta"
    H_C = "h_c"
    OVERBEND = "overbend"
    CONES = "cones"


class MeshLevel(Choice):
    """How fine a simulated sheet's mesh is (``coarse`` is a preview)."""

    COARSE = "coarse"
    NORMAL = "normal"
    FINE = "fine"

    @property
    def checked(self) -> bool:
        """Whether simulate solves again on a finer mesh by default (its
        convergence check): on every level but the coarse preview."""
        return self is not MeshLevel.COARSE

    @property
    def coarser(self) -> MeshLevel | None:
        """The next coarser level (None for the coarse preview)."""
        return {MeshLevel.FINE: MeshLevel.NORMAL, MeshLevel.NORMAL: MeshLevel.COARSE}.get(self)


class CheckMesh(Choice):
    """The mesh ``onefold simulate``'s convergence check solves again on.

    FINER: every target edge divided by sqrt 2, about twice the nodes.
    COARSER: the next coarser level's own mesh (normal: coarse; fine:
    normal), a fraction of the cost; for a discretisation of second order
    its change overstates the answer's error, where the finer mesh's
    understates it (docs/mechanics.md, "The convergence check's mesh").
    The default is :meth:`default_for`'s.
    """

    FINER = "finer"
    COARSER = "coarser"

    @staticmethod
    def default_for(level: str, h_max: float | None = None) -> CheckMesh:
        """The check's default mesh: the next coarser level's where the
        ``level`` has one and no ``h_max`` is given, else the finer mesh."""
        coarser = MeshLevel.parse(level).coarser
        return CheckMesh.COARSER if coarser is not None and h_max is None else CheckMesh.FINER


#: ``onefold simulate``'s default settings (the convergence check's: :attr:`MeshLevel.checked`).
SIMULATION_DEFAULTS: dict[str, Choice] = {
    "supports": Supports.ANCHORED,
    "reference": Reference.FLAT,
    "crease": Crease.HELD,
    "law": Law.J2,
    "mesh": MeshLevel.NORMAL,
}
