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
profile with :func:`fit_decay_rate`. The profiles are simulated by DER
(``knotmech.scenes.capstan``, one pulled capstan per D/d run through
:func:`knotmech.sweep.sweep`), with a control run whose friction acts at the
centreline (no couple: it must decay at mu). Without the scene (or with
``der=False``) only the closed forms are drawn and the summary says so in its
notes and in ``numbers["profile_source"]``.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from knotmech.analytic.capstan import mu_eff, mu_from_mu_eff
from knotmech.errors import InputError
from knotmech.materials import CLOVE_ROD_DIAMETER, VPS32_DENSITY, VPS32_YOUNGS_MODULUS
from knotmech.plotting import new_axes, tension_decay_plot
from knotmech.sweep import TaskFailure

from ._common import finish, save_figure

NAME = "capstan_decay"
#: one sentence for the validation page: what this case checks, and against what
SUMMARY = (
    "DER tension along a rod sliding on a post: its fitted decay rate against the thick-rod "
    "closed form mu_eff(D/d) (clove-hitch paper, eq. 3) for several D/d, and against mu "
    "itself (Euler-Eytelwein) for a control run whose friction acts at the centreline."
)
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


# DER set-up (the clove-hitch paper's rod: d = 4 mm, VPS32 E = 1.26 MPa, 1160 kg/m^3)
ROD_DIAMETER = CLOVE_ROD_DIAMETER  #: [m]
YOUNGS_MODULUS = VPS32_YOUNGS_MODULUS  #: [Pa]
DENSITY = VPS32_DENSITY  #: [kg/m^3]
T_LOW = 0.05  #: [N] dead load on the low-tension end
EPS2 = 0.01  #: EI / (T_low R^2): rope-like bending, short lift-off boundary layers
TRIM = 0.1  #: fraction of the contact arc left out of the fit at each end (lift-off layers)
#: largest wrap of the thickest rods (D/d < 2): wrapped twice round a post of its own diameter,
#: the surface-friction rod rolls off the post in DER (full mode, 2 pi: no contact left at the
#: end; the old solver failed to converge there), so D/d = 1 keeps the quick mode's half turn
THICK_ROD_MAX_WRAP = np.pi


def _wrap_of(D_over_d, wrap_angle):
    """The wrap a rod of this D/d is simulated with (see :data:`THICK_ROD_MAX_WRAP`)."""
    return min(wrap_angle, THICK_ROD_MAX_WRAP) if D_over_d < 2 else wrap_angle


def _der_runs(ratios, *, wrap_angle):
    """Keyword sets of :func:`knotmech.scenes.capstan.capstan`, one per D/d, plus a control.

    The control (last entry) puts the friction at the centreline instead of the rod's
    surface on the thickest rod (smallest D/d): it must decay at the material mu.
    """
    runs = []
    for Dt in ratios:
        D = Dt * ROD_DIAMETER
        R = 0.5 * (D + ROD_DIAMETER)
        runs.append(
            dict(
                wrap_angle=_wrap_of(Dt, wrap_angle),
                mu=MU,
                rod_diameter=ROD_DIAMETER,
                post_diameter=D,
                youngs_modulus=YOUNGS_MODULUS,
                density=DENSITY,
                t_low=T_LOW,
                bending_stiffness=EPS2 * T_LOW * R**2,
                mode="pull",
                surface_friction=True,
            )
        )
    control = dict(runs[0], surface_friction=False)
    return runs + [control]


def _profile(result):
    """(s/R from the start of contact, T/T at the start, fit mask) of a capstan run."""
    R = 0.5 * (result.post_diameter + result.rod_diameter)
    c = np.asarray(result.contact, dtype=bool)
    idx = np.flatnonzero(c[:-1] & c[1:])  # edges with both nodes on the post
    if result.status != "success" or idx.size < 8:
        return None
    s = (result.s[idx] - result.s[idx[0]]) / R
    t = result.tension[idx] / result.tension[idx[0]]
    n = idx.size
    keep = np.zeros(n, dtype=bool)
    keep[int(TRIM * n) : n - int(TRIM * n)] = True
    return s, t, keep


