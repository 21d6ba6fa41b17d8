"""onefold_cad: the One-Fold curved-origami construction as fabrication files.

For scripts (Jupyter, Rhino 8's CPython, COMPAS)::

    import onefold_cad as of

    d = of.load_template("patkau-one-fold")            # or of.make_design(alpha=40, ...)
    d = d.with_changes(name="mine")                    # a frozen Design: change a copy
    of.export(d, "mine.step")                          # the writer chosen by the suffix
    of.write_files(d, "out/", formats=["dxf", "json"]) # as onefold build writes them
    report = of.design_report(d)                       # the JSON report as a dict
    sim = of.simulate(d, mesh="coarse")                # the sheet as steel, its stages

The core (:mod:`onefold_cad.geometry`) is pure numpy; the fabrication rules
(:mod:`onefold_cad.fabrication`) too; the adapters in :mod:`onefold_cad.export`
turn their results into STEP (build123d), DXF (ezdxf), previews and JSON
reports. docs/architecture.md draws the layers.

The public names below are imported on first use (PEP 562), so importing a
submodule such as :mod:`onefold_cad.cli.main` does not load the geometry core
until a command needs it (``onefold --help`` starts in a few milliseconds),
and ``import onefold_cad`` loads neither numpy nor a CAD library.
"""

from __future__ import annotations

import importlib
import os
import sys
import types
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar, cast

#: public name -> the module that defines it
_EXPORTS: dict[str, str] = {
    "Design": "onefold_cad.design",
    "fold_design": "onefold_cad.design",
    "write_files": "onefold_cad.export.files",
    "Simulation": "onefold_cad.mechanics.results",
    "FitResult": "onefold_cad.fit",
    "Body": "onefold_cad.choices",
    "Compensation": "onefold_cad.choices",
    "Placement": "onefold_cad.choices",
    "ExportError": "onefold_cad.errors",
    "FabricationError": "onefold_cad.errors",
    "InvalidParameterError": "onefold_cad.errors",
    "InvalidSheetError": "onefold_cad.errors",
    "NoSolutionError": "onefold_cad.errors",
    "OneFoldError": "onefold_cad.errors",
    "CreaseHalf": "onefold_cad.geometry.folding",
    "Developability": "onefold_cad.geometry.developability",
    "FoldedSheet": "onefold_cad.geometry.folding",
    "fold": "onefold_cad.geometry.folding",
    "BendValues": "onefold_cad.geometry.bend_model",
    "Material": "onefold_cad.geometry.material",
    "SheetSurface": "onefold_cad.choices",
    "Units": "onefold_cad.choices",
    "bend_values": "onefold_cad.geometry.bend_model",
    "FrameCurve": "onefold_cad.geometry.frame_curve",
    "Model": "onefold_cad.choices",
    "RestingPlacement": "onefold_cad.geometry.resting.placement",
    "Placement2D": "onefold_cad.geometry.sheet",
    "Sheet": "onefold_cad.geometry.sheet",
    "Solution": "onefold_cad.geometry.solver",
    "solve": "onefold_cad.geometry.solver",
}

#: the functions defined here, for scripts
_HERE = ["design_report", "export", "fit", "load_template", "make_design", "simulate", "site"]

__all__ = sorted([*_EXPORTS, *_HERE])


def __getattr__(name: str) -> Any:
    if name == "__version__":  # read from the package metadata on first use
        from onefold_cad import version

        return version.__version__
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'onefold_cad' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value  # later look-ups skip this function
    return value


def __dir__() -> list[str]:
    return sorted([*globals(), *_EXPORTS])


_F = TypeVar("_F", bound=Callable[..., Any])


