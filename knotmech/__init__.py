"""knotmech: mechanics of capstans and knots.

The public API is re-exported here explicitly. Implementation lives in the
subpackages: :mod:`knotmech.analytic` (closed forms, importable alone),
:mod:`knotmech.rod` (the discrete-elastic-rods solver with frictional contact),
:mod:`knotmech.scenes` (the papers' experiments in simulation),
:mod:`knotmech.diagnose` (the mismatch engine), :mod:`knotmech.sweep` (parallel,
cached parameter sweeps) and :mod:`knotmech.plotting`.

``knotmech.hold(knot, ...)`` is the hold verdict (:func:`knotmech.verdict.hold`, loaded on
first use); :mod:`knotmech.knots` is the knot registry. Only the closed forms are imported eagerly;
``knotmech.rod``, ``knotmech.scenes`` and ``knotmech.diagnose`` load on first attribute
access (numba compilation and SciPy imports cost seconds that a classroom using
``mu_eff`` should not pay).
"""

from __future__ import annotations

import importlib

__version__ = "0.1.0"

from knotmech.analytic import *  # noqa: F403  (explicit list in analytic.__all__)
from knotmech.analytic import __all__ as _analytic_all
from knotmech.errors import InputError, KnotmechError, RecordingError, SolverError

_LAZY_SUBPACKAGES = (
    "rod",
    "scenes",
    "diagnose",
    "sweep",
    "plotting",
    "units",
    "materials",
    "knots",
    "verdict",
)
_LAZY_NAMES = {
    # name: (module, attribute)
    "simulate": ("knotmech.rod", "simulate"),
    "diagnose_recording": ("knotmech.diagnose", "diagnose"),
    "read_recording": ("knotmech.diagnose", "read_recording"),
    "sweep_parameters": ("knotmech.sweep", "sweep"),
    "parse_quantity": ("knotmech.units", "parse_quantity"),
    "hold": ("knotmech.verdict", "hold"),
    "Verdict": ("knotmech.verdict", "Verdict"),
    "hold_verdict": ("knotmech.verdict", "hold_verdict"),
    "material": ("knotmech.materials", "material"),
}

__all__ = [
    "__version__",
    "KnotmechError",
    "InputError",
    "SolverError",
    "RecordingError",
    *_analytic_all,
    *_LAZY_NAMES,
    *_LAZY_SUBPACKAGES,
]


# ``knotmech.hold_verdict`` is the deprecated alias of ``knotmech.hold`` (same verdict as the
# command), loaded lazily below; the closed forms' own answer the star import brought in stays
# ``knotmech.analytic.hold_verdict``
del hold_verdict  # noqa: F821 (star-imported above)


def __getattr__(name: str):
    if name in _LAZY_SUBPACKAGES:
        return importlib.import_module(f"knotmech.{name}")
    if name in _LAZY_NAMES:
        module, attr = _LAZY_NAMES[name]
        return getattr(importlib.import_module(module), attr)
    raise AttributeError(f"module 'knotmech' has no attribute {name!r}")
