"""Figures shared by the command line, the validation cases, the examples and the notebooks.

Every function draws on a matplotlib ``Axes`` passed as ``ax=`` (for example from
``plt.subplots()`` in a notebook, where the figure then shows inline) or, when
``ax`` is omitted, on a new :class:`matplotlib.figure.Figure` that is not
registered with pyplot: it needs no display and is saved with
``ax.figure.savefig(path)`` (or :func:`save_figure`). Each returns the ``Axes``.

Theory curves are dashed or dotted, simulation or measured data solid or
markers, and one colour stands for one geometry throughout.

Modules: ``_style`` (axes, colours, curve checks, saving), ``capstan`` (tension decay,
holding ratio), ``knots`` (phase diagrams, force curves), ``rod`` (snapshots and node
tracks of a DER run).
"""

from ._style import colours, new_axes, new_figure, save_figure
from .capstan import capstan_ratio_plot, tension_decay_plot
from .knots import force_curve_plot, phase_diagram_plot
from .rod import node_track_plot, rod_snapshots_plot

__all__ = [
    "new_axes",
    "new_figure",
    "colours",
    "save_figure",
    "tension_decay_plot",
    "capstan_ratio_plot",
    "phase_diagram_plot",
    "force_curve_plot",
    "rod_snapshots_plot",
    "node_track_plot",
]
