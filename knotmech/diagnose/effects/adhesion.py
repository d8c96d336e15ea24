r"""``adhesion``: a load-independent tangential force (pinch), :math:`F_t \to F_t + F_a`.

Free parameter ``adhesion_force_N`` in [0, max |F_t|] (Bowden & Tabor 1950:
:math:`F = \mu N + F_a`).
"""

from __future__ import annotations

import numpy as np

from knotmech.diagnose.effects._common import fmt
from knotmech.diagnose.effects.base import Effect
from knotmech.diagnose.model import param_vector

__all__ = ["Adhesion"]


class Adhesion(Effect):
    name = "adhesion"
    experiments = ("pinch",)
    parameters = {"adhesion_force_N": (0.0, "load-independent tangential force [N]")}
    signature = "an intercept at zero normal load"
    reference = "Bowden & Tabor, The Friction and Lubrication of Solids (1950): F = mu N + F_a"
    acts_everywhere = True
    report_keys = ("adhesion_force_N",)
    key_parameter = ("adhesion_force_N", "adhesion_force_N", "rel")

    def add_parameters(self, rec, names, lower, upper, fixed):
        names += ["adhesion_force_N"]
        lower += [0.0]
        upper += [float(np.max(np.abs(rec.y))) or 1.0]

    def output(self, rec, p, value):
        return value + p["adhesion_force_N"]

    def starts(self, current, model, data, starts):
        slope, icpt = np.polyfit(model.rec.x, data.y, 1)
        v = dict(current.params)
        v["adhesion_force_N"] = max(icpt, 0.0)
        v2 = dict(v)
        v2["mu"] = max(slope / 2, 1e-3)
        return [param_vector(model, v), param_vector(model, v2)]

    def sentence(self, p, rec):
        return f"adhesion: F_t = {fmt(p['adhesion_force_N'])} N at zero normal load"

    def plant(self, kind, s):
        p = dict(s.p)
        p["adhesion_force_N"] = float(s.size * s.sd[0])
        return p, {"adhesion_force_N": p["adhesion_force_N"]}
