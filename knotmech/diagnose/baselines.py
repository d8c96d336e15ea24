r"""The baseline families, registered like the experiment kinds and the effects.

A baseline is what a recording is compared with before any effect is added: the
closed form of its experiment kind (:mod:`knotmech.diagnose.experiments`, every kind),
the DER capstan (:mod:`knotmech.diagnose.der`, ``capstan_pull``) or the DER overhand
knot (:mod:`knotmech.diagnose.der_knot`, ``knot_pull``). Each is one object with a
family name (what ``--baseline`` takes), the kinds it runs on, a :meth:`~Baseline.check`
that refuses a recording before any simulation and a :meth:`~Baseline.fit`.
:func:`get_baseline` is the one lookup, by family and kind. A new baseline is one class
and one :func:`_register` line below.

:class:`~knotmech.diagnose.model.Model` and :func:`~knotmech.diagnose.model.build_model`
live in the leaf module :mod:`knotmech.diagnose.model` (re-exported here);
:data:`MEANS` gives the mean of a kind with effects named.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from knotmech.analytic.pinch import pinch_load_parameter
from knotmech.diagnose.der import check_der_recording, fit_der_baseline
from knotmech.diagnose.der_knot import fit_knot_der_baseline
from knotmech.diagnose.effects import get_effect
from knotmech.diagnose.experiments import EXPERIMENT_KINDS, get_experiment
from knotmech.diagnose.fitting import Fit, fit_baseline
from knotmech.diagnose.model import Model, build_model, canonical_effects
from knotmech.diagnose.noisefloor import without_rows
from knotmech.diagnose.recording import Recording
from knotmech.errors import InputError

__all__ = [
    "Baseline",
    "BaselineFit",
    "Model",
    "build_model",
    "canonical_effects",
    "get_baseline",
    "BASELINES",
    "MEANS",
    "pinch_load_parameter",
]


class _Means(Mapping):
    """``MEANS[kind](rec, p, effect_names)``: the mean of a kind with effects named."""

    def __getitem__(self, kind):
        exp = get_experiment(kind)

        def mean(rec, p, effects=()):
            return exp.mean(rec, p, canonical_effects([get_effect(n) for n in effects]))

        return mean

    def __iter__(self):
        return iter(EXPERIMENT_KINDS)

    def __len__(self):
        return len(EXPERIMENT_KINDS)


MEANS = _Means()


# --- the baselines ---------------------------------------------------------------------


@dataclass
class BaselineFit:
    """A fitted baseline.

    Attributes
    ----------
    rec : Recording
        The recording to diagnose from here on (the DER knot attaches its force law).
    fit : Fit
        The baseline's fit.
    der : tuple or None
        The DER capstan's curves and mu grid, for its own selection
        (:func:`knotmech.diagnose.der.select_der`); None for the other baselines, whose
        effects are selected by the closed-form engine.
    """

    rec: Recording
    fit: Fit
    der: tuple | None = None


class Baseline:
    """Base class of a baseline.

    Class attributes
    ----------------
    family : str
        The name ``--baseline`` takes (``closed-form``, ``der``).
    experiments : tuple of str
        Kinds it runs on.
    refits_outliers : bool
        The engine looks for outliers again on this baseline's remainder and refits.
    """

    family = ""
    experiments: tuple = ()
    refits_outliers = False

    def check(self, rec: Recording) -> None:
        """Refuse, before any simulation, a recording this baseline cannot run on."""

    def restrict(self, rec: Recording):
        """The rows this baseline judges, and a note for the report (None: every row)."""
        return rec, None

    def fit(self, rec: Recording, data, starts, given_sigma) -> BaselineFit:
        """The baseline fitted to ``rec`` (``data``: :class:`~knotmech.diagnose.fitting.Data`)."""
        raise NotImplementedError

    def __repr__(self) -> str:
        return f"<baseline {self.family} ({', '.join(self.experiments)})>"


class ClosedFormBaseline(Baseline):
    """The closed-form baselines of the experiment kinds, for every kind."""

    family = "closed-form"
    experiments = tuple(EXPERIMENT_KINDS)
    refits_outliers = True

    def restrict(self, rec):
        """The rows inside the closed form's validity (:meth:`Experiment.validity`).

        A recording is not refused because part of it lies beyond the closed form (a
        knot pulled to tight): the rows inside are judged, and the note says which and
        how many; ``--baseline der`` judges every row. Refused only when fewer than the
        kind's ``min_rows`` rows remain.
        """
        kind = get_experiment(rec.experiment)
        valid = kind.validity(rec)
        if valid is None:
            return rec, None
        ok, reason = valid
        k = int(np.sum(ok))
        if k < kind.min_rows:
            raise InputError(
                f"{rec.source}: {k} of {rec.n} rows lie inside the closed form's validity "
                f"({reason}); the closed form needs {kind.min_rows}: use --baseline der"
            )
        kept = without_rows(rec, np.flatnonzero(~ok))
        note = {
            "rows_judged": k,
            "rows": int(rec.n),
            "judged_range": [float(np.min(kept.x)), float(np.max(kept.x))],
            "reason": f"{rec.n - k} rows left out: {reason}; --baseline der judges every row",
        }
        return kept, note

    def fit(self, rec, data, starts, given_sigma):
        return BaselineFit(rec, fit_baseline(rec, data, starts, given_sigma=given_sigma))


class DERCapstanBaseline(Baseline):
    """DER-simulated capstan baseline (kinetic friction only).

    The clove-hitch paper's FEM used kinetic friction only, so its two-loops curve had
    no peak; ``static_friction`` re-runs the scene with ``mu_s > mu_k``
    (:mod:`knotmech.diagnose.der`).
    """

    family = "der"
    experiments = ("capstan_pull",)

    def check(self, rec):
        """See :func:`knotmech.diagnose.der.check_der_recording`."""
        check_der_recording(rec)

    def fit(self, rec, data, starts, given_sigma):
        der, fit = fit_der_baseline(rec, data, starts, given_sigma)
        return BaselineFit(rec, fit, der)


class DERKnotBaseline(Baseline):
    """DER overhand-knot baseline: its interpolated force law replaces the closed form.

    The selection, its parametric bootstrap included, is the closed-form one on that
    surrogate (:mod:`knotmech.diagnose.der_knot`, whose set-up checks the recording).
    """

    family = "der"
    experiments = ("knot_pull",)

    def fit(self, rec, data, starts, given_sigma):
        drec, fit = fit_knot_der_baseline(rec, data, starts, given_sigma)
        return BaselineFit(drec, fit)


#: family -> experiment kind -> Baseline, in registration order
BASELINES: dict[str, dict[str, Baseline]] = {}


def _register(baseline: Baseline) -> None:
    kinds = BASELINES.setdefault(baseline.family, {})
    for kind in baseline.experiments:
        if kind in kinds:  # pragma: no cover - a programming error
            raise ValueError(f"baseline {baseline.family!r} registered twice for {kind}")
        kinds[kind] = baseline


_register(ClosedFormBaseline())
_register(DERCapstanBaseline())
_register(DERKnotBaseline())


def get_baseline(name: str, experiment: str) -> Baseline:
    """The baseline of family ``name`` (``closed-form`` or ``der``) for ``experiment``.

    Raises
    ------
    InputError
        Unknown family, or a family that does not run on this kind.
    """
    if name not in BASELINES:
        raise InputError(f"baseline must be one of {', '.join(BASELINES)}, got {name!r}")
    kinds = BASELINES[name]
    if experiment not in kinds:
        raise InputError(
            f"baseline {name!r} is not available for {experiment} recordings "
            f"({' and '.join(kinds)} only); use closed-form"
        )
    return kinds[experiment]
