"""Per-pair friction census of rod-rod contact (issue 24, part 1): what each pair carries.

A diagnostic that is off unless used: :func:`recording` patches
:class:`knotmech.rod.contact.RodContact` for the duration of a ``with`` block, so the
library's code path is untouched (zero cost) otherwise. Inside it, every accepted step
(``end_step``, before the anchors are committed) and every Newton iterate (``assemble``)
of every rod-rod contact is passed through
:func:`knotmech.rod._kernels.contact_rodrod.rodrod_friction_census`, which reports per pair
|F_n|, the anchor law's |F_t| and mu, the tangential gap over the cap's width |u|/a,
stick/slide, whether the anchor was made afresh this step, edge-edge vs node-edge
geometry, the midpoints' tangential speed and the friction direction.

    OPENBLAS_NUM_THREADS=1 python validation/_sticking_census.py run OUT.npz \
        [--law anchor] [--mu 0.6] [--turns 3] [--pull-time 3]
    python validation/_sticking_census.py report OUT.npz [OUT2.npz ...] [--figure PNG]

``run`` pulls the coated-rod paper's overhand (151 nodes, 30 mm/s, dt 5 ms, 0.5 s wait;
the quick mesh of tests/scenes/test_overhand.py) and saves the per-step rows of the pairs
in contact; ``report`` prints the distributions as JSON and draws them.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import time

import numpy as np

from knotmech.rod._kernels.contact_rodrod import (
    CENSUS_COLUMNS,
    Z_CUTOFF,
    rodrod_friction_census,
)
from knotmech.rod.contact import RodContact
from knotmech.rod.friction import FLOOR_RULES, AnchorFriction

QUICK = dict(n_nodes=151, pull_speed=0.03, dt=5e-3, wait_time=0.5)
COL = {name: i for i, name in enumerate(CENSUS_COLUMNS)}
#: [m] end-to-end window of the pulls table's mean force (the knot tight, before the
#: inversions of the regularised law at 0.43-0.46 m)
WINDOW = (0.30, 0.42)


class Census:
    """Rows of the accepted steps and the direction flips of the Newton iterates."""

    def __init__(self):
        self.steps = []  # (time index, rows (k, ncol)) per accepted step
        self.iterates = []  # per step attempt: list of (n_pairs, ncol) tables
        self._attempt = None
        self.flips = []  # per attempt: (pairs that flip, |u|/a and |F_n| of the flips)

    def table(self, contact, system, q, q_old, dt):
        """The census table of ``contact``'s candidate pairs at ``q``."""
        pairs = contact.pairs
        rad, en, nd = contact._arrays(system)[:3]
        out = np.zeros((pairs.shape[0], len(CENSUS_COLUMNS)))
        pos, pos_old = np.asarray(q, float)[nd], np.asarray(q_old, float)[nd]
        if isinstance(contact.friction, AnchorFriction):
            if contact._anc is None:
                contact._align_anchors(system)
            mu_s, mu_k, k_t = contact._anchor_params()
            floor = float(contact.friction.cap_floor)
            mode = FLOOR_RULES.index(contact.friction.floor_rule)
            _, anc, slip, _, known = contact._anc
        else:
            mu_s = mu_k = float(getattr(contact.friction, "mu", 0.0))
            k_t = floor = 0.0
            mode = 0
            anc = np.zeros((pairs.shape[0], 2))
            slip = known = np.zeros(pairs.shape[0], dtype=bool)
        rodrod_friction_census(
            pos, pos_old, float(dt) if dt else 1.0, pairs, en, rad, contact.sharpness,
            contact.stiffness, Z_CUTOFF, mu_s, mu_k, k_t, anc, slip, known, out, floor, mode,
        )  # fmt: skip
        return out

    def on_iterate(self, contact, system, q, q_old, dt):
        if contact.pairs is None or contact.pairs.shape[0] == 0:
            return
        tab = self.table(contact, system, q, q_old, dt)
        if self._attempt is not None and self._attempt.shape == tab.shape:
            d_old = self._attempt[:, COL["ux"] : COL["uz"] + 1]
            d_new = tab[:, COL["ux"] : COL["uz"] + 1]
            live = (self._attempt[:, 0] > 0) & (tab[:, 0] > 0)
            flip = live & (np.sum(d_old * d_new, axis=1) < 0.0)
            self.flips.append(
                (int(live.sum()), tab[flip][:, [COL["fnorm"], COL["gap_over_a"], COL["a"]]])
            )
        self._attempt = tab

    def on_accept(self, contact, system, q_new, q_old, dt):
        self._attempt = None
        if contact.pairs is None or contact.pairs.shape[0] == 0:
            return
        tab = self.table(contact, system, q_new, q_old, dt)
        keys = contact.pairs[:, 0] * system.edge_nodes.shape[0] + contact.pairs[:, 1]
        live = tab[:, 0] > 0
        self.steps.append((keys[live], tab[live]))


