"""Stick-slip chatter and nulls on short pinch recordings: verdict counts (a helper).

The numbers of docs/notes/diagnose-noise-and-statistics/issue26-tight-pull-prior-ripple.md,
section 3. Pinch recordings of 50 and 60 rows (sorted uniform loads, x up to 0.3), white
or correlated noise of sd 0.4 % of the top force; ``chatter``: a ripple growing linearly
with the load to ``--size`` noise sd, 3-7 periods over the range. ``--off`` disables the
ripple test (the verdicts before it). Prints the verdict counts.

    python -m validation._ripple_census chatter --size 6 --seeds 200 220 [--off]
    python -m validation._ripple_census ar1-0.9 --seeds 100 130
"""

from __future__ import annotations

import argparse
from collections import Counter

import numpy as np
from scipy.signal import lfilter

from knotmech.diagnose.engine import diagnose
from knotmech.diagnose.recording import recording_from_arrays

#: noise of the nulls: AR coefficients (AR(1) scaled by its stationary sd, AR(2) by the
#: series' own)
NOISE = {
    "white": (),
    "ar1-0.5": (0.5,),
    "ar1-0.9": (0.9,),
    "ar2-a": (0.6, 0.2),
    "ar2-b": (1.0, -0.5),
}


def make(kind: str, n: int, size: float, seed: int):
    """One recording: ``kind`` "chatter" (white noise) or a key of :data:`NOISE`."""
    rng = np.random.default_rng([seed, 26])
    d = 0.004
    meta = {"rod_diameter_m": d, "pinch_diameter_m": 0.01, "youngs_modulus_Pa": 1.0e6}
    scale = np.pi * 1e6 * d * 0.01 / 4
    mu = rng.uniform(0.2, 0.45)
    x = np.sort(rng.uniform(0.01, 0.3, n)) * scale
    mean = 2 * mu * x
    sd = 0.004 * mean.max()
    if kind == "chatter":
        t = (x - x[0]) / (x[-1] - x[0])
        k, ph = rng.uniform(3, 7), rng.uniform(0, 2 * np.pi)
        mean = mean + size * sd * t * np.sin(2 * np.pi * k * t + ph)
    phi = NOISE.get(kind, ())
    e = lfilter([1.0], np.r_[1.0, -np.asarray(phi, float)], rng.standard_normal(n + 200))[200:]
    if len(phi) == 1:  # the stationary variance
        e = e * np.sqrt(1.0 - phi[0] ** 2)
    elif phi:  # the sample's
        e = e / np.std(e)
    return recording_from_arrays("pinch", x, mean + sd * e, metadata=meta)


def main(argv=None) -> dict:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("kind", choices=["chatter", *NOISE])
    p.add_argument("--size", type=float, default=8.0)
    p.add_argument("--seeds", type=int, nargs=2, default=(0, 10))
    p.add_argument("--off", action="store_true", help="without the ripple test")
    a = p.parse_args(argv)
    if a.off:
        import knotmech.diagnose.noisefloor as nf

        nf.ripple_p_value = lambda *args, **kw: 1.0
    out = Counter()
    for seed in range(*a.seeds):
        for n in (50, 60):
            out[diagnose(make(a.kind, n, a.size, seed), seed=seed).verdict] += 1
    print(a.kind, a.size if a.kind == "chatter" else "", dict(out))
    return dict(out)


if __name__ == "__main__":
    main()
