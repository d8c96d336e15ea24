"""The axial-sliding curve of three hitches: sliding force against the normal load.

Sabater, Park, Crassous, Neukirch & Reis (J. Mech. Phys. Solids 2026, DOI
10.1016/j.jmps.2026.106628; arXiv 2604.06962) report a *superlinear* sliding strength of the
clove hitch against the legs' pre-tension (exponent not in the abstract we could read; the
surgical knots they start from: 1.6). Here the DER axial pull
(:func:`knotmech.scenes.axial.axial_pull`, d = 4 mm VPS32 rod, D = 30 mm pole, mu = 0.3) of

- the clove hitch (both legs at T perpendicular to the pole, clamped and dragged 12 d along
  it, as in the note's table; at 8 d the knot had not travelled one diameter at T >= 1 N;
  60 nodes),
- the rolling hitch (the standing part along the pole and the working end set at T; the
  standing part's end dragged 8 d along the pole, the working end keeping T; 90 nodes),
- the Prusik (two turns a side, both legs set at T along the pole and dragged 4 d; 200-node
  sling),

at a few normal loads each, the sliding force (F when the knot has travelled one rod
diameter) and the exponent of a log-log fit of it against T, each run with its CPU seconds
(``time.process_time``). Run::

    python -m validation._axial_hitches --out validation-out [--knots clove-hitch,rolling-hitch]

``--knots`` runs a subset (the JSON keeps the rows; :func:`summarise` assembles the figure
from rows of several runs). ``--sweep`` drags each hitch at T = 0.5 N instead, at mu = 0.1,
0.3 and 0.6 (rod-rod and rod-pole alike) and at the bending scale kappa = 0.01 (a fibre
rope's: EI / 100) at mu = 0.3, into ``axial_hitches_mu_kappa.json`` and its figure::

    python -m validation._axial_hitches --out validation-out --sweep
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from knotmech.scenes.axial import axial_pull

from ._axial_sliding import fit_exponent
from ._common import finish, format_result, save_figure

NAME = "axial_hitches"
#: normal loads T [N] of each hitch, and its drag
LOADS = {
    "clove-hitch": (0.25, 0.5, 1.0, 2.0),
    "rolling-hitch": (0.25, 0.5, 1.0, 2.0),
    "prusik": (0.25, 0.5, 1.0),
}
DRAG = {
    "clove-hitch": {"n_nodes": 60, "n_frames": 41, "drag_speed": 0.02, "drag_distance": 0.048},
    "rolling-hitch": {"n_nodes": 90, "n_frames": 21, "drag_speed": 0.02,
                      "drag_distance": 0.032},
    "prusik": {"wraps": 2, "post_diameter": 30e-3, "n_frames": 11, "drag_speed": 0.02,
               "drag_distance": 0.016},
}  # fmt: skip


#: the sweep over friction and bending scale (:func:`sweep`): each hitch at SWEEP_LOAD [N],
#: at these (mu, kappa)
SWEEP_LOAD = 0.5
SWEEP = ((0.1, 1.0), (0.3, 1.0), (0.6, 1.0), (0.3, 0.01))


def drag_row(knot: str, normal_load: float, *, mu: float = 0.3, bending_scale: float = 1.0) -> dict:
    """One drag of ``knot`` at ``normal_load`` [N], friction ``mu`` (rod-rod and rod-pole)
    and bending scale ``bending_scale``: its numbers, CPU [s] and curve."""
    t0 = time.process_time()
    r = axial_pull(knot, normal_load=normal_load, mu_rod_post=mu, mu_rod_rod=mu,
                   bending_scale=bending_scale, **DRAG[knot])  # fmt: skip
    cpu = time.process_time() - t0
    return {
        "knot": knot, "normal_load": normal_load, "mu": mu, "bending_scale": bending_scale,
        "sliding_force": r.sliding_force,
        "peak_force": r.peak_force, "plateau_force": r.plateau_force, "slid": r.slid,
        "topology_preserved": r.topology_preserved, "status": r.status, "message": r.message,
        "cpu_s": cpu, "wall_s": float(r.stats.get("wall_s", np.nan)),
        "grip_mm": (r.grip_displacement * 1e3).tolist(), "force_N": r.axial_force.tolist(),
        "travel_mm": (r.knot_displacement * 1e3).tolist(),
    }  # fmt: skip


def run(quick: bool = True, out_dir=".", knots=tuple(LOADS)) -> dict:
    """Drag each hitch of ``knots`` at its loads; the figure, the exponents and the JSON."""
    rows = [drag_row(k, t) for k in knots for t in LOADS[k]]
    return summarise(rows, quick=quick, out_dir=out_dir)


def exponents(rows) -> dict:
    """Per knot: (exponent of the log-log fit of F_s against T, number of points used)."""
    out = {}
    for knot in dict.fromkeys(r["knot"] for r in rows):
        mine = [r for r in rows if r["knot"] == knot]
        t = [r["normal_load"] for r in mine]
        f = [r["sliding_force"] if r["topology_preserved"] else np.nan for r in mine]
        n = int(np.count_nonzero(np.isfinite(np.asarray(f, float))))
        out[knot] = (fit_exponent(t, f), n)
    return out


def _figure(rows, alphas):
    """Left: F against the grips' travel for every run; right: F_s against T, log-log."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(11, 4.2), layout="constrained")
    a0, a1 = fig.subplots(1, 2)
    marks = {"clove-hitch": "o", "rolling-hitch": "s", "prusik": "^"}
    for k, knot in enumerate(alphas):
        mine = [r for r in rows if r["knot"] == knot]
        for j, r in enumerate(mine):
            a0.plot(r["grip_mm"], r["force_N"], color=f"C{k}", lw=0.6 + 0.4 * j,
                    label=knot if j == len(mine) - 1 else None)  # fmt: skip
        t = np.array([r["normal_load"] for r in mine])
        f = np.array([r["sliding_force"] for r in mine])
        a, n = alphas[knot]
        a1.loglog(t, f, marks.get(knot, "o") + "-", color=f"C{k}",
                  label=f"{knot}: exponent {a:.2f} ({n} points)")  # fmt: skip
    t = np.array([0.25, 2.0])
    a1.loglog(t, 2.0 * t / t[0], "k:", label="slope 1 (linear)")
    a1.loglog(t, 2.0 * (t / t[0]) ** 1.6, "k-.", label="slope 1.6 (surgical knots)")
    a0.set_xlabel("grips' travel along the pole [mm]")
    a0.set_ylabel("axial force F [N]")
    a0.set_title("d = 4 mm VPS32, D = 30 mm, mu = 0.3 (thicker line: larger T)", fontsize=8)
    a0.legend(fontsize=7)
    a1.set_xlabel("normal load T [N]")
    a1.set_ylabel("sliding force F_s [N] (1 d of knot travel)")
    a1.set_title("superlinear (Sabater et al. 2026): slope > 1", fontsize=8)
    a1.legend(fontsize=7)
    return fig


