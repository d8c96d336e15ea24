"""Synthetic recordings with a known (possibly concealed) effect.

Used by ``validation/concealed_effects.py`` and the tests. Each recording is a
baseline of its experiment (random physical parameters), plus at most one
effect of a chosen *size*: the largest difference the effect makes to the
noiseless curve (same other parameters), in units of the noise standard
deviation at that point. Noise is white or AR(1) (lag-one correlation ``rho``),
with a standard deviation constant or growing with the signal.

For ``finite_thickness`` the data alone cannot show the effect (it is a smaller
mu); its size is the prior's pull ``(mu - mu_eff)/mu_nominal_sigma`` instead.

Effects outside the catalogue (``out_of_catalogue``): a plateau that keeps
rising (capstan_pull), a stiffening, super-linear F_t (pinch), a local tension
bump (tension_profile).
"""

from __future__ import annotations

import numpy as np

from knotmech.analytic.capstan import mu_eff
from knotmech.diagnose.baselines import MEANS, pinch_load_parameter
from knotmech.diagnose.recording import EXPERIMENTS, Recording
from knotmech.diagnose.stats import NoiseModel, trial_starts

__all__ = ["make_recording", "SYNTH_EFFECTS"]

#: effects the generator can plant, per experiment (plus None and "out_of_catalogue")
SYNTH_EFFECTS = {
    "capstan_pull": (
        "static_friction",
        "finite_thickness",
        "displacement_offset",
        "rate_dependent_friction",
    ),
    "pinch": ("adhesion", "contact_flattening", "rate_dependent_friction"),
    "tension_profile": ("finite_thickness", "self_contact_nip"),
}

_SPEEDS = np.array([1e-4, 1e-3, 1e-2])


def _base_setup(experiment, rng, n, speeds):
    if experiment == "capstan_pull":
        meta = {
            "wrap_angle_rad": float(2 * np.pi * rng.choice([1.0, 1.5, 2.0])),
            "T_low_N": float(rng.uniform(0.5, 2.0)),
            "rod_diameter_m": 0.004,
            "post_diameter_m": float(rng.uniform(0.016, 0.04)),
            "youngs_modulus_Pa": 1.26e6,
        }
        m = n // len(speeds)
        u1 = np.linspace(0.0, 0.05, m)
        x = np.tile(u1, len(speeds))
        params = {"mu": float(rng.uniform(0.2, 0.4)), "delta0_m": float(rng.uniform(0.0, 0.004))}
        plateau = meta["T_low_N"] * np.exp(params["mu"] * meta["wrap_angle_rad"])
        u_b = rng.uniform(0.015, 0.025)
        params["k_N_per_m"] = float((plateau - meta["T_low_N"]) / (u_b - params["delta0_m"]))
    elif experiment == "pinch":
        meta = {
            "rod_diameter_m": float(rng.choice([0.004, 0.008])),
            "pinch_diameter_m": 0.008,
            "youngs_modulus_Pa": 1.26e6,
        }
        scale = np.pi * meta["youngs_modulus_Pa"] * meta["rod_diameter_m"] * 0.008 / 4
        m = n // len(speeds)
        x = np.tile(np.linspace(0.01, 0.3, m) * scale, len(speeds))
        params = {"mu": float(rng.uniform(0.2, 0.45))}
    else:
        meta = {
            "T_high_N": float(rng.uniform(5.0, 20.0)),
            "rod_diameter_m": 0.004,
            "post_diameter_m": float(rng.uniform(0.016, 0.04)),
        }
        r = 0.5 * (meta["rod_diameter_m"] + meta["post_diameter_m"])
        m = n
        x = np.linspace(0.0, 2 * np.pi * r * rng.uniform(1.0, 2.0), m)
        params = {"mu": float(rng.uniform(0.2, 0.4))}
    trial = np.repeat(np.arange(len(speeds)), m)
    speed = np.repeat(speeds, m) if len(speeds) > 1 else None
    return meta, x, trial, speed, params