class _Verb:
    """A verb of the API named like a subpackage of onefold_cad (``export``,
    ``fit``, ``site``): called, it is the function; its attributes are the
    subpackage's, so ``onefold_cad.export.writers`` still reaches the module."""

    def __init__(self, fn: Callable[..., Any]) -> None:
        self._fn = fn
        self.__doc__ = fn.__doc__
        self.__name__ = self.__qualname__ = fn.__name__
        self.__module__ = __name__
        self.__wrapped__ = fn

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return self._fn(*args, **kwargs)

    def __getattr__(self, name: str) -> Any:
        return getattr(importlib.import_module(f"{__name__}.{self.__name__}"), name)

    def __repr__(self) -> str:
        return f"<function onefold_cad.{self.__name__}>"


def _verb(fn: _F) -> _F:
    return cast(_F, _Verb(fn))


class _Package(types.ModuleType):
    """onefold_cad itself: importing its subpackage ``export`` (``fit``,
    ``site``) binds the name on the package; the verb of that name stays."""

    def __setattr__(self, name: str, value: Any) -> None:
        if isinstance(value, types.ModuleType) and isinstance(self.__dict__.get(name), _Verb):
            return
        super().__setattr__(name, value)


def load_template(template: str | os.PathLike[str]) -> Design:
    """A template as a design.

    Args:
        template: a shipped template's name (``onefold templates`` lists them)
            or a TOML file.

    Returns:
        The validated design.

    Raises:
        InvalidParameterError: no such template, a site file, or a value out of
            its range (named, with the range).
    """
    from onefold_cad.templates import load_template as load

    return load(os.fspath(template))


def _number(value: float) -> str:
    """``value`` as a user types it on the command line: 1200, 0.4, 1e-05."""
    text = repr(float(value))
    return text.removesuffix(".0")


def make_design(template: str | None = None, *, name: str | None = None, **values: Any) -> Design:
    """A design from values, as ``onefold solve TEMPLATE --FLAG VALUE ...`` makes it.

    Args:
        template: a shipped template's name or a TOML file; None: the default
            template (``patkau-one-fold``), whose values the given ones override.
        name: the design's name (default: the template's with the values
            given, as the command names it).
        **values: the design flags by their Python names: ``alpha``, ``beta``
            (deg), ``hc``, ``radius``, ``divisions``, ``model`` ('exact' or
            'paper'), ``units``, the sheet (``rectangle=(w, h)`` with
            ``apex_fraction``, ``polygon=[(x, y), ...]``, or ``x_plus``,
            ``x_minus``, ``y_plus``, ``y_minus``), the material
            (``thickness``, ``bend_radius``, ``k_factor``, ``kerf``,
            ``relief_hole``, ``density``, ``sheet_surface``, ...).

    Returns:
        The validated design (solve it with :func:`fold_design`).

    Raises:
        InvalidParameterError: an unknown value name (the allowed ones listed),
            a value out of its range (named, with the range), or a template
            that is not found.
    """
    from onefold_cad.errors import InvalidParameterError
    from onefold_cad.flags.design_flags import DESIGN_FLAGS
    from onefold_cad.flags.jobs import load_jobs
    from onefold_cad.flags.parser import UsageError, parse_design_flags

    flags = {f.dest: f.flag for f in DESIGN_FLAGS}
    args = []
    for key, value in values.items():
        if key not in flags:
            allowed = ", ".join(flags)
            raise InvalidParameterError(key, f"is not a design value (allowed: {allowed})")
        if key == "rectangle" and not isinstance(value, str):
            value = "x".join(_number(v) for v in value)
        elif key == "polygon" and not isinstance(value, str):
            value = ";".join(f"{_number(x)},{_number(y)}" for x, y in value)
        elif isinstance(value, int | float) and not isinstance(value, bool):
            value = _number(value)
        args.append(f"{flags[key]}={value}")
    try:
        parsed = parse_design_flags(args)
    except UsageError as exc:  # a value the flag's parser cannot read
        raise InvalidParameterError("values", str(exc)) from None
    (job,) = load_jobs([template] if template else [], parsed, name)
    return job.design