def summarise(rows, *, quick=True, out_dir=".") -> dict:
    """The exponents, the figure, the checks and the JSON from the runs' rows."""
    alphas = exponents(rows)
    figures = [save_figure(_figure(rows, alphas), out_dir, NAME)]
    checks = {
        "topology_kept": all(r["topology_preserved"] for r in rows),
        "all_slid": all(r["slid"] for r in rows),
    }
    numbers = {
        knot: {"loads_N": [r["normal_load"] for r in rows if r["knot"] == knot],
               "sliding_force_N": [r["sliding_force"] for r in rows if r["knot"] == knot],
               "cpu_s": [r["cpu_s"] for r in rows if r["knot"] == knot],
               "exponent": a, "points": n}
        for knot, (a, n) in alphas.items()
    }  # fmt: skip
    notes = [
        "exponent > 1 is superlinear, the trend Sabater et al. report for the clove hitch; "
        "coarse meshes (60, 90 and 200 nodes), one drag per point",
    ]
    return finish(NAME, out_dir=out_dir, checks=checks, numbers=numbers, figures=figures,
                  notes=notes, quick=quick, extra={"rows": rows})  # fmt: skip


def _sweep_point(r) -> float:
    """A drag's load on the sweep's figure [N]: its sliding force, or its peak force when
    it held within the drag (a lower bound of the sliding force)."""
    return r["sliding_force"] if r["slid"] else r["peak_force"]


