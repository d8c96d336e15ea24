"""Wall and CPU time of ``knotmech hold`` answered from a DER hold table, as a whole process.

Target (issue 23): under 1 s per answer including the Python start-up and imports, now that
the answer carries the capacity (slip load from the table, breaking load), the critical mu
and, without ``--mu``, the verdict over the material's friction range. Each case runs
``python -m knotmech hold ... --json -`` in a fresh process ``--repeats`` times (default 5);
CPU is the child's user + system time (``resource.RUSAGE_CHILDREN``). Prints JSON.

    python benchmarks/hold_table.py [--repeats 5]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TARGET_S = 1.0
CASES = {
    # the command: nylon (kappa 0.01 table), the thick nip and the breaking load
    "clove_nylon_200N": ["clove-hitch", "--rod-diameter", "6mm", "--post-diameter", "40mm",
                         "--mu", "0.4", "--load", "200N", "--material", "nylon"],
    # the clove-hitch paper's rod, decided by the solid-rod table; critical mu by bisection
    "clove_vps32_table": ["clove-hitch", "--rod-diameter", "4mm", "--post-diameter", "30mm",
                          "--mu", "0.3", "--load", "1.47N", "--material", "vps32"],
    # no --mu: polyester on steel (default), verdict over the friction range
    "clove_polyester_no_mu": ["clove-hitch", "--rod-diameter", "10mm", "--post-diameter",
                              "80mm", "--load", "1kN", "--material", "polyester"],
}  # fmt: skip


def _once(argv: list, env: dict) -> tuple:
    """(wall [s], cpu [s], JSON answer) of one fresh process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "knotmech", "hold", *argv, "--json", "-"],
                          capture_output=True, text=True, env=env, check=False)  # fmt: skip
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        raise SystemExit(f"hold failed: {proc.stderr.strip()}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, json.loads(proc.stdout)


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args(argv)
    path = os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH", "")) if p)
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", PYTHONPATH=path, MPLBACKEND="Agg")
    out = {"benchmark": "hold_table", "target_s": TARGET_S, "repeats": args.repeats,
           "python": platform.python_version(), "cpus": os.cpu_count(), "cases": {}}  # fmt: skip
    for name, case in CASES.items():
        runs = [_once(case, env) for _ in range(args.repeats)]
        walls = [r[0] for r in runs]
        cpus = [r[1] for r in runs]
        answer = runs[-1][2]
        cap = answer["capacity"] or {}
        out["cases"][name] = {
            "argv": case,
            "wall_median_s": statistics.median(walls),
            "wall_min_s": min(walls),
            "cpu_median_s": statistics.median(cpus),
            "under_target": statistics.median(walls) < TARGET_S,
            "verdict": answer["verdict"],
            "capacity_N": cap.get("value_N"),
            "limited_by": cap.get("limited_by"),
            "critical_mu": (answer["friction"] or {}).get("critical_mu"),
        }
    print(json.dumps(out, indent=2))
    return out


if __name__ == "__main__":
    main()
