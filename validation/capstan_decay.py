"""Case 1: capstan tension decay on a post, ideal rope against thick rod.

Along the part of a rod that slides on a rigid post, the tension decays
exponentially. For an ideal rope (no thickness, no bending stiffness) the rate is
the friction coefficient (Euler-Eytelwein), :math:`T(s)/T_\\mathrm{high} =
e^{-\\mu s/R}`. For a rod of diameter d on a post of diameter D, friction acts
at the contact surface half a diameter off the centreline and its moment lowers
the rate to

.. math:: \\mu_\\mathrm{eff} = \\frac{-(1+\\tilde D) + \\sqrt{(1+\\tilde D)^2
          + 4\\mu^2\\tilde D}}{2\\mu}, \\qquad \\tilde D = D/d,

with :math:`R = (D+d)/2` (the clove-hitch paper, "Exploring the inner workings
of the clove hitch knot", Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788,
eq. 3, after Jung, Pan & Kang, Mech. Mach. Theory 43 (2008) 661).

This case draws :math:`e^{-\\mu s/R}` and :math:`e^{-\\mu_\\mathrm{eff} s/R}` for
several D/d (the paper's Fig. 3b style) and fits the decay rate of each
profile with :func:`fit_decay_rate`. **Hook for the DER profiles:**
:func:`der_profiles` returns the simulated T(s)/T_high from
``knotmech.scenes.capstan`` when that scene exists; until then the fitted rates
are those of the closed-form curves (a check of the fitting routine only) and
the summary says so in its notes and in ``numbers["profile_source"]``.
"""

from __future__ import annotations

import numpy as np

from knotmech.analytic.capstan import mu_eff, mu_from_mu_eff
from knotmech.errors import InputError
from knotmech.plotting import new_axes, tension_decay_plot

from ._common import finish, save_figure

NAME = "capstan_decay"
MU = 0.3  #: rod-post friction coefficient (a mid value of the clove-hitch paper's mu_rc)
D_OVER_D_QUICK = (1.0, 2.0, 7.5, 30.0)  #: 7.5 = the clove-hitch paper's D/d = 30 mm / 4 mm
D_OVER_D_FULL = (1.0, 2.0, 4.0, 7.5, 15.0, 30.0, 100.0)
WRAP_TURNS = 2.0  #: length of rod in contact, in turns (s/R up to 2 pi * WRAP_TURNS)


def fit_decay_rate(s_over_R, tension, *, s_min=None, s_max=None) -> float:
    """Exponential decay rate of a tension profile by least squares on log T.

    Parameters
    ----------
    s_over_R : (n,) array
        Arc length over R.
    tension : (n,) array
        T(s) (any scale; only the slope of log T is used) [N], > 0 in the window.
    s_min, s_max : float, optional
        Window of s/R to fit (leave out the loading ends of a simulated profile).

    Returns
    -------
    float
        The rate k in :math:`T \\propto e^{-k s/R}`; an estimate of
        :math:`\\mu_\\mathrm{eff}`.
    """
    s = np.asarray(s_over_R, dtype=float)
    t = np.asarray(tension, dtype=float)
    keep = np.ones_like(s, dtype=bool)
    if s_min is not None:
        keep &= s >= s_min
    if s_max is not None:
        keep &= s <= s_max
    if keep.sum() < 2:
        raise InputError("fit_decay_rate needs at least two points in the window")
    if np.any(t[keep] <= 0) or not np.all(np.isfinite(t[keep])):
        raise InputError("fit_decay_rate needs positive finite tensions in the window")
    slope = np.polyfit(s[keep], np.log(t[keep]), 1)[0]
    return float(-slope)


def der_profiles(mu, D_over_d, *, quick=True, progress=False, scheduler=None):
    """HOOK: simulated profiles ``{D/d: (s/R, T/T_high)}`` from the DER capstan scene.

    Returns None while ``knotmech.scenes.capstan`` does not exist (the case then
    reports the closed-form curves only). When the scene lands, this is the one
    place to wire it: run one simulation per D/d (through
    :func:`knotmech.sweep.sweep`, which caches and parallelises them), return
    s/R and T/T_high over the contact region, and set :data:`FIT_WINDOW` to the
    part of the contact away from the loading ends.
    """
    try:
        from knotmech.scenes import capstan  # noqa: F401
    except ImportError:
        return None
    return None  # scene present but not wired yet: see the docstring


#: s/R window for the fit of simulated profiles (None: the whole curve)
FIT_WINDOW = (None, None)


