"""The old import path of the DER hold/slip tables: every name now lives in
:mod:`knotmech.verdict` (:mod:`~knotmech.verdict.criterion`: the creep criterion, its limit
and the protocol; :mod:`~knotmech.verdict.tables`: the table types and their lookups;
:mod:`~knotmech.verdict.build`: one DER point and a table built through
:func:`knotmech.sweep.sweep`). ``from knotmech.scenes.phase_table import HoldTable`` and
``phase_table.simulate_point`` keep working; new code imports from :mod:`knotmech.verdict`.
"""

from __future__ import annotations

import importlib

_HOMES = ("knotmech.verdict.criterion", "knotmech.verdict.tables", "knotmech.verdict.build")


def __getattr__(name: str):
    for home in _HOMES:
        module = importlib.import_module(home)
        if hasattr(module, name):
            return getattr(module, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted({n for home in _HOMES for n in dir(importlib.import_module(home))})


__all__ = [  # noqa: PLE0604 (the homes' public names)
    *importlib.import_module("knotmech.verdict.criterion").__all__,
    *importlib.import_module("knotmech.verdict.tables").__all__,
    *importlib.import_module("knotmech.verdict.build").__all__,
]