@_verb
def export(
    design: Design,
    path: str | os.PathLike[str],
    *,
    body: Body | str | None = None,
    compensation: Compensation | str = "sharp",
    placement: Placement | str = "rest",
) -> Path:
    """Write one file of ``design``, the writer chosen by the suffix of ``path``.

    ``.step`` the folded part, ``.dxf`` the annotated flat pattern, ``.csv``
    the bend sheet, ``.fold`` the crease pattern (FOLD 1.2), ``.glb`` the
    standing form, ``.3dm`` Rhino 8 (the ``rhino`` extra), ``.json`` the
    report, ``.svg`` the flat pattern, ``.png`` the 3D picture: the bytes
    ``onefold build`` writes for that format.

    Args:
        design: the design.
        path: the file to write (atomically; its folder must exist).
        body: 'shell' or 'solid' for STEP and GLB; None: the build's default.
        compensation: 'sharp' (the blank compensates the bends) or 'none'.
        placement: 'rest' (standing on the ground) or 'frame' (fold frame).

    Returns:
        The path written.

    Raises:
        InvalidParameterError: an unknown suffix (the allowed ones listed), a
            bad option, or a design the writer refuses.
        FabricationError: the flat pattern passes the bend model's limits.
        ExportError: the file could not be written.
    """
    from onefold_cad.export.files import export_file

    return export_file(design, path, body=body, compensation=compensation, placement=placement)


def design_report(design: Design, *, compensation: Compensation | str = "sharp") -> dict[str, Any]:
    """The report of ``design`` as ``onefold solve --json`` prints it.

    Args:
        design: the design.
        compensation: 'sharp' or 'none' (which blank the report describes).

    Returns:
        The report (plain data: the apex height, angle-condition error,
        crease angles and bends, flat pattern, mass, the resting form,
        developability, warnings).

    Raises:
        NoSolutionError: the frame has no non-trivial apex.
        InvalidParameterError: a design the report cannot describe.
    """
    from onefold_cad.design import fold_design
    from onefold_cad.fabrication.report import design_report as report_of

    return report_of(design, fold_design(design), compensation=compensation)


@_verb
def fit(
    design: Design,
    height: float,
    span: float,
    depth: float | None = None,
    min_tipping_margin: float | None = None,
) -> FitResult:
    """Alpha, beta and h_c for ``design``'s sheet whose resting form has the
    target size, as ``onefold fit`` finds them.

    Args:
        design: the starting design (sheet, material and model are kept).
        height, span, depth: the resting form's targets (design unit, > 0).
        min_tipping_margin: the smallest tipping margin allowed (deg), or None.

    Returns:
        The fitted design (``.design``) and what its resting form measures.

    Raises:
        InvalidParameterError: a target that is not a positive length.
        OutOfReachError: no frame meets the targets (the ranges reached named).
    """
    from onefold_cad.fit import fit_design

    return fit_design(design, height, span, depth, min_tipping_margin)


def simulate(
    design: Design,
    *,
    supports: Supports | str = "anchored",
    reference: Reference | str = "flat",
    crease: Crease | str = "held",
    mesh: MeshLevel | str = "normal",
    check: bool | None = None,
    law: Law | str = "j2",
    check_mesh: CheckMesh | str | None = None,
) -> Simulation:
    """The sheet of ``design`` as steel, as ``onefold simulate`` computes it.

    Args:
        design: the design (its material's yield stress, modulus, density).
        supports: 'anchored' or 'frictionless' ground contacts.
        reference: 'flat' (formed from the flat sheet, released, standing) or
            'designed' (the designed form's check under its weight).
        crease: 'held' (each half keeps its angle) or 'elastic'.
        mesh: 'coarse', 'normal' or 'fine'.
        check: solve again on a second mesh (default: on every mesh but coarse).
        law: 'j2' (J2 plasticity through the thickness) or 'moment' (the 1D
            moment law: a fifth to a half of the CPU, its springback a third
            to two fifths short).
        check_mesh: the check's mesh: 'finer' (about twice the nodes) or
            'coarser' (the next coarser level's; not below coarse); default
            'coarser' where the level has one, else 'finer'.

    Returns:
        The result with its stages: ``formed``, ``released``, ``standing``,
        ``designed`` (None where the reference has no such stage), the
        per-face stress ``face_stress_MPa``, the warnings; ``to_data()``
        gives what ``onefold simulate --json`` prints.

    Raises:
        InvalidParameterError: a bad option or a design that cannot be simulated.
        ConvergenceError: a stage did not converge.
    """
    from onefold_cad.choices import CheckMesh, Crease, Law, MeshLevel, Reference, Supports
    from onefold_cad.design import fold_design
    from onefold_cad.mechanics.simulate import simulate as run

    level = MeshLevel.parse(mesh)
    return run(
        design,
        fold_design(design),
        supports=Supports.parse(supports).value,
        reference=Reference.parse(reference).value,
        crease=Crease.parse(crease).value,
        level=level.value,
        convergence=level.checked if check is None else check,
        law=Law.parse(law).value,
        check_mesh=None if check_mesh is None else CheckMesh.parse(check_mesh).value,
    )


