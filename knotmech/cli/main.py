"""Entry point of the ``knotmech`` command.

Library errors (:class:`knotmech.errors.KnotmechError`) and argument errors become
one line on stderr and exit status 2; no traceback reaches the user.
"""

from __future__ import annotations

import argparse
import importlib
import os
import re
import sys

from knotmech.errors import KnotmechError

#: subcommand modules, in the order ``knotmech --help`` lists them
SUBCOMMANDS = ("tour", "hold", "simulate", "diagnose", "validate")


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose errors are one line and exit status 2."""

    def error(self, message):  # noqa: D401 - argparse API
        self.exit(2, f"{self.prog}: error: {message}\n")


#: one-line summaries for ``knotmech --help``, which lists the commands without importing
#: their modules (each module's own ``help=`` says the same; tests/cli/test_startup.py checks)
SUMMARIES = {
    "tour": "a short tour: closed forms, a hold verdict and a figure",
    "hold": "does a rope tied to a post hold a load? (closed forms; DER tables and runs for "
    "the hitches, DER pulls for the bends)",
    "simulate": "run a simulated experiment (capstan, two-loops, pinch, overhand, the "
    "hitches, the bends, centreline)",
    "diagnose": "find where a recording differs from its baseline model and name the missing "
    "physics",
    "validate": "run the validation cases (theory vs simulation), write PNG, JSON and index.html",
}


def build_parser(only: str | None = None, *, listing: bool = False) -> argparse.ArgumentParser:
    """Build the parser.

    With ``only``, import just that subcommand's module (fast start-up); with ``listing``,
    import none and list the commands from :data:`SUMMARIES` (``--help``, ``--version``).
    """
    from knotmech import __version__

    parser = _Parser(
        prog="knotmech",
        description="Mechanics of capstans and knots: closed forms, DER simulation, diagnosis.",
        epilog="`knotmech COMMAND --help` describes a command's options.",
    )
    parser.add_argument("--version", action="version", version=f"knotmech {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for name in SUBCOMMANDS if only is None else (only,):
        if listing:
            sub.add_parser(name, help=SUMMARIES[name], add_help=False)
        else:
            importlib.import_module(f"knotmech.cli.{name}").register(sub)
    return parser


def _join_negative_values(argv: list[str]) -> list[str]:
    """Turn ``--opt -4mm`` into ``--opt=-4mm``.

    argparse takes ``-4mm`` for an option; joining it lets the physical check say
    "must be > 0" instead of "expected one argument".
    """
    out: list[str] = []
    for token in argv:
        if (
            out
            and out[-1].startswith("--")
            and "=" not in out[-1]
            and re.match(r"^-(\d|\.\d|inf|nan)", token, flags=re.IGNORECASE)
        ):
            out[-1] = f"{out[-1]}={token}"
        else:
            out.append(token)
    return out


#: options that collect a list and may be given more than once (``simulate centreline
#: --ends``, once per rod; ``validate --only``); every other option given twice is refused
REPEATABLE = frozenset({"--ends", "--only"})


def repeated_option(argv: list[str]) -> str | None:
    """The first long option given twice in ``argv`` (``--mu 1 --mu=2``), None when none is
    (options of :data:`REPEATABLE` may repeat; nothing after ``--`` is an option)."""
    seen = set()
    for token in argv:
        if token == "--":
            break
        if not token.startswith("--"):
            continue
        name = token.split("=", 1)[0]
        if name in seen and name not in REPEATABLE:
            return name
        seen.add(name)
    return None


def main(argv=None) -> int:
    """Run the command line; return the exit status (0 success, 1 a failed run, 2 bad input)."""
    argv = _join_negative_values(list(sys.argv[1:] if argv is None else argv))
    # Importing every subcommand costs seconds (numba, scipy); import only the one asked for,
    # and none for `knotmech`, `knotmech --help` or `knotmech --version`.
    only = argv[0] if argv and argv[0] in SUBCOMMANDS else None
    parser = build_parser(only, listing=only is None)
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # --help, --version, or an argument error (already printed)
        return exc.code if isinstance(exc.code, int) else 2
    if not getattr(args, "func", None):  # `knotmech` alone: the usage, and why it stopped
        parser.print_help(sys.stderr)
        print(f"knotmech: error: give a command ({', '.join(SUBCOMMANDS)})",
              file=sys.stderr)  # fmt: skip
        return 2
    twice = repeated_option(argv)
    if twice is not None:  # argparse would silently keep the last value
        print(f"knotmech {args.command}: error: {twice} is given twice; give it once",
              file=sys.stderr)  # fmt: skip
        return 2
    try:
        return int(args.func(args) or 0)
    except KnotmechError as exc:
        print(f"knotmech {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"knotmech {args.command}: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # output piped into `head` and closed early
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
