r"""Case 2: tension profile T(s) along a clove hitch with a free end.

The clove-hitch paper (Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788, sec. 7 and
Fig. 3b) computes by FEM the tension along a clove hitch on a post with
:math:`(d, D, L) = (4, 30, 374)` mm, :math:`\mu_{rr} = 0.3`, a hanging load
:math:`T_\mathrm{high} = 1.47` N on one end, the other end free, for
:math:`\mu_{rc} \in \{0.2, 0.3, 0.4\}`, and finds

(i) exponential decay where the rod lies on the post, at the rate of the
    finite-thickness capstan, eq. (3):

    .. math:: T(s) \sim e^{-\mu_\mathrm{eff} s/R}, \qquad
              \mu_\mathrm{eff} = \frac{-(1+\tilde D) + \sqrt{(1+\tilde D)^2
              + 4\mu_{rc}^2\tilde D}}{2\mu_{rc}}, \quad \tilde D = D/d;

(ii) non-exponential *nip* regions where the rod touches itself: drops at the entry and
     the exit of the knot and, in the middle, a region where T rises.

Here the profiles come from the DER scene :func:`knotmech.scenes.clove_hitch.clove_hitch`
(run through :func:`knotmech.sweep.sweep`). The nip regions are located from the profile
alone, with no contact information: the local decay rate
:math:`k(s) = -\mathrm{d}\ln T/\mathrm{d}(s/R)` is compared with :math:`\mu_\mathrm{eff}`
and the points where it differs by more than half of :math:`\mu_\mathrm{eff}` are grouped
into regions by :func:`knotmech.diagnose.locate.regions_from_mask`, the grouping step of
the diagnose engine's localisation (the engine's statistical test itself needs noisy
repeated trials; a deterministic simulated profile has none, so the deviation threshold
replaces its z-score). Between the nips, each exponential segment's rate is fitted with
:func:`validation.capstan_decay.fit_decay_rate`. The contact flags of the run are only
used afterwards, to report how many located regions contain rod-rod contact.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from knotmech.analytic.capstan import mu_eff
from knotmech.diagnose.locate import regions_from_mask
from knotmech.plotting import new_axes
from knotmech.sweep import TaskFailure

from ._common import finish, save_figure
from .capstan_decay import fit_decay_rate

NAME = "clove_tension_profile"
#: one sentence for the validation page: what this case checks, and against what
SUMMARY = (
    "DER tension profile T(s) along a free-end clove hitch against the clove-hitch paper's "
    "FEM (sec. 7, Fig. 3b): exponential decay at mu_eff on the wraps for mu_rc = 0.2, 0.3, "
    "0.4, and the nip regions at the knot's entry, middle and exit, found from the profile "
    "alone."
)
ROD_DIAMETER = 4e-3  #: d [m]
POST_DIAMETER = 30e-3  #: D [m]
ROD_LENGTH = 0.374  #: L [m]
MU_RR = 0.3
T_HIGH = 1.47  #: [N]
MU_RC = (0.2, 0.3, 0.4)
RATE_TOL = 0.15  #: relative tolerance of the fitted decay rates against mu_eff
DEVIATION = 0.5  #: |k - mu_eff| > DEVIATION * mu_eff marks a non-exponential point
MIN_SEGMENT = 5  #: points of an exponential segment to fit it
#: run protocol (the scene's slow free-end test); full: finer rod
PROTOCOL = dict(settle_time=0.2, load_time=0.2, hold_time=0.4, dt=2e-3, n_frames=21)
N_NODES = {True: 120, False: 180}


def _runs(mu_values, quick):
    return [
        dict(
            loading="free",
            t_high=T_HIGH,
            rod_diameter=ROD_DIAMETER,
            post_diameter=POST_DIAMETER,
            rod_length=ROD_LENGTH,
            mu_rod_post=float(m),
            mu_rod_rod=MU_RR,
            n_nodes=N_NODES[bool(quick)],
            # the law these checks were validated with (the clove-hitch scene's default is
            # now the sticking anchor law, under which held wraps need not mobilise mu_eff)
            friction="imc",
            **PROTOCOL,
        )
        for m in mu_values
    ]


def analyse_profile(s_over_R, tension, *, rate, t_high, deviation=DEVIATION):
    r"""Locate the non-exponential regions of a tension profile and fit its exponential parts.

    Parameters
    ----------
    s_over_R : (n,) array
        Arc length over R, increasing.
    tension : (n,) array [N]
    rate : float
        Expected capstan rate :math:`\mu_\mathrm{eff}`.
    t_high : float [N]
        Load on the loaded end.
    deviation : float
        A point is non-exponential where :math:`|k - \mu_\mathrm{eff}| >` deviation
        :math:`\mu_\mathrm{eff}`, with :math:`k = -\Delta\ln T/\Delta(s/R)` (centred).

    Returns
    -------
    dict
        ``span`` (first, last index of the knot: where T has left T_high and before it
        reaches 1 % of it), ``mask`` (non-exponential points), ``regions`` [(a, b)] in s/R,
        ``segments`` [(i0, i1)] index ranges of exponential parts, ``rates`` fitted on them,
        ``k`` local rate.
    """
    x = np.asarray(s_over_R, dtype=float)
    t = np.asarray(tension, dtype=float)
    n = x.size
    below = np.flatnonzero(t < 0.995 * t_high)
    above = np.flatnonzero(t > 0.01 * t_high)
    if below.size == 0 or above.size == 0:
        return {"span": None, "mask": np.zeros(n, bool), "regions": [], "segments": [], "rates": []}
    i0 = max(int(below[0]) - 1, 0)
    i1 = min(int(above[-1]) + 1, n - 1)
    lt = np.log(np.maximum(t, 1e-3 * t_high))
    k = np.zeros(n)
    k[1:-1] = -(lt[2:] - lt[:-2]) / (x[2:] - x[:-2])
    k[0], k[-1] = k[1], k[-2]
    span = np.zeros(n, bool)
    span[i0 : i1 + 1] = True
    mask = span & (np.abs(k - rate) > deviation * rate)
    mask[i0] = mask[i1] = True  # the knot's entry and exit are not capstan
    regions = regions_from_mask(x, mask)
    # exponential segments: runs of unmasked points inside the span
    segments, rates = [], []
    j = i0
    while j <= i1:
        if mask[j]:
            j += 1
            continue
        a = j
        while j <= i1 and not mask[j]:
            j += 1
        b = j - 1
        if b - a + 1 >= MIN_SEGMENT:
            segments.append((a, b))
            rates.append(fit_decay_rate(x[a : b + 1], t[a : b + 1]))
    return {
        "span": (i0, i1),
        "mask": mask,
        "regions": regions,
        "segments": segments,
        "rates": rates,
        "k": k,
    }


def _clove_task(**kw):
    """One free-end clove hitch (:func:`knotmech.scenes.clove_hitch.clove_hitch`).

    Defined here, at module level, so that the sweep's worker processes can receive it by
    name: the scene function itself is made by a factory, and pickle cannot find it under
    the module its name gives.
    """
    from knotmech.scenes.clove_hitch import clove_hitch

    return clove_hitch(**kw)


def der_runs(
    mu_values, *, quick=True, progress=False, scheduler=None, cache_dir=None, processes=None
):
    """DER free-end clove hitches, one per mu_rc (list of results or TaskFailure)."""
    from knotmech.sweep import sweep

    if processes is None:
        processes = min(2, os.cpu_count() or 1)
    return sweep(
        _clove_task,
        _runs(mu_values, quick),
        processes=processes,
        scheduler=scheduler,
        cache_dir=cache_dir,
        progress=progress,
        on_error="return",
        desc="clove hitch DER",
    )


def _analyse_run(m, r, R) -> dict | None:
    """Analysis of one DER profile at mu_rc = ``m`` (None when the run or its profile failed).

    Returns the run, its :func:`analyse_profile` result and the numbers the case reports:
    mu_eff, the entry position ``x0`` [s/R], fitted rates and their relative errors, nip
    regions in turns from the entry, how many of them contain rod-rod contact, the end
    tensions over T_high, the verdict, the creep [m] and the wall time [s].
    """
    if isinstance(r, TaskFailure) or r.status != "success":
        return None
    me = float(mu_eff(m, POST_DIAMETER / ROD_DIAMETER))
    x = r.s / R
    an = analyse_profile(x, r.tension, rate=me, t_high=T_HIGH)
    if an["span"] is None:
        return None
    x0 = x[an["span"][0]]
    nips_in_contact = sum(
        bool(np.any(r.rod_contact[(x >= a) & (x <= b)])) for a, b in an["regions"]
    )
    return {
        "result": r,
        "analysis": an,
        "mu_eff": me,
        "x0": x0,
        "rates": an["rates"],
        "rate_rel_err": [abs(k - me) / me for k in an["rates"]],
        "nip_regions_turns": [
            ((a - x0) / (2 * np.pi), (b - x0) / (2 * np.pi)) for a, b in an["regions"]
        ],
        "nips_with_rod_contact": nips_in_contact,
        "t_end_over_t_high": float(abs(r.tension[-1]) / T_HIGH),
        "t_start_over_t_high": float(r.tension[0] / T_HIGH),
        "verdict": r.verdict,
        "creep": float(r.creep),
        "wall_s": float(r.stats.get("wall_s", np.nan)),
    }


def _numbers(mus, quick, failed, per_mu) -> dict:
    """The case's JSON numbers: the set-up, then one entry per analysed mu_rc."""
    numbers = {
        "d_D_L_mm": [ROD_DIAMETER * 1e3, POST_DIAMETER * 1e3, ROD_LENGTH * 1e3],
        "mu_rr": MU_RR,
        "T_high_N": T_HIGH,
        "mu_rc": list(mus),
        "n_nodes": N_NODES[bool(quick)],
        "failed_mu_rc": failed,
        "rate_tolerance": RATE_TOL,
    }
    for m, p in per_mu.items():
        numbers[f"mu_rc={m:g}"] = {
            "mu_eff": p["mu_eff"],
            "fitted_rates": p["rates"],
            "rate_rel_err": p["rate_rel_err"],
            "nip_regions_s_over_2piR_from_entry": p["nip_regions_turns"],
            "n_nip_regions": len(p["nip_regions_turns"]),
            "nip_regions_with_rod_contact": p["nips_with_rod_contact"],
            "T_free_end_over_T_high": p["t_end_over_t_high"],
            "T_loaded_end_over_T_high": p["t_start_over_t_high"],
            "verdict": p["verdict"],
            "creep_m": p["creep"],
            "wall_s": p["wall_s"],
        }
    return numbers


