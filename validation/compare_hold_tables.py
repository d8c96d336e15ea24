"""Two DER hold tables of one knot, point by point: which verdicts a rebuild changed.

::

    python -m validation.compare_hold_tables OLD.json NEW.json [--json]

Both files are ``knotmech-hold-table`` JSON (``knotmech/data/hold_phase_table_<knot>.json``,
``validation/tables/*.json``), read by :func:`knotmech.verdict.tables.read_hold_table`.
A point's verdict is the library's own, :meth:`knotmech.verdict.tables.HoldPoint.holds`
at its table's criterion limit (``criterion.limit_d_per_s``): it holds when the run went
to the end of its hold, kept its topology, solved, and its loaded end crept slower than the
limit (|creep| < limit); ``None`` (no verdict) when the solver failed or measured no creep.

Prints the grid, the number of points that hold in each table (old -> new), every point
whose verdict changed (d/2R, T_high/EA, mu, old and new creep speed, old -> new) and each
table's ``meta.cpu_s_total``. ``--json`` prints the same as one JSON object. Two tables of
different knots or grids, or a file that does not read as a hold table: a one-line error,
exit status 2.

As a validation case (``knotmech validate``) :func:`run` compares the clove-hitch table as
shipped until session 15 (anchor law with cap floor 0, kept as
``validation/tables/hold_phase_table_clove-hitch.floor0.json``) with the shipped one, rebuilt
under the floor rule 'min' (docs note sec. 12 of the floor-rule study), and checks that no
verdict changed at the clove-hitch paper's geometry (d = 4 mm on a 30 mm post,
d/2R = 0.1176) at mu 0.3.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

from knotmech.errors import InputError
from knotmech.verdict.tables import read_hold_table
from validation._common import finish

NAME = "compare_hold_tables"
SUMMARY = (
    "The clove-hitch hold table built with cap floor 0 against the shipped one, rebuilt with "
    "the anchor law's floor rule 'min': verdicts point by point, none changed at the "
    "paper's geometry at mu 0.3."
)
ROOT = Path(__file__).resolve().parent.parent
SHIPPED = ROOT / "knotmech" / "data" / "hold_phase_table_clove-hitch.json"
FLOOR0 = ROOT / "validation" / "tables" / "hold_phase_table_clove-hitch.floor0.json"
#: the clove-hitch paper's geometry (d = 4 mm, D = 30 mm: d/2R = 4/34) and friction
PAPER_D_OVER_2R, PAPER_MU = 0.1176, 0.3
_AXES = ("d_over_2R", "t_over_EA", "mu")


def _limit(table) -> float:
    """The table's creep-speed limit [d/s] (its criterion)."""
    return float(table.criterion["limit_d_per_s"])


def _same_grid(old, new) -> None:
    """InputError unless both tables are of one knot on one grid."""
    if old.knot != new.knot:
        raise InputError(f"the tables are of different knots: {old.knot} and {new.knot}")
    for a in _AXES:
        x, y = old.axes[a], new.axes[a]
        if x.shape != y.shape or not np.allclose(x, y, rtol=1e-9, atol=0.0):
            raise InputError(
                f"the tables' grids differ in {a}: {[float(v) for v in x]} and "
                f"{[float(v) for v in y]}"
            )


def _creep(value: float):
    return float(value) if math.isfinite(value) else None


def _run_note(p) -> str:
    """Why a run has no creep speed to show ("" when it has one): solver failed, ran
    off, topology changed."""
    if not p.solved:
        return "failed"
    if not p.ran_to_end:
        return "ran off"
    return "" if p.topology else "topology"


def compare(old, new) -> dict:
    """The comparison of two :class:`~knotmech.verdict.tables.HoldTable` of one knot.

    Returns
    -------
    dict
        ``knot``, ``grid`` (axis -> values), ``points``, ``limits`` (old, new) [d/s],
        ``holds`` (old, new), ``changed`` (list of dicts: d_over_2R, t_over_EA, mu,
        old_creep, new_creep [d/s] (None: not measured), old, new verdicts
        True/False/None, old_run, new_run: "failed", "ran off", "topology" or "") and
        ``cpu_s_total`` (old, new; None when the meta has none).
    """
    _same_grid(old, new)
    lo, ln = _limit(old), _limit(new)
    changed, holds = [], [0, 0]
    for p in old.points:
        q = new.point(p.d_over_2R, p.t_over_EA, p.mu)
        a, b = p.holds(lo), q.holds(ln)
        holds[0] += a is True
        holds[1] += b is True
        if a != b:
            changed.append(dict(d_over_2R=p.d_over_2R, t_over_EA=p.t_over_EA, mu=p.mu,
                                old_creep=_creep(p.creep_speed),
                                new_creep=_creep(q.creep_speed), old=a, new=b,
                                old_run=_run_note(p), new_run=_run_note(q)))  # fmt: skip
    return {
        "knot": old.knot,
        "grid": {a: [float(v) for v in old.axes[a]] for a in _AXES},
        "points": len(old.points),
        "limits": [lo, ln],
        "holds": holds,
        "changed": changed,
        "cpu_s_total": [old.meta.get("cpu_s_total"), new.meta.get("cpu_s_total")],
    }


