"""Figure of a diagnosis: data, baseline and final fit, residuals before and after."""

from __future__ import annotations

import numpy as np

__all__ = ["plot_report", "axis_label", "line_groups"]

#: unit suffixes of column names (SI, as the recording format writes them)
_UNITS = (
    ("_N_per_m", "N/m"),
    ("_m_per_s", "m/s"),
    ("_Pa", "Pa"),
    ("_rad", "rad"),
    ("_N", "N"),
    ("_m", "m"),
)


def axis_label(column: str) -> str:
    """``"wrap_angle_rad"`` -> ``"wrap angle [rad]"``: a column name as an axis label."""
    for suffix, unit in _UNITS:
        if column.endswith(suffix) and len(column) > len(suffix):
            return f"{column[: -len(suffix)].replace('_', ' ')} [{unit}]"
    return column.replace("_", " ")


def line_groups(report) -> list:
    """Row indices of each line of the plot, each sorted by x.

    One line per recording (``report.row_recording``, set by ``diagnose_many``) and, within
    it, per trial at its own speed (``report.row_trial``): joining the rows of all of them
    in the order of x would zigzag between curves that differ.
    """
    n = report.x.size
    keys = []
    for ids in (getattr(report, "row_recording", None), getattr(report, "row_trial", None)):
        if ids is not None and np.asarray(ids).size == n:
            keys.append(np.asarray(ids))
    if not keys:
        return [np.argsort(report.x, kind="stable")]
    _, group = np.unique(np.column_stack(keys), axis=0, return_inverse=True)
    group = group.reshape(-1)
    out = []
    for g in np.unique(group):
        rows = np.flatnonzero(group == g)
        out.append(rows[np.argsort(report.x[rows], kind="stable")])
    return out


def plot_report(report, path=None):
    """Draw ``report`` (two panels) and save it to ``path`` when given.

    Top: data (dots), baseline fit (dashed: the report's baseline, the GLS fit under the
    noise model the report states for it, ``noise.baseline``), final fit (solid), one
    line per recording and trial (:func:`line_groups`). Bottom:
    residuals
    of the baseline and of the final model; the regions where the baseline misses
    shaded in both (and named in the legend). Axes carry the columns' names and
    units. Returns the matplotlib Figure (pyplot-free, no display needed).
    """
    # imported here for start-up speed: matplotlib is needed only when a plot is drawn
    from matplotlib.figure import Figure

    x, y = report.x, report.y
    groups = line_groups(report)
    fig = Figure(figsize=(7.0, 6.0))
    ax, axr = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [3, 2]})
    for a in (ax, axr):
        _shade_regions(a, report.regions, x, label=a is ax)
    ms = 2.5 if x.size > 60 else 5
    ax.plot(x, y, ".", ms=ms, color="0.35", label="recording")
    final_label = "final: " + (", ".join(e["name"] for e in report.effects) or "baseline")
    for k, rows in enumerate(groups):
        ax.plot(
            x[rows],
            report.baseline_mean[rows],
            "--",
            color="C0",
            lw=1.2,
            label="baseline" if k == 0 else None,
        )
        ax.plot(
            x[rows],
            report.final_mean[rows],
            "-",
            color="C3",
            lw=1.2,
            label=final_label if k == 0 else None,
        )
    ycol = report.columns[1]
    ax.set_ylabel(axis_label(ycol))
    ax.set_title(report.verdict_line, fontsize=7, wrap=True)
    ax.legend(fontsize=7)
    axr.plot(x, y - report.baseline_mean, ".", ms=ms, color="C0", label="baseline residuals")
    axr.plot(x, y - report.final_mean, ".", ms=ms, color="C3", label="final residuals")
    axr.axhline(0.0, color="k", lw=0.6)
    axr.set_xlabel(axis_label(report.columns[0]))
    axr.set_ylabel(_residual_label(ycol))
    axr.legend(fontsize=7)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


def _shade_regions(ax, regions, x, *, label: bool) -> None:
    """Shade the mismatch regions (a located point gets a visible width); the first one
    labelled when ``label``."""
    for k, (lo, hi) in enumerate(regions):
        if hi <= lo:
            pad = 0.004 * (float(np.ptp(x)) or 1.0)
            lo, hi = lo - pad, hi + pad
        name = "mismatch region" if (label and k == 0) else None
        ax.axvspan(lo, hi, color="orange", alpha=0.18, lw=0, label=name)


def _residual_label(ycol: str) -> str:
    """``residual [unit]`` with the unit of the measured column (``residual`` without)."""
    text = axis_label(ycol)
    unit = text.rpartition("[")[2].rstrip("]") if "[" in text else ""
    return f"residual [{unit}]" if unit else "residual"
