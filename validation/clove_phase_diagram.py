r"""Case 3: stability phase diagram of the clove hitch with a free end.

With a free end (:math:`T_\mathrm{low} = 0`) ideal-rope theory (Maddocks & Keller 1987,
quoted in the clove-hitch paper, Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788,
sec. 8) predicts that the clove hitch slips at any load, whatever d and D: at slip
:math:`T_\mathrm{high}` is proportional to :math:`T_\mathrm{low}`. The paper's experiments
(Fig. 4) contradict it: the hitch holds below a critical load
:math:`T_\mathrm{high}/EA` that depends on the rescaled diameter :math:`d/2R`, with an upper
bound near :math:`T_\mathrm{high}/EA \approx 0.3`.

This case maps hold/slip over :math:`(d/2R,\ T_\mathrm{high}/EA)` with the DER scene
(:func:`knotmech.scenes.phase_table.simulate_point`, one free-end clove hitch per point,
run through :func:`knotmech.sweep.sweep`), brackets the boundary per d/2R column
(largest load held, smallest load slipped above it), fits a parabola through the
bracket midpoints and draws it against the ideal-rope prediction (boundary at zero
load) and the thick-nip closed form of :mod:`knotmech.analytic.hitch` (self-locking:
holds at any load at mu = 0.3).

What the DER gives (16 runs, d = 4 mm, mu = 0.3): the hitch holds with a free end
below a critical load that depends on d/2R, largest (between 0.2 and 0.3 EA) at the
paper's d/2R = 4/34, lower for thinner rods (0.06: between 0.1 and 0.2) and thicker
rods (0.2: between 0.1 and 0.2; 0.3: nothing held). At d/2R = 0.2 the lightest load
(0.03 EA) slips too. That lower bracket is the seat, not the load: each run settles
under a pre-tension of 0.1 T_high, so the lightest load gets the loosest seat. Rerun
with a 1.2 s hold: 0.03 EA seated at 0.01 EA (the 0.1 EA run's seat) holds (creep
0.26 mm over the last 0.6 s), 0.1 EA seated at 0.003 EA (the 0.03 EA run's seat)
unties at t = 0.48 s, and both original verdicts survive the longer hold (0.03 EA
unties at 0.90 s; 0.1 EA creeps 0.24 mm over the last 0.6 s, after sliding 54 mm
during the ramp and catching). With the seat fixed at 0.01 EA for every load, the 12
points off the 0.1 EA row keep their mu = 0.3 verdicts except (0.2, 0.03 EA), which
then holds: the upper boundary does not depend on the seat, the lower bracket does.

Friction moves the whole map (tables at mu = mu_rr = 0.2, 0.3, 0.4, 0.5 on the same
grid): at 0.2 every point slips, at 0.4 and 0.5 every point holds (up to 0.3 EA at
every d/2R), so the mu = 0.3 map with its interior boundary sits in a narrow
friction window; no point that holds at a lower mu slips at a higher one. Quick mode
draws the boundary of every shipped mu from the tables; full mode simulates them.

``python -m validation.clove_phase_diagram --write-table [--mu 0.4]`` runs the full grid
and writes the table shipped in ``knotmech/data/clove_phase_table.json`` (mu = 0.3) or
``clove_phase_table_mu<mu>.json``, which ``knotmech hold`` interpolates.
``run(der=False)`` draws the diagram from the shipped tables without simulating.
"""

from __future__ import annotations

import argparse
import datetime
import math
import os
import sys
from pathlib import Path

import numpy as np

from knotmech.analytic.hitch import hold_verdict
from knotmech.errors import InputError
from knotmech.plotting import phase_diagram_plot
from knotmech.scenes import phase_table as pt
from knotmech.sweep import TaskFailure

from ._common import finish, save_figure

