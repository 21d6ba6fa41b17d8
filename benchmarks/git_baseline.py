"""The package as an earlier commit had it, importable beside today's.

``load(commit)`` extracts ``onefold_cad/`` of ``commit`` from this repository
(``git archive``) into a temporary folder, renamed ``onefold_cad_<commit>``
with its own imports rewritten, and imports it: a benchmark can then time the
old code and the new interleaved in one process, on the same inputs. Returns
None (and the reason) when git or the commit is not there (a shallow clone, a
source tarball). ``extract(commit, dest)`` puts ``onefold_cad/`` and ``templates/`` of
``commit`` under ``dest`` as they are, for a benchmark that runs the old
package in a process of its own. Nothing here is part of the package.
"""

from __future__ import annotations

import importlib
import re
import subprocess
import sys
import tarfile
import tempfile
from io import BytesIO
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parent.parent

__all__ = ["extract", "load"]

_HOME: list[tempfile.TemporaryDirectory[str]] = []  # kept alive with the process


def extract(commit: str, dest: Path) -> Path:
    """``onefold_cad/`` and ``templates/`` of ``commit`` (``git archive``)
    under ``dest``; returns ``dest``."""
    tar = subprocess.run(
        ["git", "-C", str(ROOT), "archive", commit, "onefold_cad", "templates"],
        capture_output=True,
        check=True,
    ).stdout
    with tarfile.open(fileobj=BytesIO(tar)) as archive:
        archive.extractall(dest, filter="data")
    return dest


def load(commit: str) -> tuple[ModuleType | None, str]:
    """``(package, '')`` for the package at ``commit``, or ``(None, why not)``."""
    name = "onefold_cad_" + re.sub(r"\W", "_", commit)
    if name in sys.modules:
        return sys.modules[name], ""
    try:
        tar = subprocess.run(
            ["git", "-C", str(ROOT), "archive", commit, "onefold_cad"],
            capture_output=True,
            check=True,
        ).stdout
    except (OSError, subprocess.CalledProcessError) as exc:
        return None, f"git archive {commit} failed ({exc})"
    home = tempfile.TemporaryDirectory(prefix="onefold-baseline-")
    _HOME.append(home)
    dest = Path(home.name) / name
    with tarfile.open(fileobj=BytesIO(tar)) as archive:
        for member in archive.getmembers():
            if not member.isfile() or not member.name.endswith(".py"):
                continue
            text = archive.extractfile(member).read().decode("utf-8")  # type: ignore[union-attr]
            text = re.sub(r"\bonefold_cad\b", name, text)
            out = dest / Path(member.name).relative_to("onefold_cad")
            out.parent.mkdir(parents=True, exist_ok=True)
            out.write_text(text, encoding="utf-8")
    sys.path.insert(0, home.name)
    try:
        return importlib.import_module(name), ""
    except Exception as exc:  # an old tree that does not import here
        return None, f"the package at {commit} does not import ({exc})"
