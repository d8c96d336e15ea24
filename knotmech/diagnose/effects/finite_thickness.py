r"""``finite_thickness``: rod thickness on a post, :math:`\mu \to \mu_\mathrm{eff}(\mu, D/d)`.

Friction acts half a rod diameter off the centreline; the capstan then sees
:math:`\mu_\mathrm{eff} < \mu` (clove-hitch paper, eq. 3;
:func:`knotmech.analytic.capstan.mu_eff`), and ``mu`` becomes the material
coefficient carrying the ``mu_nominal`` prior. No new free parameter: the data
alone see only a smaller mu; the effect is the reconciliation with ``mu_nominal``.
"""

from __future__ import annotations

import numpy as np

from knotmech.analytic.capstan import mu_eff, mu_from_mu_eff
from knotmech.diagnose.effects._common import CLOVE, fmt
from knotmech.diagnose.effects.base import Effect
from knotmech.diagnose.model import param_vector

__all__ = ["FiniteThickness"]


def _d_over_d(rec) -> float:
    return rec.meta("post_diameter_m") / rec.meta("rod_diameter_m")


class FiniteThickness(Effect):
    name = "finite_thickness"
    experiments = ("capstan_pull", "tension_profile", "capstan_hold")
    parameters = {
        "mu": ("mu_nominal", "material friction coefficient (prior mu_nominal)"),
        "mu_eff": ("= mu", "effective coefficient mu_eff(mu, D/d) seen by the capstan"),
    }
    requires = ("mu_nominal", "diameters")
    confusable_with = ("rate_dependent_friction",)
    signature = "a slower decay / lower ratio than mu_nominal predicts (a global rate error)"
    reference = CLOVE + ", eq. (3)"
    acts_everywhere = True
    report_keys = ("mu", "mu_eff")
    key_parameter = ("mu_eff", "mu_eff", "abs")

    def apparent(self, rec, p, mu):
        return mu_eff(np.maximum(mu, 0.0), _d_over_d(rec))

    def starts(self, current, model, data, starts):
        rec = model.rec
        values = dict(current.params)
        dt = _d_over_d(rec)
        mu_app = min(values["mu"], 0.95 * np.sqrt(dt))
        values["mu"] = float(mu_from_mu_eff(max(mu_app, 1e-6), dt))
        if "dmu_static" in values:
            values["dmu_static"] = values["dmu_static"] * 1.2
        return [param_vector(model, values)]

    def public(self, params, rec, out):
        out["mu_eff"] = float(mu_eff(params["mu"], _d_over_d(rec)))

    def sentence(self, p, rec):
        return (
            f"finite thickness on the post: mu_eff = {fmt(p['mu_eff'])} for material "
            f"mu = {fmt(p['mu'])} (D/d = {fmt(_d_over_d(rec))}, "
            f"mu_nominal = {fmt(rec.mu_nominal)})"
        )

    def plant(self, kind, s):
        dd = s.meta["post_diameter_m"] / s.meta["rod_diameter_m"]
        mu = s.p["mu"]
        shift = float(mu - mu_eff(mu, dd))
        return dict(s.p), {"mu": mu, "mu_eff": mu - shift}

    def prior_sigma(self, truth, size):
        # sized by the prior's pull: (mu - mu_eff) / mu_nominal_sigma = size
        return (truth["mu"] - truth["mu_eff"]) / max(size, 1e-9)