def _mk(experiment, x, meta, trial, speed):
    return Recording(experiment, x, np.zeros_like(x), dict(meta), None, trial, speed)


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
    rate = effect == "rate_dependent_friction"
    speeds = _SPEEDS if rate else _SPEEDS[:1]
    meta, x, trial, speed, params = _base_setup(experiment, rng, n, speeds)
    base_rec = _mk(experiment, x, meta, trial, speed)
    mean0 = MEANS[experiment](base_rec, params, ())
    fmax = float(np.max(np.abs(mean0)))
    sigma0 = 0.004 * fmax
    nm = NoiseModel(sigma0, growth, rho if noise == "ar1" else 0.0, fmax)
    sd = nm.sd(mean0)
    truth = {"effect": effect or "none", "size": float(size), "noise": noise}
    effects = ()
    p = dict(params)
    use_prior = bool(mu_nominal) or effect == "finite_thickness"
    mean = mean0
    if effect == "static_friction":
        t_low, theta = meta["T_low_N"], meta["wrap_angle_rad"]
        plateau = t_low * np.exp(p["mu"] * theta)
        i = int(np.argmax(mean0 >= plateau * (1 - 1e-12)))
        peak = plateau + size * sd[i]
        p["dmu_static"] = float(np.log(peak / t_low) / theta - p["mu"])
        p["decay_length_m"] = float(rng.uniform(0.001, 0.004))
        effects = ("static_friction",)
        truth.update({"mu_static": p["mu"] + p["dmu_static"], "mu_kinetic": p["mu"]})
    elif effect == "displacement_offset":
        p.pop("delta0_m")
        k = p["k_N_per_m"]
        p["offset_m"] = float(size * sd[0] / k)
        effects = ("displacement_offset",)
        truth["offset_m"] = p["offset_m"]
    elif effect == "rate_dependent_friction":
        lnv = np.log(speed) - np.mean(np.log(speed))
        if experiment == "capstan_pull":
            plateau = meta["T_low_N"] * np.exp(p["mu"] * meta["wrap_angle_rad"])
            slope = plateau * meta["wrap_angle_rad"] * np.max(np.abs(lnv))
        else:
            slope = 2 * np.max(x) * np.max(np.abs(lnv))
        p["dmu_dlnv"] = float(size * np.max(sd) / slope) * rng.choice([-1.0, 1.0])
        effects = ("rate_dependent_friction",)
        truth["dmu_dlnv"] = p["dmu_dlnv"]
    elif effect == "adhesion":
        p["adhesion_force_N"] = float(size * sd[0])
        effects = ("adhesion",)
        truth["adhesion_force_N"] = p["adhesion_force_N"]
    elif effect == "contact_flattening":
        xl = pinch_load_parameter(
            x,
            youngs_modulus=meta["youngs_modulus_Pa"],
            rod_diameter=meta["rod_diameter_m"],
            pinch_diameter=meta["pinch_diameter_m"],
        )
        xc = float(rng.uniform(0.08, 0.18))
        fc = xc / xl[-1] * x[-1]
        p["onset_load_parameter"] = xc
        p["slope_ratio"] = float(1 - size * sd[-1] / (2 * p["mu"] * (x[-1] - fc)))
        if p["slope_ratio"] < 0:
            p["slope_ratio"] = 0.0
        effects = ("contact_flattening",)
        truth["onset_load_parameter"] = xc
    elif effect == "self_contact_nip":
        n_nips = int(rng.integers(1, 3))
        span = x[-1] - x[0]
        pos = np.sort(rng.uniform(0.2, 0.8, n_nips)) * span + x[0]
        if n_nips == 2 and pos[1] - pos[0] < 0.15 * span:
            pos[1] = min(pos[0] + 0.15 * span, x[0] + 0.9 * span)
        cur = dict(p)
        for j, s_j in enumerate(pos):
            level = MEANS[experiment](base_rec, cur, ("self_contact_nip",))
            i = int(np.searchsorted(x, s_j, side="right"))
            drop = float(min(size * sd[i] / level[i], 0.9))
            cur[f"nip_position_{j}"] = float(s_j)
            cur[f"nip_drop_{j}"] = drop
        p = cur
        effects = ("self_contact_nip",)
        truth["positions_m"] = [float(v) for v in pos]
    elif effect == "finite_thickness":
        effects = ("finite_thickness",)
        dd = meta["post_diameter_m"] / meta["rod_diameter_m"]
        shift = float(p["mu"] - mu_eff(p["mu"], dd))
        truth.update({"mu": p["mu"], "mu_eff": p["mu"] - shift})
    if effects:
        mean = MEANS[experiment](base_rec, p, effects)
    if effect == "out_of_catalogue":
        span = x[-1] - x[0]
        if experiment == "capstan_pull":
            plateau = meta["T_low_N"] * np.exp(p["mu"] * meta["wrap_angle_rad"])
            on = mean0 >= plateau * (1 - 1e-12)
            u_b = np.min(x[on])
            ramp = np.where(on, (x - u_b) / (x[-1] - u_b), 0.0)
            mean = mean0 + size * sd[-1] * ramp
        elif experiment == "pinch":
            fc = x[0] + 0.4 * span
            bend = np.maximum(x - fc, 0.0) ** 2 / (x[-1] - fc) ** 2
            mean = mean0 + size * sd[-1] * bend
        else:
            c = x[0] + rng.uniform(0.3, 0.7) * span
            w = 0.04 * span
            i = int(np.argmin(np.abs(x - c)))
            mean = mean0 + size * sd[i] * np.exp(-0.5 * ((x - c) / w) ** 2)
    y = mean + nm.sample(mean, trial_starts(trial), rng)
    truth["noise_sd"] = nm.sd(mean)
    metadata = dict(meta)
    metadata["experiment"] = experiment
    if use_prior:
        if effect == "finite_thickness":
            msig = truth["mu"] - truth["mu_eff"]
            msig = msig / max(size, 1e-9)
        else:
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
        EXPERIMENTS[experiment][:2],
    )
    return rec, truth
