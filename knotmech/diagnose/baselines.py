r"""A baseline plus effects as one model, and the baseline families.

A :class:`Model` is one experiment kind's baseline
(:mod:`knotmech.diagnose.experiments`) plus a tuple of catalogue effects
(:mod:`knotmech.diagnose.effects`): its free parameters are the baseline's, then
each effect's (in registry order), with bounds from the recording; its mean is the
experiment's, each effect acting at the stages it implements, so effects compose
freely. Baselines and augmentations are documented in the experiment and effect
modules.

The baseline family is chosen with :func:`get_baseline`: ``closed-form`` (every
kind) or ``der`` (``capstan_pull``; :mod:`knotmech.diagnose.der`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from knotmech.analytic.pinch import pinch_load_parameter
from knotmech.diagnose.experiments import Experiment, get_experiment
from knotmech.diagnose.recording import Recording
from knotmech.errors import InputError

__all__ = [
    "Model",
    "build_model",
    "canonical_effects",
    "get_baseline",
    "BASELINES",
    "MEANS",
    "pinch_load_parameter",
]


def canonical_effects(added) -> tuple:
    """``added`` (Effect objects, repeats allowed), each once, in registry order."""
    out = {}
    for e in added:
        out.setdefault(e.name, e)
    return tuple(sorted(out.values(), key=lambda e: e.rank))


@dataclass
class Model:
    """A baseline plus effects, with free and fixed parameters.

    Attributes
    ----------
    rec : Recording
    effects : tuple of str
        Effect names in the order they were added (``self_contact_nip`` may repeat).
    names : list of str
        Free parameter names (the order of parameter vectors).
    lower, upper : arrays
        Bounds of the free parameters.
    fixed : dict
        Parameters held fixed (nip positions).
    experiment : Experiment
    effect_objects_added : tuple of Effect
        The effects as added (``effects`` are their names).
    """

    rec: Recording
    effects: tuple
    names: list
    lower: np.ndarray
    upper: np.ndarray
    fixed: dict = field(default_factory=dict)
    experiment: Experiment | None = None
    effect_objects_added: tuple = ()

    @property
    def effect_objects(self) -> tuple:
        """Each effect once, in registry order (the order they act in)."""
        return canonical_effects(self.effect_objects_added)

    def params(self, p: np.ndarray) -> dict:
        d = dict(self.fixed)
        d.update(zip(self.names, (float(v) for v in p), strict=True))
        return d

    def mean(self, p: np.ndarray) -> np.ndarray:
        return self.experiment.mean(self.rec, self.params(p), self.effect_objects)

    @property
    def n_free(self) -> int:
        return len(self.names)


def build_model(rec: Recording, effects: tuple = (), fixed: dict | None = None) -> Model:
    """Model of ``rec``'s experiment with ``effects`` (Effect objects, in the order added)."""
    exp = get_experiment(rec.experiment)
    fixed = dict(fixed or {})
    names, lo, hi = (list(v) for v in exp.parameters(rec))
    for e in canonical_effects(effects):
        e.add_parameters(rec, names, lo, hi, fixed)
    return Model(
        rec,
        tuple(e.name for e in effects),
        names,
        np.array(lo, float),
        np.array(hi, float),
        fixed,
        exp,
        tuple(effects),
    )


class _Means(Mapping):
    """``MEANS[kind](rec, p, effect_names)``: the mean of a kind with effects named."""

    def __getitem__(self, kind):
        exp = get_experiment(kind)

        def mean(rec, p, effects=()):
            from knotmech.diagnose.effects import get_effect

            return exp.mean(rec, p, canonical_effects([get_effect(n) for n in effects]))

        return mean

    def __iter__(self):
        from knotmech.diagnose.experiments import EXPERIMENT_KINDS

        return iter(EXPERIMENT_KINDS)

    def __len__(self):
        from knotmech.diagnose.experiments import EXPERIMENT_KINDS

        return len(EXPERIMENT_KINDS)


MEANS = _Means()


# --- baseline families: closed-form (default) and DER ---------------------------------


@dataclass(frozen=True)
class ClosedFormBaseline:
    """The closed-form baselines of the experiment kinds, for every kind."""

    name: str = "closed-form"

    def check(self, rec: Recording) -> None:
        return None


@dataclass(frozen=True)
class DERBaseline:
    """DER-simulated capstan baseline (kinetic friction only), ``capstan_pull`` only.

    The clove-hitch paper's FEM used kinetic friction only, so its two-loops curve had
    no peak; ``static_friction`` re-runs the scene with ``mu_s > mu_k``
    (:mod:`knotmech.diagnose.der`).
    """

    name: str = "der"

    def check(self, rec: Recording) -> None:
        if rec.experiment not in ("capstan_pull", "knot_pull"):
            raise InputError(
                f"baseline 'der' is not available for {rec.experiment} recordings "
                "(capstan_pull and knot_pull only); use closed-form"
            )


BASELINES = {"closed-form": ClosedFormBaseline(), "der": DERBaseline()}


def get_baseline(name: str):
    """Baseline by name: ``closed-form`` or ``der``.

    Raises
    ------
    InputError
        Unknown name.
    """
    if name not in BASELINES:
        raise InputError(f"baseline must be one of {', '.join(BASELINES)}, got {name!r}")
    return BASELINES[name]
