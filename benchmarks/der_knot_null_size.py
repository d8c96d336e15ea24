"""Null size and power of ``knot_pull --baseline der`` on DER-made recordings.

Each recording is :func:`knotmech.diagnose.der_knot.der_made_recording` (turns 1 + seed % 2,
mu 0.3 + 0.1 (seed % 2) for nulls, 0.35 for effects; the law that makes it is a surface
fitted to runs at 0.85 and 1.2 times the true mu), diagnosed with ``baseline="der"``
twice: with the surrogate's own error in the baseline (``der_knot.SURROGATE_ERROR``
True, ``on``, the default) and without it (``off``). The DER runs are cached on disk
(``--cache``): a run depends only on the knot, mu and the pulled range, so the two
diagnoses of one recording share the baseline's runs, and recordings of one (turns, mu)
share the runs that make them. Prints one JSON line per recording and a summary (counts,
Wilson 95 % intervals, median seconds per diagnosis with its runs, and without them).

    python benchmarks/der_knot_null_size.py --seeds 2000 2100 [--effect displacement_offset]
        [--size 8] [--cache /tmp/der_runs] [--variants on off]
"""

from __future__ import annotations

import argparse
import hashlib
import json
import pickle
import time
from pathlib import Path

import numpy as np

from knotmech.diagnose import der_knot, diagnose, get_effect
from knotmech.diagnose.stats import wilson_interval


def _cached_runs(cache: Path) -> None:
    """Make ``DERKnotLaw.run`` read and write its raw runs under ``cache``."""
    cache.mkdir(parents=True, exist_ok=True)
    plain = der_knot.DERKnotLaw.run

    def run(self, mu):
        key = (
            self.turns,
            self.h,
            self.E,
            self.L,
            self.rho,
            self.nu,
            self.v,
            round(self.d0, 12),
            round(self.d1, 12),
            self.n_nodes,
            round(float(mu), 6),
        )
        path = cache / (hashlib.sha1(repr(key).encode()).hexdigest() + ".pkl")
        m = round(float(mu), 6)
        if m in self._raw:
            return self._raw[m]
        if path.exists():
            d, f, sec = pickle.loads(path.read_bytes())
            self._raw[m] = (d, f)
            self.seconds += sec
            self._refit()
            return d, f
        t0 = self.seconds
        out = plain(self, mu)
        path.write_bytes(pickle.dumps((out[0], out[1], self.seconds - t0)))
        return out

    der_knot.DERKnotLaw.run = run


def one(seed, effect, size, variants) -> dict:
    if effect is None:
        turns, mu = 1 + seed % 2, 0.3 + 0.1 * (seed % 2)
    else:
        turns, mu = 1 + seed % 2, 0.35
    rec, truth = der_knot.der_made_recording(turns, mu, effect, size=size, seed=seed)
    row = {"seed": seed, "turns": turns, "mu_true": mu, "effect": effect or "none"}
    if effect is not None:
        key = get_effect(effect).key_parameter[0]
        row[key + "_true"] = float(f"{truth[key]:.4g}")
    default = der_knot.SURROGATE_ERROR
    for v in variants:
        der_knot.SURROGATE_ERROR = v == "on"
        t0 = time.perf_counter()
        rep = diagnose(rec, baseline="der", seed=seed)
        sec = time.perf_counter() - t0
        der = rep.details["der"]
        row[v] = {
            "verdict": rep.verdict,
            "mu": rep.final["parameters"]["mu"],
            "seconds": round(sec, 2),
            "simulation_seconds": der["simulation_seconds"],
            "p_structure": rep.details["located"]["baseline_residuals"]["p_value"],
            **({"surrogate_error": der["surrogate_error"]} if "surrogate_error" in der else {}),
        }
        if effect is not None:
            row[v][key] = rep.final["parameters"].get(key)
    der_knot.SURROGATE_ERROR = default
    return row


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, nargs=2, default=[2000, 2010])
    ap.add_argument("--effect", default="none")
    ap.add_argument("--size", type=float, default=8.0)
    ap.add_argument("--cache", type=Path, default=Path("/tmp/knotmech_der_runs"))
    ap.add_argument("--variants", nargs="+", default=["on", "off"])
    a = ap.parse_args(argv)
    _cached_runs(a.cache)
    effect = None if a.effect == "none" else a.effect
    rows = []
    for seed in range(*a.seeds):
        row = one(seed, effect, a.size, a.variants)
        rows.append(row)
        print(json.dumps(row), flush=True)
    out = {"effect": a.effect, "size_sd": a.size, "recordings": len(rows), "variants": {}}
    for v in a.variants:
        hit = sum(r[v]["verdict"] == (effect or "none") for r in rows)
        n = len(rows)
        k = hit if effect is not None else n - hit
        out["variants"][v] = {
            ("named" if effect is not None else "not_none"): k,
            "rate": k / max(n, 1),
            "wilson95": [round(x, 4) for x in wilson_interval(k, n)] if n else None,
            "verdicts": {
                vv: sum(r[v]["verdict"] == vv for r in rows)
                for vv in sorted({r[v]["verdict"] for r in rows})
            },
            "median_seconds": float(np.median([r[v]["seconds"] for r in rows])),
        }
    print(json.dumps(out, indent=2))
    return out


if __name__ == "__main__":
    main()