def der_profiles(
    ratios, *, quick=True, progress=False, scheduler=None, cache_dir=None, processes=None
):
    """Simulated profiles from the DER capstan scene (``knotmech.scenes.capstan``).

    One pulled capstan per D/d (wrap pi in quick mode, 2 pi in full), run through
    :func:`knotmech.sweep.sweep` (parallel, cached in ``cache_dir``), plus the
    centreline-friction control.

    Returns
    -------
    dict or None
        None when the scene is not available; else ``{"profiles": {D/d: (s/R, T/T0,
        fit_mask)}, "control": (s/R, T/T0, mask) or None, "ratio": {D/d: T_high/T_low},
        "failed": [D/d, ...], "wrap_angle": float, "stats": {...}}``.
    """
    try:
        from knotmech.scenes.capstan import capstan
    except ImportError:
        return None
    from knotmech.sweep import sweep

    wrap = np.pi if quick else 2 * np.pi
    runs = _der_runs(ratios, wrap_angle=wrap)
    if processes is None:
        processes = min(2, os.cpu_count() or 1)
    res = sweep(
        capstan,
        runs,
        processes=processes,
        scheduler=scheduler,
        cache_dir=cache_dir,
        progress=progress,
        on_error="return",
        desc="capstan DER",
    )
    out = {
        "profiles": {},
        "ratio": {},
        "failed": [],
        "wrap_angle": wrap,
        "control": None,
        "n_computed": res.n_computed,
        "n_cached": res.n_cached,
    }
    for Dt, r in zip(list(ratios) + ["control"], res, strict=True):
        prof = None if isinstance(r, TaskFailure) else _profile(r)
        if Dt == "control":
            out["control"] = prof
        elif prof is None:
            out["failed"].append(Dt)
        else:
            out["profiles"][Dt] = prof
            out["ratio"][Dt] = float(r.ratio)
    return out


def run(quick=True, out_dir=".", progress=False, scheduler=None, der=None, processes=None) -> dict:
    """Compute, plot and summarise case 1; see the module docstring.

    ``der``: None uses the DER scene when it is importable, False skips it (closed
    forms only), True requires it. DER runs are cached in ``<out_dir>/cache/``;
    ``processes`` local worker processes (default 2; 1 runs them here, which shares
    numba's compiled kernels with the calling process).
    """
    ratios = D_OVER_D_QUICK if quick else D_OVER_D_FULL
    me = {Dt: float(mu_eff(MU, Dt)) for Dt in ratios}
    # closed-form curves, and the fitting routine checked on them
    s_cf = np.linspace(0.0, 2 * np.pi * WRAP_TURNS, 200 if quick else 1000)
    sim = None
    if der is not False:
        sim = der_profiles(
            ratios,
            quick=quick,
            progress=progress,
            scheduler=scheduler,
            cache_dir=Path(out_dir) / "cache" / NAME,
            processes=processes,
        )
        if sim is None and der:
            raise InputError("der=True but knotmech.scenes.capstan is not available")
    source = "DER (knotmech.scenes.capstan)" if sim else "closed form only (no DER scene)"
    numbers, checks, notes = _closed_form_summary(ratios, me, s_cf, source)
    profiles, der_fitted = {}, {}
    if sim:
        profiles, der_fitted = _der_summary(sim, ratios, me, numbers, checks, notes)
        s_plot = np.linspace(0.0, max(p[0].max() for p in profiles.values()), 200)
    else:
        notes.append(
            "DER tension profiles are not in this run (knotmech.scenes.capstan unavailable or "
            "der=False); the fitted rates only check the fitting routine."
        )
        s_plot = s_cf
    figures = [
        _profiles_figure(s_plot, ratios, profiles, sim, out_dir),
        _mu_eff_figure(ratios, der_fitted, numbers, out_dir),
    ]
    return finish(
        NAME,
        out_dir=out_dir,
        checks=checks,
        numbers=numbers,
        figures=figures,
        notes=notes,
        quick=quick,
    )


