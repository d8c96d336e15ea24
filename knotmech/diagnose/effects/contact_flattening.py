r"""``contact_flattening``: sub-linear pinch force beyond an onset load (non-Amontons).

Beyond :math:`F_c = x_c\,\pi E d D/4` the slope is multiplied by ``slope_ratio``
:math:`r \in [0, 1]`: :math:`F_t = 2\mu\,(F_n - (1-r)\max(F_n - F_c, 0))`. Free
parameters ``onset_load_parameter`` :math:`x_c` (within the recorded load range) and
``slope_ratio``. Clove-hitch paper, sec. 9 and Fig. 5(d): Amontons holds for
:math:`4F_n/(\pi E d D) < 0.1` or so.
"""

from __future__ import annotations

import numpy as np

from knotmech.analytic.pinch import pinch_load_parameter
from knotmech.diagnose.effects._common import CLOVE, fmt
from knotmech.diagnose.effects.base import Effect
from knotmech.diagnose.fitting import whiten_columns
from knotmech.diagnose.model import fit_step_name, param_vector
from knotmech.diagnose.stats import ls_solve

__all__ = ["ContactFlattening"]


class ContactFlattening(Effect):
    name = "contact_flattening"
    experiments = ("pinch",)
    parameters = {
        "onset_load_parameter": ("any", "x_c = 4 F_c/(pi E d D) where the bend starts"),
        "slope_ratio": (1.0, "slope of F_t beyond the onset / 2 mu"),
    }
    confusable_with = ("rate_dependent_friction",)
    signature = "sub-linear F_t beyond a load parameter (a bend at high load)"
    reference = CLOVE + ", sec. 9 and Fig. 5(d): Amontons holds for 4F_n/(pi E d D) < ~0.1"
    report_keys = ("onset_load_parameter", "slope_ratio")
    #: material parameters, fitted once for all recordings by diagnose_many
    shared_parameters = ("onset_load_parameter", "slope_ratio")
    key_parameter = ("onset_load_parameter", "onset_load_parameter", "abs")

    @staticmethod
    def _xl(rec, fn=None):
        return pinch_load_parameter(
            rec.x if fn is None else fn,
            youngs_modulus=rec.meta("youngs_modulus_Pa"),
            rod_diameter=rec.meta("rod_diameter_m"),
            pinch_diameter=rec.meta("pinch_diameter_m"),
        )

    def add_parameters(self, rec, names, lower, upper, fixed):
        xl = self._xl(rec)
        names += ["onset_load_parameter", "slope_ratio"]
        lower += [float(np.min(xl)), 0.0]
        upper += [float(np.max(xl)), 1.0]

    def load(self, rec, p, fn):
        fc = p["onset_load_parameter"] * (
            np.pi
            * rec.meta("youngs_modulus_Pa")
            * rec.meta("rod_diameter_m")
            * rec.meta("pinch_diameter_m")
            / 4.0
        )
        return fn - (1.0 - p["slope_ratio"]) * np.maximum(fn - fc, 0.0)

    def starts(self, current, model, data, starts):
        """Two starts from a linear scan of 17 onsets (two-slope GLS at each)."""
        rec = model.rec
        xl = self._xl(rec)
        scale = rec.x / np.where(xl > 0, xl, 1.0)
        scale = float(np.median(scale[xl > 0])) if np.any(xl > 0) else 1.0
        sd = current.noise.sd(current.mean)
        yw = current.noise.whiten(data.y, sd, starts)
        cands = np.quantile(xl, np.linspace(0.1, 0.9, 17))
        adh = "adhesion" in model.effects
        best = []
        for xc in cands:
            fc = xc * scale
            cols = [rec.x, -np.maximum(rec.x - fc, 0.0)]
            if adh:
                cols.append(np.ones_like(rec.x))
            xw = whiten_columns(current.noise, sd, starts, np.column_stack(cols))
            coef = ls_solve(xw, yw, step=fit_step_name(model))
            ss = float(np.sum((yw - xw @ coef) ** 2))
            a, b = coef[0], coef[1]
            ratio = float(np.clip(1 - b / a, 0.0, 1.0)) if a > 0 else 1.0
            best.append((ss, xc, max(a / 2, 1e-4), ratio, coef[2] if adh else 0.0))
        best.sort(key=lambda t: t[0])
        out = []
        for _ss, xc, mu, ratio, fa in best[:2]:
            v = dict(current.params)
            v.update({"onset_load_parameter": xc, "slope_ratio": min(ratio, 0.98), "mu": mu})
            if adh:
                v["adhesion_force_N"] = max(fa, 0.0)
            out.append(param_vector(model, v))
        return out

    def sentence(self, p, rec):
        return (
            f"contact flattening at high load: Amontons up to 4F_n/(pi E d D) = "
            f"{fmt(p['onset_load_parameter'])}, slope x{fmt(p['slope_ratio'])} beyond"
        )

    def plant(self, kind, s):
        p = dict(s.p)
        x = s.x
        xl = self._xl(s.rec, x)
        xc = float(s.rng.uniform(0.08, 0.18))
        fc = xc / xl[-1] * x[-1]
        p["onset_load_parameter"] = xc
        p["slope_ratio"] = float(1 - s.size * s.sd[-1] / (2 * p["mu"] * (x[-1] - fc)))
        if p["slope_ratio"] < 0:
            p["slope_ratio"] = 0.0
        return p, {"onset_load_parameter": xc}
