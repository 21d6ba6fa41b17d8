"""The exception hierarchy of onefold_cad.

Every error derives from :class:`OneFoldError` and from the matching builtin,
so callers' ``except ValueError`` keeps working (as in ezdxf).
"""

from __future__ import annotations

import math

__all__ = [
    "OneFoldError",
    "InvalidParameterError",
    "InvalidSheetError",
    "NoSolutionError",
    "ExportError",
    "FabricationError",
    "ConvergenceError",
    "memory_message",
    "not_installed",
    "shown",
]


def not_installed(what: str, modules: list[str] | tuple[str, ...], extra: str) -> str:
    """The one sentence for optional packages that are missing: ``what`` needs
    ``modules``, which are not installed, and the ``pip install`` of the
    package's optional ``extra`` (rhino, bim, cluster) that brings them.

    ``not_installed("onefold hops", ["ghhops_server", "rhino3dm"], "rhino")``:
    "onefold hops needs ghhops_server and rhino3dm, which are not installed:
    pip install 'onefold_cad[rhino]'" (one line).
    """
    names = list(modules)
    listed = names[0] if len(names) == 1 else f"{', '.join(names[:-1])} and {names[-1]}"
    verb = "is" if len(names) == 1 else "are"
    return f"{what} needs {listed}, which {verb} not installed: pip install 'onefold_cad[{extra}]'"


class OneFoldError(Exception):
    """Root of every error raised by onefold_cad."""


class InvalidParameterError(OneFoldError, ValueError):
    """A scalar input is missing, not finite or outside its allowed range.

    Attributes:
        parameter: the name of the offending parameter, as the API spells it.
    """

    def __init__(self, parameter: str, message: str) -> None:
        super().__init__(f"{parameter}: {message}")
        self.parameter = parameter


class InvalidSheetError(InvalidParameterError):
    """The flat sheet is not a simple polygon star-shaped about H."""


class NoSolutionError(OneFoldError, ValueError):
    """The design has no non-trivial apex (the angle condition cannot be met)."""


class ExportError(OneFoldError, RuntimeError):
    """A valid design could not be turned into a file (CAD kernel failure)."""


class FabricationError(OneFoldError, ValueError):
    """The geometry is solved, but a fabrication file of it would be wrong.

    Raised only by writers (DXF blank, STEP solid) when the bend model's
    limits are passed (a bend zone reaching a sheet corner, a set-back large
    beside the flanges, ...). ``solve`` never raises it: it reports the same
    message as a warning.

    Attributes:
        parameter: what to change, as the CLI spells it (e.g. 'bend_radius').
    """

    def __init__(self, parameter: str, message: str) -> None:
        super().__init__(f"{parameter}: {message}")
        self.parameter = parameter


class ConvergenceError(OneFoldError, RuntimeError):
    """An iterative solver (the mechanics' Newton method) did not converge.

    No unconverged state is ever returned as a result: the solver raises this
    instead, naming its iteration count and last residual.

    Attributes:
        iterations: the steps taken.
        residual: the last residual (N, as the solver measures it).
    """

    def __init__(self, message: str, *, iterations: int, residual: float) -> None:
        super().__init__(message)
        self.iterations = iterations
        self.residual = residual


def memory_message(exc: MemoryError) -> str:
    """One line for an allocation that failed (``MemoryError``, numpy's
    ``_ArrayMemoryError`` among them): the CLI prints it (exit 2), the
    servers answer it and stay up. The size comes from what the request
    asked for, so the line says what sets it."""
    detail = " ".join(str(exc).split()) or "an allocation failed"
    return (
        f"out of memory ({detail[:200]}): the request needs more memory than this "
        "machine gives it; ask for less (the divisions, the polygon's vertices, "
        "the mesh or the number of sheets set the size)"
    )


def shown(x: float) -> str:
    """A value as a refusal shows it: ``{x:g}`` when that reads back as ``x``
    (``1e+308``, ``0.5``, ``100``), else the shortest text that does
    (``0.999999999999``, which ``:g`` shows as ``1``: "must be below 1, got
    1"; ``1e-320``, not ``9.99989e-321``). Here, numpy-free, so that the
    quick commands' parsers can use it."""
    short = f"{x:g}"
    try:
        value = float(x)
    except (TypeError, ValueError, OverflowError):
        return short
    exact = repr(value)
    if math.isnan(value) or (float(short) == value and len(short) <= len(exact)):
        return short
    return exact
