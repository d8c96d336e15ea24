"""The experiment kinds of ``knotmech diagnose``: one module each, registered here.

A new kind is one module with an :class:`~knotmech.diagnose.experiments.base.Experiment`
subclass and one line below. :func:`get_experiment` is the one lookup by name.
"""

from __future__ import annotations

from knotmech.diagnose.experiments.base import Experiment, Stages
from knotmech.diagnose.experiments.capstan_hold import CapstanHold
from knotmech.diagnose.experiments.capstan_pull import CapstanPull
from knotmech.diagnose.experiments.knot_pull import KnotPull
from knotmech.diagnose.experiments.pinch import Pinch
from knotmech.diagnose.experiments.tension_profile import TensionProfile
from knotmech.errors import InputError

__all__ = ["Experiment", "Stages", "EXPERIMENT_KINDS", "get_experiment"]

#: kind name -> Experiment, in the order of the spec (later kinds appended)
EXPERIMENT_KINDS: dict[str, Experiment] = {}


def _register(exp: Experiment) -> None:
    if exp.name in EXPERIMENT_KINDS:  # pragma: no cover - a programming error
        raise ValueError(f"experiment {exp.name!r} registered twice")
    EXPERIMENT_KINDS[exp.name] = exp


_register(CapstanPull())
_register(Pinch())
_register(TensionProfile())
_register(CapstanHold())
_register(KnotPull())


def get_experiment(name: str) -> Experiment:
    """The experiment kind called ``name``.

    Raises
    ------
    InputError
        Unknown kind (the message lists the known ones).
    """
    try:
        return EXPERIMENT_KINDS[str(name)]
    except KeyError:
        raise InputError(
            f"unknown experiment {name!r} (allowed: {', '.join(EXPERIMENT_KINDS)})"
        ) from None
