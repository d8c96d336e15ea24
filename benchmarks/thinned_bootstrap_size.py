"""Null size of the thinned parametric bootstrap (issue 14 part 3).

Beyond ``fitting.BOOT_ROWS`` rows the engine's bootstrap draws are recordings of
every k-th row (``fitting.thinned_null``). This script measures, on effect-free
recordings of ``--rows`` rows, the null distribution of the likelihood ratio of one
effect (the engine's statistic: ``fit_with_effect`` against the null refitted under
the augmented noise) from full-size draws and from thinned draws, and the rejection
rate of full-size null statistics against the thinned draws' 95 % and 99 % quantiles
(the size of the bootstrap test; nominal 5 % and 1 %), and the share of full-size
null statistics above the engine's BIC gate ``k log n`` (``k`` the degrees of freedom
the effect adds): the engine runs the bootstrap only above that gate.

The size is counted on the full-size draws against quantiles of ``--thin-draws``
thinned draws (default four times as many, so that the quantile's own sampling error,
which the Wilson interval of the count leaves out, is small beside the count's); a
two-sample Kolmogorov-Smirnov p-value compares the two distributions as a whole.
``--seed`` seeds the draws (independent runs need different seeds).

    python benchmarks/thinned_bootstrap_size.py [--rows 20000] [--draws 150]
        [--thin-draws 600] [--seed 1] [--kinds pinch]

Prints JSON.
"""

from __future__ import annotations

import argparse
import json

import numpy as np
from scipy.stats import ks_2samp

from knotmech.diagnose import get_effect, make_recording
from knotmech.diagnose.engine import _null_under
from knotmech.diagnose.fitting import Data, fit_baseline, fit_model, fit_with_effect, thinned_null
from knotmech.diagnose.stats import trial_starts, wilson_interval

CASES = [("tension_profile", "self_contact_nip"), ("pinch", "contact_flattening")]


def _lr(null, effect, data, starts, rng):
    y = null.mean + null.noise.sample(null.mean, starts, rng)
    d = Data(y, data.mu_nominal, data.mu_sigma)
    n0 = fit_model(null.model, d, [null.p], null.noise, starts)
    alt = fit_with_effect(n0, effect, d, starts)
    k = alt.model.n_free - n0.model.n_free + effect.extra_dof
    return 2.0 * (alt.loglik - _null_under(n0, alt, d, starts, None).loglik), k


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=int, default=20_000)
    parser.add_argument("--draws", type=int, default=150)
    parser.add_argument("--thin-draws", type=int, default=None)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--kinds", nargs="*", default=[c[0] for c in CASES])
    args = parser.parse_args(argv)
    thin_draws = args.thin_draws or 4 * args.draws
    out = {
        "rows": args.rows,
        "draws": args.draws,
        "thin_draws": thin_draws,
        "seed": args.seed,
        "cases": {},
    }
    for kind, name in CASES:
        if kind not in args.kinds:
            continue
        rec, _ = make_recording(kind, None, seed=7, n=args.rows)
        starts = trial_starts(rec.trial)
        data = Data(rec.y, rec.mu_nominal, rec.mu_nominal_sigma)
        base = fit_baseline(rec, data, starts)
        thin, tdata, tstarts, _ = thinned_null(base, data, starts, None)
        eff = get_effect(name)
        rng = np.random.default_rng(args.seed)
        full, ks = np.array([_lr(base, eff, data, starts, rng) for _ in range(args.draws)]).T
        th = np.array([_lr(thin, eff, tdata, tstarts, rng)[0] for _ in range(thin_draws)])
        gate = float(np.max(ks)) * np.log(rec.n)
        q95, q99 = np.quantile(th, [0.95, 0.99])
        k95, k99 = int(np.sum(full > q95)), int(np.sum(full > q99))
        out["cases"][f"{kind}:{name}"] = {
            "thinned_rows": int(tdata.y.size),
            "quantiles_full_50_90_95_99": [
                float(f"{v:.4g}") for v in np.quantile(full, [0.5, 0.9, 0.95, 0.99])
            ],
            "quantiles_thinned_50_90_95_99": [
                float(f"{v:.4g}") for v in np.quantile(th, [0.5, 0.9, 0.95, 0.99])
            ],
            "size_at_5pc": [
                k95 / args.draws,
                [round(v, 3) for v in wilson_interval(k95, args.draws)],
            ],
            "size_at_1pc": [
                k99 / args.draws,
                [round(v, 3) for v in wilson_interval(k99, args.draws)],
            ],
            "ks_pvalue_full_vs_thinned": float(f"{ks_2samp(full, th).pvalue:.3g}"),
            "bic_gate": round(gate, 2),
            "share_full_above_bic_gate": float(np.mean(full > gate)),
            "max_full": float(f"{np.max(full):.4g}"),
        }
    print(json.dumps(out, indent=2))
    return out


if __name__ == "__main__":
    main()