def _closed_form_summary(ratios, me, s_cf, source):
    """Numbers, checks and notes of the closed forms (mu_eff and the fitting routine)."""
    cf_fitted = {Dt: fit_decay_rate(s_cf, np.exp(-me[Dt] * s_cf)) for Dt in ratios}
    cf_err = max(abs(cf_fitted[Dt] - me[Dt]) / me[Dt] for Dt in ratios)
    numbers = {
        "mu": MU,
        "D_over_d": list(ratios),
        "mu_eff": [me[Dt] for Dt in ratios],
        "closed_form_fitted_rate": [cf_fitted[Dt] for Dt in ratios],
        "closed_form_max_rel_err_fit": cf_err,
        "mu_eff_at_D_over_d_1e4": float(mu_eff(MU, 1e4)),
        "T_over_T_high_one_turn_ideal": float(np.exp(-MU * 2 * np.pi)),
        "T_over_T_high_one_turn_mu_eff": [float(np.exp(-me[Dt] * 2 * np.pi)) for Dt in ratios],
        "profile_source": source,
    }
    roundtrip = float(np.max(np.abs(mu_from_mu_eff(np.array(list(me.values())), ratios) - MU)))
    checks = {
        "mu_eff < mu for every D/d": all(me[Dt] < MU for Dt in ratios),
        "mu_eff increases with D/d": bool(np.all(np.diff([me[Dt] for Dt in ratios]) > 0)),
        "mu_eff -> mu for D/d -> infinity (rel. diff < 1e-3 at D/d = 1e4)": abs(
            numbers["mu_eff_at_D_over_d_1e4"] - MU
        )
        / MU
        < 1e-3,
        "mu_from_mu_eff inverts mu_eff (to 1e-12)": roundtrip < 1e-12,
        "fit_decay_rate recovers mu_eff from the closed-form curves (1e-9)": cf_err < 1e-9,
    }
    notes = [
        f"Profiles: {source}.",
        "R = (D + d)/2 is the radius of the rod centreline on the post; s is measured from "
        "where the rod meets the post.",
        "Reference: clove-hitch paper (Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788), "
        "eq. 3 and Fig. 3b; Jung, Pan & Kang, Mech. Mach. Theory 43 (2008) 661.",
    ]
    return numbers, checks, notes


