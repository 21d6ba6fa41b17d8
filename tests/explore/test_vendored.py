"""three.js is vendored unchanged, with its licence, at the version recorded."""

from __future__ import annotations

import hashlib
import re
from importlib.resources import files

THREE = files("onefold_cad.explore").joinpath("static", "three")


def _record() -> tuple[str, dict[str, str]]:
    text = THREE.joinpath("VENDORED.txt").read_text()
    version = re.search(r"^version: (\S+)$", text, re.M).group(1)
    found = re.findall(r"^  ([0-9a-f]{64})  (\S+)$", text, re.M)
    sums = {name: digest for digest, name in found}
    return version, sums


def test_the_vendored_files_are_the_recorded_ones():
    _, sums = _record()
    assert set(sums) == {"three.module.js", "three.core.js", "OrbitControls.js", "LICENSE"}
    for name, digest in sums.items():
        assert hashlib.sha256(THREE.joinpath(name).read_bytes()).hexdigest() == digest, name


def test_the_build_is_the_recorded_version_under_the_mit_licence():
    version = _record()[0]
    core = THREE.joinpath("three.core.js").read_text()
    assert re.search(r"const REVISION = '(\d+)'", core).group(1) == version.split(".")[1]
    assert THREE.joinpath("LICENSE").read_text().startswith("The MIT License")
    assert "from './three.core.js'" in THREE.joinpath("three.module.js").read_text()