@_verb
def site(
    spec: str | os.PathLike[str],
    folder: str | os.PathLike[str],
    *,
    formats: str | None = None,
    sheet_formats: str | None = None,
    jobs: int = 1,
    allow_touching: bool = False,
) -> list[Path]:
    """Build a site of several sheets, as ``onefold site SPEC -o FOLDER`` does.

    Args:
        spec: the site file (TOML: a ``[site]`` table and ``[[sheet]]`` tables,
            each a template or an inline design with a position and a turn).
        folder: the output folder: every sheet's files in ``FOLDER/NAME/``, the
            site's STEP, GLB, IFC, plan, order and picture beside them.
        formats, sheet_formats: the site's and the sheets' formats
            (comma-separated names; None: all).
        jobs: sheets built at a time in worker processes.
        allow_touching: build a site whose sheets touch.

    Returns:
        The files written.

    Raises:
        InvalidParameterError: a bad site file or option (named), or sheets
            that touch.
        ExportError: a file could not be written (the folder is as it was).
    """
    import contextlib
    import io

    from onefold_cad.cli.site import cmd_site
    from onefold_cad.cli.site_parser import site_parser

    args = [os.fspath(spec), "-o", os.fspath(folder), "--quiet", "-j", str(jobs)]
    args += ["--formats", formats] if formats else []
    args += ["--sheet-formats", sheet_formats] if sheet_formats else []
    args += ["--allow-touching"] if allow_touching else []
    ns = site_parser("onefold site").parse_args(args)
    out = io.StringIO()
    with contextlib.redirect_stdout(out):  # the command prints the paths it wrote
        cmd_site(ns)
    return [Path(line) for line in out.getvalue().splitlines() if line]


if TYPE_CHECKING:  # static type checkers and IDEs see the names directly
    # ruff: noqa: F401
    from onefold_cad.choices import (
        Body,
        CheckMesh,
        Compensation,
        Crease,
        Law,
        MeshLevel,
        Model,
        Placement,
        Reference,
        SheetSurface,
        Supports,
        Units,
    )
    from onefold_cad.design import Design, fold_design
    from onefold_cad.errors import (
        ExportError,
        FabricationError,
        InvalidParameterError,
        InvalidSheetError,
        NoSolutionError,
        OneFoldError,
    )
    from onefold_cad.export.files import write_files
    from onefold_cad.fit import FitResult
    from onefold_cad.geometry.bend_model import BendValues, bend_values
    from onefold_cad.geometry.developability import Developability
    from onefold_cad.geometry.folding import CreaseHalf, FoldedSheet, fold
    from onefold_cad.geometry.frame_curve import FrameCurve
    from onefold_cad.geometry.material import Material
    from onefold_cad.geometry.resting.placement import RestingPlacement
    from onefold_cad.geometry.sheet import Placement2D, Sheet
    from onefold_cad.geometry.solver import Solution, solve
    from onefold_cad.mechanics.results import Simulation
    from onefold_cad.version import __version__


sys.modules[__name__].__class__ = _Package