NAME = "clove_phase_diagram"
#: one sentence for the validation page: what this case checks, and against what
SUMMARY = (
    "DER hold/slip map of a free-end clove hitch over (d/2R, T_high/EA) against the paper's "
    "experiments (Fig. 4: a critical load that depends on d/2R, at most about 0.3 EA) and "
    "against ideal-rope theory (slips at any load); DER spot checks reproduce the shipped "
    "phase table."
)
PAPER_D_OVER_2R = 4.0 / 34.0  #: the paper's (d, D) = (4, 30) mm, R = (D + d)/2
GRID_QUICK = {"d_over_2R": (0.06, 0.1176, 0.2), "t_over_EA": (0.1, 0.2, 0.3)}
#: quick mode: DER spot checks of the shipped table on both sides of its boundaries
#: (the cheapest discriminating points: about 2.5 CPU-minutes in all)
SPOT_CHECKS = ((0.1176, 0.1), (0.2, 0.1), (0.2, 0.2), (0.3, 0.1))
GRID_FULL = {"d_over_2R": (0.06, 0.1176, 0.2, 0.3), "t_over_EA": (0.03, 0.1, 0.2, 0.3)}
TABLE_PATH = Path(__file__).resolve().parents[1] / "knotmech" / "data" / pt.TABLE_RESOURCE
NOTE = (
    "Ideal rope: no thickness, no bending stiffness -> slips at any load.\n"
    "DER: finite thickness d (nips deflect the strands, friction acts at the\n"
    "rod surface) and bending stiffness EI hold the free end below a\n"
    "critical T_high/EA; d/2R sets both (thicker rod on a thinner post).\n"
    "Friction moves the boundary strongly: mu = 0.2 slips, mu >= 0.4 holds, all 16 points.\n"
    "Slip at d/2R = 0.2, 0.03 EA: seated under 0.1 T_high only (loose seat), see notes."
)


def grid_points(grid, mu=None) -> list[dict]:
    """Parameter sets of :func:`knotmech.scenes.phase_table.simulate_point` for a grid.

    ``mu`` (rod-post and rod-rod friction) enters the parameters only when it differs
    from the default :data:`knotmech.scenes.phase_table.MU`; the rod-rod law is the shipped
    tables' (``friction="imc"``).
    """
    extra = {} if mu is None or abs(mu - pt.MU) <= pt.MU_TOL else {"mu": mu, "mu_rr": mu}
    # the rod-rod law of the shipped tables (the smooth law of the coated-rod paper); the
    # anchor-law table at mu = 0.3 is knotmech/data/anchor_clove_phase_table_mu0.3*.json
    extra["friction"] = "imc"
    return [
        {"d_over_2R": float(x), "t_over_EA": float(y), **extra}
        for x in grid["d_over_2R"]
        for y in grid["t_over_EA"]
    ]


def simulate_grid(grid, *, mu=None, progress=False, scheduler=None, cache_dir=None, processes=None):
    """Run the DER points of ``grid`` (at friction ``mu`` = mu_rr, default 0.3);
    return (list of point dicts, list of failures)."""
    return simulate_grid_points(
        grid_points(grid, mu),
        progress=progress,
        scheduler=scheduler,
        cache_dir=cache_dir,
        processes=processes,
    )


def simulate_grid_points(params, *, progress=False, scheduler=None, cache_dir=None, processes=None):
    """Run DER points (list of ``{"d_over_2R", "t_over_EA"}``); (points, failures)."""
    from knotmech.sweep import sweep

    if processes is None:
        processes = min(2, os.cpu_count() or 1)
    res = sweep(
        pt.simulate_point,
        list(params),
        processes=processes,
        scheduler=scheduler,
        cache_dir=cache_dir,
        progress=progress,
        on_error="return",
        desc="clove hitch phase diagram",
    )
    points, failed = [], []
    for params, r in zip(res.params, res, strict=True):
        if isinstance(r, TaskFailure) or r.get("holds") is None:
            failed.append(params)
        else:
            points.append(r)
    return points, failed