def run(quick=True, out_dir=".", progress=False, scheduler=None) -> dict:
    """Compute, plot and summarise case 1; see the module docstring."""
    ratios = D_OVER_D_QUICK if quick else D_OVER_D_FULL
    s_max = 2 * np.pi * WRAP_TURNS
    s = np.linspace(0.0, s_max, 200 if quick else 1000)
    me = {Dt: float(mu_eff(MU, Dt)) for Dt in ratios}

    simulated = der_profiles(MU, ratios, quick=quick, progress=progress, scheduler=scheduler)
    if simulated:
        profiles, source = simulated, "DER (knotmech.scenes.capstan)"
        window = FIT_WINDOW
    else:
        profiles = {Dt: (s, np.exp(-me[Dt] * s)) for Dt in ratios}
        source = "closed form (no DER capstan scene yet)"
        window = (None, None)
    fitted = {Dt: fit_decay_rate(*profiles[Dt], s_min=window[0], s_max=window[1]) for Dt in ratios}
    rel_err = {Dt: abs(fitted[Dt] - me[Dt]) / me[Dt] for Dt in ratios}

    figures = []
    ax = tension_decay_plot(
        s,
        mu=MU,
        D_over_d=ratios,
        profiles=profiles if simulated else None,
        title=f"capstan decay on a post, mu = {MU:g} (profiles: {source})",
    )
    figures.append(save_figure(ax.figure, out_dir, f"{NAME}_profiles"))

    dense = np.geomspace(0.5, 1000.0, 200)
    ax = new_axes()
    for m in (0.1, 0.3, 0.5, 1.0):
        ax.semilogx(dense, mu_eff(m, dense) / m, label=rf"$\mu$ = {m:g}")
    ax.semilogx(
        list(ratios),
        [fitted[Dt] / MU for Dt in ratios],
        "ko",
        mfc="none",
        label=rf"fitted decay rate / $\mu$ ($\mu$={MU:g}, {source})",
    )
    ax.axhline(1.0, color="k", ls="--", lw=1, label="ideal rope")
    ax.set_xlabel(r"$D/d$")
    ax.set_ylabel(r"$\mu_\mathrm{eff}/\mu$")
    ax.set_title("thick rods grip less: effective friction on a post")
    ax.legend(fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    figures.append(save_figure(ax.figure, out_dir, f"{NAME}_mu_eff"))

    mu_eff_large = float(mu_eff(MU, 1e4))
    roundtrip = float(np.max(np.abs(mu_from_mu_eff(np.array(list(me.values())), ratios) - MU)))
    tol = 0.05 if simulated else 1e-9
    checks = {
        "mu_eff < mu for every D/d": all(me[Dt] < MU for Dt in ratios),
        "mu_eff increases with D/d": bool(np.all(np.diff([me[Dt] for Dt in ratios]) > 0)),
        "mu_eff -> mu for D/d -> infinity (rel. diff < 1e-3 at D/d = 1e4)": abs(mu_eff_large - MU)
        / MU
        < 1e-3,
        "mu_from_mu_eff inverts mu_eff (to 1e-12)": roundtrip < 1e-12,
        f"fitted decay rate = mu_eff within {tol:g} (relative)": max(rel_err.values()) < tol,
    }
    notes = [
        f"Profiles: {source}.",
        "R = (D + d)/2 is the radius of the rod centreline on the post.",
        "Reference: clove-hitch paper (Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788), "
        "eq. 3 and Fig. 3b; "
        "Jung, Pan & Kang, Mech. Mach. Theory 43 (2008) 661.",
    ]
    if not simulated:
        notes.append(
            "DER tension profiles are not in this run: knotmech.scenes.capstan is not wired "
            "(hook: validation/capstan_decay.py der_profiles); the fitted rates only check "
            "the fitting routine on the closed-form curves."
        )
    numbers = {
        "mu": MU,
        "D_over_d": list(ratios),
        "mu_eff": [me[Dt] for Dt in ratios],
        "fitted_rate": [fitted[Dt] for Dt in ratios],
        "max_rel_err_fit": max(rel_err.values()),
        "mu_eff_at_D_over_d_1e4": mu_eff_large,
        "T_over_T_high_one_turn_ideal": float(np.exp(-MU * 2 * np.pi)),
        "T_over_T_high_one_turn_mu_eff": [float(np.exp(-me[Dt] * 2 * np.pi)) for Dt in ratios],
        "profile_source": source,
    }
    return finish(
        NAME,
        out_dir=out_dir,
        checks=checks,
        numbers=numbers,
        figures=figures,
        notes=notes,
        quick=quick,
    )


if __name__ == "__main__":
    import sys

    from ._common import main

    sys.exit(main(run))
