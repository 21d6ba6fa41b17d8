"""Refusals through ``main()``: whatever the input, one line on stderr
naming what to change, exit status 2, no traceback, nothing written."""

from __future__ import annotations

import pytest

BAD_FILES = {
    "latin1": 'name = "t"\nunits = "mm"\ndescription = "caf\u00e9"\n'.encode("latin-1"),
    "deep": b"a = " + b"[" * 2000 + b"]" * 2000 + b"\n",
}


@pytest.mark.parametrize("kind", sorted(BAD_FILES))
@pytest.mark.parametrize("command", ["solve", "build", "site"])
def test_a_bad_file_is_one_line(cli, tmp_path, kind, command):
    p = tmp_path / f"{kind}.toml"
    p.write_bytes(BAD_FILES[kind])
    out = tmp_path / "out"
    args = [command, str(p)] + ([] if command == "solve" else ["-o", str(out)])
    rc, _, err = cli(*args)
    assert rc == 2
    assert len(err.splitlines()) == 1, err
    name = "SITE" if command == "site" else "template"
    assert err.startswith(f"onefold: error: {name}: {p}: ")
    assert not out.exists()