@contextlib.contextmanager
def anchor_cap_floor(cap_floor):
    """Inside the block, the scenes' anchor law (``friction="anchor"``) is built with
    ``AnchorFriction(..., cap_floor=cap_floor)`` (the scenes take the law by name only)."""
    import functools
    import importlib

    scene = importlib.import_module("knotmech.scenes.overhand")

    orig = scene.AnchorFriction
    scene.AnchorFriction = functools.partial(AnchorFriction, cap_floor=float(cap_floor))
    try:
        yield
    finally:
        scene.AnchorFriction = orig


@contextlib.contextmanager
def recording():
    """Record the friction census of every RodContact inside the block; yields a
    :class:`Census`."""
    census = Census()
    orig_assemble, orig_end = RodContact.assemble, RodContact.end_step

    def assemble(self, system, q, q_old, dt, *a, **k):
        self._ensure_pairs(system, q)
        census.on_iterate(self, system, q, q_old, dt)
        return orig_assemble(self, system, q, q_old, dt, *a, **k)

    def end_step(self, system, q_new, q_old, dt):
        self._ensure_pairs(system, q_old)
        census.on_accept(self, system, q_new, q_old, dt)
        return orig_end(self, system, q_new, q_old, dt)

    RodContact.assemble, RodContact.end_step = assemble, end_step
    try:
        yield census
    finally:
        RodContact.assemble, RodContact.end_step = orig_assemble, orig_end


def run(out, law, mu, turns, pull_time, n_frames=61, cap_floor=0.0, census=True):
    """Pull the coated overhand with the census on; save rows, flips and the curve."""
    from knotmech.scenes.overhand import overhand

    kw = dict(QUICK, pull_time=pull_time)
    c0 = time.process_time()
    rec = recording() if census else contextlib.nullcontext(None)
    with anchor_cap_floor(cap_floor), rec as census:
        r = overhand(turns, mu, params="coated", n_frames=n_frames, friction=law, **kw)
    cpu = time.process_time() - c0
    meta = dict(law=law, mu=mu, turns=turns, pull_time=pull_time, cpu_s=cpu)
    meta.update(cap_floor=cap_floor, status=r.status, **r.stats)
    if census is None:
        np.savez(out, end_to_end=r.end_to_end, pull_force=r.pull_force, times=r.times,
                 meta=json.dumps(meta, default=str))  # fmt: skip
        print(json.dumps(meta, default=str), flush=True)
        return
    step_of = np.concatenate([np.full(len(k), i) for i, (k, _) in enumerate(census.steps)])
    rows = np.concatenate([t for _, t in census.steps])
    keys = np.concatenate([k for k, _ in census.steps])
    flips = [f for _, f in census.flips]
    flip_rows = np.concatenate(flips) if flips else np.zeros((0, 3))
    n_live = np.array([n for n, _ in census.flips])
    n_flip = np.array([len(f) for f in flips])
    np.savez(
        out, rows=rows, keys=keys, step_of=step_of, flip_rows=flip_rows, n_live=n_live,
        n_flip=n_flip, end_to_end=r.end_to_end, pull_force=r.pull_force, times=r.times,
        meta=json.dumps(meta, default=str),
    )  # fmt: skip
    print(json.dumps(meta, default=str), flush=True)


def _gaps_of_returning_pairs(keys, step_of):
    """How many times a pair leaves the contact and comes back, and after how many steps
    (a returning pair gets a new anchor)."""
    last = {}
    gaps = []
    for s, k in zip(step_of.tolist(), keys.tolist(), strict=True):
        if k in last and s - last[k] > 1:
            gaps.append(s - last[k] - 1)
        last[k] = s
    return np.array(gaps, dtype=int), len(last)


