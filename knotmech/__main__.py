"""``python -m knotmech``: the same as the ``knotmech`` command."""

from knotmech.cli.main import main

if __name__ == "__main__":
    raise SystemExit(main())
