"""The ``onefold`` command: build, solve, templates, explore and fit.

``onefold_cad.cli.main.main(argv=None) -> int`` is the entry point (``onefold``
and ``python -m onefold_cad``), so tests can call it directly. Every error of
the package, every usage error and every OSError becomes one line ``onefold:
error: ...`` on stderr and exit status 2; warnings are lines ``onefold:
warning: ...``. The parsers are :mod:`.parser`'s, ``build`` is :mod:`.build`,
the other commands :mod:`.commands`, the text summary :mod:`.summary`.
"""
