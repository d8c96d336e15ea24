"""Figures of a DER run (:class:`knotmech.rod.Result`): shape snapshots, a node's track."""

from __future__ import annotations

import numpy as np

from knotmech.errors import InputError

from ._style import new_axes

__all__ = ["rod_snapshots_plot", "node_track_plot"]

_AXES = {"x": 0, "y": 1, "z": 2}


def _plane(plane: str) -> tuple[int, int]:
    if len(plane) != 2 or plane[0] not in _AXES or plane[1] not in _AXES or plane[0] == plane[1]:
        raise InputError(f"plane must be two of x, y, z (e.g. 'xz'), got {plane!r}")
    return _AXES[plane[0]], _AXES[plane[1]]


def rod_snapshots_plot(result, *, n_frames: int = 9, plane: str = "xz", ax=None, title=None):
    """The rod's centreline at ``n_frames`` recorded times, evenly spread (viridis, early to
    late), and the last frame in black, projected on ``plane`` [m].

    Parameters
    ----------
    result : knotmech.rod.Result
        ``positions`` (n_frames, n_nodes, 3) [m] and ``times`` [s].
    n_frames : int
        Snapshots drawn (at least 2).
    plane : str
        Two axes of the projection, horizontal first ("xz": side view).
    ax : matplotlib Axes, optional
    title : str, optional

    Returns
    -------
    matplotlib Axes
    """
    from matplotlib import colormaps

    i, j = _plane(plane)
    if int(n_frames) != n_frames or n_frames < 2:
        raise InputError(f"n_frames must be an integer >= 2, got {n_frames!r}")
    pos = np.asarray(result.positions)
    if pos.ndim != 3 or pos.shape[0] == 0:
        raise InputError("result has no recorded positions")
    ax = new_axes(ax)
    cmap = colormaps["viridis"]
    frames = np.linspace(0, len(result.times) - 1, int(n_frames)).astype(int)
    for k in frames:
        ax.plot(pos[k, :, i], pos[k, :, j], color=cmap(k / max(frames[-1], 1)), lw=1.5)
    t_end = float(result.times[-1])
    ax.plot(pos[-1, :, i], pos[-1, :, j], "k", lw=2.5, label=f"t = {t_end:g} s")
    ax.set_aspect("equal")
    ax.set_xlabel(f"{plane[0]} [m]")
    ax.set_ylabel(f"{plane[1]} [m]")
    if title:
        ax.set_title(title)
    ax.legend(loc="lower left")
    return ax


def node_track_plot(result, *, node: int = -1, axis: str = "z", ax=None, title=None):
    """One coordinate [m] of one node against time [s] (e.g. a cantilever's tip height).

    Parameters
    ----------
    result : knotmech.rod.Result
    node : int
        Global node index (negative counts from the end).
    axis : {"x", "y", "z"}
    ax : matplotlib Axes, optional
    title : str, optional

    Returns
    -------
    matplotlib Axes
    """
    if axis not in _AXES:
        raise InputError(f"axis must be 'x', 'y' or 'z', got {axis!r}")
    pos = np.asarray(result.positions)
    if not -pos.shape[1] <= node < pos.shape[1]:
        raise InputError(f"node must be in [-{pos.shape[1]}, {pos.shape[1] - 1}], got {node!r}")
    ax = new_axes(ax)
    ax.plot(result.times, pos[:, node, _AXES[axis]], "C0")
    ax.set_xlabel("t [s]")
    ax.set_ylabel(f"{axis} of node {node} [m]")
    if title:
        ax.set_title(title)
    return ax
