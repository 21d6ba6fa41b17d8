"""onefold's side of the CalculiX forming benchmark (``calculix_forming.py
--onefold``): the public command ``onefold simulate TEMPLATE --json`` for each
mesh, crease model and law, each a child process timed by its wall and CPU
time (``getrusage`` of the children), so the numbers and the times sit beside
CalculiX's in one run."""

from __future__ import annotations

import json
import resource
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]


def _child(cmd: list[str]) -> tuple[str, float, float]:
    """Run ``cmd`` from the repository root: ``(stdout, wall s, CPU s)``."""
    ru0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, check=True)
    wall = time.perf_counter() - t0
    ru1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = ru1.ru_utime + ru1.ru_stime - ru0.ru_utime - ru0.ru_stime
    return proc.stdout, wall, cpu


def onefold_side(
    template: str,
    meshes: list[str],
    creases: list[str],
    laws: tuple[str, ...] = ("moment",),
    extra: tuple[str, ...] = (),
) -> list[dict[str, Any]]:
    """``onefold simulate TEMPLATE --json`` (and the flags ``extra``) for each
    mesh, crease model and ``--law`` (``moment`` or ``j2``: the laws of
    ``onefold simulate``): the formed plastic share, the springback's max and
    rms deviation after the best fit, the share that yields again, wall and
    CPU time."""
    rows: list[dict[str, Any]] = []
    for mesh, crease, law in ((m, c, w) for m in meshes for c in creases for w in laws):
        cmd = [sys.executable, "-m", "onefold_cad", "simulate", template, "--json", "-q"]
        cmd += ["--mesh", mesh, "--crease", crease, "--law", law, *extra]
        out, wall, cpu = _child(cmd)
        sim = json.loads(out)["simulation"]
        rows.append(
            {
                "what": " ".join(
                    ["onefold simulate --mesh", mesh, "--crease", crease, "--law", law, *extra]
                ),
                "plastic_share": sim["formed"]["plastic_area_share"],
                "springback_max": sim["released"]["max_deviation"],
                "springback_rms": sim["released"]["rms_deviation"],
                "yields_again_share": sim["released"].get("reloaded_area_share"),
                "wall_s": wall,
                "cpu_s": cpu,
            }
        )
    return rows
