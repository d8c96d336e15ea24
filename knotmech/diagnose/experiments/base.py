"""The :class:`Experiment` protocol: one experiment kind of ``knotmech diagnose``.

An experiment kind owns its recording columns and metadata, its baseline model
(free parameters with bounds taken from the recording, a starting guess, the mean)
and its synthetic recordings. The mean is written as a few named *stages*; an
effect (:class:`knotmech.diagnose.effects.base.Effect`) changes the mean by
implementing a method of the stage's name, which :class:`Stages` calls in turn
(see each experiment's ``stages`` for what it passes).
"""

from __future__ import annotations

import numpy as np

__all__ = ["Experiment", "Stages"]


class Stages:
    """The effects of a model, applied at the named stages of an experiment's mean.

    Parameters
    ----------
    rec : Recording
    p : dict
        Parameter values (free and fixed) by name.
    effects : tuple of Effect
        The model's effects, each once, in registry order.
    """

    def __init__(self, rec, p, effects):
        self.rec, self.p, self.effects = rec, p, effects

    def apply(self, stage: str, value, **parts):
        """``value`` passed through every effect's ``stage`` method, in registry order."""
        for e in self.effects:
            f = getattr(e, stage, None)
            if f is not None:
                value = f(self.rec, self.p, value, **parts)
        return value

    def provides(self, stage: str) -> bool:
        """True when one of the effects acts at ``stage``."""
        return any(getattr(e, stage, None) is not None for e in self.effects)


class Experiment:
    """Base class of an experiment kind (a subclass per file in this folder).

    Class attributes
    ----------------
    name : str
        Kind as written in ``# experiment: ...``.
    columns : (str, str)
        Control column (x axis) and measured column.
    required_metadata : tuple of str
        Keys every recording of this kind must carry.
    optional_columns : tuple of str
        Columns of this kind beyond ``sigma``, ``trial``, ``speed_m_per_s``.
    word_columns : dict
        Column -> {word: number} for columns that hold words (``direction``).
    min_rows : int
        Fewest data rows.
    control_nonnegative : bool
        The control column must be >= 0.
    stages : str
        The stages of the mean and what each passes (documentation).
    """

    name = ""
    columns = ("x", "y")
    required_metadata: tuple = ()
    optional_columns: tuple = ()
    word_columns: dict = {}
    min_rows = 8  # knotmech.diagnose.recording.MIN_ROWS (spec section 1)
    control_nonnegative = False
    stages = ""

    # --- recording ---------------------------------------------------------------
    def check(self, rec) -> str | None:
        """A problem with ``rec`` beyond the per-column checks (a message), or None."""
        return None

    def validity(self, rec):
        """The rows the closed-form baseline is valid on: a bool mask and the reason the
        others are not (a sentence), or None when it is valid on every row.

        A recording is never refused for its closed form's sake: the closed-form baseline
        judges the valid rows (:class:`knotmech.diagnose.baselines.ClosedFormBaseline`)
        and a simulated baseline (``--baseline der``) all of them.
        """
        return None

    def reduce(self, rec):
        """The recording the engine diagnoses, and a note of what was done (or None).

        The default is the recording itself; a kind whose rows may be repeated readings
        of one state (``capstan_hold``: a sensor read many times during one hold)
        reduces them to one row per state.
        """
        return rec, None

    # --- baseline ------------------------------------------------------------------
    def parameters(self, rec):
        """Free baseline parameters of ``rec``: (names, lower bounds, upper bounds)."""
        return ["mu"], [0.0], [5.0]

    def priors(self, rec) -> dict:
        """Gaussian priors N(0, sd^2) on baseline parameters of ``rec``: name -> sd (in the
        parameter's units). Each enters every fit as one more whitened residual
        ``value / sd`` (as ``mu_nominal`` does); none by default."""
        return {}

    def start(self, rec, y) -> dict:
        """Heuristic starting values of the baseline parameters (more keys allowed)."""
        raise NotImplementedError

    def mean(self, rec, p: dict, effects=()) -> np.ndarray:
        """Mean of the measured column [its units] with ``effects`` (Effect objects)."""
        raise NotImplementedError

    # --- synthetic recordings ----------------------------------------------------------
    def synth_setup(self, rng, n: int, speeds) -> tuple:
        """A random set-up: (metadata, x, trial, speed, baseline parameters, extra columns)."""
        raise NotImplementedError

    def synth_noise_scale(self, meta, mean0) -> float:
        """Noise sd of synthetic recordings [units of y]: 0.4 % of the largest mean."""
        return 0.004 * float(np.max(np.abs(mean0)))

    def out_of_catalogue(self, x, meta, p, mean0, sd, size, rng) -> np.ndarray:
        """A mean with a shape outside the catalogue, ``size`` noise sd at its strongest."""
        raise NotImplementedError

    def __repr__(self) -> str:
        return f"<experiment {self.name}>"