def summary(path):
    """Distributions of one census file as a dict (ratios, loads, flips)."""
    d = np.load(path)
    rows, meta = d["rows"], json.loads(str(d["meta"]))
    fn, ft, mu = rows[:, COL["fnorm"]], rows[:, COL["ft"]], rows[:, COL["mu"]]
    anchored = meta["law"] != "imc"
    out = dict(meta, pair_steps=int(len(rows)), steps=int(d["step_of"].max() + 1))
    if not anchored:
        return out
    ratio = ft / (mu * fn)
    slides = rows[:, COL["slides"]] > 0
    fmax = fn.max()
    q = [0.0, 0.01, 0.1, 0.5, 0.9, 1.0]
    pct = lambda v: [float(x) for x in np.quantile(v, q)] if len(v) else []  # noqa: E731
    light = fn < 1e-3 * fmax
    edge_edge = (rows[:, COL["free_s"]] > 0) & (rows[:, COL["free_t"]] > 0)
    gaps, n_keys = _gaps_of_returning_pairs(d["keys"], d["step_of"])
    w_all = np.sum(mu * fn)
    out.update(
        quantiles=q,
        sliding_ratio=pct(ratio[slides]),
        sticking_ratio=pct(ratio[~slides]),
        sticking_above_one=int(np.sum(ratio[~slides] > 1.0 + 1e-12)),
        share_sliding=float(slides.mean()),
        load_share_sliding=float(np.sum(fn[slides]) / np.sum(fn)),
        friction_carried_over_mu_fn=float(np.sum(ft) / w_all),
        friction_lost_sticking=float(np.sum((mu * fn - ft)[~slides]) / w_all),
        friction_lost_sliding=float(np.sum((mu * fn - ft)[slides]) / w_all),
        light_pairs_share=float(light.mean()),
        light_pairs_load_share=float(np.sum(fn[light]) / np.sum(fn)),
        edge_edge_share=float(edge_edge.mean()),
        node_edge_share=float(1.0 - edge_edge.mean()),
        ratio_median_edge_edge=float(np.median(ratio[edge_edge])) if edge_edge.any() else None,
        ratio_median_node_edge=float(np.median(ratio[~edge_edge])) if (~edge_edge).any() else None,
        plane_from_pair_normal_share=float(np.mean(rows[:, COL["plane_n"]] > 0)),
        anchor_outside_edges_share=float(np.mean(rows[:, COL["anchor_in_edge"]] == 0)),
        cap_width_a_m=pct(rows[:, COL["a"]]),
        pairs_seen=n_keys,
        returns=int(len(gaps)),
        return_after_steps=pct(gaps) if len(gaps) else [],
        newton_iterates_compared=int(len(d["n_live"])),
        pair_iterates=int(np.sum(d["n_live"])),
        direction_flips=int(np.sum(d["n_flip"])),
        iterates_with_flip=int(np.sum(d["n_flip"] > 0)),
    )
    fr = d["flip_rows"]
    if len(fr):
        out["flip_fnorm_over_max"] = pct(fr[:, 0] / fmax)
        out["flip_gap_over_a"] = pct(fr[:, 1])
        out["flip_a_m"] = pct(fr[:, 2])
    return out


