"""Capstan figures: tension along a rod on a post, holding ratio against wrap angle."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from knotmech.errors import InputError, check_nonnegative, check_positive

from ._style import as_curve, colours, new_axes

__all__ = ["tension_decay_plot", "capstan_ratio_plot"]


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
    for colour, Dt in zip(colours(len(ratios)), ratios, strict=False):
        _decay_curves(ax, s, mu, Dt, profiles.get(Dt), colour)
    _shade(ax, regions or ())
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


def _decay_curves(ax, s, mu: float, Dt: float, profile, colour) -> None:
    """The finite-thickness decay e^(-mu_eff s/R) at D/d = ``Dt`` (dotted) and, if given,
    its profile ``(s/R, T/T_high)`` (solid), in one colour."""
    from knotmech.analytic.capstan import mu_eff as _mu_eff

    me = float(_mu_eff(mu, Dt))
    ax.plot(
        s,
        np.exp(-me * s),
        ":",
        color=colour,
        lw=2,
        label=rf"$e^{{-\mu_{{eff}} s/R}}$, $D/d$={Dt:g} ($\mu_{{eff}}$={me:.3f})",
    )
    if profile is not None:
        x, y = as_curve(f"profiles[{Dt!r}]", profile)
        ax.plot(x, y, "-", color=colour, lw=1.5, label=rf"profile, $D/d$={Dt:g}")


def _shade(ax, regions) -> None:
    """Shade the intervals ``regions`` = [(start, end), ...] of s/R."""
    for i, region in enumerate(regions):
        try:
            a, b = (float(v) for v in region)
        except (TypeError, ValueError):
            raise InputError(f"regions[{i}] must be a pair (start, end), got {region!r}") from None
        label = "non-exponential region" if i == 0 else None
        ax.axvspan(a, b, color="C1", alpha=0.2, lw=0, label=label)


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
    for colour, Dt in zip(colours(len(D_over_d)), D_over_d, strict=False):
        me = float(_mu_eff(mu, float(check_positive("D_over_d", Dt))))
        ax.plot(
            turns,
            np.exp(me * theta),
            "-",
            color=colour,
            label=rf"$D/d$={Dt:g}: $e^{{\mu_{{eff}}\theta}}$, $\mu_{{eff}}$={me:.3f}",
        )
    for marker, (label, curve) in zip("osD^v<>", (measured or {}).items(), strict=False):
        x, y = as_curve(f"measured[{label!r}]", curve)
        ax.plot(x / (2 * np.pi), y, marker, ls="none", mfc="none", color="C3", label=str(label))
    if logy:
        ax.set_yscale("log")
    ax.set_xlabel(r"wrap angle $\theta/2\pi$ [turns]")
    ax.set_ylabel(r"$T_\mathrm{high}/T_\mathrm{low}$ at slip")
    ax.set_title(title or rf"capstan, $\mu$ = {mu:g}")
    ax.legend(fontsize=7, loc="upper left")
    ax.grid(True, which="both", alpha=0.3)
    return ax