def fit_boundary(table: pt.PhaseTable):
    """Upper hold/slip boundary: bracket midpoints per column and a quadratic fit.

    Columns where nothing held use the smallest slipped load as their midpoint's upper
    bound (midpoint = half of it). The quadratic least-squares fit of the midpoints
    against d/2R (three or more columns) locates the d/2R of the largest critical load.

    Returns
    -------
    dict
        ``columns, lower, upper, mid`` per d/2R column, ``coef`` (quadratic, highest
        power first, or None), ``peak_d_over_2R`` and ``peak_t_over_EA`` (None unless the
        fit has an interior maximum).
    """
    xs, lo, hi, mid = table.boundary()
    ok = np.isfinite(mid)
    out = {"columns": xs, "lower": lo, "upper": hi, "mid": mid, "coef": None}
    out.update(peak_d_over_2R=None, peak_t_over_EA=None)
    if ok.sum() >= 3:
        coef = np.polyfit(xs[ok], mid[ok], 2)
        out["coef"] = coef
        if coef[0] < 0:
            xp = -coef[1] / (2 * coef[0])
            if xs[ok].min() < xp < xs[ok].max():
                out["peak_d_over_2R"] = float(xp)
                out["peak_t_over_EA"] = float(np.polyval(coef, xp))
    return out


def _boundary_numbers(table: pt.PhaseTable) -> dict:
    xs, lo, hi, mid = table.boundary()
    return {
        "columns_d_over_2R": xs,
        "lower_t_over_EA": lo,
        "upper_t_over_EA": hi,
        "mid_t_over_EA": mid,
        "lower_boundary_slipped_t_over_EA": [table.low_slip(float(c)) for c in xs],
    }


def hold_to_slip_as_mu_rises(by_mu: dict) -> list:
    """Grid points that hold at a lower friction and slip at a higher one.

    More friction should not make a hitch slip; each entry ``[d/2R, T/EA, mu_lo, mu_hi]``
    is a point where the tables say otherwise (every pair of tables, all common points).
    """
    out = []
    mus = sorted(by_mu)
    for i, m1 in enumerate(mus):
        held = {(p.d_over_2R, p.t_over_EA): p.holds for p in by_mu[m1].points}
        for m2 in mus[i + 1 :]:
            for p in by_mu[m2].points:
                if held.get((p.d_over_2R, p.t_over_EA)) is True and not p.holds:
                    out.append([p.d_over_2R, p.t_over_EA, m1, m2])
    return out


def _tables_by_mu(table, *, simulate, grid, progress, scheduler, cache_dir, processes, failed):
    """{mu: PhaseTable} at every friction of the shipped tables: ``table`` at mu = 0.3, the
    others simulated on ``grid`` (``simulate``; failed runs appended to ``failed``) or
    read from the shipped tables."""
    try:
        shipped = pt.load_tables()
    except InputError:
        return {pt.MU: table}, "shipped"
    out = {pt.MU: table}
    for m in shipped.mus:
        if abs(m - pt.MU) <= pt.MU_TOL:
            continue
        if not simulate:
            out[m] = shipped.table(m)
            continue
        points, lost = simulate_grid(
            grid,
            mu=m,
            progress=progress,
            scheduler=scheduler,
            cache_dir=cache_dir,
            processes=processes,
        )
        failed += lost
        out[m] = pt.PhaseTable(
            [pt.PhasePoint(p["d_over_2R"], p["t_over_EA"], bool(p["holds"])) for p in points],
            mu=m,
            mu_rr=m,
        )
    return out, "DER" if simulate else "shipped"


def _thick_nip_note():
    v = hold_verdict(
        "clove-hitch", rod_diameter=4e-3, post_diameter=30e-3, mu=pt.MU, load=1.47, free_end_load=0
    )
    nip = next(a for a in v.answers if a.model == "thick-nip")
    return bool(nip.holds), float(nip.critical_mu)


