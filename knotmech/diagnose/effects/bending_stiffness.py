r"""``bending_stiffness``: an elastic rope lifts off the post near both ends and grips less.

An elastic rod of bending stiffness :math:`B` meets and leaves the post through
short elastica of length :math:`\sqrt{B/T}`; the contact arc shrinks and
concentrated reactions appear at the lift-off points. To first order in
:math:`B` (:func:`knotmech.analytic.capstan.capstan_ratio_bending`,
``derivations/capstan_ode.py``)

.. math::
    \frac{T_\mathrm{high}}{T_\mathrm{low}} = e^{\mu\theta}\Bigl[1 - \frac{1+\mu^2}{2}
        \frac{B}{R^2}\Bigl(\frac{1}{T_\mathrm{low}} - \frac{1}{T_\mathrm{high}}\Bigr)\Bigr],

with :math:`T_\mathrm{low} = W, T_\mathrm{high} = T` for raise and
:math:`T_\mathrm{high} = W, T_\mathrm{low} = T` for lower (solved for :math:`T` by
fixed-point iteration; the bracket is kept >= 0.05). The correction is largest where
a tension is small, so lowered rows (small T at large angles) lose much more grip
than raised ones: raise and lower disagree with one mu, in the direction opposite to
``bending_resistance``. Fitted as :math:`b = B/(R^2 W)` in [0, 1] (``R`` the
centreline radius, :math:`(D+d)/2`, or :math:`D/2` without a rod diameter); reported as
``bending_stiffness_N_m2`` :math:`B = bR^2\bar W`. Needs ``post_diameter_m``.

References
----------
Stuart, Quart. J. Mech. Appl. Math. 14 (1961) 401 (capstan with bending stiffness);
Jung, Pan & Kang, Tribol. Int. 41 (2008) 524; this package's derivation.
"""

from __future__ import annotations

import numpy as np

from knotmech.diagnose.effects._common import amplitude_beyond_mu, fmt
from knotmech.diagnose.effects.base import Effect
from knotmech.diagnose.experiments.capstan_hold import hold_load, hold_radius, hold_sign
from knotmech.diagnose.model import param_vector

__all__ = ["BendingStiffness"]


class BendingStiffness(Effect):
    name = "bending_stiffness"
    experiments = ("capstan_hold",)
    parameters = {
        "bending_number": (0.0, "b = B / (R^2 W): bending stiffness over R^2 times the load"),
        "bending_stiffness_N_m2": (0.0, "B = EI of the rope [N m^2]"),
    }
    requires = ("post_diameter",)
    confusable_with = ("bending_resistance", "pressure_dependent_friction")
    signature = (
        "less grip than one mu, most where a tension is small: lowered rows at large angles "
        "read above the capstan curve, raised rows slightly below"
    )
    reference = "Stuart (1961); Jung, Pan & Kang, Tribol. Int. 41 (2008) 524: stiff ropes grip less"
    acts_everywhere = True
    report_keys = ("bending_stiffness_N_m2", "bending_number")
    key_parameter = ("bending_number", "bending_number", "rel")

    def missing(self, rec):
        out = super().missing(rec)
        if hold_radius(rec) is None:
            out.append("post_diameter_m metadata")
        return out

    def add_parameters(self, rec, names, lower, upper, fixed):
        names += ["bending_number"]
        lower += [0.0]
        upper += [1.0]

    def log_ratio(self, rec, p, value, *, mu):
        s = hold_sign(rec)
        c = 0.5 * (1.0 + mu**2) * p["bending_number"]
        lr = value
        for _ in range(4):  # T enters only through the small correction
            q = np.exp(-lr)  # W / T
            raise_term = np.maximum(1.0 - c * (1.0 - q), 0.05)
            lower_term = np.maximum(1.0 - c * (q - 1.0), 0.05)
            corr = np.where(s > 0, raise_term, lower_term)
            lr = value + s * np.log(corr)
        return lr

    def starts(self, current, model, data, starts):
        v = dict(current.params)
        return [param_vector(model, dict(v, bending_number=b)) for b in (0.01, 0.1)]

    def public(self, params, rec, out):
        r = hold_radius(rec)
        w = float(np.mean(hold_load(rec)))
        out["bending_stiffness_N_m2"] = float(params["bending_number"] * r**2 * w)

    def sentence(self, p, rec):
        return (
            f"bending stiffness of the rope: it lifts off the post and grips less, "
            f"B = {fmt(p['bending_stiffness_N_m2'])} N m^2 "
            f"(B/(R^2 W) = {fmt(p['bending_number'])}, mu = {fmt(p['mu'])})"
        )

    def plant(self, kind, s):
        p = dict(s.p)

        def mean_of(a):
            return s.experiment.mean(s.rec, dict(p, bending_number=a), (self,))

        def base_of(mu):
            return s.experiment.mean(s.rec, dict(p, mu=mu), ())

        # sized by what a refitted mu cannot absorb
        p["bending_number"] = amplitude_beyond_mu(mean_of, base_of, p["mu"], s.sd, s.size, 0.01)
        return p, {"bending_number": p["bending_number"]}
