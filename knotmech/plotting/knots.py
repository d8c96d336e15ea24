"""Knot figures: hold/slip phase diagrams, force against displacement."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from knotmech.errors import InputError, check_finite

from ._style import as_curve, colours, new_axes

__all__ = ["phase_diagram_plot", "force_curve_plot"]


def phase_diagram_plot(
    x,
    y,
    holds,
    *,
    boundary=None,
    theory: Mapping | None = None,
    ax=None,
    xlabel: str = r"$d/2R$",
    ylabel: str = r"$T_\mathrm{high}/EA$",
    title: str | None = None,
    note: str | None = None,
    boundary_label: str = "fitted boundary",
):
    """Hold / slip scatter with a fitted boundary and theory lines.

    Parameters
    ----------
    x, y : (n,) arrays
        The two control parameters of each run (e.g. d/2R and T_high/EA).
    holds : (n,) bool array
        True where the knot held, False where it slipped.
    boundary : pair of arrays, optional
        ``(x_b, y_b)`` of the fitted boundary (solid line).
    theory : mapping, optional
        ``{label: (x_t, y_t)}`` theoretical boundaries (dashed lines); a curve whose
        y is all ``inf`` or ``nan`` is skipped and only its label is kept (e.g. an
        ideal rope that slips at any load).
    ax, xlabel, ylabel, title : figure decoration
    note : str, optional
        A sentence written in the lower right corner (what moves the boundary).
    boundary_label : str
        Legend entry of ``boundary`` (e.g. "computed boundary" for a closed form).

    Returns
    -------
    matplotlib Axes
    """
    x = check_finite("x", x)
    y = check_finite("y", y)
    holds = np.asarray(holds)
    if holds.dtype != bool:
        raise InputError(f"holds must be a boolean array, got dtype {holds.dtype}")
    if not (x.ndim == 1 and x.shape == y.shape == holds.shape):
        raise InputError(
            f"x, y and holds must be 1-D of equal length, got {x.shape}, {y.shape}, {holds.shape}"
        )
    ax = new_axes(ax)
    ax.scatter(x[holds], y[holds], marker="o", color="C2", label="holds", zorder=3)
    ax.scatter(x[~holds], y[~holds], marker="x", color="C3", label="slips", zorder=3)
    if boundary is not None:
        bx, by = as_curve("boundary", boundary)
        ax.plot(bx, by, "-", color="k", lw=1.5, label=boundary_label)
    for ls, (label, curve) in zip(["--", "-.", ":"] * 3, (theory or {}).items(), strict=False):
        tx, ty = np.asarray(curve[0], dtype=float), np.asarray(curve[1], dtype=float)
        if np.all(~np.isfinite(ty)):
            ax.plot([], [], ls, color="0.4", label=str(label))
        else:
            ax.plot(tx, ty, ls, color="0.4", label=str(label))
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title)
    if note:
        ax.text(
            0.98,
            0.02,
            note,
            transform=ax.transAxes,
            ha="right",
            va="bottom",
            fontsize=7,
            wrap=True,
            bbox={"fc": "white", "ec": "0.7", "alpha": 0.9},
        )
    ax.legend(fontsize=7, loc="best", framealpha=0.9)
    ax.grid(True, alpha=0.3)
    return ax


def force_curve_plot(
    curves: Mapping,
    *,
    markers: Mapping | None = None,
    ax=None,
    xlabel: str = "end-to-end length [m]",
    ylabel: str = r"$F r^2/EI$",
    title: str | None = None,
    logy: bool = False,
):
    """Force (or ratio) against displacement for several cases, with marked points.

    For the overhand-knot pulls of the coated-rod paper (Fig. 10: regularised pull
    force against end-to-end length, one curve per mu, inversion points marked) and
    the clove hitch against the two-loops capstan (clove-hitch paper, Fig. 1d:
    T_high/T_low against displacement).

    Parameters
    ----------
    curves : mapping
        ``{label: (x, y)}`` drawn as lines in order; a label containing "theory"
        or "closed form" is dashed.
    markers : mapping, optional
        ``{label: (x_points, y_points)}`` drawn as open markers (e.g. inversion points).
    ax, xlabel, ylabel, title, logy : figure decoration

    Returns
    -------
    matplotlib Axes
    """
    if not isinstance(curves, Mapping) or not curves:
        raise InputError("curves must be a non-empty mapping label -> (x, y)")
    ax = new_axes(ax)
    for colour, (label, curve) in zip(colours(len(curves)), curves.items(), strict=False):
        x, y = as_curve(f"curves[{label!r}]", curve)
        dashed = "theory" in str(label).lower() or "closed form" in str(label).lower()
        ax.plot(x, y, "--" if dashed else "-", color=colour, label=str(label))
    for marker, (label, pts) in zip("ovs^D<>", (markers or {}).items(), strict=False):
        x, y = as_curve(f"markers[{label!r}]", (np.atleast_1d(pts[0]), np.atleast_1d(pts[1])))
        ax.plot(x, y, marker, ls="none", mfc="none", color="k", ms=7, label=str(label))
    if logy:
        ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title)
    ax.legend(fontsize=7, loc="best")
    ax.grid(True, alpha=0.3)
    return ax
