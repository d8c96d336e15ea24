"""Print the checks of a shipped hold table as markdown: verdict maps, mu and light loads, CPU.

``python -m validation._hold_table_maps KNOT|PATH.json [--cache DIR]`` reads
``knotmech/data/hold_phase_table_<KNOT>.json`` and prints

- one verdict map per mu (rows d/2R, columns T_high/EA): ``H`` hold / ``S`` slip with the
  creep speed [d/s] over the scene's window (of the 3 s re-run where one ran, marked
  ``*``), ``S(off)`` the loaded end ran off, ``S(topo)`` the topology changed, ``failed``;
- monotonicity in mu: every (d/2R, T_high/EA) where a hold at one mu meets a slip at a
  larger mu;
- the lightest-loads property: per (d/2R, mu) column, whether the two lightest loads agree
  (the table then answers lighter loads from the lightest, rule ``settled-light-load``);
- counts of holds, slips, failed runs and re-runs, and the CPU per point (from the meta;
  with ``--cache`` the sweep cache of the build, per point and per column).

Not a validation case (the leading underscore keeps it out of ``knotmech validate``).
"""

from __future__ import annotations

import argparse
import math
import pickle
from pathlib import Path

from knotmech.scenes import phase_table as pt


def _cell(p, limit, rechecked) -> str:
    if not p.solved:
        return "failed"
    v = p.creep_speed
    if p.holds(limit):
        tag = "H"
    elif not p.ran_to_end:
        return "S(off)"
    elif not p.topology:
        return "S(topo)"
    else:
        tag = "S"
    star = "*" if (p.d_over_2R, p.t_over_EA, p.mu) in rechecked else ""
    return f"{tag} {v:.1e}{star}" if math.isfinite(v) else tag


def maps(table) -> str:
    ax = table.axes
    lim = table.criterion["limit_d_per_s"]
    rechecked = {tuple(r[:3]) for r in table.meta.get("rechecked", {}).get("points", [])}
    out = []
    for m in ax["mu"]:
        out.append(f"\nmu = mu_rr = {m:g}\n")
        out.append("| d/2R (d/D) | " + " | ".join(f"{y:g}" for y in ax["t_over_EA"]) + " |")
        out.append("|---" * (len(ax["t_over_EA"]) + 1) + "|")
        for x in ax["d_over_2R"]:
            cells = [_cell(table.point(x, y, m), lim, rechecked) for y in ax["t_over_EA"]]
            out.append(f"| {x:g} ({x / (1 - x):.3g}) | " + " | ".join(cells) + " |")
    return "\n".join(out)


def checks(table) -> str:
    ax = table.axes
    lim = table.criterion["limit_d_per_s"]
    mus = list(ax["mu"])
    bad = []
    for x in ax["d_over_2R"]:
        for y in ax["t_over_EA"]:
            pts = [table.point(x, y, m) for m in mus]
            for i, a in enumerate(pts):
                if not (a.solved and a.holds(lim)):
                    continue
                for b in pts[i + 1 :]:
                    if b.solved and not b.holds(lim):
                        bad.append((x, y, a.mu, b.mu))
    lines = [f"\nmonotonicity in mu: {len(bad)} (d/2R, T/EA) with a hold at a lower mu and a "
             "slip at a higher one" + (": " + "; ".join(
                 f"({x:g}, {y:g}): holds at {a:g}, slips at {b:g}" for x, y, a, b in bad)
                 if bad else "")]  # fmt: skip
    y0, y1 = ax["t_over_EA"][:2]
    agree, differ = 0, []
    for m in mus:
        for x in ax["d_over_2R"]:
            a, b = table.point(x, y0, m), table.point(x, y1, m)
            if a.solved and b.solved and a.holds(lim) == b.holds(lim):
                agree += 1
            else:
                differ.append(f"(d/2R {x:g}, mu {m:g}: {_cell(a, lim, set())} / "
                              f"{_cell(b, lim, set())})")  # fmt: skip
    n = len(mus) * len(ax["d_over_2R"])
    lines.append(
        f"lightest loads ({y0:g}, {y1:g} EA) agree in {agree} of {n} (d/2R, mu) "
        "columns" + ("; not in " + ", ".join(differ) if differ else "")
    )
    solved = [p for p in table.points if p.solved]
    held = sum(p.holds(lim) for p in solved)
    meta = table.meta
    lines.append(
        f"points {len(table.points)}: {held} hold, {len(solved) - held} slip, "
        f"{len(table.points) - len(solved)} failed; re-runs "
        f"{len(meta.get('rechecked', {}).get('points', []))}; CPU total "
        f"{meta.get('cpu_s_total')} s, per point {meta.get('cpu_s_per_point')} s; nodes "
        f"{meta.get('n_nodes')}; elapsed {meta.get('elapsed_s')} s"
    )
    return "\n".join(lines)


def cache_cpu(cache, knot) -> str:
    """CPU per point and per d/2R column from a build's sweep cache (first runs and re-runs)."""
    rows = []
    for f in Path(cache).glob("*/*.pkl"):
        r = pickle.loads(f.read_bytes())
        res = r.get("result") if isinstance(r, dict) else None
        if isinstance(res, dict) and res.get("knot", "clove-hitch") == knot:
            rows.append(res)
    by = {}
    for r in rows:
        key = (r["d_over_2R"], r.get("hold_time", 1.5) > 1.5)
        by.setdefault(key, []).append(float(r["cpu_s"]))
    out = [f"\ncache {cache}: {len(rows)} runs, CPU {sum(sum(v) for v in by.values()):.0f} s"]
    for (x, again), v in sorted(by.items()):
        out.append(f"  d/2R {x:g}{' re-runs' if again else ''}: {len(v)} runs, CPU "
                   f"{sum(v):.0f} s, {min(v):.1f}-{max(v):.1f} s per run")  # fmt: skip
    return "\n".join(out)


def _main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("knot", help="a knot (its shipped solid-rod table) or a table's path")
    p.add_argument("--cache", default=None, help="the build's sweep cache, for CPU per run")
    a = p.parse_args(argv)
    if a.knot.endswith(".json"):
        table = pt.read_hold_table(a.knot)
        a.knot = table.knot
    else:
        table = pt.load_hold_tables()[a.knot]
    print(maps(table))
    print(checks(table))
    if a.cache:
        print(cache_cpu(a.cache, a.knot))
    return 0


if __name__ == "__main__":
    raise SystemExit(_main())
