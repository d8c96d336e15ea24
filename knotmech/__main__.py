"""``python -m knotmech``: the same as the ``knotmech`` command (same exit status)."""

import sys

from knotmech.cli.main import main

if __name__ == "__main__":
    sys.exit(main())
