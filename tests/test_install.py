"""The package as pip installs it from a wheel: the shipped templates travel
inside it (package data), so ``onefold templates`` and ``onefold build NAME``
work whatever the install scheme, run from a folder that is not the
repository."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

from tests.shipped import DESIGN_TEMPLATES, REPO_TEMPLATES

REPO = Path(__file__).resolve().parents[1]
#: What the wheel is built from (a copy, so the build writes nothing into the checkout).
SOURCES = ("pyproject.toml", "setup.py", "MANIFEST.in", "README.md", "onefold_cad", "templates")


def _pip(*args: str, cwd: Path, python: str = sys.executable, env: dict | None = None) -> None:
    done = subprocess.run(
        [python, "-m", "pip", "--disable-pip-version-check", "-q", *args],
        cwd=cwd, capture_output=True, text=True, timeout=300, env=env,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-2000:]


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> Path:
    """The wheel ``pip wheel . --no-deps`` builds of a copy of the checkout."""
    root = tmp_path_factory.mktemp("wheel")
    src = root / "src"
    for name in SOURCES:
        path = REPO / name
        if path.is_dir():
            shutil.copytree(path, src / name, ignore=shutil.ignore_patterns("__pycache__"))
        else:
            src.mkdir(exist_ok=True)
            shutil.copy2(path, src / name)
    _pip("wheel", ".", "--no-deps", "-w", str(root / "dist"), cwd=src)
    (found,) = (root / "dist").glob("onefold_cad-*.whl")
    return found


def test_the_wheel_carries_every_shipped_template_as_package_data(wheel):
    with zipfile.ZipFile(wheel) as z:
        shipped = sorted(Path(n).name for n in z.namelist() if n.startswith("onefold_cad/shipped/"))
        for name in shipped:
            assert z.read(f"onefold_cad/shipped/{name}") == (REPO_TEMPLATES / name).read_bytes()
    assert shipped == sorted(p.name for p in REPO_TEMPLATES.glob("*.toml"))


@pytest.mark.parametrize("scheme", ["--user", "--prefix", "--target"])
def test_an_installed_wheel_lists_and_builds_the_templates_from_another_folder(
    wheel, tmp_path, scheme
):
    base = tmp_path / "install"
    site = base / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}"
    site = site / "site-packages"
    python = sys.executable
    if scheme == "--user":
        # pip --user into PYTHONUSERBASE, with the interpreter the venv is made
        # of (a venv refuses --user); the dependencies come from this venv's
        # site-packages on PYTHONPATH, which holds no onefold_cad (editable)
        python = getattr(sys, "_base_executable", sys.executable)
        env = {**os.environ, "PYTHONUSERBASE": str(base)}
        _pip("install", "--no-deps", "--no-index", "--user", "--no-warn-script-location",
             str(wheel), cwd=tmp_path, python=python, env=env)  # fmt: skip
        env["PYTHONPATH"] = str(Path(np.__file__).resolve().parents[1])
    else:
        # --prefix: a base that is not sys.prefix; --target: a bare folder.
        # --ignore-installed: without it pip --prefix uninstalls the venv's own onefold_cad
        _pip("install", "--no-deps", "--no-index", "--ignore-installed", scheme, str(base),
             str(wheel), cwd=tmp_path)  # fmt: skip
        site = site if scheme == "--prefix" else base
        env = {**os.environ, "PYTHONPATH": str(site)}
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()

    def onefold(*args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [python, "-m", "onefold_cad", *args],
            cwd=elsewhere, env=env, capture_output=True, text=True, timeout=120,
        )  # fmt: skip

    where = subprocess.run(
        [python, "-c", "import onefold_cad; print(onefold_cad.__file__)"],
        cwd=elsewhere, env=env, capture_output=True, text=True, timeout=60,
    )  # fmt: skip
    assert Path(where.stdout.strip()).is_relative_to(site)  # the installed copy, not the checkout
    listed = onefold("templates")
    assert listed.returncode == 0, listed.stderr
    designs = listed.stdout.split("\n\n")[0]  # then the site files, after a blank line
    assert [line.split()[0] for line in designs.splitlines()] == DESIGN_TEMPLATES
    assert "site-patkau-three" in listed.stdout.split("\n\n")[1]
    built = onefold("build", "patkau-one-fold", "-o", "out", "--formats", "json")
    assert built.returncode == 0, built.stderr
    assert built.stdout.split() == [str(Path("out") / "patkau-one-fold.json")]
    assert (elsewhere / "out" / "patkau-one-fold.json").stat().st_size > 0
