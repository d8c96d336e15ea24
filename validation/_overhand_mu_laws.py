"""Do the coated overhand knots follow mu? Both rod-rod laws, n = 1..4, mu = 0.1..0.9 (issue 24).

Pulls the coated-rod paper's overhand knots (``params="coated"``) on the quick mesh of
tests/scenes/test_overhand.py and of
docs/notes/contact-and-friction/sticking-law-cap-width.md (151 nodes, 30 mm/s,
dt = 5 ms, 0.5 s wait, 9 s pull, 381 frames; n = 4 on 161 nodes, :data:`N_NODES`) with
each rod-rod friction law:

- ``imc``: the regularised law of the implicit contact model and the coated-rod paper
  (:class:`~knotmech.rod.friction.SmoothFriction`), tunnelling guard ``"displacement"``;
- ``anchor``: the elasto-plastic anchor law that sticks, as now the default of the
  library: :class:`~knotmech.rod.friction.AnchorFriction` with ``cap_floor =``
  :data:`~knotmech.rod.friction.CAP_FLOOR` (1e-2) and ``RodContact(tunnel_check="path")``.

Both are set explicitly here (not taken from the library's defaults), so the runs mean
the same whatever the defaults are. Each run is saved as ``OUT/{law}_n{n}_mu{mu}.npz``
(curve, solver counts, CPU) and skipped if present, so an interrupted campaign resumes.
The runs go in order of information: n = 3 and n = 1 at every mu, then n = 2, then n = 4.

    OPENBLAS_NUM_THREADS=1 nice -n 5 python -m validation._overhand_mu_laws run OUT
    python -m validation._overhand_mu_laws table OUT [--figure docs/img/overhand_mu_laws.png]

``table`` prints one JSON row per finished run: the mean pull force over the tight phase
(end-to-end window :data:`WINDOWS`), the force at a fixed end-to-end length
(:data:`AT`), the largest force, the force's sudden drops, steps, Newton iterations,
rejected attempts and process CPU; ``--figure`` draws the tight-phase mean force against
mu, one panel per n, both laws.
"""

from __future__ import annotations

import argparse
import contextlib
import functools
import glob
import json
import os
import time

import numpy as np

#: quick mesh of the coated pulls (tests/scenes/test_overhand.py, the sticking note)
QUICK = dict(n_nodes=151, pull_speed=0.03, dt=5e-3, wait_time=0.5, pull_time=9.0)
N_FRAMES = 381
#: nodes where QUICK's 151 are too coarse: n = 4's braid needs an edge below a sixth of its
#: helix pitch (23.9 mm), i.e. at least 152 nodes on its 0.60 m rod
N_NODES = {4: 161}
MUS = (0.1, 0.2, 0.3, 0.6, 0.9)
LAWS = ("imc", "anchor")
#: order of the campaign: the most informative knots first
TURNS_ORDER = (3, 1, 2, 4)
#: [m] end-to-end window of the tight phase, per n (n = 1, 3: the sticking note's
#: sections 5 and 3; the pulls go from the start's end-to-end length, 0.10 m for n = 1, 2,
#: 0.25 m for n = 3 and 0.20 m for n = 4, 0.27 m further: n = 2 as n = 1, n = 4 with n = 3's
#: offsets from the start and the end of its pull)
WINDOWS = {1: (0.30, 0.37), 2: (0.30, 0.37), 3: (0.30, 0.42), 4: (0.25, 0.37)}
#: [m] end-to-end length at which the force is read, per n
AT = {1: 0.35, 2: 0.35, 3: 0.45, 4: 0.40}
#: cap floor of the anchor law in these runs (the library's default after issue 24)
CAP_FLOOR = 1e-2


@contextlib.contextmanager
def law_objects(law):
    """Inside the block the overhand scene builds ``law`` as stated in the module doc
    (cap floor and tunnelling guard set explicitly)."""
    import knotmech.scenes.overhand as scene
    from knotmech.rod.contact import RodContact
    from knotmech.rod.friction import AnchorFriction

    guard = "path" if law == "anchor" else "displacement"
    orig = scene.RodContact, scene.AnchorFriction
    scene.RodContact = functools.partial(RodContact, tunnel_check=guard)
    scene.AnchorFriction = functools.partial(AnchorFriction, cap_floor=CAP_FLOOR)
    try:
        yield guard
    finally:
        scene.RodContact, scene.AnchorFriction = orig