def run(
    quick=True,
    out_dir=".",
    progress=False,
    scheduler=None,
    processes=None,
    der=True,
    grid=None,
) -> dict:
    """Simulate (or read the shipped table), fit, plot and summarise case 3.

    Quick (default): the diagram of the shipped table (16 DER runs, regenerated by
    ``--write-table``), spot-checked by new DER runs at :data:`SPOT_CHECKS` (about
    2.5 CPU-minutes). Full: the full grid :data:`GRID_FULL` simulated (about 20
    CPU-minutes). ``grid`` simulates that grid instead (e.g. :data:`GRID_QUICK`, a
    3 x 3 grid across the boundary, about 15 CPU-minutes). ``der=False`` draws the
    shipped table without simulating. DER runs are cached in ``<out_dir>/cache/``.
    """
    t0 = datetime.datetime.now()
    failed = []
    spot = []
    if der and quick and grid is None:
        # quick: the shipped table, checked by DER runs at a few points
        table = pt.load_table()
        points, failed = simulate_grid_points(
            [{"d_over_2R": a, "t_over_EA": b} for a, b in SPOT_CHECKS],
            progress=progress,
            scheduler=scheduler,
            cache_dir=Path(out_dir) / "cache" / NAME,
            processes=processes,
        )
        for q in points:
            ref = table.lookup(q["d_over_2R"], q["t_over_EA"]).holds
            spot.append([q["d_over_2R"], q["t_over_EA"], bool(q["holds"]), ref])
        source = "shipped DER table, spot-checked by new DER runs"
        wall = [q["wall_s"] for q in points]
    elif der:
        grid = grid or GRID_FULL
        points, failed = simulate_grid(
            grid,
            progress=progress,
            scheduler=scheduler,
            cache_dir=Path(out_dir) / "cache" / NAME,
            processes=processes,
        )
        table = pt.PhaseTable(
            [pt.PhasePoint(p["d_over_2R"], p["t_over_EA"], bool(p["holds"])) for p in points]
        )
        source = "DER (knotmech.scenes.phase_table.simulate_point)"
        wall = [p["wall_s"] for p in points]
    else:
        table = pt.load_table()
        points = [
            {"d_over_2R": p.d_over_2R, "t_over_EA": p.t_over_EA, "holds": p.holds}
            for p in table.points
        ]
        source = "shipped DER table (knotmech/data/clove_phase_table.json)"
        wall = []
    if not table.points:
        raise InputError("no phase point finished; nothing to draw")
    fit = fit_boundary(table)
    by_mu, mu_source = _tables_by_mu(
        table,
        simulate=der and not quick,
        grid=grid or GRID_FULL,
        progress=progress,
        scheduler=scheduler,
        cache_dir=Path(out_dir) / "cache" / NAME,
        processes=processes,
        failed=failed,
    )
    violations = hold_to_slip_as_mu_rises(by_mu)
    nip_holds, nip_mu = _thick_nip_note()
    x = np.array([p.d_over_2R for p in table.points])
    y = np.array([p.t_over_EA for p in table.points])
    holds = np.array([p.holds for p in table.points], dtype=bool)

    xs = fit["columns"]
    n_held = int(holds.sum())
    at_paper = [p for p in table.points if abs(p.d_over_2R - PAPER_D_OVER_2R) < 1e-3]
    mids = fit["mid"]
    i_paper = int(np.argmin(np.abs(xs - PAPER_D_OVER_2R)))
    peaked = bool(
        xs.size >= 3
        and 0 < i_paper < xs.size - 1
        and np.isfinite(mids[i_paper])
        and mids[i_paper] > mids[0]
        and mids[i_paper] > mids[-1]
    )
    numbers = {
        "source": source,
        "mu_rc": pt.MU,
        "mu_rr": pt.MU,
        "EA_N": pt.YOUNGS_MODULUS * np.pi * pt.ROD_DIAMETER**2 / 4,
        "points": [[p.d_over_2R, p.t_over_EA, bool(p.holds)] for p in table.points],
        "n_points": len(table.points),
        "n_hold": n_held,
        "n_slip": len(table.points) - n_held,
        "failed": failed,
        "boundary_columns_d_over_2R": xs,
        "boundary_lower_t_over_EA": fit["lower"],
        "boundary_upper_t_over_EA": fit["upper"],
        "boundary_mid_t_over_EA": fit["mid"],
        "lower_boundary_slipped_t_over_EA": [table.low_slip(float(c)) for c in xs],
        "boundary_quadratic_fit": fit["coef"],
        "boundary_peak_d_over_2R": fit["peak_d_over_2R"],
        "boundary_peak_t_over_EA": fit["peak_t_over_EA"],
        "boundary_largest_at_papers_d_over_2R": peaked,
        "ideal_rope_critical_t_over_EA": 0.0,
        "thick_nip_holds_at_any_load": nip_holds,
        "thick_nip_critical_mu": nip_mu,
        "paper_fig4_upper_bound_t_over_EA": 0.3,
        "spot_checks_d_over_2R_t_over_EA_der_table": spot,
        "wall_s_per_run": wall,
        "wall_s_total": float(np.sum(wall)) if wall else 0.0,
        "mu_tables": sorted(by_mu),
        "mu_tables_source": mu_source,
        "boundary_per_mu": {f"{m:g}": _boundary_numbers(t) for m, t in sorted(by_mu.items())},
        "hold_to_slip_as_mu_rises_d_over_2R_t_over_EA_mu_lo_mu_hi": violations,
        "elapsed_s": (datetime.datetime.now() - t0).total_seconds(),
    }
    checks = {
        "every DER run finished": not failed,
        "DER spot checks reproduce the shipped table": all(a[2] is a[3] for a in spot),
        "some points hold with a free end (ideal rope: none)": n_held > 0,
        "some points slip (a boundary exists in the grid)": n_held < len(table.points),
        "the smallest load holds at the paper's d/2R": bool(at_paper)
        and min(at_paper, key=lambda p: p.t_over_EA).holds,
        "paper's d/2R: the upper critical load is at most 0.3 EA (the paper's bound)": bool(
            at_paper
        )
        and any(not p.holds and p.t_over_EA <= 0.3 + 1e-9 for p in at_paper),
        "the critical load depends on d/2R (largest at the paper's d/2R, lower on both sides)": (
            peaked
        ),
    }
    notes = [
        f"Source: {source}.",
        "Each point: clove hitch with a free end, T_high hung on end 0 (0.2 s settle, 0.2 s "
        "ramp, 0.4 s hold); hold = end 0 creeps less than one rod diameter over the last "
        "0.2 s. d = 4 mm, E = 1.26 MPa, mu_rc = mu_rr = 0.3; d/2R varied by the post "
        "diameter (R = (D+d)/2), 64 mm tails.",
        "Boundary: per d/2R column between the largest load held and the smallest slipped "
        "above it; the line is a quadratic least-squares fit through the bracket midpoints "
        "(grid resolution limits it: each bracket is one grid step wide). A column where "
        "nothing held uses half its smallest slipped load.",
        "Ideal rope (Maddocks & Keller, clove-hitch paper sec. 8): slips at any load with a "
        "free end. Thick-nip closed form (knotmech.analytic.hitch): self-locking at mu = 0.3 "
        f"(critical mu {nip_mu:.3g}), i.e. holds at any load; neither has a critical load.",
        "Paper's Fig. 4 (experiments): the critical load depends on d/2R, upper bound near "
        "T_high/EA ~ 0.3.",
        f"Friction (tables at mu = mu_rr = {', '.join(f'{m:g}' for m in sorted(by_mu))}, "
        f"{mu_source}): "
        + "; ".join(
            f"{m:g}: {sum(p.holds for p in t.points)}/{len(t.points)} hold"
            for m, t in sorted(by_mu.items())
        )
        + f". Points that hold at a lower mu and slip at a higher one: {len(violations)}.",
        "Lower bracket at d/2R = 0.2 (0.03 EA slips, 0.1 EA holds at mu = 0.3): each run "
        "settles under 0.1 T_high, so the lightest load has the loosest seat; swapping the "
        "seats swaps the verdicts (1.2 s hold reruns), so it is the seat, not the load; "
        "seated at 0.01 EA for every load the other points keep their verdicts.",
    ]

    from matplotlib.figure import Figure

    xb = np.linspace(xs.min(), xs.max(), 100)

    # the legend has its own panel below the map: inside the axes it hid the lines drawn
    # above the grid (the mu tables that hold at every load)
    fig = Figure(figsize=(6.4, 7.4), layout="constrained")
    ax, axl, axn = fig.subplots(3, 1, height_ratios=[4, 1.3, 1])
    phase_diagram_plot(
        x,
        y,
        holds,
        boundary=(xb, np.polyval(fit["coef"], xb)) if fit["coef"] is not None else None,
        theory={
            "ideal rope: slips at any load (boundary at 0)": (xs, np.zeros_like(xs)),
            "paper Fig. 4: upper bound of the critical load ~0.3": (xs, np.full_like(xs, 0.3)),
        },
        title=(
            "clove hitch with a free end: DER hold / slip"
            + (f" (points: mu = {pt.MU:g})" if len(by_mu) > 1 else "")
        ),
        boundary_label="DER boundary (quadratic fit of the bracket midpoints)",
        ax=ax,
    )
    axn.axis("off")
    axn.text(
        0.0,
        0.5,
        NOTE,
        fontsize=7.5,
        va="center",
        ha="left",
        transform=axn.transAxes,
        bbox={"fc": "white", "ec": "0.7"},
    )
    ok = np.isfinite(fit["upper"])
    if np.any(ok):
        ax.vlines(
            xs[ok],
            fit["lower"][ok],
            fit["upper"][ok],
            color="k",
            lw=3,
            alpha=0.3,
            label="bracket (held / slipped)",
        )
    low = np.array([table.low_slip(float(c)) for c in xs])
    if np.any(low > 0):
        first_hold = [
            min(p.t_over_EA for p in table.points if p.holds and abs(p.d_over_2R - c) < 1e-12)
            if lw > 0
            else np.nan
            for c, lw in zip(xs, low, strict=True)
        ]
        m = low > 0
        ax.vlines(
            xs[m],
            low[m],
            np.array(first_hold)[m],
            color="C3",
            lw=3,
            alpha=0.3,
            label="lower bracket: loose seat (pre-tension 0.1 T_high)",
        )
    if spot:
        ax.scatter(
            [a[0] for a in spot],
            [a[1] for a in spot],
            s=140,
            facecolors="none",
            edgecolors="k",
            label="DER spot check, this run",
            zorder=4,
        )
    if len(by_mu) > 1:
        top = float(y.max())
        n_all_slip = 0
        for k, (m, t) in enumerate(sorted(by_mu.items())):
            bx, blo, bhi, bmid = t.boundary()
            held = [p.holds for p in t.points]
            what = (
                f"holds at all loads (boundary > {top:g})"
                if all(held)
                else "slips at all loads"
                if not any(held)
                else "bracket midpoints"
            )
            yy = np.where(np.isfinite(bmid), bmid, top * (1.06 + 0.05 * k))
            if not any(held):  # tables that slip everywhere: staggered so none hides another
                yy = yy * (1.0 - 0.35 * n_all_slip)
                n_all_slip += 1
            ax.plot(
                bx,
                yy,
                ls="-.",
                marker="^" if all(held) else "D",
                ms=5,
                lw=1,
                color=f"C{(k + 4) % 10}",
                label=f"mu = {m:g}: {what} ({mu_source})",
            )
        for v in violations:
            ax.annotate(
                f"holds at mu {v[2]:g}, slips at {v[3]:g}",
                (v[0], v[1]),
                fontsize=5.5,
                color="C3",
                xytext=(4, -9),
                textcoords="offset points",
            )
    ax.axvline(PAPER_D_OVER_2R, color="0.6", lw=0.8, ls=":")
    ax.set_ylim(-0.02, (1.15 if len(by_mu) == 1 else 1.06 + 0.05 * len(by_mu)) * float(y.max()))
    if ax.get_legend() is not None:
        ax.get_legend().remove()
    axl.axis("off")
    handles, labels = ax.get_legend_handles_labels()
    axl.legend(handles, labels, fontsize=6.5, loc="center", ncol=2, frameon=False)
    figures = [save_figure(ax.figure, out_dir, NAME)]
    return finish(
        NAME,
        out_dir=out_dir,
        checks=checks,
        numbers=numbers,
        figures=figures,
        notes=notes,
        quick=quick,
    )


