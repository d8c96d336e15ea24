"""The ``knotmech`` command line: parses, calls the public API, prints.

Nothing in the library imports this package. Each subcommand lives in its own
module exposing ``register(subparsers)``, which adds its parser and sets
``func(args) -> int`` as the default.
"""