def _sweep_figure(rows):
    """F_s against mu for each hitch (kappa = 1, filled line; kappa 0.01, open marker); a
    drag that held is drawn at its peak force with an up arrow (a lower bound)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.2, 4.2), layout="constrained")
    ax = fig.subplots()
    marks = {"clove-hitch": "o", "rolling-hitch": "s", "prusik": "^"}
    for k, knot in enumerate(dict.fromkeys(r["knot"] for r in rows)):
        mine = [r for r in rows if r["knot"] == knot]
        solid = sorted((r["mu"], _sweep_point(r)) for r in mine if r["bending_scale"] == 1.0)
        if solid:
            mu, f = zip(*solid, strict=True)
            ax.plot(mu, f, marks.get(knot, "o") + "-", color=f"C{k}", label=f"{knot}, kappa 1")
        for r in mine:
            if r["bending_scale"] != 1.0:
                label = f"{knot}, kappa {r['bending_scale']:g}"
                ax.plot([r["mu"]], [_sweep_point(r)], marks.get(knot, "o"), color=f"C{k}",
                        mfc="none", ms=9, label=label)  # fmt: skip
            if not r["slid"]:
                ax.annotate("", (r["mu"], 1.25 * _sweep_point(r)), (r["mu"], _sweep_point(r)),
                            arrowprops={"arrowstyle": "->", "color": f"C{k}"})  # fmt: skip
    ax.set_ylim(0.0, 1.35 * max(_sweep_point(r) for r in rows))  # room for the arrows
    ax.set_xlabel("friction coefficient mu (rod-rod and rod-pole)")
    ax.set_ylabel("sliding force F_s [N] (1 d of knot travel)")
    ax.set_title(f"d = 4 mm VPS32, D = 30 mm, T = {SWEEP_LOAD:g} N a leg; arrow: held "
                 "within the drag, at its peak force", fontsize=8)  # fmt: skip
    ax.legend(fontsize=7)
    return fig


def sweep(out_dir=".", knots=tuple(LOADS), rows=()) -> dict:
    """Each hitch of ``knots`` dragged at :data:`SWEEP_LOAD` for each (mu, kappa) of
    :data:`SWEEP` (plus the given ``rows``): the table, the figure and the JSON
    ``axial_hitches_mu_kappa.json``. Check: every drag kept its knot type; a drag that did
    not slide held to at least its peak force (``numbers``: ``[F_s or None, peak, CPU]``)."""
    rows = list(rows) + [drag_row(k, SWEEP_LOAD, mu=m, bending_scale=b)
                         for k in knots for m, b in SWEEP]  # fmt: skip
    name = f"{NAME}_mu_kappa"
    figures = [save_figure(_sweep_figure(rows), out_dir, name)]
    checks = {"topology_kept": all(r["topology_preserved"] for r in rows)}
    numbers = {
        knot: {f"mu {r['mu']:g}, kappa {r['bending_scale']:g}":
               [r["sliding_force"] if r["slid"] else None, r["peak_force"], r["cpu_s"]]
               for r in rows if r["knot"] == knot}
        for knot in dict.fromkeys(r["knot"] for r in rows)
    }  # fmt: skip
    notes = [
        "[sliding force N (None: held within the drag), peak force N, CPU s] per "
        "(mu, kappa); one drag per point, coarse meshes"
    ]
    return finish(name, out_dir=out_dir, checks=checks, numbers=numbers, figures=figures,
                  notes=notes, quick=True, extra={"rows": rows})  # fmt: skip


def _main(argv=None) -> int:
    p = argparse.ArgumentParser(description="validation._axial_hitches: the sliding curves")
    p.add_argument("--out", default="validation-out", help="output folder")
    p.add_argument("--knots", default=",".join(LOADS), help="comma-separated hitches to drag")
    p.add_argument("--rows", nargs="*", default=(), help="JSON files of earlier runs: their "
                   "rows are summarised with (or instead of) the new ones")  # fmt: skip
    p.add_argument("--sweep", action="store_true", help="drag each hitch at T = 0.5 N over "
                   "mu and kappa instead (axial_hitches_mu_kappa.json)")  # fmt: skip
    args = p.parse_args(argv)
    rows = []
    for path in args.rows:
        for r in json.loads(Path(path).read_text())["rows"]:
            for key in ("sliding_force", "peak_force", "plateau_force"):
                r[key] = float(r[key])  # NaN was written as a string
            rows.append(r)
    knots = [k for k in args.knots.split(",") if k]
    if args.sweep:
        result = sweep(args.out, knots, rows)
        print(format_result(result))
        return 0 if result["verdict"] == "pass" else 1
    rows += [drag_row(k, t) for k in knots for t in LOADS[k]]
    result = summarise(rows, out_dir=args.out)
    print(format_result(result))
    return 0 if result["verdict"] == "pass" else 1


if __name__ == "__main__":
    raise SystemExit(_main())
