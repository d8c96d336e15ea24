"""Figure of a diagnosis: data, baseline and final fit, residuals before and after."""

from __future__ import annotations

import numpy as np

__all__ = ["plot_report", "axis_label"]

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


def plot_report(report, path=None):
    """Draw ``report`` (two panels) and save it to ``path`` when given.

    Top: data (dots), baseline fit (dashed: the report's baseline, the GLS fit under the
    noise model the report states for it, ``noise.baseline``), final fit (solid). Bottom:
    residuals
    of the baseline and of the final model; the regions where the baseline misses
    shaded in both (and named in the legend). Axes carry the columns' names and
    units. Returns the matplotlib Figure (pyplot-free, no display needed).
    """
    from matplotlib.figure import Figure

    x, y = report.x, report.y
    order = np.argsort(x, kind="stable")
    fig = Figure(figsize=(7.0, 6.0))
    ax, axr = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [3, 2]})
    for a in (ax, axr):
        for k, (lo, hi) in enumerate(report.regions):
            if hi <= lo:  # a located point: give it a visible width
                pad = 0.004 * (float(np.ptp(x)) or 1.0)
                lo, hi = lo - pad, hi + pad
            label = "mismatch region" if (a is ax and k == 0) else None
            a.axvspan(lo, hi, color="orange", alpha=0.18, lw=0, label=label)
    ax.plot(x, y, ".", ms=2.5 if x.size > 60 else 5, color="0.35", label="recording")
    ax.plot(x[order], report.baseline_mean[order], "--", color="C0", lw=1.2, label="baseline")
    ax.plot(
        x[order],
        report.final_mean[order],
        "-",
        color="C3",
        lw=1.2,
        label="final: " + (", ".join(e["name"] for e in report.effects) or "baseline"),
    )
    ycol = report.columns[1]
    ax.set_ylabel(axis_label(ycol))
    ax.set_title(report.verdict_line, fontsize=7, wrap=True)
    ax.legend(fontsize=7)
    ms = 2.5 if x.size > 60 else 5
    axr.plot(x, y - report.baseline_mean, ".", ms=ms, color="C0", label="baseline residuals")
    axr.plot(x, y - report.final_mean, ".", ms=ms, color="C3", label="final residuals")
    axr.axhline(0.0, color="k", lw=0.6)
    axr.set_xlabel(axis_label(report.columns[0]))
    unit = axis_label(ycol).rpartition("[")[2].rstrip("]") if "[" in axis_label(ycol) else ""
    axr.set_ylabel(f"residual [{unit}]" if unit else "residual")
    axr.legend(fontsize=7)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig
