r"""``capstan_hold``: a load held, raised or lowered over a fixed post, at several wrap angles.

The classroom and rigging test (spec section 5): a weight hangs on one end; the
other, working end is pulled (``raise``), or held back / let down (``lower``), by
hand or by a force sensor, at a few wrap angles. Columns ``wrap_angle_rad`` (the
contact angle) and ``T_N`` (the tension measured at the working end); optional
columns ``load_N`` (the tension at the loaded end, when it varies from row to row)
and ``direction`` (``raise`` or ``lower``, when it varies), ``sigma``, ``trial``.
Metadata ``load_N`` and ``direction`` unless they are columns; optional
``rod_diameter_m``, ``post_diameter_m``, ``youngs_modulus_Pa``, ``mu_nominal``,
``mu_nominal_sigma``. At least 5 rows.

Baseline (ideal capstan, one coefficient; Euler 1762, Eytelwein 1808), with
:math:`s = +1` for ``raise`` (friction opposes the pull, :math:`T >` load) and
:math:`s = -1` for ``lower`` (friction helps hold, :math:`T <` load):

.. math:: T = W\,e^{s\,\mu\theta},

free parameter ``mu``. Stages: ``apparent(mu)`` (the mu the capstan sees),
``log_ratio(s mu theta)`` (:math:`\ln(T/W)`, for laws other than the exponential),
``output(T)`` (what the sensor reads).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from knotmech.diagnose.experiments.base import Experiment, Stages
from knotmech.errors import InputError

__all__ = ["CapstanHold", "hold_load", "hold_sign", "hold_radius"]

#: direction words and their sign s
DIRECTIONS = {"raise": 1.0, "lower": -1.0}


def hold_load(rec) -> np.ndarray:
    """Load W per row [N]: the ``load_N`` column, else the metadata value."""
    col = rec.extra.get("load_N") if rec.extra else None
    return col if col is not None else np.full(rec.n, rec.meta("load_N"))


def hold_sign(rec) -> np.ndarray:
    """s per row: +1 raise, -1 lower (the ``direction`` column, else the metadata)."""
    col = rec.extra.get("direction") if rec.extra else None
    if col is not None:
        return col
    return np.full(rec.n, DIRECTIONS[str(rec.metadata["direction"]).strip().lower()])


def hold_radius(rec) -> float | None:
    """Centreline radius on the post, (D + d)/2 (D/2 without a rod diameter) [m];
    None without a post diameter."""
    D = rec.metadata.get("post_diameter_m")
    if not isinstance(D, float):
        return None
    d = rec.metadata.get("rod_diameter_m")
    return 0.5 * (D + (d if isinstance(d, float) else 0.0))


class CapstanHold(Experiment):
    name = "capstan_hold"
    columns = ("wrap_angle_rad", "T_N")
    required_metadata = ()
    optional_columns = ("load_N", "direction")
    word_columns = {"direction": DIRECTIONS}
    min_rows = 5
    control_nonnegative = True
    stages = (
        "apparent(mu) -> the mu the capstan sees; log_ratio(s mu theta) -> ln(T/W); "
        "output(T) -> what the sensor reads"
    )

    def check(self, rec):
        if "load_N" not in rec.extra and "load_N" not in rec.metadata:
            return "a capstan_hold recording needs '# load_N: ...' metadata or a load_N column"
        if "direction" not in rec.extra:
            word = rec.metadata.get("direction")
            if word is None:
                return (
                    "a capstan_hold recording needs '# direction: raise' (or lower) "
                    "metadata or a direction column"
                )
            if str(word).strip().lower() not in DIRECTIONS:
                return f"metadata direction must be raise or lower, got {word!r}"
        if np.any(hold_load(rec) <= 0):
            return "load_N must be > 0"
        return None

    def reduce(self, rec):
        r"""Repeated readings of one hold reduced to one row (a robust mean).

        Consecutive rows with the same trial, wrap angle, direction and load are
        readings of one hold. Read at a sensor's resolution they are quantised (steps
        of about the noise), correlated in time, and hold a few spikes; the hold, not
        the reading, is the replicate of the experiment. Each hold becomes the mean of
        its readings within :math:`5\,\max(s, q)` of its median (``s`` the pooled
        robust sd of the readings about their holds' medians, 1.4826 MAD; ``q`` the
        reading step), so spikes are dropped; the noise is then estimated between
        holds. A ``sigma`` column becomes the sd of each mean. Returns the recording
        itself when every hold has one row.

        Raises
        ------
        InputError
            Fewer than ``min_rows`` holds.
        """
        y = rec.y
        keys = np.column_stack([rec.trial, rec.x, hold_sign(rec), hold_load(rec)])
        new = np.ones(rec.n, dtype=bool)
        new[1:] = np.any(keys[1:] != keys[:-1], axis=1)
        block = np.cumsum(new) - 1
        m = int(block[-1]) + 1
        if m == rec.n:
            return rec, None
        if m < self.min_rows:
            raise InputError(
                f"{rec.source}: {rec.n} readings of {m} holds (rows with the same trial, "
                f"angle, direction and load); a capstan_hold recording needs at least "
                f"{self.min_rows} holds"
            )
        med = np.array([np.median(y[block == b]) for b in range(m)])
        dev = y - med[block]
        counts = np.bincount(block)
        big = counts[block] >= 3
        s = 1.4826 * float(np.median(np.abs(dev[big]))) if np.any(big) else 0.0
        steps = np.diff(np.unique(y))
        q = float(np.median(steps)) if steps.size else 0.0
        keep = np.abs(dev) <= 5.0 * max(s, q, 1e-12 * float(np.max(np.abs(y))))
        idx = np.flatnonzero(new)
        vals = np.array([np.mean(y[(block == b) & keep]) for b in range(m)])
        sigma = None
        if rec.sigma is not None:
            sigma = np.array(
                [
                    np.sqrt(np.sum(rec.sigma[(block == b) & keep] ** 2))
                    / np.sum((block == b) & keep)
                    for b in range(m)
                ]
            )
        extra = {k: v[idx] for k, v in rec.extra.items()}
        speed = rec.speed[idx] if rec.speed is not None else None
        out = replace(
            rec,
            x=rec.x[idx],
            y=vals,
            metadata=dict(rec.metadata),
            sigma=sigma,
            trial=rec.trial[idx],
            speed=speed,
            extra=extra,
        )
        note = {
            "readings": rec.n,
            "holds": m,
            "readings_per_hold_median": float(np.median(counts)),
            "dropped_readings": int(np.sum(~keep)),
            "reading_step": float(f"{q:.4g}"),
            "rule": "mean of a hold's readings within 5 max(robust sd, step) of its median",
        }
        return out, note

    def start(self, rec, y) -> dict:
        s, w, th = hold_sign(rec), hold_load(rec), rec.x
        ok = (y > 0) & (th > 0)
        if np.sum(ok) >= 1:
            # least squares of ln(T/W) = s mu theta through the origin
            z = s[ok] * th[ok]
            mu = float(np.dot(z, np.log(y[ok] / w[ok])) / np.dot(z, z))
        else:
            mu = 0.2
        return {"mu": min(max(mu, 1e-3), 4.0)}

    def mean(self, rec, p, effects=()):
        st = Stages(rec, p, effects)
        mu = st.apply("apparent", p["mu"])
        lr = st.apply("log_ratio", hold_sign(rec) * mu * rec.x, mu=mu)
        return st.apply("output", hold_load(rec) * np.exp(lr))

    def synth_setup(self, rng, n, speeds):
        """8 wrap angles from pi/4 to 2 pi, raise and lower, replicate readings.

        Rows come in three trials; each trial reads every (direction, angle) pair,
        ``n // 48`` readings each (a sensor read a few times per hold).
        """
        meta = {
            "load_N": float(rng.uniform(2.0, 10.0)),
            "rod_diameter_m": float(rng.choice([0.002, 0.004, 0.008])),
            "post_diameter_m": float(rng.uniform(0.02, 0.06)),
        }
        angles = np.linspace(0.25 * np.pi, 2.0 * np.pi, 8)
        reps = max(n // 48, 1)
        x, sign, trial = [], [], []
        for t in range(3):
            for s in (1.0, -1.0):
                for a in angles:
                    x += [a] * reps
                    sign += [s] * reps
                    trial += [t] * reps
        params = {"mu": float(rng.uniform(0.15, 0.35))}
        return meta, np.array(x), np.array(trial), None, params, {"direction": np.array(sign)}

    def synth_noise_scale(self, meta, mean0):
        """0.4 % of the load: a sensor's resolution does not grow with the reading."""
        return 0.004 * meta["load_N"]

    def out_of_catalogue(self, x, meta, p, mean0, sd, size, rng):
        """A dip of the tension in a band of wrap angles (a snag on the post)."""
        c = rng.uniform(0.35, 0.65) * (x.max() - x.min()) + x.min()
        w = 0.06 * (x.max() - x.min())
        bump = np.exp(-0.5 * ((x - c) / w) ** 2)
        i = int(np.argmax(bump))
        return mean0 - size * sd[i] * bump