def _der_summary(sim, ratios, me, numbers, checks, notes):
    """Fit the DER profiles; add their numbers, checks and notes (in place). Returns the
    profiles {D/d: (s/R, T/T_high)} and the fitted rates {D/d: rate}."""
    profiles, der_fitted = {}, {}
    wrap = sim["wrap_angle"]
    for Dt, (s_, t_, keep) in sim["profiles"].items():
        profiles[Dt] = (s_, t_)
        der_fitted[Dt] = fit_decay_rate(s_[keep], t_[keep])
    ok = [Dt for Dt in ratios if Dt in der_fitted]
    der_err = {Dt: abs(der_fitted[Dt] - me[Dt]) / me[Dt] for Dt in ok}
    wraps = {Dt: _wrap_of(Dt, wrap) for Dt in ratios}
    ratio_err = {Dt: abs(sim["ratio"][Dt] / float(np.exp(me[Dt] * wraps[Dt])) - 1) for Dt in ok}
    control = sim["control"]
    control_rate = (
        fit_decay_rate(control[0][control[2]], control[1][control[2]]) if control else None
    )
    numbers.update(
        {
            "der_wrap_angle": wrap,
            "der_wrap_angle_per_D_over_d": [wraps[Dt] for Dt in ratios],
            "der_fitted_rate": [der_fitted.get(Dt) for Dt in ratios],
            "der_rel_err_vs_mu_eff": [der_err.get(Dt) for Dt in ratios],
            "der_ratio_T_high_over_T_low": [sim["ratio"].get(Dt) for Dt in ratios],
            "der_ratio_rel_err_vs_exp_mu_eff_theta": [ratio_err.get(Dt) for Dt in ratios],
            "der_control_centreline_friction_D_over_d": ratios[0],
            "der_control_rate": control_rate,
            "der_failed": sim["failed"],
            "der_runs_computed": sim["n_computed"],
            "der_runs_cached": sim["n_cached"],
        }
    )
    checks.update(
        {
            "every DER run slid and touched the post": not sim["failed"],
            "DER decay rate = mu_eff within 5 % for every D/d": bool(ok)
            and max(der_err.values()) < 0.05,
            "DER T_high/T_low = exp(mu_eff theta) within 5 %": bool(ok)
            and max(ratio_err.values()) < 0.05,
            "control: friction at the centreline decays at mu within 5 %": control_rate is not None
            and abs(control_rate - MU) / MU < 0.05,
        }
    )
    notes.append(
        f"DER: rod d = {ROD_DIAMETER * 1e3:g} mm, E = {YOUNGS_MODULUS / 1e6:g} MPa, pulled "
        f"over a post with T_low = {T_LOW:g} N, wrap {wrap / np.pi:g} pi, mu = {MU:g}; "
        f"bending stiffness reduced to EI = {EPS2:g} T_low R^2 (rope-like) so that the "
        "lift-off boundary layers are short; the contact diameter stays d. Rates fitted on "
        f"the contact arc without {TRIM:.0%} at each end."
    )
    notes.append(
        "Control: the same thickest rod with friction applied at the centreline (no "
        "couple) decays at mu, as the ideal rope: the couple of the surface friction is "
        "what lowers the rate to mu_eff."
    )
    return profiles, der_fitted


def _profiles_figure(s_plot, ratios, profiles, sim, out_dir):
    """Tension profiles against the closed forms (and the centreline-friction control)."""
    ax = tension_decay_plot(
        s_plot,
        mu=MU,
        D_over_d=ratios,
        profiles=profiles or None,
        title=f"capstan decay, mu = {MU:g}: "
        + ("DER (solid) vs closed forms" if sim else "closed forms"),
    )
    if sim and sim["control"] is not None:
        ax.plot(
            sim["control"][0],
            sim["control"][1],
            "-",
            color="0.3",
            lw=1,
            label=f"DER, friction at the centreline, D/d={ratios[0]:g} (control)",
        )
        ax.legend(fontsize=7, loc="lower left")
    return save_figure(ax.figure, out_dir, f"{NAME}_profiles")


def _mu_eff_figure(ratios, der_fitted, numbers, out_dir):
    """mu_eff/mu against D/d for four mu, with the DER fitted rates."""
    dense = np.geomspace(0.5, 1000.0, 200)
    ax = new_axes()
    for m in (0.1, 0.3, 0.5, 1.0):
        ax.semilogx(dense, mu_eff(m, dense) / m, label=rf"$\mu$ = {m:g}")
    if der_fitted:
        xs = [Dt for Dt in ratios if Dt in der_fitted]
        ax.semilogx(
            xs,
            [der_fitted[Dt] / MU for Dt in xs],
            "ko",
            mfc="none",
            label=rf"DER fitted decay rate / $\mu$ ($\mu$={MU:g})",
        )
        if numbers.get("der_control_rate") is not None:
            ax.semilogx(
                [ratios[0]],
                [numbers["der_control_rate"] / MU],
                "kx",
                label="DER, friction at the centreline (control)",
            )
    ax.axhline(1.0, color="k", ls="--", lw=1, label="ideal rope")
    ax.set_xlabel(r"$D/d$")
    ax.set_ylabel(r"$\mu_\mathrm{eff}/\mu$")
    ax.set_title("thick rods grip less: effective friction on a post")
    ax.legend(fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    return save_figure(ax.figure, out_dir, f"{NAME}_mu_eff")


if __name__ == "__main__":
    import sys

    from ._common import main

    sys.exit(main(run))
