"""Time to answer ``knotmech hold`` from a DER table, start-up included.

Target (issue 10): under 1 s for a clove hitch answered from the shipped table,
including the Python start-up and imports. Runs ``python -m knotmech hold ...`` in a
fresh process ``--repeats`` times per case and prints JSON with the median and
minimum wall time, plus the in-process time of ``knotmech.hold`` (imports excluded)
and the import time of ``knotmech.cli.hold``'s dependencies.

    python benchmarks/hold_speed.py [--repeats 5] [--simulate]

``--simulate`` adds the ``--simulate`` answer (target under 30 s): ``knotmech hold
clove-hitch ... --simulate`` for the clove-hitch paper's case (d = 4 mm, D = 30 mm, 1.47 N,
VPS32: 120 nodes, 2 s of simulated time, anchor law), run once in a fresh process, with the
DER run's own wall and CPU time. The first run in a fresh checkout also compiles the numba
kernels (about a minute); run it twice and read the second.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]  # the knotmech checkout this file belongs to
CASES = {
    # the clove-hitch paper's case on its rod: decided by the DER table
    "clove_table": ["clove-hitch", "--rod-diameter", "4mm", "--post-diameter", "30mm",
                    "--mu", "0.3", "--load", "1.47N", "--material", "vps32"],
    # issue 10's engineer: nylon, outside the tables, decided by the thick-nip model
    "clove_nylon_200N": ["clove-hitch", "--rod-diameter", "6mm", "--post-diameter", "40mm",
                         "--mu", "0.4", "--load", "200N", "--material", "nylon"],
    "capstan": ["capstan", "--wrap-angle", "360deg", "--rod-diameter", "4mm",
                "--post-diameter", "30mm", "--mu", "0.3", "--load", "6N",
                "--free-end-load", "1N"],
}  # fmt: skip
TARGET_S = 1.0
SIMULATE_TARGET_S = 30.0
SIMULATE_CASE = CASES["clove_table"] + ["--simulate"]


def _run(argv, env):
    t0 = time.perf_counter()
    proc = subprocess.run(
        [sys.executable, "-m", "knotmech", "hold", *argv, "--json", "-"],
        capture_output=True,
        text=True,
        env=env,
        check=False,
    )
    dt = time.perf_counter() - t0
    if proc.returncode != 0:
        raise SystemExit(f"hold failed: {proc.stderr.strip()}")
    return dt, json.loads(proc.stdout)


def _wall(argv, env) -> float:
    return _run(argv, env)[0]


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument(
        "--simulate", action="store_true", help="also time one --simulate answer (~30 s)"
    )
    args = parser.parse_args(argv)
    path = os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH", "")) if p)
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", PYTHONPATH=path)
    sys.path.insert(0, str(ROOT))
    out = {
        "benchmark": "hold_speed",
        "target_s": TARGET_S,
        "python": platform.python_version(),
        "machine": platform.machine(),
        "cpus": os.cpu_count(),
        "load_average": list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
        "repeats": args.repeats,
        "cases": {},
    }
    for name, case in CASES.items():
        walls = [_wall(case, env) for _ in range(args.repeats)]
        out["cases"][name] = {
            "median_s": round(statistics.median(walls), 4),
            "min_s": round(min(walls), 4),
            "under_target": statistics.median(walls) < TARGET_S,
        }
    # in-process: the verdict itself, once the modules are loaded
    t0 = time.perf_counter()
    import knotmech.cli.hold  # noqa: F401
    import knotmech.verdict as hold_module

    out["import_s"] = round(time.perf_counter() - t0, 4)
    kw = dict(rod_diameter=4e-3, post_diameter=30e-3, mu=0.3, load=1.47, material="vps32")
    hold_module.hold("clove-hitch", **kw)  # reads the shipped tables once
    t0 = time.perf_counter()
    n = 20
    for _ in range(n):
        hold_module.hold("clove-hitch", **kw)
    out["verdict_in_process_s"] = round((time.perf_counter() - t0) / n, 5)
    if args.simulate:
        import resource

        c0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        wall, data = _run(SIMULATE_CASE, env)
        c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        der = data.get("der") or {}
        creep = data.get("creep") or {}
        out["simulate"] = {
            "case": " ".join(["knotmech", "hold", *SIMULATE_CASE]),
            "target_s": SIMULATE_TARGET_S,
            "wall_s": round(wall, 2),
            "cpu_s": round((c1.ru_utime + c1.ru_stime) - (c0.ru_utime + c0.ru_stime), 2),
            "under_target": wall < SIMULATE_TARGET_S,
            "verdict": data.get("verdict"),
            "decided_by": data.get("decided_by"),
            "creep_speed_d_per_s": creep.get("speed_d_per_s"),
            "n_nodes": 120,
            "message": der.get("message"),
        }
    from knotmech import _json

    print(_json.dumps(out, indent=2))
    return out


if __name__ == "__main__":
    main()
