"""Benchmark: ``knotmech simulate`` of the tied bends at their default mesh (issue 25).

Each bend of :mod:`knotmech.scenes.tied` pulled by :func:`knotmech.scenes.bends.bend` at its
record's defaults (d = 4 mm, E = 1 MPa, the nodes per rope of its record, settle 0.2 s,
set up to 20 d, pull 20 d at 40 mm/s, 20 frames each checked; the anchor law with its cap
floored at 1e-2). Prints JSON to stdout: per knot the median process CPU time [s] of
``--repeats`` runs (the kernels compiled by a first, untimed call), the steps, Newton
iterations and rejected steps, the nodes, the verdict and slip load. Target: cpu_s < 60
for each knot.

    OPENBLAS_NUM_THREADS=1 python benchmarks/tied.py [--knots sheet-bend,...] [--mu 0.3]
        [--repeats 1]

Measured (shared 2-core machine, 3-6 other jobs; mu = 0.3, one run each): see
``docs/notes/knots-and-curves/tied-knots-pulled.md``.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time

from knotmech import knots
from knotmech.scenes.bends import bend

TIED = tuple(
    k.name for k in knots.records(family="bend") if k.curve.startswith("knotmech.scenes.tied.")
)


def _one(kind: str, mu: float) -> dict:
    t = time.process_time()
    r = bend(kind, mu_rod_rod=mu)
    cpu = time.process_time() - t
    return {
        "cpu_s": cpu,
        "steps": int(r.stats.get("steps", 0)),
        "newton_iterations": int(r.stats.get("newton_iterations", 0)),
        "rejected_steps": int(r.stats.get("rejected_steps", 0)),
        "nodes": int(r.positions.shape[1]),
        "status": r.status,
        "message": r.message,
        "verdict": r.verdict,
        "slip_load_N": r.slip_load if r.verdict == "slips" else None,
        "max_force_N": r.max_force,
        "tail_drawn": r.tail_drawn,
        "roll_d": r.roll / 4e-3,
        "frames_checked": r.frames_checked,
    }


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--knots", default=",".join(TIED))
    p.add_argument("--mu", type=float, default=0.3)
    p.add_argument("--repeats", type=int, default=1)
    a = p.parse_args()
    bend("sheet-bend", settle_time=0.01, set_travel=1e-4, pull_distance=1e-4, n_frames=10)
    out = {"mu": a.mu, "repeats": a.repeats, "knots": {}}
    for kind in a.knots.split(","):
        runs = [_one(kind, a.mu) for _ in range(a.repeats)]
        last = dict(runs[-1])
        last["cpu_s"] = statistics.median(r["cpu_s"] for r in runs)
        out["knots"][kind] = last
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
