"""Benchmark: ``knotmech simulate`` of the tied bends and loops at their default mesh (issue 25).

Each bend of :mod:`knotmech.scenes.tied` pulled by :func:`knotmech.scenes.bends.bend` at its
record's defaults (d = 4 mm, E = 1 MPa, the nodes per rope of its record, settle 0.2 s,
set up to 20 d, pull 20 d at 40 mm/s, 20 frames each checked; the anchor law with its cap
floored at 1e-2). Prints JSON to stdout: per knot the median process CPU time [s] of
``--repeats`` runs (the kernels compiled by a first, untimed call), the steps, Newton
iterations and rejected steps, the nodes, the verdict and slip load. Target: cpu_s < 60
for each knot.

    OPENBLAS_NUM_THREADS=1 python benchmarks/tied.py [--knots sheet-bend,...] [--mu 0.3]
        [--repeats 1]
    OPENBLAS_NUM_THREADS=1 python benchmarks/tied.py --loops [--knots bowline,...] [--mu 0.3]
        [--pin-diameter 0.02] [--loading loop|end-to-end]

The loops (:func:`knotmech.scenes.loops.loop`: the eye round a fixed pin of
``--pin-diameter`` [m], default 20 mm = 5 d; settle 0.2 s, set both ends to 0.1 B/d^2,
release the tail 0.2 s, pull the standing part 20 d at 40 mm/s) report the slip load, the
tail drawn in and the eye growth [d] at the last frame. ``--loading end-to-end`` (the alpine
butterfly): no pin, both ends set and pulled apart 20 d each at 40 mm/s, the eye free; the
row's ``tail_draw_in_d`` is then the right end's growth outside the knot and
``eye_growth_d`` the eye drawn in [d] (:class:`knotmech.scenes.loops.LoopResult`).

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
from knotmech.scenes.loops import LOOPS, loop

D = 4e-3  #: the scenes' default rope diameter [m]
TIED = tuple(
    k.name for k in knots.records(family="bend") if k.curve.startswith("knotmech.scenes.tied.")
)


def _one(kind: str, mu: float) -> dict:
    t = time.process_time()
    r = bend(kind, mu_rod_rod=mu)
    return {"cpu_s": time.process_time() - t, **r.summary(rod_diameter=D)}


def _one_loop(knot: str, mu: float, pin: float, loading: str = "loop") -> dict:
    t = time.process_time()
    r = loop(knot, pin_diameter=None if loading == "end-to-end" else pin, mu_rod_rod=mu,
             loading=loading)  # fmt: skip
    return {"cpu_s": time.process_time() - t, **r.summary(rod_diameter=D)}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--knots", default=None, help="default: every tied bend (every loop)")
    p.add_argument("--mu", type=float, default=0.3)
    p.add_argument("--repeats", type=int, default=1)
    p.add_argument("--loops", action="store_true", help="the loops round a pin")
    p.add_argument("--pin-diameter", type=float, default=0.02)
    p.add_argument(
        "--loading",
        default="loop",
        choices=("loop", "end-to-end"),
        help="loops: on the loop (eye round the pin) or end to end [loop]",
    )
    a = p.parse_args()
    out = {"mu": a.mu, "repeats": a.repeats, "knots": {}}
    names = a.knots.split(",") if a.knots else (LOOPS if a.loops else TIED)
    if not a.loops:  # the kernels compiled by a first, untimed call
        bend("sheet-bend", settle_time=0.01, set_travel=1e-4, pull_distance=1e-4, n_frames=10)
    else:
        loop("bowline", pin_diameter=a.pin_diameter, settle_time=0.01, set_travel=1e-3,
             pull_distance=1e-3, n_frames=10)  # fmt: skip
        out["pin_diameter"] = a.pin_diameter
        out["loading"] = a.loading
    for kind in names:
        one = (lambda k=kind: _one_loop(k, a.mu, a.pin_diameter, a.loading)) if a.loops else (
            lambda k=kind: _one(k, a.mu))  # fmt: skip
        runs = [one() for _ in range(a.repeats)]
        last = dict(runs[-1])
        last["cpu_s"] = statistics.median(r["cpu_s"] for r in runs)
        out["knots"][kind] = last
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