def figure(paths, png):
    """Distributions of |F_t|/(mu|F_n|) against load (sliding and sticking), and of the
    flipping pairs' loads, one column per census file."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, len(paths), figsize=(4.2 * len(paths), 6.5), squeeze=False)
    for col, path in enumerate(paths):
        d = np.load(path)
        rows, meta = d["rows"], json.loads(str(d["meta"]))
        fn, ft, mu = rows[:, COL["fnorm"]], rows[:, COL["ft"]], rows[:, COL["mu"]]
        ratio = ft / (mu * fn)
        slides = rows[:, COL["slides"]] > 0
        ax = axes[0, col]
        ax.scatter(fn[slides], ratio[slides], s=2, c="C3", alpha=0.3, label="sliding")
        ax.scatter(fn[~slides], ratio[~slides], s=2, c="C0", alpha=0.3, label="sticking")
        ax.set_xscale("log")
        ax.axhline(1.0, color="k", lw=0.5)
        ax.set_ylim(-0.02, 1.05)
        ax.set_xlabel("|F_n| of the pair [N]")
        ax.set_ylabel("|F_t| / (mu |F_n|) at accepted steps")
        scheme = f"anchor cap_floor {meta.get('cap_floor', 0):g}"
        ax.set_title(f"n={meta['turns']} mu={meta['mu']:g} {scheme}", fontsize=9)
        ax.legend(loc="lower right", markerscale=4, fontsize=8)
        ax = axes[1, col]
        bins = np.logspace(-8, 0, 33)
        ax.hist(fn / fn.max(), bins=bins, histtype="step", label="all pair-steps")
        fr = d["flip_rows"]
        if len(fr):
            ax.hist(fr[:, 0] / fn.max(), bins=bins, histtype="step", label="direction flips")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("|F_n| / max |F_n|")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def pulls_table(paths, png=None, at=0.45):
    """Table (JSON rows) of full pulls saved by ``run --no-census``: pull force at
    end-to-end ``at`` [m], its mean over :data:`WINDOW`, largest force, inversions, steps
    and CPU; optional figure of the
    force curves (one panel per law/scheme)."""
    from knotmech.scenes.overhand import inversion_points

    rows, curves = [], {}
    for path in paths:
        d = np.load(path)
        meta = json.loads(str(d["meta"]))
        e, f, t = d["end_to_end"], d["pull_force"], d["times"]
        pulling = t > QUICK["wait_time"] + 0.2
        order = np.argsort(e[pulling])
        f_at = float(np.interp(at, e[pulling][order], f[pulling][order]))
        inv = inversion_points(e[pulling], f[pulling], span=0.05)
        win = pulling & (e >= WINDOW[0]) & (e <= WINDOW[1])
        name = meta["law"] if meta["law"] == "imc" else f"anchor floor {meta['cap_floor']:g}"
        rows.append(dict(law=name, mu=meta["mu"], turns=meta["turns"], force_at_mN=1e3 * f_at,
                         force_mean_mN=1e3 * float(f[win].mean()) if win.any() else None,
                         force_max_mN=1e3 * float(f[pulling].max()),
                         inversions_m=[round(float(x), 4) for x in inv], steps=meta["steps"],
                         newton_iterations=meta["newton_iterations"],
                         rejected=meta["rejected_steps"], cpu_s=round(meta["cpu_s"], 1),
                         status=meta["status"]))  # fmt: skip
        curves.setdefault(name, []).append((meta["mu"], e, f))
    if png:
        import matplotlib.pyplot as plt

        names = sorted(curves)
        fig, axes = plt.subplots(1, len(names), figsize=(4.4 * len(names), 4), sharey=True)
        for ax, name in zip(np.atleast_1d(axes), names, strict=True):
            for mu, e, f in sorted(curves[name], key=lambda c: c[0]):
                ax.plot(e, 1e3 * f, lw=1, label=f"mu = {mu:g}")
            ax.axvline(at, color="k", lw=0.5, ls=":")
            ax.set_title(name, fontsize=9)
            ax.set_xlabel("end-to-end length [m]")
            ax.legend(fontsize=8)
        np.atleast_1d(axes)[0].set_ylabel("pull force [mN]")
        fig.tight_layout()
        fig.savefig(png, dpi=110)
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("out")
    r.add_argument("--law", default="anchor")
    r.add_argument("--mu", type=float, default=0.6)
    r.add_argument("--turns", type=int, default=3)
    r.add_argument("--pull-time", type=float, default=3.0)
    r.add_argument("--frames", type=int, default=61)
    r.add_argument("--cap-floor", type=float, default=0.0)
    r.add_argument("--no-census", action="store_true")
    p = sub.add_parser("report")
    p.add_argument("files", nargs="+")
    p.add_argument("--figure")
    t = sub.add_parser("table")
    t.add_argument("files", nargs="+")
    t.add_argument("--figure")
    t.add_argument("--at", type=float, default=0.45)
    a = ap.parse_args(argv)
    if a.cmd == "run":
        run(a.out, a.law, a.mu, a.turns, a.pull_time, a.frames, a.cap_floor, not a.no_census)
    elif a.cmd == "table":
        for row in pulls_table(a.files, a.figure, a.at):
            print(json.dumps(row))
    else:
        print(json.dumps([summary(f) for f in a.files], indent=1, default=str))
        if a.figure:
            figure(a.files, a.figure)


if __name__ == "__main__":
    main()
