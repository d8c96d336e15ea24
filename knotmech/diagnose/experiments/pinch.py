r"""``pinch``: a rod pulled out from between two pressed cylinders (spec section 2).

Columns ``normal_force_N``, ``tangential_force_N``; metadata ``rod_diameter_m``,
``pinch_diameter_m``, ``youngs_modulus_Pa``. Baseline (Amontons-Coulomb on both
faces) :math:`F_t = 2\mu F_n`, free parameter ``mu``. The load parameter
:math:`x = 4F_n/(\pi E d D_\mathrm{pinch})` is the natural axis for deviations.
"""

from __future__ import annotations

import numpy as np

from knotmech.analytic.pinch import pinch_load_parameter
from knotmech.diagnose.experiments.base import Experiment, Stages
from knotmech.materials import VPS32_YOUNGS_MODULUS

__all__ = ["Pinch"]


class Pinch(Experiment):
    name = "pinch"
    columns = ("normal_force_N", "tangential_force_N")
    required_metadata = ("rod_diameter_m", "pinch_diameter_m", "youngs_modulus_Pa")
    control_nonnegative = True
    stages = (
        "friction(mu) -> mu per row; load(F_n) -> the load friction acts on; "
        "output(F_t) -> the measured force"
    )

    def load_parameter(self, rec, fn=None):
        """Load parameter :math:`4F_n/(\\pi E d D)` of the rows (or of ``fn`` [N])."""
        return pinch_load_parameter(
            rec.x if fn is None else fn,
            youngs_modulus=rec.meta("youngs_modulus_Pa"),
            rod_diameter=rec.meta("rod_diameter_m"),
            pinch_diameter=rec.meta("pinch_diameter_m"),
        )

    def start(self, rec, y) -> dict:
        x = rec.x
        return {"mu": max(np.dot(x, y) / (2 * np.dot(x, x)), 1e-3)}

    def mean(self, rec, p, effects=()):
        st = Stages(rec, p, effects)
        mu = st.apply("friction", p["mu"])
        return st.apply("output", 2.0 * mu * st.apply("load", rec.x))

    def synth_setup(self, rng, n, speeds):
        meta = {
            "rod_diameter_m": float(rng.choice([0.004, 0.008])),
            "pinch_diameter_m": 0.008,
            "youngs_modulus_Pa": VPS32_YOUNGS_MODULUS,
        }
        scale = np.pi * meta["youngs_modulus_Pa"] * meta["rod_diameter_m"] * 0.008 / 4
        m = n // len(speeds)
        x = np.tile(np.linspace(0.01, 0.3, m) * scale, len(speeds))
        params = {"mu": float(rng.uniform(0.2, 0.45))}
        trial = np.repeat(np.arange(len(speeds)), m)
        speed = np.repeat(speeds, m) if len(speeds) > 1 else None
        return meta, x, trial, speed, params, {}

    def out_of_catalogue(self, x, meta, p, mean0, sd, size, rng):
        """A stiffening: F_t super-linear (quadratic) beyond 40 % of the load range."""
        span = x[-1] - x[0]
        fc = x[0] + 0.4 * span
        bend = np.maximum(x - fc, 0.0) ** 2 / (x[-1] - fc) ** 2
        return mean0 + size * sd[-1] * bend
