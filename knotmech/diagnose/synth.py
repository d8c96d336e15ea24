"""Synthetic recordings with a known (possibly concealed) effect.

Used by ``validation/concealed_effects.py`` and the tests. Each recording is a
baseline of its experiment (random physical parameters), plus at most one
effect of a chosen *size*: the largest difference the effect makes to the
noiseless curve (same other parameters), in units of the noise standard
deviation at that point. Noise is white or AR(1) (lag-one correlation ``rho``),
with a standard deviation constant or growing with the signal.

For ``finite_thickness`` the data alone cannot show the effect (it is a smaller
mu); its size is the prior's pull ``(mu - mu_eff)/mu_nominal_sigma`` instead. The
capstan_hold effects that mu can partly mimic (``bending_resistance``,
``bending_stiffness``, ``pressure_dependent_friction``) are sized by the largest change
left after the baseline's mu is refitted (each effect's ``plant``).

Effects outside the catalogue (``out_of_catalogue``): a plateau that keeps
rising (capstan_pull), a stiffening, super-linear F_t (pinch), a local tension
bump (tension_profile).
"""

from __future__ import annotations

import numpy as np

from knotmech.diagnose.effects import CATALOGUE, PlantContext, get_effect
from knotmech.diagnose.experiments import EXPERIMENT_KINDS, get_experiment
from knotmech.diagnose.recording import Recording
from knotmech.diagnose.stats import NoiseModel, trial_starts

__all__ = ["make_recording", "SYNTH_EFFECTS", "plantable_effects"]


def plantable_effects(kind: str) -> tuple:
    """Names of the catalogue effects that claim ``kind`` (the generator plants each)."""
    return tuple(name for name, e in CATALOGUE.items() if kind in e.experiments)


#: effects the generator can plant, per experiment (plus None and "out_of_catalogue")
SYNTH_EFFECTS = {kind: plantable_effects(kind) for kind in EXPERIMENT_KINDS}

_SPEEDS = np.array([1e-4, 1e-3, 1e-2])


def _mk(experiment, x, meta, trial, speed, extra):
    return Recording(
        experiment, x, np.zeros_like(x), dict(meta), None, trial, speed, extra=dict(extra)
    )


def make_recording(
    experiment: str,
    effect: str | None = None,
    *,
    size: float = 5.0,
    noise: str = "white",
    rho: float = 0.9,
    growth: float = 0.0,
    n: int = 240,
    seed: int = 0,
    mu_nominal: bool | None = None,
):
    """One synthetic recording and the truth behind it.

    Parameters
    ----------
    experiment : str
    effect : str or None
        A catalogue effect of the experiment, ``"out_of_catalogue"``, or None.
    size : float
        Effect size in noise standard deviations at its strongest point
        (``finite_thickness``: prior pulls).
    noise : {"white", "ar1"}
    rho : float
        Lag-one correlation for ``"ar1"``.
    growth : float
        Noise growth ``g`` (0: constant).
    n : int
        Rows (split over three speeds for rate-dependent friction).
    seed : int
    mu_nominal : bool, optional
        Put a ``mu_nominal`` prior in the metadata (default: only for finite_thickness).

    Returns
    -------
    rec : Recording
    truth : dict
        ``effect``, ``size``, true parameters (report names where they exist), and
        ``noise_sd`` (the true noise standard deviation per row, an array).
    """
    rng = np.random.default_rng(seed)
    exp = get_experiment(experiment)
    eff = get_effect(effect) if effect not in (None, "out_of_catalogue") else None
    speeds = _SPEEDS if eff is not None and "speed" in eff.requires else _SPEEDS[:1]
    meta, x, trial, speed, params, extra = exp.synth_setup(rng, n, speeds)
    base_rec = _mk(experiment, x, meta, trial, speed, extra)
    mean0 = exp.mean(base_rec, params, ())
    fmax = float(np.max(np.abs(mean0)))
    sigma0 = exp.synth_noise_scale(meta, mean0)
    nm = NoiseModel(sigma0, growth, rho if noise == "ar1" else 0.0, fmax)
    sd = nm.sd(mean0)
    truth = {"effect": effect or "none", "size": float(size), "noise": noise}
    p = dict(params)
    use_prior = bool(mu_nominal) or (eff is not None and "mu_nominal" in eff.requires)
    mean = mean0
    if eff is not None:
        ctx = PlantContext(
            experiment=exp,
            rec=base_rec,
            meta=meta,
            x=x,
            speed=speed,
            p=dict(p),
            mean0=mean0,
            sd=sd,
            size=size,
            rng=rng,
        )
        p, planted = eff.plant(experiment, ctx)
        truth.update(planted)
        mean = exp.mean(base_rec, p, (eff,))
    if effect == "out_of_catalogue":
        mean = exp.out_of_catalogue(x, meta, p, mean0, sd, size, rng)
    y = mean + nm.sample(mean, trial_starts(trial), rng)
    truth["noise_sd"] = nm.sd(mean)
    metadata = dict(meta)
    metadata["experiment"] = experiment
    if use_prior:
        msig = eff.prior_sigma(truth, size) if eff is not None else None
        if msig is None:
            msig = 0.02
        metadata["mu_nominal"] = float(p["mu"] + msig * rng.standard_normal())
        metadata["mu_nominal_sigma"] = float(msig)
    rec = Recording(
        experiment,
        x,
        y,
        metadata,
        None,
        trial,
        speed,
        "<synthetic>",
        exp.columns,
        dict(extra),
    )
    return rec, truth