def table_path(mu: float = pt.MU) -> Path:
    """Where the shipped table at mu = mu_rr = ``mu`` lives in the source tree."""
    return TABLE_PATH.parent / pt.table_resource(mu)


def write_table(
    path=None,
    *,
    mu: float = pt.MU,
    progress=True,
    processes=None,
    scheduler=None,
    cache_dir=None,
    note: str | None = None,
):
    """Run the full grid at friction ``mu`` = mu_rr and write the phase table that
    ``knotmech hold`` interpolates (default path: the shipped table of that mu)."""
    t0 = datetime.datetime.now()
    mu = float(mu)
    path = table_path(mu) if path is None else path
    points, failed = simulate_grid(
        GRID_FULL,
        mu=mu,
        progress=progress,
        scheduler=scheduler,
        cache_dir=cache_dir,
        processes=processes,
    )
    if failed:
        raise InputError(f"{len(failed)} runs failed; not writing a table with holes: {failed}")
    wall = [p["wall_s"] for p in points]
    gen = "python -m validation.clove_phase_diagram --write-table"
    if abs(mu - pt.MU) > pt.MU_TOL:
        gen += f" --mu {mu:g}"
    table = pt.PhaseTable(
        [pt.PhasePoint(p["d_over_2R"], p["t_over_EA"], bool(p["holds"])) for p in points],
        mu=mu,
        mu_rr=mu,
        meta={
            "what": "DER clove hitch with a free end: holds at (d/2R, T_high/EA)",
            "generator": gen,
            "grid": GRID_FULL,
            "rod": {"d_m": pt.ROD_DIAMETER, "E_Pa": pt.YOUNGS_MODULUS, "rho": pt.DENSITY},
            "protocol": pt.IMC_PROTOCOL,
            "law": "imc",
            "hold_criterion": "end 0 creeps < d over the last half of the hold",
            "runs": len(points),
            "cpu_s_total": round(float(np.sum(wall)), 1),
            "cpu_s_per_run": [round(float(np.min(wall)), 1), round(float(np.max(wall)), 1)],
            "creep_m_of_holds": [
                [p["d_over_2R"], p["t_over_EA"], round(p["creep"], 6)] for p in points if p["holds"]
            ],
            "slips_that_broke_topology": [
                [p["d_over_2R"], p["t_over_EA"]]
                for p in points
                if not p["holds"] and not p["topology_preserved"]
            ],
            "written": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "elapsed_s": round((datetime.datetime.now() - t0).total_seconds(), 1),
            **({"note": note} if note else {}),
        },
    )
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    table.write(path)
    return table


