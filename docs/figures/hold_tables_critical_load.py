"""The critical load of every shipped hold table over (d/D, mu): the clove-hitch paper's Fig. 4
for each hitch, solid rod and fibre rope at each shipped kappa (issue 23, item 4).

For each table, each friction mu = mu_rr and each d/2R column, the slip band is the
bracket :func:`knotmech.verdict.capacity.column_bracket` reads (the slip load's band of
``knotmech hold``): the last load held above the lightest hold and the first load that
slipped, in T_high/EA. Drawn as a bar from the one to the other at d/D = x / (1 - x)
(x = d/2R, R = (D + d)/2), with a marker at the geometric mid-point; an arrow up where
nothing slipped above the holds (the slip load lies above 0.3 EA, the top of the tables);
a cross at the bottom where nothing held (slips at the lightest load, 1e-4 EA). A run that
failed in the solver is no evidence of a slip, as in ``hold``'s band: passed over below a
real slip; where only failed runs lie above the last hold, the bar ends at the first of them.

    python docs/figures/hold_tables_critical_load.py [OUT.png]   # default: next to this file

Prints the bands as JSON ({table: {mu: [[d/D, low, high], ...]}}; high null: open above).
Reads the tables only (about 2 s).
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import matplotlib
import matplotlib.ticker

from knotmech.verdict.capacity import column_bracket
from knotmech.verdict.tables import load_hold_table_sets, load_legs_table_sets

FLOOR = 3e-5  #: where "slips at the lightest load" is drawn [T_high/EA]
TOP = 1.0  #: where an open band's arrow ends [T_high/EA]
COLOURS = {0.1: "#1b9e77", 0.2: "#d95f02", 0.3: "#7570b3", 0.5: "#e7298a", 0.8: "#66a61e"}


def bands(table) -> dict:
    """{mu: [(d/D, low, high)]} of one table (T_high/EA; low 0: slips at the lightest
    load; high inf: nothing slipped above the holds)."""
    ax = table.axes
    ys = [float(y) for y in ax["t_over_EA"]]
    out = {}
    for m in ax["mu"]:
        rows = []
        for x in ax["d_over_2R"]:
            votes = [table.point(x, y, m).holds() for y in ys]
            lo, hi = column_bracket(ys, votes)
            rows.append((float(x) / (1 - float(x)), lo, hi))
        out[float(m)] = rows
    return out


def tables() -> dict:
    """{title: table} of every shipped hold table: solid rods first, then the fibre-rope
    tables of each knot from the stiffest kappa to the softest."""
    out = {}
    sets = load_hold_table_sets()
    for knot in sorted(sets):
        if 1.0 in sets[knot]:
            out[f"{knot} (solid rod)"] = sets[knot][1.0]
    for knot in sorted(sets):
        for kappa in sorted((k for k in sets[knot] if k != 1.0), reverse=True):
            out[f"{knot} (fibre rope, kappa {kappa:g})"] = sets[knot][kappa]
    for knot, by_kappa in sorted(load_legs_table_sets().items()):
        for kappa, by_f in sorted(by_kappa.items()):
            for f, t in sorted(by_f.items()):
                out[f"{knot}, T_low {f:g} T_high (kappa {kappa:g})"] = t
    return out


def _panel(ax, title: str, b: dict) -> None:
    for k, (m, rows) in enumerate(sorted(b.items())):
        c = COLOURS.get(m, "k")
        shift = 1 + 0.06 * (k - 2)  # side by side within a column
        for dD, lo, hi in rows:
            xx = dD * shift
            if lo == 0:
                ax.plot([xx], [FLOOR], "x", color=c, ms=4)
                continue
            top = hi if math.isfinite(hi) else TOP
            ax.plot([xx, xx], [lo, top], "-", color=c, lw=2.2, alpha=0.8)
            if math.isfinite(hi):
                ax.plot([xx], [math.sqrt(lo * hi)], "o", color=c, ms=3.5)
            else:
                ax.plot([xx], [TOP], "^", color=c, ms=4)
        ax.plot([], [], "-", color=c, lw=2.2, label=f"mu {m:g}")
    ax.set_xscale("log")
    ax.set_xticks([0.02, 0.05, 0.133, 0.3], ["0.02", "0.05", "0.133", "0.3"])
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xlim(0.014, 0.42)
    ax.set_yscale("log")
    ax.set_ylim(FLOOR / 2, TOP * 2)
    ax.axhline(0.3, color="0.6", lw=0.6, ls=":")
    ax.set_title(title, fontsize=7.5)
    ax.tick_params(labelsize=6.5)


def main(out=None) -> dict:
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    tabs = tables()
    allb = {name: bands(t) for name, t in tabs.items()}
    n = len(allb)
    cols = 4
    rows = math.ceil(n / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(11, 2.6 * rows), sharex=True, sharey=True)
    flat = list(getattr(axes, "flat", [axes]))
    for ax, (name, b) in zip(flat, allb.items(), strict=False):
        _panel(ax, name, b)
    for ax in flat[n:]:
        ax.axis("off")
    for ax in flat[::cols]:
        ax.set_ylabel("critical T_high/EA", fontsize=7)
    for ax in flat[-cols:]:
        ax.set_xlabel("d/D", fontsize=7)
    flat[0].legend(fontsize=6, loc="lower left")
    fig.suptitle(
        "Slip band of each shipped hold table (bar: last load held to first slip; ^: nothing "
        "slipped up to 0.3 EA; x: slips at 1e-4 EA; a bar may end at a failed run)",
        fontsize=8.5,
    )
    fig.tight_layout()
    path = Path(out) if out else Path(__file__).with_suffix(".png")
    fig.savefig(path, dpi=130)
    plt.close(fig)

    def num(v):
        return v if math.isfinite(v) else None

    return {
        name: {f"{m:g}": [[round(d, 4), lo, num(hi)] for d, lo, hi in r] for m, r in b.items()}
        for name, b in allb.items()
    }


if __name__ == "__main__":
    print(json.dumps(main(sys.argv[1] if len(sys.argv) > 1 else None)))
