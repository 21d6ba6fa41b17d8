"""Odd values into the commands' flags: does bad input get one clear line?

Runs the installed ``onefold`` once per (command, flag, value) for the values
of :data:`VALUES` (NaN, infinities, zero, subnormals, huge, empty, words) and
reports every run that breaks the project's rule for bad input: an exit
status other than 0, 1 or 2, a Python traceback on stderr, or on status 2
more than one line of stderr or any file written. Runs past ``--timeout``
are listed apart (slow, not wrong). ``simulate`` runs on the coarse mesh
(unless ``--mesh`` is the flag tried), a sweep on two designs and a build
of the DXF and the JSON report (unless ``--formats`` is the flag tried).

Run from the repository root::

    .venv/bin/python scripts/fuzz_cli_values.py [--timeout 120] [--only sweep simulate ...]
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

VALUES = ("nan", "inf", "-inf", "-1", "0", "-0", "1e308", "1e-320", "", "abc", "90")
FLAGS = {
    "sweep": ("--samples", "--seed", "--objectives", "--vary", "--sampler", "--measure",
              "--scheduler", "--mesh", "--supports", "--alpha", "--thickness",
              "--youngs-modulus", "--yield-stress", "--density", "--poisson"),
    "simulate": ("--supports", "--reference", "--crease", "--mesh", "--alpha", "--thickness",
                 "--youngs-modulus", "--poisson", "--yield-stress", "--density",
                 "--bend-radius", "--k-factor", "--relief-hole"),
    "fit": ("--height", "--span", "--depth", "--min-tipping-margin"),
    "solve": ("--alpha", "--beta", "--hc", "--radius", "--divisions", "--x-plus", "--polygon",
              "--rectangle", "--apex-fraction", "--thickness", "--bend-radius", "--k-factor",
              "--kerf", "--relief-hole", "--density", "--units", "--model", "--sheet-surface",
              "--name"),
    "build": ("--formats", "--body", "--compensation", "--placement", "--name", "--thickness",
              "--bend-radius", "--k-factor", "--kerf", "--relief-hole", "--alpha", "--beta"),
}  # fmt: skip


def _argv(exe: str, command: str, flag: str, value: str, out: Path) -> list[str]:
    argv = [exe, command, "patkau-one-fold", flag, value]
    if command == "sweep":
        argv += ["-o", str(out / "sweep"), "--no-images"]
        argv += [] if flag == "--vary" else ["--vary", "alpha=30,40"]
        argv += ["--measure", "simulate"] if flag in ("--mesh", "--supports") else []
    if command == "simulate" and flag != "--mesh":
        argv += ["--mesh", "coarse"]
    if command == "fit" and flag != "--height":
        argv += ["--height", "3000"]
    if command == "build":
        argv += (
            ["-o", str(out / "build"), "--formats", "dxf,json"]
            if flag != "--formats"
            else ["-o", str(out / "build")]
        )
    return argv


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--timeout", type=float, default=120.0, help="seconds a run may take")
    ap.add_argument("--only", nargs="*", choices=sorted(FLAGS), help="these commands only")
    args = ap.parse_args(argv)
    exe = str(Path(sys.executable).parent / "onefold")
    broken, slow, runs = [], [], 0
    for command in args.only or FLAGS:
        for flag in FLAGS[command]:
            for value in VALUES:
                out = Path(tempfile.mkdtemp(prefix="fuzz-cli-"))
                cmd = _argv(exe, command, flag, value, out)
                runs += 1
                try:
                    p = subprocess.run(
                        cmd, capture_output=True, text=True, timeout=args.timeout, cwd=out
                    )
                except subprocess.TimeoutExpired:
                    slow.append(cmd[1:])
                    shutil.rmtree(out, ignore_errors=True)
                    continue
                lines = p.stderr.strip().splitlines()
                wrote = sorted(f.name for f in out.iterdir())
                if (
                    p.returncode not in (0, 1, 2)
                    or "Traceback" in p.stderr
                    or (p.returncode == 2 and (len(lines) != 1 or wrote))
                ):
                    broken.append((p.returncode, cmd[1:], lines[-2:], wrote))
                shutil.rmtree(out, ignore_errors=True)
    for b in broken:
        print("BROKEN", *b)
    for s in slow:
        print(f"SLOW (over {args.timeout:g} s)", s)
    print(f"{runs} runs: {len(broken)} broken, {len(slow)} over {args.timeout:g} s")
    return 1 if broken else 0


if __name__ == "__main__":
    raise SystemExit(main())
