"""Clove-hitch hold points with the anchor law as shipped and with a floored cap (issue 24).

The quick free-end case of tests/scenes/test_clove_hitch.py (the clove-hitch paper's
parameters: mu = 0.3 on post and between the strands, T_high = 1.47 N, 120 nodes,
dt = 2 ms, hold 0.4 s) and its asymmetric case (T_low = 0.5 N), each with
``AnchorFriction.cap_floor`` = 0 (the law of every shipped table) and the given floors:

    OPENBLAS_NUM_THREADS=1 python validation/_sticking_hitch.py [CAP_FLOOR ...]

Prints one JSON line per run: verdict, creep, end displacement, steps, CPU.
"""

from __future__ import annotations

import contextlib
import functools
import importlib
import json
import sys
import time

from knotmech.rod.friction import AnchorFriction

QUICK = dict(settle_time=0.2, load_time=0.2, hold_time=0.4, n_nodes=120, dt=2e-3, n_frames=21)
CASES = {
    "free": dict(loading="free", t_high=1.47, mu_rod_post=0.3, mu_rod_rod=0.3),
    "asymmetric": dict(loading="asymmetric", t_high=1.47, t_low=0.5),
}


@contextlib.contextmanager
def hitch_cap_floor(cap_floor):
    """Inside the block the hitch scenes build their rod-rod anchor law with ``cap_floor``."""
    mod = importlib.import_module("knotmech.scenes._hitch")
    orig = mod.AnchorFriction
    mod.AnchorFriction = functools.partial(AnchorFriction, cap_floor=float(cap_floor))
    try:
        yield
    finally:
        mod.AnchorFriction = orig


def main(floors):
    from knotmech.scenes.clove_hitch import clove_hitch

    for case, kw in CASES.items():
        for floor in floors:
            c0 = time.process_time()
            with hitch_cap_floor(floor):
                r = clove_hitch(**kw, **QUICK)
            row = dict(
                case=case, cap_floor=floor, verdict=r.verdict, cpu_s=time.process_time() - c0
            )
            for name in ("creep_speed", "end_displacement", "stats", "topology_preserved"):
                val = getattr(r, name, None)
                if val is not None and hasattr(val, "tolist"):
                    val = val.tolist()
                    val = val[-1] if isinstance(val, list) and val else val
                row[name] = val
            print(json.dumps(row, default=str), flush=True)


if __name__ == "__main__":
    main([0.0] + [float(x) for x in sys.argv[1:]] if sys.argv[1:] else [0.0, 1e-2])
