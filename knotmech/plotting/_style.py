"""The shared style of knotmech's figures: axes, colours, curve checks, saving.

Every plot draws on a matplotlib ``Axes`` passed as ``ax=`` or, when omitted, on a new
pyplot-free :class:`matplotlib.figure.Figure` (:func:`new_axes`). Theory curves are dashed
or dotted, simulated or measured data solid or markers, and one colour stands for one
geometry throughout (:func:`colours`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from knotmech.errors import InputError, check_finite

__all__ = ["new_axes", "new_figure", "colours", "as_curve", "save_figure"]


def new_axes(ax=None, *, figsize=(6.0, 4.2)):
    """Return ``ax`` or, when None, the axes of a new pyplot-free Figure."""
    if ax is not None:
        return ax
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, layout="constrained")
    return fig.add_subplot()


def colours(n: int):
    """``n`` colours of the viridis map (one per geometry), avoiding its pale end."""
    from matplotlib import colormaps

    cmap = colormaps["viridis"]
    return [cmap(x) for x in np.linspace(0.05, 0.85, max(n, 1))]


def as_curve(name: str, curve):
    """``curve`` = (x, y) checked: two finite 1-D arrays of equal length (InputError naming
    ``name`` otherwise)."""
    try:
        x, y = curve
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a pair (x, y) of 1-D arrays") from None
    x = check_finite(f"{name} x", x)
    y = check_finite(f"{name} y", y)
    if x.ndim != 1 or x.shape != y.shape:
        raise InputError(f"{name} must be two 1-D arrays of equal length, got {x.shape}, {y.shape}")
    return x, y


def new_figure(ncols: int = 1, *, figsize=(6.0, 4.2), width_ratios=None):
    """A new pyplot-free Figure with ``ncols`` axes side by side; returns (figure, axes)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, layout="constrained")
    axes = fig.subplots(1, ncols, width_ratios=width_ratios)
    return fig, axes


def save_figure(fig, path, *, dpi: int = 120) -> Path:
    """Write ``fig`` to ``path`` (its folder created) and return the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=dpi)
    return path