def write_hold_table(path=None, *, knot="clove-hitch", cache_dir=None, processes=2,
                     progress=True, note=None, bending_scale=1.0, loads=None,
                     t_low_fraction=0.0, columns=None):  # fmt: skip
    """Run the anchor-law hold-table grid of ``knot`` (:data:`knotmech.scenes.phase_table.
    HOLD_GRID`; ``loads``, a sequence of T_high/EA, replaces its loads, ``columns``, a
    sequence of d/2R, its columns) through the sweep,
    with the rods' bending scale ``bending_scale`` and the other end at ``t_low_fraction`` x
    T_high (0: a free end; the cow hitch on both legs otherwise), and write the shipped table
    (default ``knotmech/data/`` + :func:`~knotmech.scenes.phase_table.hold_table_resource`)."""
    t0 = datetime.datetime.now()
    k, frac = float(bending_scale), float(t_low_fraction)
    if path is None:
        path = TABLE_PATH.parent / pt.hold_table_resource(knot, k, frac)
    gen = f"python -m validation.clove_phase_diagram --write-hold-table --knot {knot}"
    if k != 1.0:
        gen += f" --bending-scale {k:g}"
    if frac != 0.0:
        gen += f" --t-low-fraction {frac:g}"
    grid = None
    if loads is not None:
        ys = sorted({float(y) for y in loads})
        if not ys or not all(math.isfinite(y) and 0 < y < 1 for y in ys):
            raise InputError(f"loads must be T_high/EA values in (0, 1), got {list(loads)!r}")
        grid = {**pt.HOLD_GRID, "t_over_EA": tuple(ys)}
        gen += " --loads " + ",".join(f"{y:g}" for y in ys)
    if columns is not None:
        xs = sorted({float(x) for x in columns})
        if not xs or not all(math.isfinite(x) and 0 < x < 0.5 for x in xs):
            raise InputError(f"columns must be d/2R values in (0, 0.5), got {list(columns)!r}")
        grid = {**(grid or pt.HOLD_GRID), "d_over_2R": tuple(xs)}
        gen += " --columns " + ",".join(f"{x:g}" for x in xs)
    meta = {"generator": gen}
    if note:
        meta["note"] = note
    table = pt.build_hold_table(knot, grid, processes=processes, cache_dir=cache_dir,
                                progress=progress, meta=meta, bending_scale=k,
                                t_low_fraction=frac)  # fmt: skip
    table.meta["written"] = datetime.datetime.now(datetime.timezone.utc).isoformat(
        timespec="seconds")  # fmt: skip
    table.meta["elapsed_s"] = round((datetime.datetime.now() - t0).total_seconds(), 1)
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    table.write(path)
    return table


