r"""``displacement_offset``: a wrong zero of the displacement axis (capstan_pull).

The slack :math:`\delta_0 \ge 0` of the baseline is replaced by a signed shift,
:math:`u - \delta_0 \to u + u_\mathrm{off}`; a pre-stretch (:math:`u_\mathrm{off} > 0`,
tension above T_low at zero displacement) is what the baseline cannot fit. The
signed range lets the model nest the baseline (:math:`u_\mathrm{off} = -\delta_0`),
so the relaxed inequality counts as one degree of freedom.

``knot_pull``: the end-to-end distance is read from a wrong zero,
:math:`D \to D + u_\mathrm{off}` (the baseline has no shift of its own, so the offset
is one new free parameter, bounded by half the recorded range either way).
"""

from __future__ import annotations

import numpy as np

from knotmech.diagnose.effects._common import amplitude_for_size, fmt
from knotmech.diagnose.effects.base import Effect
from knotmech.diagnose.experiments import get_experiment
from knotmech.diagnose.model import param_vector

__all__ = ["DisplacementOffset"]


class DisplacementOffset(Effect):
    name = "displacement_offset"
    experiments = ("capstan_pull", "knot_pull")
    parameters = {"offset_m": (0.0, "pre-stretch: true displacement = recorded + offset_m [m]")}
    confusable_with = ("static_friction",)
    signature = "the whole curve shifted along x (tension above T_low at zero displacement)"
    reference = "Measurement practice: zero of the displacement axis set under pre-tension"
    extra_dof = 1
    report_keys = ("offset_m",)
    key_parameter = ("offset_m", "offset_m", "rel")

    def add_parameters(self, rec, names, lower, upper, fixed):
        span = float(np.ptp(rec.x)) or 1.0
        if "delta0_m" not in names:  # knot_pull: a new signed shift
            names += ["offset_m"]
            lower += [-0.5 * span]
            upper += [0.5 * span]
            return
        i = names.index("delta0_m")
        names[i] = "offset_m"
        lower[i] = -(float(np.max(rec.x)) if np.max(rec.x) > 0 else span)
        upper[i] = span

    def capstan_shift(self, rec, p, value):
        return rec.x + p["offset_m"]

    def knot_shift(self, rec, p, value):
        return rec.x + p["offset_m"]

    def starts(self, current, model, data, starts):
        if "delta0_m" not in current.params:  # knot_pull: no shift, then either way
            span = float(np.ptp(model.rec.x)) or 1.0
            v = dict(current.params)
            return [param_vector(model, dict(v, offset_m=s * span)) for s in (0.0, -0.02, 0.02)]

        b = get_experiment(model.rec.experiment).start(model.rec, data.y)
        values = current.params
        v = dict(values)
        v["offset_m"] = b["offset_m"] if b["offset_m"] > 0 else -values["delta0_m"]
        return [param_vector(model, v), param_vector(model, dict(v, offset_m=-values["delta0_m"]))]

    def sentence(self, p, rec):
        return f"displacement offset: the curve is shifted by {fmt(1e3 * p['offset_m'])} mm"

    def plant(self, kind, s):
        if kind == "knot_pull":
            p = dict(s.p)

            # the size counts what the baseline cannot absorb: F = mu f(D) is linear in
            # mu, so the shifted curve is compared with its best rescaling of mean0
            m0 = s.mean0

            def mean_of(a):
                f = s.experiment.mean(s.rec, dict(p, offset_m=a), (self,))
                return f - m0 * (np.dot(f, m0) / np.dot(m0, m0)) + m0

            dx = 1e-3 * float(np.ptp(s.x))
            a = amplitude_for_size(mean_of, s.mean0, s.sd, s.size, dx)
            p["offset_m"] = float(a * s.rng.choice([-1.0, 1.0]))
            return p, {"offset_m": p["offset_m"]}
        p = dict(s.p)
        p.pop("delta0_m")
        p["offset_m"] = float(s.size * s.sd[0] / p["k_N_per_m"])
        return p, {"offset_m": p["offset_m"]}
