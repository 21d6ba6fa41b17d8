"""scripts/compare_builds.py: equal folders pass, and each kind of change it
exists to catch (a byte of a DXF, a report value, a file missing, a STEP
whose shape changed) is told apart; a report's timings alone are not."""

from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path
from types import ModuleType

import pytest

SCRIPT = Path(__file__).resolve().parents[1] / "scripts" / "compare_builds.py"


@pytest.fixture(scope="module")
def compare_builds() -> ModuleType:
    spec = importlib.util.spec_from_file_location("onefold_compare_builds", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def _report(seconds: float, mass: float) -> str:
    return json.dumps({"mass_kg": mass, "timings_s": {"step": seconds}, "sheets": [{}]})


@pytest.fixture
def folders(tmp_path: Path) -> tuple[Path, Path]:
    base, new = tmp_path / "base", tmp_path / "new"
    for d, seconds in ((base, 1.25), (new, 3.5)):
        (d / "north").mkdir(parents=True)
        (d / "x.dxf").write_bytes(b"0\nSECTION\n")
        (d / "north" / "x-bends.csv").write_text("bend,angle\n1,90\n")
        (d / "x.json").write_text(_report(seconds, 12.5))
    return base, new


def test_equal_folders_pass_though_the_timings_differ(compare_builds, folders, capsys):
    base, new = folders
    assert compare_builds.main([str(base), str(new)]) == 0
    assert "3 of 3 files equal, 0 differ" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("change", "expected"),
    [
        (lambda d: (d / "x.dxf").write_bytes(b"0\nSECTION \n"), "x.dxf: bytes differ"),
        (lambda d: (d / "x.json").write_text(_report(3.5, 12.6)), "x.json: JSON differs"),
        (lambda d: (d / "north" / "x-bends.csv").unlink(), "only in BASE_DIR"),
        (lambda d: (d / "extra.fold").write_text("{}"), "extra.fold: only in NEW_DIR"),
    ],
    ids=["dxf-byte", "report-value", "missing", "extra"],
)
def test_a_change_is_found(compare_builds, folders, capsys, change, expected):
    base, new = folders
    change(new)
    assert compare_builds.main([str(base), str(new)]) == 1
    out = capsys.readouterr().out
    assert expected in out and "1 differ" in out


def test_a_step_whose_volume_changed_is_found(compare_builds, tmp_path, capsys):
    from build123d import Box, export_step

    base, new = tmp_path / "base", tmp_path / "new"
    base.mkdir()
    new.mkdir()
    export_step(Box(1, 2, 3), str(base / "p.step"))
    export_step(Box(1, 2, 3), str(new / "p.step"))
    assert compare_builds.compare(base, new)[0][1] in (
        None,
        "STEP bytes differ (same topology and volume)",
    )
    export_step(Box(1, 2, 4), str(new / "p.step"))
    ((name, why),) = compare_builds.compare(base, new)
    assert name == "p.step" and why.startswith("STEP shape differs: volume 6.0")
    assert "area" in why and "faces" not in why


def test_a_missing_folder_is_refused(compare_builds, tmp_path, capsys):
    assert compare_builds.main([str(tmp_path), str(tmp_path / "nowhere")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "NEW_DIR" in err and "is not a folder" in err
