r"""``capstan_pull``: pulling a rod wrapped around a fixed post (spec section 2).

Columns ``displacement_m``, ``T_high_N``; metadata ``wrap_angle_rad``, ``T_low_N``,
``rod_diameter_m``, ``post_diameter_m``, ``youngs_modulus_Pa``. Baseline (Coulomb
friction, one coefficient): the free span stretches while the rod sticks, then the
rod slides at the capstan limit,

.. math::
    T_\mathrm{high} = \min\bigl(T_\mathrm{low} + k\max(u-\delta_0, 0),
        \; T_\mathrm{low} e^{\mu\theta}\bigr),

free parameters ``mu``, ``k_N_per_m`` (stick stiffness), ``delta0_m`` (slack, >= 0).
"""

from __future__ import annotations

import numpy as np

from knotmech.diagnose.experiments.base import Experiment, Stages
from knotmech.materials import VPS32_YOUNGS_MODULUS

__all__ = ["CapstanPull"]


class CapstanPull(Experiment):
    name = "capstan_pull"
    columns = ("displacement_m", "T_high_N")
    required_metadata = (
        "wrap_angle_rad",
        "T_low_N",
        "rod_diameter_m",
        "post_diameter_m",
        "youngs_modulus_Pa",
    )
    stages = (
        "friction(mu) -> mu per row; apparent(mu) -> the mu the capstan sees; "
        "capstan_shift(None) -> shifted displacement (default u - delta0_m); "
        "capstan_curve(None, parts) -> T_high (default min(stick, plateau))"
    )

    def parameters(self, rec):
        span = float(np.ptp(rec.x)) or 1.0
        return (
            ["mu", "k_N_per_m", "delta0_m"],
            [0.0, 1e-12, 0.0],
            [5.0, np.inf, float(np.max(rec.x)) if np.max(rec.x) > 0 else span],
        )

    def start(self, rec, y) -> dict:
        x = rec.x
        t_low, theta = rec.meta("T_low_N"), rec.meta("wrap_angle_rad")
        top = np.quantile(y, 0.8)
        plateau = float(np.median(y[y >= top]))
        mu = max(np.log(max(plateau, t_low * 1.0001) / t_low) / theta, 1e-3)
        rise = plateau - t_low
        sel = (y > t_low + 0.05 * rise) & (y < t_low + 0.6 * rise)
        span = float(np.ptp(x)) or 1.0
        if sel.sum() >= 3 and np.ptp(x[sel]) > 0:
            b, a = np.polyfit(x[sel], y[sel], 1)
        else:
            b, a = rise / (0.3 * span), t_low
        b = max(b, rise / span * 0.1, 1e-9)
        zero = (t_low - a) / b
        return {"mu": mu, "k_N_per_m": b, "delta0_m": max(zero, 0.0), "offset_m": max(-zero, 0.0)}

    def mean(self, rec, p, effects=()):
        st = Stages(rec, p, effects)
        t_low = rec.meta("T_low_N")
        theta = rec.meta("wrap_angle_rad")
        mu = st.apply("friction", p["mu"])
        plateau = t_low * np.exp(st.apply("apparent", mu) * theta)
        xs = st.apply("capstan_shift", None)
        if xs is None:
            xs = rec.x - p["delta0_m"]
        k = p["k_N_per_m"]
        stick = t_low + k * np.maximum(xs, 0.0)
        parts = {"stick": stick, "plateau": plateau, "xs": xs, "mu": mu, "stages": st}
        out = st.apply("capstan_curve", None, parts=parts)
        return np.minimum(stick, plateau) if out is None else out

    def synth_setup(self, rng, n, speeds):
        meta = {
            "wrap_angle_rad": float(2 * np.pi * rng.choice([1.0, 1.5, 2.0])),
            "T_low_N": float(rng.uniform(0.5, 2.0)),
            "rod_diameter_m": 0.004,
            "post_diameter_m": float(rng.uniform(0.016, 0.04)),
            "youngs_modulus_Pa": VPS32_YOUNGS_MODULUS,
        }
        m = n // len(speeds)
        u1 = np.linspace(0.0, 0.05, m)
        x = np.tile(u1, len(speeds))
        params = {"mu": float(rng.uniform(0.2, 0.4)), "delta0_m": float(rng.uniform(0.0, 0.004))}
        plateau = meta["T_low_N"] * np.exp(params["mu"] * meta["wrap_angle_rad"])
        u_b = rng.uniform(0.015, 0.025)
        params["k_N_per_m"] = float((plateau - meta["T_low_N"]) / (u_b - params["delta0_m"]))
        trial = np.repeat(np.arange(len(speeds)), m)
        speed = np.repeat(speeds, m) if len(speeds) > 1 else None
        return meta, x, trial, speed, params, {}

    def out_of_catalogue(self, x, meta, p, mean0, sd, size, rng):
        """A sliding plateau that keeps rising (linearly in u)."""
        plateau = meta["T_low_N"] * np.exp(p["mu"] * meta["wrap_angle_rad"])
        on = mean0 >= plateau * (1 - 1e-12)
        u_b = np.min(x[on])
        ramp = np.where(on, (x - u_b) / (x[-1] - u_b), 0.0)
        return mean0 + size * sd[-1] * ramp
