"""The scripting API of ``import onefold_cad as of``: a script's files are
``onefold build``'s, the verbs are documented, the import stays light."""

from __future__ import annotations

import inspect
import json
import subprocess
import sys

import pytest

import onefold_cad as of
from onefold_cad.cli.main import main
from onefold_cad.errors import InvalidParameterError, OneFoldError
from onefold_cad.flags.jobs import load_jobs


def _built(tmp_path, *args):
    out = tmp_path / "built"
    assert main(["build", *args, "-o", str(out), "--quiet"]) == 0
    return out


def test_export_by_suffix_writes_the_bytes_onefold_build_writes(tmp_path, capsys):
    d = of.load_template("patkau-one-fold")
    step, dxf = of.export(d, tmp_path / "x.step"), of.export(d, tmp_path / "x.dxf")
    out = _built(tmp_path, "patkau-one-fold", "--formats", "step,dxf")
    assert step.read_bytes() == (out / "patkau-one-fold.step").read_bytes()
    assert dxf.read_bytes() == (out / "patkau-one-fold.dxf").read_bytes()


def test_an_unknown_suffix_names_the_allowed_ones_and_writes_nothing(tmp_path):
    with pytest.raises(InvalidParameterError) as err:
        of.export(of.load_template("paper-square"), tmp_path / "x.stl")
    assert err.value.parameter == "path"
    for suffix in (".step", ".dxf", ".fold", ".glb", ".3dm", ".json", ".svg", ".png"):
        assert suffix in str(err.value)
    assert list(tmp_path.iterdir()) == []


def test_write_files_is_the_build_s_path_into_an_existing_folder(tmp_path, capsys):
    d = of.load_template("paper-square")
    formats = ["dxf", "cut", "bends", "fold", "json"]
    (tmp_path / "mine").mkdir()
    files = of.write_files(d, tmp_path / "mine", formats=formats)
    out = _built(tmp_path, "paper-square", "--formats", ",".join(formats))
    assert sorted(p.name for p in files) == sorted(p.name for p in out.iterdir())
    for p in files:
        if p.suffix == ".json":  # its timings and file paths are the call's own
            ours, theirs = json.loads(p.read_text()), json.loads((out / p.name).read_text())
            for report in (ours, theirs):  # sources: the command's flags and template
                for key in ("timings_s", "files", "sources"):
                    report.pop(key, None)
            assert ours == theirs
        else:
            assert p.read_bytes() == (out / p.name).read_bytes(), p.name


def test_write_files_refuses_before_writing_anything(tmp_path):
    d = of.make_design("paper-square", relief_hole=1e6)
    with pytest.raises(OneFoldError):
        of.write_files(d, tmp_path / "out", formats="dxf,json")
    assert not (tmp_path / "out").exists()


def test_make_design_is_the_command_s_design_from_the_same_values():
    ours = of.make_design("table1-row1", alpha=40.0, rectangle=(1200, 2400), apex_fraction=0.4)
    flags = {"alpha": 40.0, "rectangle": "1200x2400", "apex_fraction": 0.4}  # as typed
    (job,) = load_jobs(["table1-row1"], flags)
    assert ours.name == job.design.name
    assert ours.description == job.design.description
    assert ours.frame == job.design.frame
    assert (ours.sheet.vertices == job.design.sheet.vertices).all()


def test_make_design_names_an_unknown_value_and_the_allowed_ones():
    with pytest.raises(InvalidParameterError) as err:
        of.make_design(alpah=40)
    assert err.value.parameter == "alpah" and "alpha" in str(err.value)


def test_every_public_function_says_its_args_returns_and_raises():
    missing = []
    for name in of.__all__:
        value = getattr(of, name)
        if inspect.isclass(value) or not callable(value):
            continue
        doc = inspect.getdoc(value) or ""
        missing += [f"{name}: {part}" for part in ("Args", "Returns", "Raises") if part not in doc]
    assert missing == []


def test_the_verbs_named_like_subpackages_stay_callable():
    import onefold_cad.export.writers
    import onefold_cad.fit
    import onefold_cad.site.spec  # noqa: F401 - binds the subpackages' names

    assert callable(of.export) and callable(of.fit) and callable(of.site)
    assert of.export.writers is sys.modules["onefold_cad.export.writers"]
    assert of.fit.fit_design is sys.modules["onefold_cad.fit"].fit_design


def test_importing_the_package_loads_no_numpy_and_no_cad_library():
    code = (
        "import sys, onefold_cad as of\n"
        "print(sorted(m for m in ('numpy', 'build123d', 'ezdxf') if m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_simulate_takes_the_law_and_the_check_s_mesh_as_the_command_does(monkeypatch):
    """``of.simulate`` passes the law and the check's mesh on, in any case,
    and refuses a name that is not one before any simulation."""
    from onefold_cad.mechanics import simulate as sim_module

    seen: dict = {}
    monkeypatch.setattr(sim_module, "simulate", lambda *a, **k: seen.update(k) or "sim")
    d = of.load_template("patkau-one-fold")
    assert of.simulate(d, law="J2", check_mesh="Coarser") == "sim"
    assert seen["law"] == "j2" and seen["check_mesh"] == "coarser"
    assert seen["level"] == "normal" and seen["convergence"] is True
    of.simulate(d, mesh="coarse")
    # J2 by default, the check's mesh left to the level (coarser where it has one)
    assert seen["law"] == "j2" and seen["check_mesh"] is None
    assert seen["convergence"] is False
    for bad in ({"law": "tresca"}, {"check_mesh": "sideways"}):
        with pytest.raises(InvalidParameterError):
            of.simulate(d, **bad)