def _checks(failed, per_mu) -> dict:
    """The case's pass/fail checks; each fails when no profile was analysed."""
    ps = list(per_mu.values())
    ok = bool(ps)
    return {
        "every DER run finished": not failed and ok,
        "two or more exponential segments per profile": ok
        and all(len(p["rates"]) >= 2 for p in ps),
        f"fitted decay rates = mu_eff within {RATE_TOL:.0%}": ok
        and all(p["rates"] and max(p["rate_rel_err"]) < RATE_TOL for p in ps),
        "at least two nip regions located per profile": ok
        and all(len(p["nip_regions_turns"]) >= 2 for p in ps),
        "T at the free end < 2 % of T_high": ok and all(p["t_end_over_t_high"] < 0.02 for p in ps),
        "the loaded end carries T_high (2 %)": ok
        and all(abs(p["t_start_over_t_high"] - 1) < 0.02 for p in ps),
    }


def _notes(quick) -> list[str]:
    """What the case did and how to read it, for the validation page."""
    return [
        "DER (knotmech.scenes.clove_hitch, free end): a pre-shaped hitch relaxed on the post, "
        f"loaded with T_high = {T_HIGH} N on end 0 (0.2 s settle, 0.2 s ramp, 0.4 s hold), "
        f"{N_NODES[bool(quick)]} nodes.",
        "s is measured from the knot's entry (where T first leaves T_high); the paper's Fig. 3b "
        "puts the entry nip at s/(2 pi R) ~ 0.1, the middle region at 1.0-1.5 and the exit at "
        "~2.25 of its own origin.",
        f"Nip regions: |k - mu_eff| > {DEVIATION:g} mu_eff with k = -dlnT/d(s/R), grouped by "
        "knotmech.diagnose.locate.regions_from_mask; found from T(s) alone.",
        "Centreline DER: the pinched cross-section of a real nip is not modelled (the paper's "
        "FEM resolves it); the nips here come from rod-rod contact with friction on the surface.",
        "Reference: clove-hitch paper, DOI 10.1016/j.eml.2022.101788, sec. 7, eq. 3, Fig. 3b.",
    ]


