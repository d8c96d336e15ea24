r"""``pressure_dependent_friction``: fibre friction :math:`f = aN^n` (Howell), not Amontons.

Yarns, fibres and polymers rub with a friction force that grows less than linearly
with the normal force, :math:`f = aN^n`, :math:`n < 1` (Howell 1953, 1954; Howell &
Mazur 1953). On a post :math:`N = T/R` per unit length, and with :math:`\mu` the
apparent coefficient at the load :math:`W`, :math:`dT/d\varphi = s\,\mu W^{1-n}T^n`
integrates to (:func:`knotmech.analytic.capstan.capstan_high_tension_nonlinear`)

.. math:: \Bigl(\frac{T}{W}\Bigr)^{1-n} = 1 + s(1-n)\,\mu\theta,

:math:`n = 1` giving the exponential. Free parameter ``friction_exponent``
:math:`n \in [0.2, 1]`. Signature: :math:`\ln(T/W)` curves with the angle --
the friction coefficient grows where the tension is small, so a lowered rope holds
ever better with the angle, and a raised one gains less than exponentially.
"""

from __future__ import annotations

import numpy as np

from knotmech.diagnose.effects._common import amplitude_beyond_mu, fmt
from knotmech.diagnose.effects.base import Effect
from knotmech.diagnose.model import param_vector

__all__ = ["PressureDependentFriction"]


class PressureDependentFriction(Effect):
    name = "pressure_dependent_friction"
    experiments = ("capstan_hold",)
    parameters = {
        "friction_exponent": (1.0, "n of f = a N^n (1: Amontons)"),
    }
    confusable_with = ("bending_stiffness", "sensor_offset")
    signature = "ln(T/load) curved in the wrap angle (a friction coefficient that varies with T)"
    reference = (
        "Howell, J. Text. Inst. 44 (1953) T359 and 45 (1954) T575; Howell & Mazur, "
        "J. Text. Inst. 44 (1953) T59: f = a N^n for fibres"
    )
    acts_everywhere = True
    report_keys = ("friction_exponent",)
    key_parameter = ("friction_exponent", "friction_exponent", "abs")

    def add_parameters(self, rec, names, lower, upper, fixed):
        names += ["friction_exponent"]
        lower += [0.2]
        upper += [1.0]

    def log_ratio(self, rec, p, value, *, mu):
        k = 1.0 - p["friction_exponent"]
        if k < 1e-9:
            return value
        # (T/W)^(1-n) = 1 + k s mu theta; a lowered rope that holds everything reads ~0
        return np.log(np.maximum(1.0 + k * value, 1e-6)) / k

    def starts(self, current, model, data, starts):
        v = dict(current.params)
        return [param_vector(model, dict(v, friction_exponent=n)) for n in (0.97, 0.75)]

    def sentence(self, p, rec):
        return (
            f"pressure-dependent (fibre) friction: f = a N^n with n = "
            f"{fmt(p['friction_exponent'])} (mu = {fmt(p['mu'])} at the load)"
        )

    def plant(self, kind, s):
        p = dict(s.p)

        def mean_of(d):
            return s.experiment.mean(s.rec, dict(p, friction_exponent=1.0 - d), (self,))

        def base_of(mu):
            return s.experiment.mean(s.rec, dict(p, mu=mu), ())

        # sized by what a refitted mu cannot absorb
        d = amplitude_beyond_mu(mean_of, base_of, p["mu"], s.sd, s.size, 0.02)
        p["friction_exponent"] = float(max(1.0 - d, 0.2))
        return p, {"friction_exponent": p["friction_exponent"]}
