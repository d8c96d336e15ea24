r"""``sensor_offset``: a zero offset of the force sensor at the working end (capstan_hold).

The sensor reads :math:`T + c` instead of :math:`T`: a tare taken with a little load
on it, or a drift of the bridge between tare and reading. Free parameter
``sensor_offset_N`` :math:`c` (signed, at most half the largest reading). Its
signature is an additive level, the same for raise and lower rows and for every
angle, which an exponential in the wrap angle cannot absorb (it shows most at the
smallest readings). The load is taken as given (a weight, or read with a tare of
its own).
"""

from __future__ import annotations

import numpy as np

from knotmech.diagnose.effects._common import fmt
from knotmech.diagnose.effects.base import Effect
from knotmech.diagnose.model import param_vector

__all__ = ["SensorOffset"]


class SensorOffset(Effect):
    name = "sensor_offset"
    experiments = ("capstan_hold",)
    parameters = {"sensor_offset_N": (0.0, "reading minus tension at the working end [N]")}
    confusable_with = ("bending_resistance", "pressure_dependent_friction")
    signature = "a constant level added to every reading (most visible at small tensions)"
    reference = (
        "Measurement practice (zero drift of a strain-gauge load cell; e.g. OIML R 60 "
        "(2017), minimum dead load output return)"
    )
    acts_everywhere = True
    report_keys = ("sensor_offset_N",)
    key_parameter = ("sensor_offset_N", "sensor_offset_N", "rel")

    def add_parameters(self, rec, names, lower, upper, fixed):
        half = 0.5 * (float(np.max(np.abs(rec.y))) or 1.0)
        names += ["sensor_offset_N"]
        lower += [-half]
        upper += [half]

    def output(self, rec, p, value):
        return value + p["sensor_offset_N"]

    def starts(self, current, model, data, starts):
        v = dict(current.params)
        r = data.y - current.mean
        return [param_vector(model, v), param_vector(model, dict(v, sensor_offset_N=np.median(r)))]

    def sentence(self, p, rec):
        return (
            f"force-sensor zero offset: the working-end sensor reads "
            f"{fmt(p['sensor_offset_N'])} N at zero tension"
        )

    def plant(self, kind, s):
        p = dict(s.p)
        p["sensor_offset_N"] = float(s.size * np.min(s.sd)) * float(s.rng.choice([-1.0, 1.0]))
        return p, {"sensor_offset_N": p["sensor_offset_N"]}
