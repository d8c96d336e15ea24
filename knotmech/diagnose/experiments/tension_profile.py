r"""``tension_profile``: tension along a rod wrapped on a post (spec section 2).

Columns ``arclength_m`` (from the loaded end), ``tension_N``; metadata ``T_high_N``,
``rod_diameter_m``, ``post_diameter_m``. Baseline (ideal capstan along the
centreline) :math:`T(s) = T_\mathrm{high}\,e^{-\mu s/R}`, :math:`R = (D+d)/2`, free
parameter ``mu``.
"""

from __future__ import annotations

import numpy as np

from knotmech.diagnose.experiments.base import Experiment, Stages

__all__ = ["TensionProfile"]


class TensionProfile(Experiment):
    name = "tension_profile"
    columns = ("arclength_m", "tension_N")
    required_metadata = ("T_high_N", "rod_diameter_m", "post_diameter_m")
    control_nonnegative = True
    stages = "apparent(mu) -> the mu the capstan sees; output(T) -> the measured tension"

    def radius(self, rec) -> float:
        """Centreline radius on the post, (D + d)/2 [m]."""
        return 0.5 * (rec.meta("post_diameter_m") + rec.meta("rod_diameter_m"))

    def start(self, rec, y) -> dict:
        x = rec.x
        r = self.radius(rec)
        pos = y > 0
        if pos.sum() >= 2 and np.ptp(x[pos]) > 0:
            slope = np.polyfit(x[pos], np.log(y[pos] / rec.meta("T_high_N")), 1)[0]
            mu = max(-slope * r, 1e-3)
        else:
            mu = 0.3
        return {"mu": mu}

    def mean(self, rec, p, effects=()):
        st = Stages(rec, p, effects)
        mu = st.apply("apparent", p["mu"])
        return st.apply("output", rec.meta("T_high_N") * np.exp(-mu * rec.x / self.radius(rec)))

    def synth_setup(self, rng, n, speeds):
        meta = {
            "T_high_N": float(rng.uniform(5.0, 20.0)),
            "rod_diameter_m": 0.004,
            "post_diameter_m": float(rng.uniform(0.016, 0.04)),
        }
        r = 0.5 * (meta["rod_diameter_m"] + meta["post_diameter_m"])
        x = np.linspace(0.0, 2 * np.pi * r * rng.uniform(1.0, 2.0), n)
        params = {"mu": float(rng.uniform(0.2, 0.4))}
        trial = np.repeat(np.arange(len(speeds)), n)
        speed = np.repeat(speeds, n) if len(speeds) > 1 else None
        return meta, x, trial, speed, params, {}

    def out_of_catalogue(self, x, meta, p, mean0, sd, size, rng):
        """A local tension bump (Gaussian, 4 % of the span wide)."""
        span = x[-1] - x[0]
        c = x[0] + rng.uniform(0.3, 0.7) * span
        w = 0.04 * span
        i = int(np.argmin(np.abs(x - c)))
        return mean0 + size * sd[i] * np.exp(-0.5 * ((x - c) / w) ** 2)
