"""docs/mechanics.md's table of every shipped template simulated as steel.

Runs ``onefold simulate TEMPLATE [flags] --json -q`` for each template (the
normal mesh, with the convergence check) and pastes the table into
docs/mechanics.md between ``<!-- BEGIN mechanics-templates -->`` and
``<!-- END mechanics-templates -->``. The two steel templates run as shipped;
the others carry no steel (paper, or no thickness, or the paper's fan model),
so they run as 1 mm 304 stainless with the exact model: the flags are in the
table, so every row is a command anyone can rerun.

Run from the repository root::

    .venv/bin/python docs/make_mechanics_templates.py [--mesh normal] [--only NAME ...]
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benchmarks"))

from docs_block import machine_line, write_block  # noqa: E402

from onefold_cad.templates import list_templates, load_template  # noqa: E402

#: 304 stainless (the patkau template's values), for templates that have none.
STEEL = ["--youngs-modulus", "193", "--poisson", "0.29", "--yield-stress", "215",
         "--density", "8000"]  # fmt: skip


def flags_for(name: str) -> list[str]:
    """The flags that make a template simulable (none for the steel ones)."""
    design = load_template(name)
    m = design.material
    if design.model.value == "exact" and m.thickness > 0 and m.youngs_modulus is not None:
        return []
    out = [*STEEL]
    if design.model.value != "exact":
        out += ["--model", "exact"]
    out += ["--thickness", "1"]
    if m.relief_hole is not None and m.relief_hole <= 0:
        out += ["--relief-hole", "4"]
    return out


def simulate(name: str, flags: list[str], mesh: str) -> tuple[dict, float]:
    """The report's ``simulation`` section and the command's CPU time (s, user +
    system of the process, imports included)."""
    exe = shutil.which("onefold", path=str(Path(sys.executable).parent)) or "onefold"
    argv = [exe, "simulate", name, *flags, "--mesh", mesh, "--json", "-q"]
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        proc = subprocess.Popen(argv, stdout=out, stderr=err, text=True)
        _, status, usage = os.wait4(proc.pid, 0)
        proc.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        if proc.returncode:
            raise SystemExit(f"{' '.join(argv)} failed:\n{err.read()}")
        return json.loads(out.read())["simulation"], usage.ru_utime + usage.ru_stime


def fmt(x: float | None, digits: str = ".4g") -> str:
    return "-" if x is None else format(x, digits)


def row(name: str, flags: list[str], sim: dict, cpu: float) -> str:
    u = sim["units"]
    f, r, s = sim["formed"], sim["released"], sim["standing"]
    conv = sim.get("convergence") or {}
    change = conv.get("max_deviation_change")
    stands = f"yes ({s['tipping_margin_deg']:.3g} deg)" if s["stands"] else f"no: {s['reason']}"
    command = f"`{name}{(' ' + ' '.join(flags)) if flags else ''}`"
    return (
        f"| {command} | {sim['mesh']['nodes']} | {100 * f['plastic_area_share']:.3g} % "
        f"(to {fmt(f['plastic_radius_max'])} {u}) | {f['bending_energy_J']:.4g} | "
        f"{fmt(r['max_deviation'])} / {fmt(r['rms_deviation'])} {u} | "
        f"{fmt(s['max_deviation'])} / {fmt(s['rms_deviation'])} {u} | {stands} | "
        f"{fmt(s['max_stress_MPa'])} | {'-' if change is None else f'{100 * change:.2g} %'} | "
        f"{cpu:.1f} |"
    )


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--mesh", default="normal")
    ap.add_argument("--only", nargs="+")
    args = ap.parse_args(argv)
    names = args.only or [t.name for t in list_templates()]
    rows = [
        "| template and flags | nodes | formed: plastic share (to r) | work of bending (J) | "
        "released: deviation max / rms | standing (anchored): deviation max / rms | stands "
        "(tipping margin) | largest stress (MPa) | convergence change | CPU (s) |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for name in names:
        flags = flags_for(name)
        sim, cpu = simulate(name, flags, args.mesh)
        rows.append(row(name, flags, sim, cpu))
        print(rows[-1], file=sys.stderr, flush=True)
    body = "\n".join(rows) + "\n\n" + machine_line()
    print(body)
    if not args.only:
        command = "docs/make_mechanics_templates.py " + " ".join(argv or sys.argv[1:])
        write_block("mechanics-templates", body, command.strip(), ROOT / "docs" / "mechanics.md")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
