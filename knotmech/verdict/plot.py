"""Drawing a verdict's DER answer: the query on the phase diagram, or the simulated knot."""

from __future__ import annotations

from pathlib import Path

from knotmech.errors import InputError
from knotmech.verdict.answer import Verdict

__all__ = ["PLOT_FORMATS", "check_plot_path", "plot_verdict"]

PLOT_FORMATS = ("png", "pdf", "svg")


def check_plot_path(path) -> Path:
    """Refuse a plot path whose folder is missing or whose format is not png/pdf/svg."""
    p = Path(path)
    fmt = p.suffix.lower().lstrip(".")
    if fmt not in PLOT_FORMATS:
        raise InputError(
            f"plot {str(path)!r}: the format must be one of {', '.join(PLOT_FORMATS)} "
            "(from the file name)"
        )
    if not p.parent.is_dir():
        raise InputError(f"plot {str(path)!r}: folder {str(p.parent)!r} does not exist")
    return p


def plot_verdict(verdict: Verdict, path, *, phase_table=None) -> Path:
    """Draw the DER answer: the query on the phase diagram, or the simulated knot; and the
    capacity against friction.

    Table answer: one panel per friction table used, grid points held (dots) and
    slipped (crosses), the interpolated upper boundary and the query (star, labelled with
    the verdict); then the capacity panel (:func:`_draw_capacity`): the slip band of the
    hold table at the user's d/2R against mu, the breaking load and the user's load and
    friction. Without a table answer, the capacity panel alone. Simulation: the knot's
    centreline at the end of the hold in 3-D, coloured by the tension T(s), with the post
    (axis z through the origin).

    Raises
    ------
    InputError
        The verdict has neither a table answer nor a simulated knot, or a bad path.
    """
    p = check_plot_path(path)
    if verdict.shape is not None:
        return _plot_knot(verdict, p)
    der = verdict.der or {}
    has_table = der.get("source") == "table" and bool(der.get("mu_tables"))
    if not has_table and verdict.capacity is None:
        raise InputError(
            "plot: there is no DER answer to draw (a hitch with a DER table, free end, E "
            "given, inside the table's reach, or simulate)"
        )
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    from knotmech.verdict.tables import HoldTable

    tables, used, lim = _tables_used(verdict, der, has_table, phase_table)
    n = len(used) + (verdict.capacity is not None)
    fig, axes = plt.subplots(1, n, figsize=(5.2 * n, 4.2), squeeze=False)
    for ax, t in zip(axes[0], used, strict=False):
        _draw_slice(ax, t, der, verdict)
    if verdict.capacity is not None:
        hold_table = tables if isinstance(tables, HoldTable) else None
        _draw_capacity(axes[0][-1], verdict, hold_table, lim)
    fig.tight_layout()
    fig.savefig(p)
    plt.close(fig)
    return p


def _tables_used(verdict: Verdict, der: dict, has_table: bool, phase_table):
    """(the DER table the verdict read or None, the (d/2R, T/EA) slices to draw, the creep
    limit [d per protocol s] they are judged at)."""
    from knotmech.verdict.criterion import CREEP_LIMIT
    from knotmech.verdict.der import load_user_table, shipped_hold_table
    from knotmech.verdict.tables import HoldTable

    tables = None
    if der.get("source") == "table" and "refused" not in der:
        tables = (shipped_hold_table(verdict.knot, der.get("table_bending_scale", 1.0))
                  if phase_table is None else load_user_table(phase_table))  # fmt: skip
    lim = (verdict.creep or {}).get("limit_d_per_protocol_s") or CREEP_LIMIT
    used = []
    if has_table and isinstance(tables, HoldTable):
        used = [tables.slice(m, creep_limit=lim) for m in der["mu_tables"]]
    elif has_table and tables is not None:
        used = [tables.table(m) for m in der["mu_tables"]]
    return tables, used, lim


def _draw_slice(ax, t, der: dict, verdict: Verdict) -> None:
    """One friction's (d/2R, T_high/EA) slice: points held and slipped, the interpolated
    upper boundary and the query."""
    import matplotlib.ticker
    import numpy as np

    held = [(q.d_over_2R, q.t_over_EA) for q in t.points if q.holds]
    slip = [(q.d_over_2R, q.t_over_EA) for q in t.points if not q.holds]
    if held:
        ax.scatter(*zip(*held, strict=True), marker="o", color="tab:green", label="held")
    if slip:
        ax.scatter(*zip(*slip, strict=True), marker="x", color="tab:red", label="slipped")
    xs, lo, hi, _ = t.boundary()
    ok = np.isfinite(hi)
    if ok.any():
        ax.plot(xs[ok], 0.5 * (lo[ok] + hi[ok]), "k--", lw=1, label="upper boundary")
    ax.scatter([der["d_over_2R"]], [der["t_over_EA"]], marker="*", s=220,
               color="tab:blue", zorder=5, label=f"query: {verdict.state}")  # fmt: skip
    ax.set_xscale("log")
    ax.set_yscale("log")
    cols = sorted({q.d_over_2R for q in t.points})  # ticks at the table's columns
    ax.xaxis.set_major_locator(matplotlib.ticker.FixedLocator(cols))
    ax.xaxis.set_major_formatter(matplotlib.ticker.FixedFormatter([f"{c:.3g}" for c in cols]))
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xlabel("d/2R")
    ax.set_ylabel("T_high/EA")
    ax.set_title(f"{verdict.knot}, free end, mu = mu_rr = {t.mu:g}", fontsize=10)
    ax.legend(loc="best", fontsize=8, framealpha=0.6)


