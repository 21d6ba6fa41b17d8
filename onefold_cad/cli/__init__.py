"""The ``onefold`` command: build, solve, templates, explore, fit, hops,
sweep, simulate, site, compensate and loads (:data:`.commands.COMMANDS`, the one list).

``onefold_cad.cli.main.main(argv=None) -> int`` is the entry point (``onefold``
and ``python -m onefold_cad``), so tests can call it directly. Every error of
the package, every usage error and every OSError becomes one line ``onefold:
error: ...`` on stderr and exit status 2; warnings are lines ``onefold:
warning: ...``. The parsers are :mod:`.parser`'s, ``build`` is :mod:`.build`,
``simulate`` :mod:`.simulate`, ``site`` :mod:`.site` (its parser
:mod:`.site_parser`), the Hops parser :mod:`.hops_parser`, the other
commands :mod:`.commands`, the text summary :mod:`.summary`, the progress
and warning lines :mod:`.output`, the help layout :mod:`.help_format`.
"""