def run_one(path, law, turns, mu):
    """Pull one coated overhand with ``law`` and save its curve and counts to ``path``."""
    from knotmech.scenes.overhand import overhand

    c0 = time.process_time()
    with law_objects(law) as guard:
        kw = {**QUICK, "n_nodes": N_NODES.get(turns, QUICK["n_nodes"])}
        r = overhand(turns, mu, params="coated", n_frames=N_FRAMES, friction=law, **kw)
    meta = dict(law=law, mu=mu, turns=turns, cpu_s=time.process_time() - c0, status=r.status,
                cap_floor=CAP_FLOOR if law == "anchor" else None, tunnel_check=guard,
                knot_end=r.knot_end, **r.stats)  # fmt: skip
    tmp = path + ".tmp.npz"
    np.savez(tmp, end_to_end=r.end_to_end, pull_force=r.pull_force, times=r.times,
             meta=json.dumps(meta, default=str))  # fmt: skip
    os.replace(tmp, path)
    print(json.dumps(meta, default=str), flush=True)


def campaign(out):
    """Every (n, mu, law) of the campaign not yet in ``out``, in order of information."""
    os.makedirs(out, exist_ok=True)
    for turns in TURNS_ORDER:
        for mu in MUS:
            for law in LAWS:
                path = os.path.join(out, f"{law}_n{turns}_mu{mu:g}.npz")
                if not os.path.exists(path):
                    run_one(path, law, turns, mu)


def row(path):
    """The table row of one saved run: forces [mN], the end-to-end lengths of the force's
    sudden drops (:func:`~knotmech.scenes.overhand.inversion_points`, span 5 % as in the
    sticking note: an inversion, or a stick-slip release of the sticking law), counts,
    CPU [s]."""
    from knotmech.scenes.overhand import inversion_points

    d = np.load(path)
    meta = json.loads(str(d["meta"]))
    n, e, f, t = meta["turns"], d["end_to_end"], d["pull_force"], d["times"]
    pulling = t > QUICK["wait_time"] + 0.2
    order = np.argsort(e[pulling])
    lo, hi = WINDOWS[n]
    win = pulling & (e >= lo) & (e <= hi)
    reached = bool(e[pulling].max() >= AT[n])
    f_at = np.interp(AT[n], e[pulling][order], f[pulling][order]) if reached else np.nan
    inv = inversion_points(e[pulling], f[pulling], span=0.05)
    return dict(law=meta["law"], turns=n, mu=meta["mu"],
                mean_mN=round(1e3 * float(f[win].mean()), 2) if win.any() else None,
                at_m=AT[n], force_at_mN=None if np.isnan(f_at) else round(1e3 * float(f_at), 2),
                max_mN=round(1e3 * float(f[pulling].max()), 1),
                inversions_m=[round(float(x), 3) for x in inv], steps=meta["steps"],
                newton_iterations=meta["newton_iterations"], rejected=meta["rejected_steps"],
                cpu_s=round(meta["cpu_s"], 1), status=meta["status"],
                knot_end=meta.get("knot_end"))  # fmt: skip


def table(out):
    """Rows of every finished run in ``out``, ordered by n, law and mu."""
    rows = [row(p) for p in glob.glob(os.path.join(out, "*_n*_mu*.npz")) if ".tmp" not in p]
    return sorted(rows, key=lambda r: (r["turns"], r["law"], r["mu"]))


def figure(rows, png):
    """Tight-phase mean pull force against mu, one panel per n, both laws."""
    import matplotlib.pyplot as plt

    turns = sorted({r["turns"] for r in rows})
    fig, axes = plt.subplots(1, len(turns), figsize=(3.3 * len(turns), 3.4), squeeze=False)
    style = {"imc": ("o-", "regularised (imc)"), "anchor": ("s--", "anchor, cap floor 1e-2")}
    for ax, n in zip(axes[0], turns, strict=True):
        for law, (fmt, label) in style.items():
            pts = [(r["mu"], r["mean_mN"]) for r in rows
                   if r["turns"] == n and r["law"] == law and r["mean_mN"] is not None]  # fmt: skip
            if pts:
                mu, f = np.array(sorted(pts)).T
                ax.plot(mu, f, fmt, ms=4, label=label)
        lo, hi = WINDOWS[n]
        ax.set_title(f"n = {n}: mean force, end-to-end {lo:g}-{hi:g} m", fontsize=8)
        ax.set_xlabel("mu")
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("pull force [mN]")
    axes[0][0].legend(fontsize=7)
    fig.suptitle("coated overhand pulls (151 nodes, n = 4: 161; 30 mm/s, dt 5 ms)", fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    sub.add_parser("run").add_argument("out")
    t = sub.add_parser("table")
    t.add_argument("out")
    t.add_argument("--figure")
    a = ap.parse_args(argv)
    if a.cmd == "run":
        campaign(a.out)
        return
    rows = table(a.out)
    for r in rows:
        print(json.dumps(r))
    if a.figure and rows:
        figure(rows, a.figure)


if __name__ == "__main__":
    main()