def compare_files(old_path, new_path) -> dict:
    """:func:`compare` of two hold-table files (one-line InputError when one does not
    read, or they differ in knot or grid); adds ``files``."""
    result = compare(read_hold_table(old_path), read_hold_table(new_path))
    result["files"] = [str(old_path), str(new_path)]
    return result


def _word(v) -> str:
    return {True: "holds", False: "slips", None: "no verdict"}[v]


def _num(v) -> str:
    return "-" if v is None else f"{v:.4g}"


def format_comparison(r: dict) -> str:
    """The comparison for people: grid, counts, the changed points, CPU seconds."""
    g = r["grid"]
    lines = [f"knot: {r['knot']}"]
    if "files" in r:
        lines.append(f"old: {r['files'][0]}\nnew: {r['files'][1]}")
    lines += [
        f"grid: d/2R {g['d_over_2R']} x T/EA {g['t_over_EA']} x mu {g['mu']} "
        f"({r['points']} points)",
        f"criterion: |creep| < {r['limits'][0]:g} d/s (old), {r['limits'][1]:g} d/s (new)",
        f"holds: {r['holds'][0]} -> {r['holds'][1]} of {r['points']}",
        f"verdicts changed: {len(r['changed'])} of {r['points']}",
    ]
    if r["changed"]:
        lines.append(f"  {'d/2R':>8} {'T/EA':>8} {'mu':>5} {'old creep':>11} "
                     f"{'new creep':>11}  old -> new")  # fmt: skip
    for c in r["changed"]:
        lines.append(
            f"  {c['d_over_2R']:>8.4g} {c['t_over_EA']:>8.3g} {c['mu']:>5.3g} "
            f"{c['old_run'] or _num(c['old_creep']):>11} "
            f"{c['new_run'] or _num(c['new_creep']):>11}  "
            f"{_word(c['old'])} -> {_word(c['new'])}"
        )
    cpu = ["-" if v is None else f"{v:g}" for v in r["cpu_s_total"]]
    lines.append(f"cpu_s_total: old {cpu[0]}, new {cpu[1]}")
    return "\n".join(lines)


def run(quick: bool = True, out_dir=".") -> dict:
    """Validation case: the clove-hitch table built with cap floor 0 against the shipped one
    (floor rule 'min'; reads two committed files, no simulation)."""
    r = compare_files(FLOOR0, SHIPPED)
    paper = [c for c in r["changed"]
             if abs(c["d_over_2R"] - PAPER_D_OVER_2R) < 1e-3 and c["mu"] == PAPER_MU]  # fmt: skip
    checks = {
        "same knot and grid": True,
        "no verdict changed at the paper's geometry (d/2R 0.1176) at mu 0.3": not paper,
    }
    numbers = {"holds_old": r["holds"][0], "holds_new": r["holds"][1],
               "changed": len(r["changed"]), "points": r["points"],
               "cpu_s_total": r["cpu_s_total"]}  # fmt: skip
    notes = [format_comparison(r)]
    return finish(NAME, out_dir=out_dir, checks=checks, numbers=numbers, figures=[],
                  notes=notes, quick=quick, extra={"comparison": r})  # fmt: skip


def main(argv=None) -> int:
    p = argparse.ArgumentParser(
        prog="python -m validation.compare_hold_tables", description=__doc__.splitlines()[0]
    )
    p.add_argument("old", help="the old hold table (JSON)")
    p.add_argument("new", help="the new hold table of the same knot and grid (JSON)")
    p.add_argument("--json", action="store_true", help="print the comparison as JSON")
    a = p.parse_args(argv)
    try:
        r = compare_files(a.old, a.new)
    except InputError as exc:
        print(f"compare_hold_tables: error: {exc}", file=sys.stderr)
        return 2
    print(json.dumps(r, allow_nan=False) if a.json else format_comparison(r))
    return 0


if __name__ == "__main__":
    sys.exit(main())