def _numbers(parser, flag: str, text):
    """``text`` ("1e-4,0.3") as floats, None when not given; a usage error otherwise."""
    if text is None:
        return None
    try:
        return [float(v) for v in text.split(",")]
    except ValueError:
        parser.error(f"{flag}: comma-separated numbers, got {text!r}")


def _main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=f"{NAME}: run case 3 or write the phase table")
    parser.add_argument("--full", action="store_true", help="full grid (default quick)")
    parser.add_argument("--out", default="validation-out", help="output folder")
    parser.add_argument(
        "--write-table",
        nargs="?",
        const="",
        default=None,
        metavar="PATH",
        help="run the full grid and write the phase table (default: the shipped table of "
        f"--mu, {TABLE_PATH.parent}/clove_phase_table[_mu<mu>].json)",
    )
    parser.add_argument(
        "--mu", type=float, default=pt.MU, help="--write-table: friction mu = mu_rr (default 0.3)"
    )
    parser.add_argument("--cache", default=None, help="sweep cache folder for --write-table")
    parser.add_argument("--note", default=None, help="--write-table: a note kept in the meta")
    parser.add_argument(
        "--write-hold-table",
        nargs="?",
        const="",
        default=None,
        metavar="PATH",
        help="run the anchor-law hold-table grid of --knot (d/2R x T_high/EA x mu) and write "
        f"it (default {TABLE_PATH.parent}/hold_phase_table_<knot>.json)",
    )
    parser.add_argument("--knot", default="clove-hitch", help="--write-hold-table: the knot")
    parser.add_argument("--processes", type=int, default=2, help="sweep worker processes")
    parser.add_argument(
        "--bending-scale", type=float, default=1.0,
        help="--write-hold-table: the rods' bending scale kappa, B = kappa E pi d^4/64 "
        "(default 1, a solid rod; a fibre rope is of order 0.01)",
    )  # fmt: skip
    parser.add_argument(
        "--loads", default=None, metavar="Y1,Y2,...",
        help="--write-hold-table: the T_high/EA values (default the grid's 1e-4,1e-3,1e-2,0.1,0.3)",
    )  # fmt: skip
    parser.add_argument(
        "--columns", default=None, metavar="X1,X2,...",
        help="--write-hold-table: the d/2R values (default the grid's 0.0196,0.0476,0.1176,0.2308)",
    )  # fmt: skip
    parser.add_argument(
        "--t-low-fraction", type=float, default=0.0, metavar="F",
        help="--write-hold-table: load the cow hitch's other leg with F x T_high in every run "
        "(default 0, a free end)",
    )  # fmt: skip
    args = parser.parse_args(argv)
    if args.write_hold_table is not None:
        loads = _numbers(parser, "--loads", args.loads)
        columns = _numbers(parser, "--columns", args.columns)
        try:
            table = write_hold_table(args.write_hold_table or None, knot=args.knot,
                                     cache_dir=args.cache, processes=args.processes,
                                     note=args.note, bending_scale=args.bending_scale,
                                     loads=loads, t_low_fraction=args.t_low_fraction,
                                     columns=columns)  # fmt: skip
        except InputError as e:
            parser.exit(2, f"error: {e}\n")
        print(f"wrote the {table.knot} hold table (kappa = {table.bending_scale:g}): "
              f"{len(table.points)} points")  # fmt: skip
        return 0
    if args.write_table is not None:
        path = args.write_table or table_path(args.mu)
        table = write_table(path, mu=args.mu, cache_dir=args.cache, note=args.note)
        print(f"wrote {path}: {len(table.points)} points at mu = mu_rr = {table.mu:g}")
        return 0
    from ._common import main

    return main(run, ["--out", args.out] + (["--full"] if args.full else []))


if __name__ == "__main__":
    sys.exit(_main())
