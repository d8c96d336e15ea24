r"""``bending_resistance``: the work of bending a rope onto the post and straightening it.

A real rope or yarn is not a perfectly flexible string: bending it onto the post
and straightening it where it leaves costs work (friction between its fibres; its
bending moment lags its curvature). Coulomb measured this *rope stiffness* on
pulleys and found the extra pull linear in the tension, :math:`(a + bT)/D`
(Coulomb 1781, *roideur des cordes*); keeping the proportional part, each of the
two transitions multiplies the tension in the direction of motion by a fixed
factor, so that

.. math:: T = W\,e^{s(\mu\theta + \beta)},\qquad \beta \ge 0,

with :math:`s = +1` raise, :math:`-1` lower. Free parameter ``bending_loss``
:math:`\beta` (reported with ``bending_factor`` :math:`e^\beta`, the ratio the
working end needs at zero wrap). Signature: :math:`\ln(T/W)` extrapolates to
:math:`\pm\beta` at :math:`\theta = 0` instead of 0 -- raised rows ask more, lowered
rows less, than one mu allows: raise and lower disagree with a single mu through
the origin. (A constant error :math:`\delta` of the wrap angle looks the same,
:math:`\beta = \mu\delta`: the data cannot tell them apart.)

References
----------
C.-A. Coulomb, *Théorie des machines simples* (1781; Mém. Acad. Sci. Paris 10, 1785),
experiments on the stiffness of ropes; J. Weisbach, *Principles of the Mechanics of
Machinery and Engineering* (1848), sec. on rope stiffness.
"""

from __future__ import annotations

import numpy as np

from knotmech.diagnose.effects._common import amplitude_beyond_mu, fmt
from knotmech.diagnose.effects.base import Effect
from knotmech.diagnose.experiments.capstan_hold import hold_load, hold_sign
from knotmech.diagnose.model import fit_step_name, param_vector
from knotmech.diagnose.stats import ls_solve

__all__ = ["BendingResistance"]


class BendingResistance(Effect):
    name = "bending_resistance"
    experiments = ("capstan_hold",)
    parameters = {
        "bending_loss": (0.0, "beta: ln of the tension ratio the rope needs at zero wrap"),
        "bending_factor": (1.0, "exp(beta)"),
    }
    confusable_with = ("sensor_offset", "bending_stiffness")
    signature = (
        "ln(T/load) extrapolates to +beta (raise) / -beta (lower) at zero wrap: a larger "
        "ratio than one mu through the origin, the same at every angle"
    )
    reference = "Coulomb (1781), rope stiffness (roideur des cordes): extra pull (a + bT)/D"
    acts_everywhere = True
    report_keys = ("bending_loss", "bending_factor")
    key_parameter = ("bending_loss", "bending_loss", "rel")

    def add_parameters(self, rec, names, lower, upper, fixed):
        names += ["bending_loss"]
        lower += [0.0]
        upper += [2.0]

    def log_ratio(self, rec, p, value, *, mu):
        return value + hold_sign(rec) * p["bending_loss"]

    def starts(self, current, model, data, starts):
        """From current values, and from ln(T/W) = s mu theta + s beta (least squares)."""
        rec = model.rec
        v = dict(current.params)
        out = [param_vector(model, v)]
        s, w = hold_sign(rec), hold_load(rec)
        ok = data.y > 0
        if np.sum(ok) >= 3:
            design = np.column_stack([s[ok] * rec.x[ok], s[ok]])
            mu, beta = ls_solve(design, np.log(data.y[ok] / w[ok]), step=fit_step_name(model))
            out.append(param_vector(model, dict(v, mu=max(mu, 1e-3), bending_loss=max(beta, 0.0))))
        return out

    def public(self, params, rec, out):
        out["bending_factor"] = float(np.exp(params["bending_loss"]))

    def sentence(self, p, rec):
        return (
            f"bending resistance of the rope: the working end needs x{fmt(p['bending_factor'])} "
            f"(raise) or /{fmt(p['bending_factor'])} (lower) at zero wrap, "
            f"beta = {fmt(p['bending_loss'])} (mu = {fmt(p['mu'])})"
        )

    def plant(self, kind, s):
        p = dict(s.p)

        def mean_of(a):
            return s.experiment.mean(s.rec, dict(p, bending_loss=a), (self,))

        def base_of(mu):
            return s.experiment.mean(s.rec, dict(p, mu=mu), ())

        # sized by what a refitted mu cannot absorb
        p["bending_loss"] = amplitude_beyond_mu(mean_of, base_of, p["mu"], s.sd, s.size, 0.01)
        return p, {"bending_loss": p["bending_loss"]}
