"""The package's version (``onefold_cad.__version__``), in a module of its own
so that every layer can name it without importing the package's public API.

One source: ``version`` in pyproject.toml, read back from the installed
package's metadata (``onefold --version`` prints it). It is read on first
use (PEP 562): importlib.metadata loads csv, email and zipfile, which a
command that does not ask for the version should not pay for."""

from __future__ import annotations

__all__ = ["__version__"]  # noqa: F822 - read on first use (__getattr__)


def __getattr__(name: str) -> str:
    if name != "__version__":
        raise AttributeError(f"module 'onefold_cad.version' has no attribute {name!r}")
    from importlib.metadata import PackageNotFoundError, version

    try:
        value = version("onefold_cad")
    except PackageNotFoundError:  # run from a source tree that was never installed
        value = "0+unknown"
    globals()["__version__"] = value  # later look-ups skip this function
    return value
