"""``knot_pull --baseline der`` on DER-made recordings: verdicts, fitted mu, timings.

Each recording is made by :func:`knotmech.diagnose.der_knot.der_made_recording` (the
DER overhand knot of the implicit-contact-model paper's rod, its force surface fitted to
runs at 0.85 and 1.2 times the true mu: a grid of its own, not the baseline's; noise 3 %
of the local force plus a floor), null or with an effect planted at 8 noise sd, and
diagnosed with ``baseline="der"`` (the baseline runs its own grid). Prints JSON: per
case the verdict, fitted and true mu, the planted and fitted key parameter, the
seconds of the diagnosis (its simulations included) and the false-positive count on
the nulls (the measured size of the test at alpha = 0.01).

    python -m validation._knot_pull_der [--nulls 6] [--effects 2]
"""

from __future__ import annotations

import argparse
import json
import time

from knotmech.diagnose import diagnose, get_effect
from knotmech.diagnose.der_knot import der_made_recording


def run(nulls: int = 6, effects: int = 2) -> dict:
    cases = [(None, 1 + k % 2, 0.3 + 0.1 * (k % 2), k) for k in range(nulls)]
    for k in range(effects):
        cases.append(("displacement_offset", 1 + k % 2, 0.35, 100 + k))
        cases.append(("rate_dependent_friction", 1 + k % 2, 0.35, 200 + k))
    rows = []
    for effect, turns, mu, seed in cases:
        rec, truth = der_made_recording(turns, mu, effect, size=8.0, seed=seed)
        t0 = time.perf_counter()
        rep = diagnose(rec, baseline="der", seed=seed)
        row = {
            "effect": effect or "none",
            "turns": turns,
            "seed": seed,
            "verdict": rep.verdict,
            "mu_true": mu,
            "mu_fitted": rep.final["parameters"]["mu"],
            "seconds": round(time.perf_counter() - t0, 1),
            "simulations": rep.details["der"]["simulations"],
        }
        if effect is not None:
            key = get_effect(effect).key_parameter[0]
            row[key + "_true"] = float(f"{truth[key]:.4g}")
            row[key + "_fitted"] = rep.final["parameters"].get(key)
        rows.append(row)
        print(json.dumps(row), flush=True)
    nul = [r for r in rows if r["effect"] == "none"]
    eff = [r for r in rows if r["effect"] != "none"]
    out = {
        "case": "knot_pull_der",
        "rows": rows,
        "nulls": len(nul),
        "null_false_positives": sum(r["verdict"] != "none" for r in nul),
        "effects": len(eff),
        "effects_named": sum(r["verdict"] == r["effect"] for r in eff),
        "median_seconds": sorted(r["seconds"] for r in rows)[len(rows) // 2],
    }
    return out


def main(argv=None) -> dict:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--nulls", type=int, default=6)
    p.add_argument("--effects", type=int, default=2)
    a = p.parse_args(argv)
    out = run(a.nulls, a.effects)
    print(json.dumps(out, indent=2))
    return out


if __name__ == "__main__":
    main()
