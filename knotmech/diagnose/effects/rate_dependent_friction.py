r"""``rate_dependent_friction``: friction that depends on the sliding speed.

:math:`\mu \to \max(\mu + \beta\ln(v/v_\mathrm{ref}), 0)` per row,
:math:`v_\mathrm{ref}` the geometric-mean speed of the recording (at which ``mu`` is
reported); free parameter ``dmu_dlnv`` :math:`\beta \in [-2, 2]`. Needs at least two
sliding speeds. Rabinowicz, The Friction and Wear of Materials (1995).
"""

from __future__ import annotations

import numpy as np

from knotmech.diagnose.effects._common import fmt, ln_speed, reference_speed
from knotmech.diagnose.effects.base import Effect

__all__ = ["RateDependentFriction"]


class RateDependentFriction(Effect):
    name = "rate_dependent_friction"
    experiments = ("capstan_pull", "pinch", "knot_pull")
    parameters = {
        "dmu_dlnv": (0.0, "d mu / d ln(v): change of mu per e-fold of speed"),
        "reference_speed_m_per_s": ("-", "geometric-mean speed at which mu is reported"),
    }
    requires = ("speed",)
    confusable_with = ("finite_thickness", "contact_flattening")
    signature = "a plateau level (friction) that changes with sliding speed"
    reference = "Rabinowicz, The Friction and Wear of Materials (1995): velocity-dependent friction"
    acts_everywhere = True
    report_keys = ("dmu_dlnv", "reference_speed_m_per_s")
    #: material parameters, fitted once for all recordings by diagnose_many
    shared_parameters = ("dmu_dlnv",)
    key_parameter = ("dmu_dlnv", "dmu_dlnv", "rel")

    def add_parameters(self, rec, names, lower, upper, fixed):
        names += ["dmu_dlnv"]
        lower += [-2.0]
        upper += [2.0]

    def friction(self, rec, p, mu):
        return np.maximum(mu + p["dmu_dlnv"] * ln_speed(rec), 0.0)

    def public(self, params, rec, out):
        out["reference_speed_m_per_s"] = reference_speed(rec)

    def sentence(self, p, rec):
        return (
            f"rate-dependent friction: dmu/dln(v) = {fmt(p['dmu_dlnv'])} (mu = {fmt(p['mu'])} "
            f"at {fmt(p['reference_speed_m_per_s'])} m/s)"
        )

    def plant(self, kind, s):
        p = dict(s.p)
        lnv = np.log(s.speed) - np.mean(np.log(s.speed))
        if kind == "capstan_pull":
            plateau = s.meta["T_low_N"] * np.exp(p["mu"] * s.meta["wrap_angle_rad"])
            slope = plateau * s.meta["wrap_angle_rad"] * np.max(np.abs(lnv))
        elif kind == "knot_pull":  # F = mu f(D): dF/dmu = F/mu
            slope = float(np.max(s.mean0)) / p["mu"] * np.max(np.abs(lnv))
        else:
            slope = 2 * np.max(s.x) * np.max(np.abs(lnv))
        p["dmu_dlnv"] = float(s.size * np.max(s.sd) / slope) * s.rng.choice([-1.0, 1.0])
        return p, {"dmu_dlnv": p["dmu_dlnv"]}
