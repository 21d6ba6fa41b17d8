"""OCC's default area and volume of the STEP solid (what FreeCAD's ``Volume``
and build123d's ``volume`` report) against the converged integration.

The default rule takes a fixed number of Gauss points per face: across a
ruled face's theta as few as 8, and along a planar sliver's edges a small
difference of large integrals when the sliver lies askew in its plane's
axes. The solid's faces are shaped for it (:mod:`onefold_cad.export.brep.solid`,
:func:`onefold_cad.export.aligned_plane.aligned_plane`), so a take-off in
the user's program agrees with ours within 0.1 %.
"""

from __future__ import annotations

import shutil
import subprocess

import build123d as bd
import pytest
from OCP.BRepGProp import BRepGProp
from OCP.GProp import GProp_GProps
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS

from onefold_cad.export.brep.measure import measure
from onefold_cad.export.brep.step import export_design_step
from onefold_cad.templates import load_template
from tests.export.brep.test_step import _solid_trip
from tests.shipped import REPO_TEMPLATES

#: The take-off's agreement the issue asks for (relative).
TAKE_OFF = 1e-3


def _default(shape, what: str) -> float:
    """OCC's default (fixed-order) integration, as FreeCAD and build123d call it."""
    props = GProp_GProps()
    if what == "volume":
        BRepGProp.VolumeProperties_s(shape, props)
    else:
        BRepGProp.SurfaceProperties_s(shape, props)
    return props.Mass()


def _converged(shape, what: str) -> float:
    props = GProp_GProps()
    if what == "volume":
        BRepGProp.VolumeProperties_s(shape, props, 1e-9)
    else:
        BRepGProp.SurfaceProperties_s(shape, props, 1e-9)
    return props.Mass()


def _shipped_step(name: str, tmp_path_factory):
    design = load_template(REPO_TEMPLATES / f"{name}.toml")
    path = tmp_path_factory.mktemp("takeoff") / f"{name}.step"
    export_design_step(design, path, placement="frame")
    return path


@pytest.fixture(scope="module")
def patkau_step(tmp_path_factory):
    return _shipped_step("patkau-one-fold", tmp_path_factory)


@pytest.mark.parametrize("what", ["volume", "area"])
def test_default_properties_of_the_shipped_solid_agree_with_the_converged(patkau_step, what):
    shape = bd.import_step(patkau_step)
    assert len(shape.solids()) == 1
    converged = measure(shape, what)
    assert _converged(shape.wrapped, what) == pytest.approx(converged, rel=1e-6)
    assert _default(shape.wrapped, what) == pytest.approx(converged, rel=TAKE_OFF)


def test_default_properties_of_the_shipped_inch_solid_agree(tmp_path_factory):
    """broken-vault (inches): its default volume was 60.7 % light."""
    shape = bd.import_step(_shipped_step("broken-vault", tmp_path_factory))
    assert len(shape.solids()) == 1
    for what in ("volume", "area"):
        converged = _converged(shape.wrapped, what)
        assert _default(shape.wrapped, what) == pytest.approx(converged, rel=TAKE_OFF)


#: A face's own agreement: a planar sliver t wide and metres long integrates
#: along edges of many knot spans (0.13 % on rect-ft-in-mm-mid's mitre faces).
FACE_TAKE_OFF = 5e-3


@pytest.mark.parametrize("name", ["rect-ft-in-mm-mid", "star-inside"])
def test_default_properties_of_every_solid_case_agree(name, tmp_path_factory):
    """In total within :data:`TAKE_OFF`, face by face within :data:`FACE_TAKE_OFF`."""
    _, _, shape = _solid_trip(name, tmp_path_factory)
    for what in ("volume", "area"):
        converged = _converged(shape.wrapped, what)
        assert _default(shape.wrapped, what) == pytest.approx(converged, rel=TAKE_OFF)
    ex = TopExp_Explorer(shape.wrapped, TopAbs_FACE)
    while ex.More():
        face = TopoDS.Face(ex.Current())
        ex.Next()
        exact = _converged(face, "area")
        assert _default(face, "area") == pytest.approx(exact, rel=FACE_TAKE_OFF, abs=1e-9)


def test_freecad_weighs_the_shipped_solid_as_we_do(patkau_step, tmp_path):
    """FreeCAD's own take-off (Debian's freecad-python3: make test installs it)."""
    FREECAD = shutil.which("freecadcmd")
    assert FREECAD is not None, "FreeCAD is not installed: make test installs freecad-python3"
    script = tmp_path / "weigh.py"
    script.write_text(
        "import Part\n"
        f"s = Part.read({str(patkau_step)!r})\n"
        f"out = open({str(tmp_path / 'out.txt')!r}, 'w')\n"
        "out.write(f'{s.Volume!r} {s.Area!r} {s.isValid()}')\n"
    )
    subprocess.run([FREECAD, str(script)], check=True, capture_output=True, timeout=120)
    volume, area, valid = (tmp_path / "out.txt").read_text().split()
    shape = bd.import_step(patkau_step)
    assert valid == "True"
    assert float(volume) == pytest.approx(measure(shape, "volume"), rel=TAKE_OFF)
    assert float(area) == pytest.approx(measure(shape, "area"), rel=TAKE_OFF)
