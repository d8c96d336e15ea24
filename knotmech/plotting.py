"""Figures shared by the command line, the validation cases and the notebooks.

Every function draws on a matplotlib ``Axes`` passed as ``ax=`` (for example from
``plt.subplots()`` in a notebook, where the figure then shows inline) or, when
``ax`` is omitted, on a new :class:`matplotlib.figure.Figure` that is not
registered with pyplot: it needs no display and is saved with
``ax.figure.savefig(path)``. Each returns the ``Axes``.

Theory curves are dashed or dotted, simulation or measured data solid or
markers, and one colour stands for one geometry throughout.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from knotmech.errors import InputError, check_finite, check_nonnegative, check_positive

__all__ = [
    "new_axes",
    "tension_decay_plot",
    "capstan_ratio_plot",
    "phase_diagram_plot",
    "force_curve_plot",
]


def new_axes(ax=None, *, figsize=(6.0, 4.2)):
    """Return ``ax`` or, when None, the axes of a new pyplot-free Figure."""
    if ax is not None:
        return ax
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, layout="constrained")
    return fig.add_subplot()


def _colours(n: int):
    from matplotlib import colormaps

    cmap = colormaps["viridis"]
    return [cmap(x) for x in np.linspace(0.05, 0.85, max(n, 1))]


def _as_curve(name: str, curve):
    try:
        x, y = curve
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a pair (x, y) of 1-D arrays") from None
    x = check_finite(f"{name} x", x)
    y = check_finite(f"{name} y", y)
    if x.ndim != 1 or x.shape != y.shape:
        raise InputError(f"{name} must be two 1-D arrays of equal length, got {x.shape}, {y.shape}")
    return x, y


def tension_decay_plot(
    s_over_R,
    *,
    mu: float,
    D_over_d: Sequence[float] = (),
    profiles: Mapping | None = None,
    ax=None,
    logy: bool = True,
    title: str | None = None,
    regions: Sequence | None = None,
):
    r"""Tension along a rod on a post: capstan theory against profiles.

    Draws :math:`T/T_\mathrm{high} = e^{-\mu s/R}` (ideal rope, black dashed) and,
    for each post-to-rod ratio :math:`\tilde D = D/d`, the finite-thickness decay
    :math:`e^{-\mu_\mathrm{eff}(\mu,\tilde D) s/R}` (dotted, one colour per
    :math:`\tilde D`), with the simulated or measured profiles on top in the same
    colour (the clove-hitch paper's Fig. 3b style).

    Parameters
    ----------
    s_over_R : (n,) array
        Arc length over the effective radius :math:`R = (D+d)/2` for the theory curves.
    mu : float
        Material (rod-post) friction coefficient [-].
    D_over_d : sequence of float
        Post-to-rod diameter ratios for the :math:`\mu_\mathrm{eff}` curves.
    profiles : mapping, optional
        ``{D_over_d: (s_over_R, T_over_T_high)}``; keys not in ``D_over_d`` get
        their own theory curve too.
    ax : matplotlib Axes, optional
    logy : bool
        Logarithmic tension axis (exponentials are straight lines).
    title : str, optional
    regions : sequence of (start, end), optional
        Intervals of s/R to shade, e.g. the non-exponential nip regions located
        on a clove hitch's profile.

    Returns
    -------
    matplotlib Axes
    """
    from knotmech.analytic.capstan import mu_eff as _mu_eff

    s = check_nonnegative("s_over_R", s_over_R)
    if s.ndim != 1:
        raise InputError(f"s_over_R must be a 1-D array, got shape {s.shape}")
    mu = float(check_nonnegative("mu", mu))
    profiles = dict(profiles or {})
    ratios = list(D_over_d) + [k for k in profiles if k not in list(D_over_d)]
    if ratios:
        check_positive("D_over_d", np.asarray(ratios, dtype=float))
    ax = new_axes(ax)
    ax.plot(s, np.exp(-mu * s), "k--", lw=1.5, label=rf"ideal rope $e^{{-\mu s/R}}$, $\mu$={mu:g}")
    for colour, Dt in zip(_colours(len(ratios)), ratios, strict=False):
        me = float(_mu_eff(mu, Dt))
        ax.plot(
            s,
            np.exp(-me * s),
            ":",
            color=colour,
            lw=2,
            label=rf"$e^{{-\mu_{{eff}} s/R}}$, $D/d$={Dt:g} ($\mu_{{eff}}$={me:.3f})",
        )
        if Dt in profiles:
            x, y = _as_curve(f"profiles[{Dt!r}]", profiles[Dt])
            ax.plot(x, y, "-", color=colour, lw=1.5, label=rf"profile, $D/d$={Dt:g}")
    for i, region in enumerate(regions or ()):
        try:
            a, b = (float(v) for v in region)
        except (TypeError, ValueError):
            raise InputError(f"regions[{i}] must be a pair (start, end), got {region!r}") from None
        label = "non-exponential region" if i == 0 else None
        ax.axvspan(a, b, color="C1", alpha=0.2, lw=0, label=label)
    if logy:
        ax.set_yscale("log")
    ax.set_xlabel(r"$s/R$  ($R=(D+d)/2$)")
    ax.set_ylabel(r"$T(s)/T_\mathrm{high}$")
    ax.set_xlim(0, float(s.max()) if s.size else 1.0)
    if title:
        ax.set_title(title)
    ax.legend(fontsize=7, loc="lower left")
    ax.grid(True, which="both", alpha=0.3)
    return ax


def capstan_ratio_plot(
    wrap_angle,
    *,
    mu: float,
    D_over_d: Sequence[float] = (),
    measured: Mapping | None = None,
    ax=None,
    logy: bool = True,
    title: str | None = None,
):
    r"""Holding ratio :math:`T_\mathrm{high}/T_\mathrm{low}` against wrap angle.

    Ideal rope :math:`e^{\mu\theta}` (black dashed) and thick rods
    :math:`e^{\mu_\mathrm{eff}\theta}` for each :math:`D/d`; the x axis is in turns
    (:math:`\theta/2\pi`).

    Parameters
    ----------
    wrap_angle : (n,) array [rad]
    mu : float
        Material friction coefficient [-].
    D_over_d : sequence of float
    measured : mapping, optional
        ``{label: (wrap_angle [rad], ratio)}`` drawn as markers.
    ax, logy, title : see :func:`tension_decay_plot`

    Returns
    -------
    matplotlib Axes
    """
    from knotmech.analytic.capstan import mu_eff as _mu_eff

    theta = check_nonnegative("wrap_angle", wrap_angle)
    if theta.ndim != 1:
        raise InputError(f"wrap_angle must be a 1-D array, got shape {theta.shape}")
    mu = float(check_nonnegative("mu", mu))
    ax = new_axes(ax)
    turns = theta / (2 * np.pi)
    ax.plot(turns, np.exp(mu * theta), "k--", lw=1.5, label=r"ideal rope $e^{\mu\theta}$")
    for colour, Dt in zip(_colours(len(D_over_d)), D_over_d, strict=False):
        me = float(_mu_eff(mu, float(check_positive("D_over_d", Dt))))
        ax.plot(
            turns,
            np.exp(me * theta),
            "-",
            color=colour,
            label=rf"$D/d$={Dt:g}: $e^{{\mu_{{eff}}\theta}}$, $\mu_{{eff}}$={me:.3f}",
        )
    for marker, (label, curve) in zip("osD^v<>", (measured or {}).items(), strict=False):
        x, y = _as_curve(f"measured[{label!r}]", curve)
        ax.plot(x / (2 * np.pi), y, marker, ls="none", mfc="none", color="C3", label=str(label))
    if logy:
        ax.set_yscale("log")
    ax.set_xlabel(r"wrap angle $\theta/2\pi$ [turns]")
    ax.set_ylabel(r"$T_\mathrm{high}/T_\mathrm{low}$ at slip")
    ax.set_title(title or rf"capstan, $\mu$ = {mu:g}")
    ax.legend(fontsize=7, loc="upper left")
    ax.grid(True, which="both", alpha=0.3)
    return ax


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
        bx, by = _as_curve("boundary", boundary)
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
    for colour, (label, curve) in zip(_colours(len(curves)), curves.items(), strict=False):
        x, y = _as_curve(f"curves[{label!r}]", curve)
        dashed = "theory" in str(label).lower() or "closed form" in str(label).lower()
        ax.plot(x, y, "--" if dashed else "-", color=colour, label=str(label))
    for marker, (label, pts) in zip("ovs^D<>", (markers or {}).items(), strict=False):
        x, y = _as_curve(f"markers[{label!r}]", (np.atleast_1d(pts[0]), np.atleast_1d(pts[1])))
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
