"""The fold the geometry property tests check, shared by their modules."""

from __future__ import annotations

from onefold_cad import FrameCurve, Sheet, fold, solve
from onefold_cad.errors import NoSolutionError
from onefold_cad.geometry.folding import FoldedSheet


def fold_or_none(frame: FrameCurve, sheet: Sheet, model: str) -> FoldedSheet | None:
    """The fold, or None for a design the solver refuses (no non-trivial
    apex, or one beyond double precision) or answers outside the properties'
    premises: an angle-condition error above 1e-9 deg or an apex below 1e-9 R
    (the trivial root h = 0 within rounding)."""
    try:
        solution = solve(frame, model)
    except NoSolutionError:
        return None
    ok = solution.angle_condition_error_deg <= 1e-9
    if not (ok and solution.apex_height > 1e-9 * frame.radius):
        return None
    return fold(solution, sheet)
