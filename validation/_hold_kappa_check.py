"""Do a hitch's hold verdicts depend on the rope's bending scale kappa within the ropes'
range 0.003-0.03 (issue 23, item 4: "tables at 0.003 and 0.03 if the answers depend on
kappa")?

``python -m validation._hold_kappa_check KNOT [--cache-root DIR] [--out FILE]`` runs the
shipped kappa-0.01 table's columns d/2R 0.04762 and 0.1176 at mu 0.3 and 0.5 (the five
loads 1e-4 to 0.3 EA) at kappa 0.003 and 0.03 through
:func:`knotmech.verdict.build.build_hold_table` (the tables' protocol and rechecks, 2
processes, cached per kappa under ``--cache-root``), compares each verdict with the shipped
table's and prints JSON: per kappa the points, how many agree, the CPU.

Not a validation case (the leading underscore keeps it out of ``knotmech validate``): 40
DER runs, 2-25 minutes of CPU.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from knotmech.verdict.build import build_hold_table
from knotmech.verdict.tables import load_hold_table_sets

GRID = {"d_over_2R": (0.04762, 0.1176), "t_over_EA": (1e-4, 1e-3, 1e-2, 0.1, 0.3), "mu": (0.3, 0.5)}
KAPPAS = (0.003, 0.03)


def check(knot: str, cache_root, kappas=KAPPAS, processes: int = 2) -> dict:
    """{kappa: {"rows": [[d/2R, T/EA, mu, holds at kappa, holds at 0.01]], "same", "n",
    "cpu_s", "wall_s"}} against the shipped kappa-0.01 table of ``knot``."""
    ref = load_hold_table_sets()[knot][0.01]
    out = {}
    for k in kappas:
        t0 = time.time()
        cache = None if cache_root is None else Path(cache_root) / f"{knot}_kappa{k:g}"
        t = build_hold_table(knot, GRID, processes=processes, cache_dir=cache, bending_scale=k)
        rows = [
            [p.d_over_2R, p.t_over_EA, p.mu, p.holds(),
             ref.point(p.d_over_2R, p.t_over_EA, p.mu).holds()]
            for p in t.points
        ]  # fmt: skip
        out[f"{k:g}"] = {
            "rows": rows,
            "same": sum(r[3] == r[4] for r in rows),
            "n": len(rows),
            "cpu_s": t.meta.get("cpu_s_total"),
            "wall_s": round(time.time() - t0, 1),
        }
    return out


def _main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("knot", help="a hitch with a shipped kappa-0.01 table")
    p.add_argument("--cache-root", default=None, help="folder of the sweep caches")
    p.add_argument("--out", default=None, help="also write the JSON here")
    a = p.parse_args(argv)
    res = check(a.knot, a.cache_root)
    text = json.dumps({"knot": a.knot, "kappas": res})
    if a.out:
        Path(a.out).write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(_main())
