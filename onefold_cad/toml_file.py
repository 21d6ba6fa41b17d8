"""A TOML file read whatever its bytes: the one reader of templates and site
files (:func:`read_toml`), so that a file in another encoding or nested
thousands deep is one line naming it, not a traceback."""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

from onefold_cad.errors import InvalidParameterError

__all__ = ["MAX_TOML_DEPTH", "read_toml"]

#: The deepest nesting of tables and arrays a TOML file may have (the sites use 4).
MAX_TOML_DEPTH = 64


def read_toml(path: str | Path, parameter: str) -> dict[str, Any]:
    """The raw TOML data of a template or site file, whatever its bytes; else
    InvalidParameterError, one line naming ``parameter`` ('template', 'SITE')
    and the file: unreadable, not UTF-8, not TOML, nested over MAX_TOML_DEPTH."""
    p = Path(path)
    try:
        raw = p.read_bytes()
    except OSError as exc:
        raise InvalidParameterError(parameter, f"cannot read {str(p)!r}: {exc.strerror}") from None
    deep = f"at most {MAX_TOML_DEPTH} levels are allowed"
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except UnicodeDecodeError as exc:
        byte = raw[exc.start : exc.start + 1].hex()
        why = f"not UTF-8 text (byte 0x{byte} at offset {exc.start}); save it as UTF-8"
    except tomllib.TOMLDecodeError as exc:
        why = f"not valid TOML: {exc}"
    except RecursionError:  # the parser recurses once per level of nesting
        why = f"arrays and tables nested too deeply to read; {deep}"
    else:
        depth = _depth(data)  # measured before anything recurses into it
        if depth <= MAX_TOML_DEPTH:
            return data
        why = f"arrays and tables nested {depth} levels deep; {deep}"
    raise InvalidParameterError(parameter, f"{p}: {why}") from None


def _depth(data: object) -> int:
    """The nesting depth of parsed TOML data (a table of scalars: 1), no recursion."""
    deepest, stack = 0, [(data, 1)]
    while stack:
        value, level = stack.pop()
        deepest = max(deepest, level)
        if not isinstance(value, dict | list):
            continue
        children = value.values() if isinstance(value, dict) else value
        stack.extend((c, level + 1) for c in children if isinstance(c, dict | list))
    return deepest
