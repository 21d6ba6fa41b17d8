"""``python -m onefold_cad``: the ``onefold`` command."""

from onefold_cad.cli.main import main

if __name__ == "__main__":
    raise SystemExit(main())
