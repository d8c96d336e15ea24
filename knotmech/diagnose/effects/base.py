"""The :class:`Effect` protocol: one catalogue entry of ``knotmech diagnose``.

An effect is physics a baseline leaves out, written as an augmentation of the
baseline's mean. It owns its name and the experiment kinds it claims, its free
parameters and their bounds (from the recording), its starting values, how it
changes the mean (methods named after the stages of an experiment's mean, see
:mod:`knotmech.diagnose.experiments.base`), its public parameters and its sentence
in the verdict, and how to plant it in a synthetic recording. One subclass per
file in this folder, registered in :mod:`knotmech.diagnose.effects`.
"""

from __future__ import annotations

from types import SimpleNamespace

from knotmech.diagnose.model import param_vector

__all__ = ["Effect", "PlantContext"]


class PlantContext(SimpleNamespace):
    """What :meth:`Effect.plant` gets: ``experiment`` (object), ``rec`` (the noiseless
    recording), ``meta``, ``x``, ``speed``, ``p`` (baseline parameters, a copy),
    ``mean0`` (baseline mean), ``sd`` (noise sd per row), ``size`` (effect size in noise
    sd) and ``rng``."""


class Effect:
    """Base class of a catalogue effect.

    Class attributes
    ----------------
    name : str
        Spec name (``shared/spec/recordings.md`` section 3, or one this package adds).
    experiments : tuple of str
        Kinds it applies to.
    parameters : dict
        Parameter name -> (no-effect value, meaning with units) (documentation).
    requires : tuple of str
        What the recording must carry: ``mu_nominal`` (an independent friction
        coefficient), ``speed`` (two or more sliding speeds), ``diameters`` (both
        ``rod_diameter_m`` and ``post_diameter_m``); an effect may check more in
        :meth:`missing`.
    confusable_with : tuple of str
    signature : str
        The residual shape it leaves on the baseline.
    reference : str
    repeatable : bool
        May be added more than once.
    acts_everywhere : bool
        Its region is the whole range of the control variable.
    extra_dof : int
        Degrees of freedom beyond its new free parameters (a searched position, a
        relaxed inequality), charged in the BIC.
    report_keys : tuple of str
        Public parameters that belong to it (spec section 4).
    key_parameter : tuple or None
        (report name, truth name, ``"abs"`` or ``"rel"``): the number the validation
        compares with the planted truth.
    """

    name = ""
    experiments: tuple = ()
    parameters: dict = {}
    requires: tuple = ()
    confusable_with: tuple = ()
    signature = ""
    reference = ""
    repeatable = False
    acts_everywhere = False
    extra_dof = 0
    report_keys: tuple = ()
    key_parameter: tuple | None = None
    #: position in the registry (set on registration): the order in which effects
    #: add parameters and act on a mean, whatever the order they were added in
    rank = 0

    # --- model ---------------------------------------------------------------------
    def add_parameters(self, rec, names: list, lower: list, upper: list, fixed: dict) -> None:
        """Append (or substitute) its free parameters and bounds, in place."""

    def is_internal(self, key: str) -> bool:
        """True for a fitted parameter that is reported under another name (or not)."""
        return False

    # --- fitting -----------------------------------------------------------------------
    def starts(self, current, model, data, starts) -> list:
        """Starting parameter vectors of ``model`` (``current`` plus this effect)."""
        return [param_vector(model, current.params)]

    def fit(self, current, data, starts, *, given_sigma=None, known=None):
        """A fit of its own (searched positions...), or None for the default
        (:func:`knotmech.diagnose.fitting.fit_with_effect`). ``known`` (long recordings,
        second pass): a fit of its own from the same model, which it may return when it
        finds that model again."""
        return None

    # --- report --------------------------------------------------------------------------
    def public(self, params: dict, rec, out: dict) -> None:
        """Add its report parameters (``mu_static``...) to ``out``, in place."""

    def sentence(self, p: dict, rec) -> str:
        """Its verdict line (without the held-out change)."""
        return self.name

    # --- synthetic recordings ------------------------------------------------------------
    def plant(self, kind: str, s: PlantContext) -> tuple[dict, dict]:
        """Parameters with the effect of size ``s.size`` planted, and the truth.

        Returns
        -------
        p : dict
            Parameters of the mean with this effect.
        truth : dict
            True values under their report names.
        """
        raise NotImplementedError(f"{self.name} cannot be planted in {kind}")

    def prior_sigma(self, truth: dict, size: float) -> float | None:
        """``mu_nominal_sigma`` of a planted recording (None: the generator's default)."""
        return None

    def missing(self, rec) -> list:
        """What ``rec`` lacks for this effect (empty when it can be tested)."""
        out = []
        if "mu_nominal" in self.requires and rec.mu_nominal is None:
            out.append("mu_nominal metadata")
        if "speed" in self.requires:
            if rec.speed is None:
                out.append("sliding speeds (speed_m_per_s column or metadata)")
            elif len(set(rec.speed.tolist())) < 2:
                out.append("at least two different sliding speeds")
        if "diameters" in self.requires:
            for key in ("rod_diameter_m", "post_diameter_m"):
                if not isinstance(rec.metadata.get(key), float):
                    out.append(f"{key} metadata")
        return out

    def __repr__(self) -> str:
        return f"<effect {self.name}>"
