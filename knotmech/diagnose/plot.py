"""Figure of a diagnosis: data, baseline and final fit, residuals before and after."""

from __future__ import annotations

import numpy as np

__all__ = ["plot_report"]


def plot_report(report, path=None):
    """Draw ``report`` (two panels) and save it to ``path`` when given.

    Top: data (dots), baseline fit (dashed), final fit (solid). Bottom: residuals
    of the baseline and of the final model; located regions shaded in both.
    Returns the matplotlib Figure (pyplot-free, no display needed).
    """
    from matplotlib.figure import Figure

    x, y = report.x, report.y
    order = np.argsort(x, kind="stable")
    fig = Figure(figsize=(7.0, 6.0))
    ax, axr = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [3, 2]})
    for a in (ax, axr):
        for lo, hi in report.regions:
            a.axvspan(lo, hi, color="orange", alpha=0.18, lw=0)
    ax.plot(x, y, ".", ms=2.5, color="0.35", label="recording")
    ax.plot(x[order], report.baseline_mean[order], "--", color="C0", lw=1.2, label="baseline")
    ax.plot(
        x[order],
        report.final_mean[order],
        "-",
        color="C3",
        lw=1.2,
        label="final: " + (", ".join(e["name"] for e in report.effects) or "baseline"),
    )
    ax.set_ylabel(report.columns[1])
    ax.set_title(report.verdict_line, fontsize=8)
    ax.legend(fontsize=7)
    axr.plot(x, y - report.baseline_mean, ".", ms=2.5, color="C0", label="baseline residuals")
    axr.plot(x, y - report.final_mean, ".", ms=2.5, color="C3", label="final residuals")
    axr.axhline(0.0, color="k", lw=0.6)
    axr.set_xlabel(report.columns[0])
    axr.set_ylabel("residual")
    axr.legend(fontsize=7)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig
