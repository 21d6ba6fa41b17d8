"""What the CLI and pipeline benchmarks share: the machine they ran on and how
they paste their tables into docs/benchmarks.md (between ``<!-- BEGIN name -->``
and ``<!-- END name -->``, with the command and the date)."""

from __future__ import annotations

import os
import platform
import re
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs" / "benchmarks.md"

__all__ = ["DOCS", "ROOT", "machine_info", "machine_line", "write_block"]


def machine_info() -> dict[str, str]:
    """CPU model (from /proc/cpuinfo), core count, Python, numpy and OS."""
    import numpy as np

    cpu = platform.processor() or "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {
        "cpu": cpu,
        "cores": str(os.cpu_count()),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "os": f"{platform.system()} {platform.release()}",
    }


def machine_line() -> str:
    """One sentence naming the machine."""
    m = machine_info()
    return (
        f"Machine: {m['cpu']}, {m['cores']} cores, {m['os']}; Python {m['python']}, "
        f"numpy {m['numpy']}."
    )


def write_block(name: str, body: str, command: str, path: Path = DOCS) -> None:
    """Replace block ``name`` of ``path`` with ``body``, stamped with the command and date."""
    text = path.read_text()
    pat = re.compile(
        rf"(<!-- BEGIN {re.escape(name)} -->\n).*?(<!-- END {re.escape(name)} -->)", re.S
    )
    if not pat.search(text):
        raise SystemExit(f"{path}: markers for {name!r} not found")
    block = f"Generated on {time.strftime('%Y-%m-%d')} by `{command}`.\n\n{body}\n"
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(pat.sub(lambda m: m.group(1) + block + m.group(2), text))
    os.replace(tmp, path)
