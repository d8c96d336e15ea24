"""Entry point of the ``knotmech`` command.

Library errors (:class:`knotmech.errors.KnotmechError`) and argument errors become
one line on stderr and exit status 2; no traceback reaches the user.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from knotmech.errors import KnotmechError

#: subcommand modules, in the order ``knotmech --help`` lists them
SUBCOMMANDS = ("tour", "hold", "simulate", "diagnose", "validate")


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose errors are one line and exit status 2."""

    def error(self, message):  # noqa: D401 - argparse API
        self.exit(2, f"{self.prog}: error: {message}\n")


def build_parser() -> argparse.ArgumentParser:
    from knotmech import __version__

    parser = _Parser(
        prog="knotmech",
        description="Mechanics of capstans and knots: closed forms, DER simulation, diagnosis.",
    )
    parser.add_argument("--version", action="version", version=f"knotmech {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for name in SUBCOMMANDS:
        try:
            module = importlib.import_module(f"knotmech.cli.{name}")
        except ModuleNotFoundError as exc:  # a subcommand not built yet
            if exc.name == f"knotmech.cli.{name}":
                continue
            raise
        module.register(sub)
    return parser


def main(argv=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
    try:
        return int(args.func(args) or 0)
    except KnotmechError as exc:
        print(f"knotmech {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"knotmech {args.command}: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
