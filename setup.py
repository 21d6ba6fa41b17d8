"""The build's one step beyond pyproject.toml: ship the repository's
``templates/*.toml`` inside the package, as ``onefold_cad/shipped/``.

The templates stay in ``templates/`` at the repository's root (the README and
the docs name ``templates/NAME.toml`` paths, and a source checkout or an
editable install reads them there); a wheel, and so every install scheme
(``pip install .``, ``--user``, ``--prefix``, ``--target``), carries them as
package data, found with :mod:`importlib.resources`
(:func:`onefold_cad.templates.template_dirs`).
"""

from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

HERE = Path(__file__).resolve().parent


class BuildWithTemplates(build_py):
    """``build_py`` that also copies ``templates/*.toml`` to ``onefold_cad/shipped/``."""

    def run(self) -> None:
        super().run()
        dest = Path(self.build_lib) / "onefold_cad" / "shipped"
        self.mkpath(str(dest))
        for src in sorted((HERE / "templates").glob("*.toml")):
            self.copy_file(str(src), str(dest / src.name))


setup(cmdclass={"build_py": BuildWithTemplates})
