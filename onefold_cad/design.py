"""A whole design: frame curve, sheet, model, material and units; its fold, and
the one cache of what is derived from a design or its fold.

This is what the fabrication rules, the adapters (STEP, DXF, previews,
report) and the CLI consume. A design holds geometry and fabrication inputs;
it never refuses a value for a fabrication reason (a relief hole too large
for the sheet, an implausible density):
:func:`onefold_cad.fabrication.rules.fabrication_warnings` names those,
``solve`` prints them and the writers refuse.

The cache (:func:`derived`): a design and a fold are immutable, so whatever
is computed from one (the fold of a design, a fold's resting placement, its
smallest relief hole, its developability, its flat pattern) is computed once
and held by the object it derives from, freed with it. It is the only cache
of such results in the package.
"""

from __future__ import annotations

import re
import threading
import weakref
from collections.abc import Callable, Hashable
from dataclasses import dataclass, field, replace
from typing import Any, TypeVar

import numpy as np

from onefold_cad.choices import Body, Model, Units
from onefold_cad.errors import InvalidParameterError, OneFoldError
from onefold_cad.geometry.checks import check_magnitudes
from onefold_cad.geometry.folding import FoldedSheet, fold
from onefold_cad.geometry.frame_curve import FrameCurve, check_design_divisions
from onefold_cad.geometry.material import Material
from onefold_cad.geometry.placement import RestingPlacement, rest_form
from onefold_cad.geometry.sheet import Sheet
from onefold_cad.geometry.solver import solve

__all__ = ["DERIVED", "Design", "derived", "fold_design", "rest_once"]

_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._-]{0,63}$")


@dataclass(frozen=True, eq=False)
class Design:
    """Everything needed to solve and fabricate one One-Fold form.

    Attributes:
        name: file-safe design name (letters, digits, '.', '_', '-').
        frame: the frame curve (alpha, beta, h_c, radius, divisions).
        sheet: the flat sheet in the fold frame.
        model: 'exact' (default) or 'paper'.
        material: thickness, bend radius, K-factor, kerf, relief hole, density.
        units: the design's length unit: every length of ``frame``, ``sheet``
            and ``material`` is in it (the density is in kg/m^3 whatever it is).
        description: free text for reports and notes.
    """

    name: str
    frame: FrameCurve
    sheet: Sheet
    model: Model = Model.EXACT
    material: Material = field(default_factory=Material)
    units: Units = Units.MM
    description: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not _NAME.match(self.name):
            raise InvalidParameterError(
                "name",
                "must be 1-64 characters of letters, digits, '.', '_' or '-', "
                f"starting with a letter or digit, got {self.name!r}",
            )
        object.__setattr__(self, "model", Model.parse(self.model))
        object.__setattr__(self, "units", Units.parse(self.units))
        check_design_divisions(self.frame)
        check_magnitudes(self.frame.radius, self.sheet.size, self.material)

    def with_changes(self, **changes: Any) -> Design:
        """A copy with some fields replaced (validated again)."""
        return replace(self, **changes)

    def in_units(self, units: Units | str) -> Design:
        """The same design with every length converted into ``units``.

        Converted: the frame's radius and h_c, the sheet (its inputs, so a
        rectangle stays a rectangle), the thickness, bend radius, kerf and
        an explicit relief hole. Angles, divisions, the K-factor and the
        density (kg/m^3) do not depend on the length unit. The factor is
        ``Units.factor_to`` (1 in = 25.4 mm, 1 ft = 304.8 mm exactly).
        """
        to = Units.parse(units)
        if to is self.units:
            return self
        f = self.units.factor_to(to)
        fr, m = self.frame, self.material
        frame = fr.with_changes(radius=fr.radius * f, h_c=fr.h_c * f)
        material = m.with_changes(
            thickness=m.thickness * f,
            bend_radius=m.bend_radius * f,
            kerf=m.kerf * f,
            relief_hole=None if m.relief_hole is None else m.relief_hole * f,
        )
        return replace(
            self, frame=frame, sheet=_scaled_sheet(self.sheet, f), material=material, units=to
        )


def _scaled_sheet(sheet: Sheet, f: float) -> Sheet:
    """``sheet`` with every length multiplied by ``f``, rebuilt from its inputs."""
    inputs = sheet.inputs
    if sheet.kind == "rectangle":
        return Sheet.rectangle(
            float(inputs["width"]) * f,
            float(inputs["height"]) * f,
            float(inputs["apex_fraction"]),
        )
    if sheet.kind == "quadrilateral":
        return Sheet.quadrilateral(**{k: float(v) * f for k, v in inputs.items()})
    points = np.asarray(inputs.get("polygon", sheet.vertices), dtype=float) * f
    return Sheet.polygon(points, name="polygon")


T = TypeVar("T")

#: What is derived from each live design or fold: owner -> {key: result} (the
#: tests and benchmarks read it; a benchmark swaps it for one that forgets). A
#: result must not refer to its owner (it would keep it alive); an error is
#: kept without its traceback (whose frames do).
DERIVED: weakref.WeakKeyDictionary[Any, dict[Hashable, Any]] = weakref.WeakKeyDictionary()
_LOCK = threading.Lock()
_MISSING = object()


def derived(
    owner: Design | FoldedSheet, key: Hashable, compute: Callable[[], T], *, errors: bool = True
) -> T:
    """``compute()`` the first time ``(owner, key)`` is asked for, then its result
    again: the one cache of the package (see the module docstring).

    Args:
        owner: the design or fold the result derives from (it holds the result).
        key: what else the result depends on (hashable, no reference to ``owner``).
        compute: makes the result.
        errors: also keep the OneFoldError ``compute`` raised and raise it
            again (else it is raised and nothing is kept).
    """
    with _LOCK:
        known = DERIVED.setdefault(owner, {}).get(key, _MISSING)
    if known is _MISSING:
        try:
            known = compute()
        except OneFoldError as exc:
            if not errors:
                raise
            known = exc.with_traceback(None)
        with _LOCK:
            known = DERIVED.setdefault(owner, {}).setdefault(key, known)
    if isinstance(known, OneFoldError):
        raise known
    return known


def fold_design(design: Design) -> FoldedSheet:
    """Solve the direction-surface and fold the sheet of ``design`` (once per
    design object: the same :class:`FoldedSheet` again afterwards).

    Args:
        design: the design.

    Returns:
        The folded sheet.

    Raises:
        NoSolutionError: the frame has no non-trivial apex.
        InvalidSheetError: the sheet does not fold (H outside it, ...).
    """
    return derived(
        design, "fold", lambda: fold(solve(design.frame, design.model), design.sheet), errors=False
    )


def rest_once(
    folded: FoldedSheet, material: Material | None = None, body: Body = Body.SHELL
) -> RestingPlacement:
    """:func:`~onefold_cad.geometry.placement.rest_form` of ``folded``,
    ``material`` (None: a zero-thickness sheet without a hole) and ``body``,
    computed once per fold, material and body."""
    return derived(folded, ("rest", material, body), lambda: rest_form(folded, material, body))
