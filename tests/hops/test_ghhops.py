"""ghhops-server is imported with its logging kept to ghhops' own logger."""

from __future__ import annotations

import subprocess
import sys


def test_other_libraries_debug_lines_stay_quiet_and_hops_keeps_its_own():
    code = (
        "import logging\n"
        "import onefold_cad.hops.server\n"
        "from onefold_cad.hops.ghhops import hlogger\n"
        "logging.getLogger('PIL.PngImagePlugin').debug('a debug line of another library')\n"
        "hlogger.setLevel(logging.INFO)\n"
        "hlogger.info('a request line')\n"
        "print(logging.getLogger().level)\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    assert "another library" not in proc.stderr
    assert proc.stderr == "[INFO] a request line\n"
    assert proc.stdout == f"{30}\n"  # the root logger's default level, WARNING