def _plot_fits(ax, p, R, col, first) -> None:
    """The exponential mu_eff decay through each fitted segment of one profile (dashed)."""
    r, an = p["result"], p["analysis"]
    x = r.s / R
    for j, (a, b) in enumerate(an["segments"]):
        xs = x[a : b + 1]
        ts = r.tension[a : b + 1] / T_HIGH
        xm = 0.5 * (xs[0] + xs[-1])
        tm = float(np.exp(np.interp(xm, xs, np.log(ts))))
        xx = np.linspace(xs[0] - 0.3, xs[-1] + 0.3, 20)
        ax.semilogy(
            (xx - p["x0"]) / (2 * np.pi),
            tm * np.exp(-p["mu_eff"] * (xx - xm)),
            "--",
            color=col,
            lw=1,
            label=r"$e^{-\mu_{eff}s/R}$" if (first and j == 0) else None,
        )


def _shade_nips(ax, p, u) -> None:
    """Shade the located non-exponential (nip) regions of one profile."""
    dx = 0.5 * float(np.median(np.diff(u)))
    for k, (a, b) in enumerate(p["nip_regions_turns"]):
        label = "non-exponential (nip) region, located" if k == 0 else None
        ax.axvspan(a - dx, b + dx, color="C1", alpha=0.2, lw=0, label=label)