def _draw_capacity(ax, verdict: Verdict, table, limit: float) -> None:
    """Capacity against friction at the user's d/2R: the hold table's slip band and its
    interpolated value [N] (where bounded), the knot's breaking load (line and band), the
    user's load (dashed), mu (dotted) and the material's friction range (shaded)."""
    import math

    import numpy as np

    from knotmech.verdict.capacity import slip_from_table

    i = verdict.inputs
    mus = np.linspace(0.05, 1.0, 39)
    if table is not None and "youngs_modulus" in i:
        d, D = i["rod_diameter"], i["post_diameter"]
        EA = i["youngs_modulus"] * math.pi * d * d / 4
        rows = [slip_from_table(table, x=d / (D + d), mu=float(m), creep_limit=limit) for m in mus]
        val = np.array([r[0] if r else np.nan for r in rows]) * EA
        lo = np.array([r[1] if r else np.nan for r in rows]) * EA
        hi = np.array([r[2] if r else np.nan for r in rows]) * EA
        top = np.nanmax(np.where(np.isfinite(hi), hi, lo))
        ax.fill_between(mus, lo, np.where(np.isfinite(hi), hi, 10 * top), color="tab:orange",
                        alpha=0.25, label="slip band (DER table)")  # fmt: skip
        ax.plot(mus, np.where(np.isfinite(val), val, np.nan), color="tab:orange", label="slip load")
    cap = verdict.capacity
    if cap.breaking is not None:
        b = cap.breaking
        ax.axhspan(b.low, b.high, color="tab:purple", alpha=0.15)
        ax.axhline(b.value, color="tab:purple", label="breaking load")
    ax.axhline(i["load"], color="k", ls="--", lw=1, label=f"load {i['load']:.4g} N")
    ax.axvline(i["mu"], color="tab:blue", ls=":", label=f"mu = {i['mu']:.3g}")
    f = verdict.friction or {}
    rng = f.get("range")
    if rng:
        what = "searched mu (none published)" if f.get("published") is False else (
            "material's mu range")  # fmt: skip
        ax.axvspan(rng[0], rng[1], color="tab:blue", alpha=0.1, label=what)
    ax.set_yscale("log")
    ax.set_xlabel("mu = mu_rr")
    ax.set_ylabel("load [N]")
    ax.set_title(f"{verdict.knot}: capacity against friction ({verdict.state})", fontsize=10)
    ax.legend(loc="best", fontsize=7, framealpha=0.6)


def _plot_knot(verdict: Verdict, p: Path) -> Path:
    """The simulated knot's last frame in 3-D (mm): coloured by the tension T(s) when the
    run gives it (the hitches), else one colour a rope (the bends' two ropes); the post,
    pin or pole it is tied round (axis z through the origin) as grey rings."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    import numpy as np

    sh = verdict.shape
    x = np.asarray(sh["positions"], dtype=float) * 1e3  # mm
    fig = plt.figure(figsize=(6.4, 5.6))
    ax = fig.add_subplot(projection="3d")
    _draw_rods(fig, ax, x, sh)
    support = sh.get("support") or "post"
    lo, hi = x.min(axis=0), x.max(axis=0)
    if sh.get("post_diameter") is not None:
        R = 0.5 * float(sh["post_diameter"]) * 1e3
        phi = np.linspace(0, 2 * np.pi, 41)
        for z in np.linspace(lo[2], hi[2], 5):
            ax.plot(R * np.cos(phi), R * np.sin(phi), np.full_like(phi, z), color="0.7", lw=0.6)
        lo[:2], hi[:2] = np.minimum(lo[:2], -R), np.maximum(hi[:2], R)
    mid, half = 0.5 * (lo + hi), 0.525 * max(float(np.max(hi[:2] - lo[:2])), 1e-9)
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)
    zlo, zhi = (lo[2], hi[2]) if hi[2] > lo[2] else (lo[2] - half, hi[2] + half)
    ax.set_zlim(zlo, zhi)
    ax.set_box_aspect((1.0, 1.0, max(0.25, min(1.0, (zhi - zlo) / (2 * half)))))
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_zlabel(f"z [mm] ({support} axis)" if sh.get("post_diameter") is not None else "z [mm]")
    ax.set_title(f"{verdict.knot}: {verdict.state} (DER simulation, last frame)")
    fig.tight_layout()
    fig.savefig(p)
    plt.close(fig)
    return p


def _draw_rods(fig, ax, x, sh) -> None:
    """The centreline ``x`` [mm]: one tube coloured by ``sh["tension"]`` with a colour bar,
    or ``sh["ropes"]`` equal parts in colours C0, C1, ... with a legend."""
    import numpy as np
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    if sh.get("tension") is not None:
        t = np.asarray(sh["tension"], dtype=float)
        segs = np.stack([x[:-1], x[1:]], axis=1)
        lc = Line3DCollection(segs, cmap="viridis", linewidths=3)
        lc.set_array(t[: len(segs)])
        ax.add_collection3d(lc)
        fig.colorbar(lc, ax=ax, shrink=0.7, pad=0.12, label="tension T(s) [N]")
        return
    n = max(int(sh.get("ropes") or 1), 1)
    for k, part in enumerate(np.array_split(x, n)):
        label = f"rope {k + 1}" if n > 1 else "rope"
        ax.plot(part[:, 0], part[:, 1], part[:, 2], color=f"C{k}", lw=2.5, label=label)
    ax.legend(loc="upper left", fontsize=8)
