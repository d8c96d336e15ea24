r"""``static_friction``: a static coefficient above the kinetic one (capstan_pull).

The rod sticks until the stick line reaches :math:`T_\mathrm{low}e^{\mu_s\theta}`
(:math:`\mu_s = \mu + \Delta\mu_s`, through the experiment's ``apparent`` stage),
then the tension relaxes to the kinetic plateau as
:math:`T_k + (T_s - T_k)\,e^{-(u-u_p)/\ell}`. Free parameters ``dmu_static`` >= 0
(reported as ``mu_static``, ``mu_kinetic``) and ``decay_length_m``.
"""

from __future__ import annotations

import numpy as np

from knotmech.diagnose.effects._common import CLOVE, fmt
from knotmech.diagnose.effects.base import Effect
from knotmech.diagnose.model import param_vector

__all__ = ["StaticFriction"]


class StaticFriction(Effect):
    name = "static_friction"
    experiments = ("capstan_pull",)
    parameters = {
        "mu_static": ("= mu_kinetic", "static coefficient reached at the onset of sliding"),
        "mu_kinetic": ("mu", "kinetic coefficient of the sliding plateau"),
        "decay_length_m": ("any", "displacement over which the peak relaxes [m]"),
    }
    confusable_with = ("displacement_offset",)
    signature = "a force peak at the onset of sliding, then a drop"
    reference = CLOVE + ", Fig. 1(c): two-loops peak absent from FEM with kinetic friction only"
    report_keys = ("mu_static", "mu_kinetic", "decay_length_m")
    key_parameter = ("mu_static", "mu_static", "abs")

    def add_parameters(self, rec, names, lower, upper, fixed):
        span = float(np.ptp(rec.x)) or 1.0
        dx = np.diff(np.unique(rec.x))
        names += ["dmu_static", "decay_length_m"]
        lower += [0.0, 0.5 * float(np.median(dx)) if dx.size else 1e-4 * span]
        upper += [3.0, span]

    def is_internal(self, key):
        return key == "dmu_static"

    def capstan_curve(self, rec, p, value, *, parts):
        t_low, theta = rec.meta("T_low_N"), rec.meta("wrap_angle_rad")
        st, stick, plateau, xs = parts["stages"], parts["stick"], parts["plateau"], parts["xs"]
        peak = t_low * np.exp(st.apply("apparent", parts["mu"] + p["dmu_static"]) * theta)
        u_peak = (peak - t_low) / p["k_N_per_m"]
        ell = p["decay_length_m"]
        after = plateau + (peak - plateau) * np.exp(-np.maximum(xs - u_peak, 0.0) / ell)
        return np.where(xs < u_peak, stick, after)

    def starts(self, current, model, data, starts):
        rec = model.rec
        values = current.params
        span = float(np.ptp(rec.x)) or 1.0
        t_low, theta = rec.meta("T_low_N"), rec.meta("wrap_angle_rad")
        mu_peak = np.log(max(np.max(data.y), t_low * 1.0001) / t_low) / theta
        base = dict(values)
        base["dmu_static"] = max(mu_peak - values["mu"], 1e-3)
        out = []
        for frac in (0.01, 0.05, 0.2):
            base["decay_length_m"] = frac * span
            out.append(param_vector(model, base))
        return out

    def public(self, params, rec, out):
        out["mu_static"] = params["mu"] + params["dmu_static"]
        out["mu_kinetic"] = params["mu"]

    def sentence(self, p, rec):
        return (
            f"static friction at the onset of sliding: mu_s = {fmt(p['mu_static'])} vs "
            f"mu_k = {fmt(p['mu_kinetic'])}"
        )

    def plant(self, kind, s):
        p = dict(s.p)
        t_low, theta = s.meta["T_low_N"], s.meta["wrap_angle_rad"]
        plateau = t_low * np.exp(p["mu"] * theta)
        i = int(np.argmax(s.mean0 >= plateau * (1 - 1e-12)))
        peak = plateau + s.size * s.sd[i]
        p["dmu_static"] = float(np.log(peak / t_low) / theta - p["mu"])
        p["decay_length_m"] = float(s.rng.uniform(0.001, 0.004))
        return p, {"mu_static": p["mu"] + p["dmu_static"], "mu_kinetic": p["mu"]}
