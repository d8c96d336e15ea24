"""Speed of ``knotmech diagnose`` on 2000-row recordings (closed-form baselines).

Target (issue 5): a 2000-row recording diagnosed in under 5 s. Prints JSON with
the median wall time over repeats for each experiment kind (with an effect
planted, so that the bootstrap and held-out refits run, and without one).

    python benchmarks/diagnose_speed.py [--repeats 5]
"""

from __future__ import annotations

import argparse
import json
import platform
import time

import numpy as np

from knotmech.diagnose import diagnose, make_recording

CASES = [
    ("capstan_pull", "static_friction", "white"),
    ("capstan_pull", None, "white"),
    ("pinch", "contact_flattening", "white"),
    ("pinch", "rate_dependent_friction", "white"),
    ("tension_profile", "self_contact_nip", "white"),
    ("tension_profile", None, "white"),
    # AR(1) rho = 0.9 noise (second fitting pass when the estimated rho is near 1)
    ("pinch", "contact_flattening", "ar1"),
    ("capstan_pull", None, "ar1"),
    # capstan_hold (issue 12): readings reduced to 48 holds before the fit
    ("capstan_hold", "bending_resistance", "white"),
    ("capstan_hold", None, "ar1"),
]


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--rows", type=int, default=2000)
    args = parser.parse_args(argv)
    out = {
        "benchmark": "diagnose_speed",
        "rows": args.rows,
        "repeats": args.repeats,
        "target_seconds": 5.0,
        "python": platform.python_version(),
        "cases": {},
    }
    for exp, eff, noise in CASES:
        times = []
        verdicts = set()
        for r in range(args.repeats):
            rec, _ = make_recording(exp, eff, size=6.0, noise=noise, seed=100 + r, n=args.rows)
            assert rec.n >= 0.95 * args.rows
            t0 = time.perf_counter()
            rep = diagnose(rec, seed=r)
            times.append(time.perf_counter() - t0)
            verdicts.add(rep.verdict)
        key = f"{exp}:{eff or 'none'}" + (":ar1" if noise == "ar1" else "")
        out["cases"][key] = {
            "median_seconds": float(np.median(times)),
            "max_seconds": float(np.max(times)),
            "verdicts": sorted(verdicts),
        }
    from pathlib import Path

    from knotmech.diagnose import read_recording

    yarn = Path(__file__).parents[1] / "knotmech" / "data" / "recordings" / "capstan_yarn_rig.csv"
    rec = read_recording(yarn)
    t0 = time.perf_counter()
    rep = diagnose(rec, seed=0)
    out["cases"]["capstan_yarn_rig.csv"] = {
        "median_seconds": time.perf_counter() - t0,
        "max_seconds": time.perf_counter() - t0,
        "verdicts": [rep.verdict],
    }
    worst = max(c["median_seconds"] for c in out["cases"].values())
    out["median_seconds"] = float(np.median([c["median_seconds"] for c in out["cases"].values()]))
    out["worst_case_median_seconds"] = worst
    out["meets_target"] = worst < 5.0
    print(json.dumps(out, indent=2))
    return out


if __name__ == "__main__":
    main()
