"""The package's version (``onefold_cad.__version__``), in a module of its own
so that every layer can name it without importing the package's public API.

One source: ``version`` in pyproject.toml, read back from the installed
package's metadata (``onefold --version`` prints it)."""

from importlib.metadata import PackageNotFoundError, version

__all__ = ["__version__"]

try:
    __version__ = version("onefold_cad")
except PackageNotFoundError:  # run from a source tree that was never installed
    __version__ = "0+unknown"
