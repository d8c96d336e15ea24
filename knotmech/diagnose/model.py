r"""A baseline plus effects as one model, and its parameter vector.

A :class:`Model` is one experiment kind's baseline
(:mod:`knotmech.diagnose.experiments`) plus a tuple of catalogue effects
(:mod:`knotmech.diagnose.effects`): its free parameters are the baseline's, then
each effect's (in registry order), with bounds from the recording; its mean is the
experiment's, each effect acting at the stages it implements, so effects compose
freely.

This module is a leaf of :mod:`knotmech.diagnose`: it imports the experiment kinds and
the recording only, so that the effects, the fits and the baselines can all import it.
Effects reach it as objects, never by name.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from knotmech.diagnose.experiments import Experiment, get_experiment
from knotmech.diagnose.recording import Recording

__all__ = ["Model", "build_model", "canonical_effects", "param_vector", "fit_step_name"]


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
    priors : dict
        Zero-mean Gaussian priors on free parameters: name -> sd (the experiment's
        :meth:`~knotmech.diagnose.experiments.base.Experiment.priors`).
    """

    rec: Recording
    effects: tuple
    names: list
    lower: np.ndarray
    upper: np.ndarray
    fixed: dict = field(default_factory=dict)
    experiment: Experiment | None = None
    effect_objects_added: tuple = ()
    priors: dict = field(default_factory=dict)

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

    def prior_residuals(self, p: np.ndarray) -> np.ndarray:
        """Whitened prior residuals ``p_j / sd_j`` of the parameters with a prior (empty
        array when none)."""
        if not self.priors:
            return np.empty(0)
        idx = [self.names.index(n) for n in self.priors]
        return np.asarray(p, float)[idx] / np.array(list(self.priors.values()))


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
        dict(exp.priors(rec)),
    )


def param_vector(model: Model, values: dict, defaults: dict | None = None) -> np.ndarray:
    """Parameter vector of ``model`` from ``values`` by name (else ``defaults``, else 0)."""
    defaults = defaults or {}
    return np.array([values.get(n, defaults.get(n, 0.0)) for n in model.names], dtype=float)


def fit_step_name(model) -> str:
    """What fitting ``model`` is called in error messages (``fitting the pinch model with ...``)."""
    effects = " + ".join(model.effects)
    return f"fitting the {model.rec.experiment} model" + (f" with {effects}" if effects else "")