def _plot(per_mu, R, out_dir):
    """T(s)/T_high against s/(2 pi R) from the entry, with the fits and the first profile's
    nips shaded; returns the saved figure's path."""
    ax = new_axes(figsize=(7.0, 4.6))
    for i, (m, p) in enumerate(per_mu.items()):
        r = p["result"]
        u = (r.s / R - p["x0"]) / (2 * np.pi)
        col = f"C{i}"
        ax.semilogy(
            u,
            np.maximum(r.tension / T_HIGH, 1e-3),
            "-",
            color=col,
            lw=1.5,
            label=rf"DER, $\mu_{{rc}}$={m:g} ($\mu_{{eff}}$={p['mu_eff']:.3f})",
        )
        _plot_fits(ax, p, R, col, first=i == 0)
        if i == 0:
            _shade_nips(ax, p, u)
    ax.set_xlabel(r"$s/(2\pi R)$ from the knot's entry  ($R=(D+d)/2$)")
    ax.set_ylabel(r"$T(s)/T_\mathrm{high}$")
    ax.set_ylim(1e-3, 1.5)
    ax.set_title(
        "clove hitch, free end: DER tension profile (cf. clove-hitch paper Fig. 3b)", fontsize=9
    )
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="lower left")
    return save_figure(ax.figure, out_dir, f"{NAME}")


def run(
    quick=True,
    out_dir=".",
    progress=False,
    scheduler=None,
    processes=None,
    mu_values=None,
) -> dict:
    """Simulate, analyse, plot and summarise case 2; see the module docstring.

    ``mu_values`` overrides the rod-post friction coefficients (default 0.2, 0.3, 0.4
    in both modes; full mode uses a finer rod, 180 nodes instead of 120). DER runs are
    cached in ``<out_dir>/cache/``.
    """
    mus = tuple(MU_RC if mu_values is None else mu_values)
    R = 0.5 * (POST_DIAMETER + ROD_DIAMETER)
    res = der_runs(
        mus,
        quick=quick,
        progress=progress,
        scheduler=scheduler,
        cache_dir=Path(out_dir) / "cache" / NAME,
        processes=processes,
    )
    per_mu, failed = {}, []
    for m, r in zip(mus, res, strict=True):
        analysed = _analyse_run(m, r, R)
        if analysed is None:
            failed.append(m)
        else:
            per_mu[m] = analysed
    return finish(
        NAME,
        out_dir=out_dir,
        checks=_checks(failed, per_mu),
        numbers=_numbers(mus, quick, failed, per_mu),
        figures=[_plot(per_mu, R, out_dir)],
        notes=_notes(quick),
        quick=quick,
    )


if __name__ == "__main__":
    import sys

    from ._common import main

    sys.exit(main(run))
