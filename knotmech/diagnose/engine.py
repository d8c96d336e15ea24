"""The mismatch engine: baseline, locate, forward selection of effects, verdict.

Procedure (one recording):

1. Fit the experiment's baseline by generalised least squares under a noise
   model estimated from the data (white or AR(1), constant or growing with the
   signal; :mod:`knotmech.diagnose.stats`).
2. Locate the structure left in its residuals (:mod:`knotmech.diagnose.locate`).
3. Forward selection: fit every applicable catalogue effect added to the
   current model; its likelihood ratio compares both means under the noise model
   estimated with the effect in the mean (the current model is refitted under it:
   a noise model estimated without the effect absorbs smooth structure into a lag-one
   correlation near 1 and hides the effect); rank the candidates by their own BIC
   (a noise growing with the signal counted as a parameter, :func:`_own_bic`);
   for the best two with a positive BIC change under the common noise compute a
   parametric-bootstrap p-value of that likelihood ratio, simulating recordings
   from the current model under that noise and repeating the whole procedure on
   each (this calibrates boundary amplitudes, onsets and positions that only exist
   under the effect, and correlated noise); accept an effect only if ``p < alpha / m`` (``m``
   the number of effects tested, Bonferroni), the BIC improves and the held-out
   error drops: contiguous blocks are held out in turn, and the RMS of their whitened
   one-step-ahead prediction errors (innovations, both models under the augmented
   model's noise) or their raw RMS must fall (for ``finite_thickness``, which adds no
   free parameter but reconciles mu with the prior ``mu_nominal``: not rise by more
   than 1 %); the report's ``heldout_rms_*`` are the raw held-out RMS. When the
   candidate's remainder has a 1/f-type high-frequency exponent
   (:data:`~knotmech.diagnose.powerlaw.BETA_RANGE`) and a power law fits the whole
   spectrum of its remainder or of the one without it at least as well as an AR(1)
   (:func:`_whole_spectrum_power_law`), its bootstrap is repeated with power-law draws
   and must reject too (:func:`_power_law_candidate`, issue 26).
   Repeat until no candidate passes.
4. Test the final residuals for structure; a located, significant remainder
   gives the verdict ``unexplained``; otherwise the verdict is the accepted
   effect with the largest likelihood gain, or ``none``.

Experiment kinds and effects are objects of the registries
(:mod:`knotmech.diagnose.experiments`, :mod:`knotmech.diagnose.effects`): the engine
turns effect names into objects once (:func:`_resolve_effects`) and loops over them.

Under ``baseline="der"`` (capstan_pull only; :mod:`knotmech.diagnose.der`) step 1
fits the DER capstan with kinetic friction only (``mu``, a signed shift ``delta0_m``,
a displacement scale ``u_scale``; :class:`DERCurves`), and step 3 tests
``static_friction`` only (a re-run with ``mu_s > mu_k``). Its p-value is the
asymptotic one, ``0.5 * P(chi2_1 > LR)`` (``dmu_static = 0`` on the boundary), with
the whitened residuals of the fitted noise model: a parametric bootstrap would need
new simulations for every draw. BIC and the (raw) held-out RMS check apply.
"""

from __future__ import annotations

import functools
import math
from dataclasses import replace
from pathlib import Path

import numpy as np

from knotmech.diagnose.baselines import get_baseline
from knotmech.diagnose.der import select_der
from knotmech.diagnose.effects import CATALOGUE, applicable_effects, get_effect
from knotmech.diagnose.experiments import get_experiment
from knotmech.diagnose.fitting import (
    Data,
    fit_baseline,
    fit_model,
    fit_with_effect,
    heldout_errors,
    heldout_innovation_rms,
    prior_heldout_z,
    thinned_null,
)
from knotmech.diagnose.locate import flexible_mismatch, regions_from_mask, smooth_mismatch
from knotmech.diagnose.noisefloor import (
    NONE_LEVEL_MAX,
    SHORT_ROWS,
    find_outliers,
    hf_sigma,
    noise_floor,
    noise_floor_verdict,
    outlier_threshold,
    outliers_of_remainder,
    short_recording_verdict,
    without_rows,
)
from knotmech.diagnose.powerlaw import (
    BETA_RANGE,
    F_HIGH,
    PowerLawNoise,
    fit_power_law,
    whittle_ar1_minus_power_law,
)
from knotmech.diagnose.recording import Recording, read_recording, recording_from_arrays
from knotmech.diagnose.report import Report, effect_parameters, public_parameters
from knotmech.diagnose.stats import NoiseModel, monte_carlo_pvalue, trial_starts
from knotmech.errors import DiagnoseError, InputError, KnotmechError

__all__ = ["diagnose"]

#: hat functions of the second structure test of an ``undetermined`` recording
#: (:func:`knotmech.diagnose.locate.smooth_mismatch`; 0: not run), and the rows it needs
#: per hat function (below, the noise estimated with the basis in the mean is too
#: biased: 40 rows of AR(1) noise at rho 0.97 give rho 0.35-0.7 under 5 hat functions)
UNDETERMINED_SMOOTH_KNOTS = 5
UNDETERMINED_ROWS_PER_KNOT = 20
_SMOOTH_REASON = (
    "a located smooth mismatch ({}, p = {:.2g}) that correlated noise, estimated with a "
    "smooth basis in the mean, does not explain"
)

#: most additions of one repeatable effect (nips)
_MAX_REPEATS = 6

#: batches an effect's parametric bootstrap draws beyond its 199 while the draws cannot
#: tell its p-value from the per-effect level (:func:`monte_carlo_pvalue`'s ``extend``):
#: up to 999 draws, so that ``alpha_each (B + 1)`` is 2.5-5 for 2-4 effects tested
_EXTEND_DRAWS = (200, 300, 300)

#: the power-law null is tried when the remainder's high-frequency spectral exponent lies in
#: this range (:data:`knotmech.diagnose.powerlaw.BETA_RANGE`); :func:`_power_law_check`
POWER_LAW_BETA_RANGE = BETA_RANGE


def _as_recording(recording, experiment, x, y, metadata, **cols) -> Recording:
    if isinstance(recording, Recording):
        return recording
    if recording is not None:
        if isinstance(recording, (str, Path)):
            return read_recording(recording)
        raise InputError(f"recording must be a Recording or a path, got {type(recording).__name__}")
    if experiment is None or x is None or y is None or metadata is None:
        raise InputError("diagnose needs a recording, or experiment=, x=, y= and metadata=")
    return recording_from_arrays(experiment, x, y, metadata=metadata, **cols)


def _n_new(current, alt, effect) -> int:
    """Degrees of freedom ``effect`` adds: its free parameters plus its ``extra_dof``
    (a searched position, a relaxed inequality)."""
    return max(alt.model.n_free - current.model.n_free + effect.extra_dof, 0)


def _resolve_effects(names) -> list | None:
    """The Effect objects of ``names`` (None: the whole catalogue); the one place the
    engine turns effect names into objects."""
    if names is None:
        return None
    return [get_effect(n) for n in names]


def _numerical_failure_named(func):
    """Last resort: a numerical exception escaping the engine becomes one DiagnoseError.

    The targeted checks (the reader's bounds, ``stats.require_finite`` before every
    factorisation, ``fitting._least_squares``) name the step themselves; anything else
    from numpy/scipy/numba (LinAlgError, ValueError, FloatingPointError, ZeroDivisionError)
    is named by the innermost knotmech function it came from.
    """

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except KnotmechError:
            raise
        except (ArithmeticError, ValueError, np.linalg.LinAlgError) as exc:
            tb, where = exc.__traceback__, func.__name__
            while tb is not None:
                mod = tb.tb_frame.f_globals.get("__name__", "")
                if mod.startswith("knotmech."):
                    where = f"{mod.removeprefix('knotmech.')}.{tb.tb_frame.f_code.co_name}"
                tb = tb.tb_next
            msg = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
            raise DiagnoseError(
                f"the diagnosis failed numerically in {where} ({type(exc).__name__}"
                f"{': ' + msg if msg else ''}); the recording's values are too extreme or "
                "degenerate for it"
            ) from exc

    return wrapper


@_numerical_failure_named
def diagnose(
    recording=None,
    *,
    experiment=None,
    x=None,
    y=None,
    metadata=None,
    sigma=None,
    trial=None,
    speed=None,
    baseline: str = "closed-form",
    seed: int = 0,
    alpha: float = 0.01,
    max_effects: int = 6,
    effects=None,
) -> Report:
    """Diagnose a recording: which catalogue effect the baseline is missing.

    Parameters
    ----------
    recording : Recording or path, optional
        A recording (see :mod:`knotmech.diagnose.recording`); or give the arrays:
    experiment : str, optional
        ``capstan_pull``, ``pinch`` or ``tension_profile`` (with ``x``, ``y``,
        ``metadata`` and optional ``sigma``, ``trial``, ``speed``).
    baseline : {"closed-form", "der"}
        Baseline model family. ``der`` for capstan_pull: the DER capstan with kinetic
        friction only (:class:`knotmech.diagnose.der.DERCurves`); only
        ``static_friction`` is tested against it, by the asymptotic likelihood ratio
        (no parametric bootstrap), BIC and the held-out check. ``der`` for knot_pull:
        the DER overhand knot (:mod:`knotmech.diagnose.der_knot`), whose interpolated
        force law replaces the closed form; the selection, its parametric bootstrap
        included, is the closed-form one on that surrogate.
    seed : int
        Seed of the parametric bootstrap.
    alpha : float
        Family-wise significance level (split over the effects tested).
    max_effects : int
        Most effects added.
    effects : iterable of str, optional
        Restrict the catalogue to these effects.

    Returns
    -------
    Report
    """
    rec = _as_recording(
        recording, experiment, x, y, metadata, sigma=sigma, trial=trial, speed=speed
    )
    family = get_baseline(baseline, rec.experiment)
    family.check(rec)
    rec, validity = family.restrict(rec)
    rec, reduced = get_experiment(rec.experiment).reduce(rec)
    rec_all = rec
    rec, outliers = _drop_outliers(rec)
    only = _resolve_effects(effects)
    if not 0 < alpha < 1:
        raise InputError(f"alpha must lie in (0, 1), got {alpha!r}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise InputError(f"seed must be an integer >= 0, got {seed!r}")
    rng = np.random.default_rng(seed)
    fitted = family.fit(rec, _data(rec), trial_starts(rec.trial), rec.sigma)
    # the DER knot attaches its law to the recording; the closed-form engine follows
    rec, base, der = fitted.rec, fitted.fit, fitted.der
    if family.refits_outliers:
        rec, outliers, base = _refit_without_outliers(rec_all, rec, outliers, base)
    starts, gs, data = trial_starts(rec.trial), rec.sigma, _data(rec)
    base_mis = _mismatch(rec, base, starts, rng, alpha)
    if der is not None:
        sel = select_der(der, base, rec, data, starts, gs, alpha, only)
    else:
        # power-law draws inside the selection: their own stream, so the AR(1) bootstrap's
        # draws (and every recording that never reaches them) stay as they were
        pl_rng = np.random.default_rng([seed, 26])
        sel = _select_closed_form(base, rec, data, starts, gs, rng, alpha, only, max_effects,
                                  pl_rng)  # fmt: skip
    final, accepted = sel[0], sel[1]
    fin_mis = base_mis if final is base else _mismatch(rec, final, starts, rng, alpha)
    verdict, regions = _first_verdict(rec, base, final, accepted, fin_mis, alpha)
    checks = {}
    if verdict != "none" and der is None:
        # structure under the AR(1) null: is it also structure under 1/f-type noise fitted
        # to the same high frequencies? (they cannot be told apart on few rows)
        unexplained = verdict == "unexplained"
        power_law = _power_law_check(rec, base, final, accepted, unexplained, fin_mis, data,
                                     starts, gs, seed, alpha, only)  # fmt: skip
        checks["power_law"] = power_law
        if power_law is not None and power_law["explains"]:
            # nothing accepted: the noise floor (with its power-law rescue) judges it
            verdict = "none" if unexplained and not accepted else "undetermined"
    if verdict == "none":
        # a remainder the power-law null explains is judged by the noise floor too, whose
        # power-law rescue must also hold (level, high frequencies, ripple; else undetermined)
        floor, verdict, reason, regions = _noise_floor_check(rec, final, starts, rng, alpha)
        if checks.get("power_law") and verdict == "unexplained":
            verdict, reason, regions = "undetermined", checks["power_law"]["reason"], []
        checks["noise_floor"] = {**floor.describe(), "reason": reason}
    verdict, checks["short_recording"] = _short_recording_check(rec, verdict)
    if accepted and verdict != "unexplained":
        checks["leftover"] = _leftover_check(rec, final, starts, seed, alpha)
    checks.update(validity=validity, reduced=reduced, outliers=outliers)
    report = _report(rec, base, final, sel, verdict, regions, (base_mis, fin_mis))
    report.details = _details(baseline, rec, base, final, sel, (base_mis, fin_mis), checks)
    report.details.update(alpha=alpha, seed=seed)
    if der is not None:
        report.details["der"] = der[0].settings()
    if getattr(rec, "force_law", None) is not None:
        report.details["der"] = rec.force_law.settings()
    report.summary = _summary(report, rec, fin_mis, base_mis, CATALOGUE.get(verdict))
    # the fits behind the report (not written to JSON; diagnose_many refits them jointly)
    report.fits = {"recording": rec, "baseline": base, "final": final}
    return report


def _data(rec) -> Data:
    """The random part of ``rec``: its values and its ``mu_nominal`` prior."""
    return Data(rec.y, rec.mu_nominal, rec.mu_nominal_sigma)


def _refit_without_outliers(rec_all, rec, outliers, base):
    """The outliers again, on the remainder of the baseline ``base`` (kinks and curvature
    of the signal no longer hide any); the baseline refitted when more are found.

    Returns the recording, its outliers' report and the baseline fit.
    """
    rec2, outliers2 = _outliers_of_remainder(rec_all, rec, outliers, base.mean)
    if rec2 is rec:
        return rec, outliers, base
    base = fit_baseline(rec2, _data(rec2), trial_starts(rec2.trial), given_sigma=rec2.sigma)
    return rec2, outliers2, base


def _mismatch(rec, fit, starts, rng, alpha):
    """The located mismatch of ``fit``'s remainder (:func:`flexible_mismatch`)."""
    return flexible_mismatch(
        rec.x,
        rec.y - fit.mean,
        fit.mean,
        fit.noise,
        starts,
        rec.trial,
        given_sigma=rec.sigma,
        rng=rng,
        decide_at=alpha,
    )


def _first_verdict(rec, base, final, accepted, fin_mis, alpha):
    """The verdict before the noise checks: ``unexplained`` (a remainder located), the
    effect of the largest gain, or ``none``; and its regions."""
    if fin_mis.p_value < alpha and bool(fin_mis.regions):
        return "unexplained", fin_mis.regions
    if not accepted:
        return "none", []
    gains = {}
    for eff, _, g in accepted:
        gains[eff.name] = gains.get(eff.name, 0.0) + g
    verdict = max(gains, key=gains.get)
    return verdict, _effect_regions(rec, base, final, [a[0] for a in accepted])


def _short_recording_check(rec, verdict):
    """``undetermined`` in place of a named verdict on a short unreplicated recording.

    As for a would-be none (noisefloor.short_recording_verdict): so few rows cannot tell
    correlated noise from a mismatch either way (AR(2) nulls of 8-20 rows were called
    unexplained or an effect 5 times in 24). Returns the verdict and the report's note
    (None when unchanged).
    """
    if verdict in ("none", "undetermined") or not _short_unreplicated(rec):
        return verdict, None
    short = {
        "rows": int(rec.n),
        "was": verdict,
        "reason": f"{rec.n} rows without a sigma column: the fit calls it {verdict}, but "
        "so few rows cannot tell correlated noise from a mismatch; record at least "
        f"{SHORT_ROWS} rows or give the sensor's sigma",
    }
    return "undetermined", short


#: the evidence keys of an accepted effect the report carries: the test, and the held-out
#: measures that show the fit improve (raw held-out RMS before/after, the whitened
#: one-step-ahead RMS [before, after], the held-out prior's z [before, after])
_EVIDENCE_KEYS = (
    "delta_bic",
    "p_value",
    "likelihood_ratio",
    "p_value_method",
    "p_value_counted_bound",
    "bootstrap_draws",
    "heldout_rms_before",
    "heldout_rms",
    "heldout_innovation_rms",
    "heldout_prior_z",
)


def _effects_out(accepted, fin_public) -> list:
    """The report's ``effects``: each accepted effect once, its parameters and evidence."""
    out = []
    for eff, ev, _ in accepted:
        if eff.name in [e["name"] for e in out]:
            continue
        out.append(
            {
                "name": eff.name,
                "parameters": effect_parameters(eff, fin_public),
                "evidence": {k: ev[k] for k in _EVIDENCE_KEYS if k in ev},
            }
        )
    return out


def _report(rec, base, final, sel, verdict, regions, mis) -> Report:
    """The report of a diagnosis (``details`` and ``summary`` filled in by the caller)."""
    accepted, held_before, held_cur = sel[1], sel[5], sel[6]
    fin_public = public_parameters(final.params, final.model.effect_objects, rec)
    base_public = public_parameters(base.params, (), rec)
    rms_base = float(np.sqrt(np.mean((rec.y - base.mean) ** 2)))
    rms_final = float(np.sqrt(np.mean((rec.y - final.mean) ** 2)))
    return Report(
        experiment=rec.experiment,
        verdict=verdict,
        effects=_effects_out(accepted, fin_public),
        regions=regions,
        baseline={"parameters": base_public, "rms": float(f"{rms_base:.6g}")},
        final={"parameters": fin_public, "rms": float(f"{rms_final:.6g}")},
        heldout_rms_before=held_before,
        heldout_rms_after=held_cur,
        summary="",
        x=rec.x,
        y=rec.y,
        baseline_mean=base.mean,
        final_mean=final.mean,
        columns=rec.columns,
        row_trial=_line_ids(rec),
    )


def _located(mis) -> dict:
    return {
        "p_value": float(f"{mis.p_value:.3g}"),
        "regions": [{"start": a, "end": b} for a, b in mis.regions],
        "shape": mis.shape,
    }


#: the optional checks of the report's details, in the order they are written
_CHECK_KEYS = (
    "validity",
    "noise_floor",
    "reduced",
    "outliers",
    "leftover",
    "power_law",
    "short_recording",
)


def _details(baseline, rec, base, final, sel, mis, checks) -> dict:
    """The report's ``details``: noise, located mismatches, the selection and the checks
    that ran (``checks``: name -> its note, left out when None or empty)."""
    accepted, tested, steps, skipped = sel[1], sel[2], sel[3], sel[4]
    base_mis, fin_mis = mis
    details = {
        "baseline_model": baseline,
        "noise": {"baseline": base.noise.describe(), "final": final.noise.describe()},
        "located": {"baseline_residuals": _located(base_mis), "final_residuals": _located(fin_mis)},
        "candidates": tested,
        # delta BIC of every applicable effect at each forward step (confusable ones
        # show here next to the accepted one)
        "selection_steps": steps,
        "confusable_with": {a[0].name: list(a[0].confusable_with) for a in accepted},
        "skipped_effects": skipped,
    }
    details.update({k: checks[k] for k in _CHECK_KEYS if checks.get(k)})
    return details


def _line_ids(rec) -> np.ndarray:
    """Per row, one id per (trial, speed) pair: the rows the plot joins into one line."""
    speed = rec.speed if rec.speed is not None else np.zeros(rec.n)
    pairs = np.column_stack([np.asarray(rec.trial, float), np.asarray(speed, float)])
    return np.unique(pairs, axis=0, return_inverse=True)[1].reshape(-1).astype(int)


def _drop_outliers(rec):
    """``rec`` without its isolated outliers, and their report (None when there are none).

    See :func:`knotmech.diagnose.noisefloor.find_outliers`; the rows are those of the
    recording as diagnosed (after any reduction), counted from 0.
    """
    rows, size = find_outliers(rec.y, rec.x, rec.trial)
    return _without_outliers(rec, rows, size)


def _outliers_of_remainder(rec_all, rec, outliers, mean):
    """The outlier search repeated on the baseline's remainder
    (:func:`knotmech.diagnose.noisefloor.outliers_of_remainder`): ``rec`` (a new
    recording when more rows were found) and the report."""
    rows = np.array(outliers["rows"] if outliers else [], int)
    size = np.array(outliers["size_sd"] if outliers else [], float)
    rows2, size2 = outliers_of_remainder(rec_all, rows, size, mean)
    if set(rows2.tolist()) == set(rows.tolist()):
        return rec, outliers
    return _without_outliers(rec_all, rows2, size2)


def _without_outliers(rec, rows, size):
    if rows.size == 0 or rec.n - rows.size < 8:
        return rec, None
    out = {
        "rows": [int(i) for i in rows],
        rec.columns[0]: [float(f"{v:.6g}") for v in rec.x[rows]],
        rec.columns[1]: [float(f"{v:.6g}") for v in rec.y[rows]],
        "size_sd": [float(f"{v:.3g}") for v in size],
        "note": "left out of every fit: farther than "
        f"{outlier_threshold(rec.n):.3g} noise sd from their neighbours (in the readings "
        "or in the remainder of the baseline)",
    }
    return without_rows(rec, rows), out


#: replicate degrees of freedom (rows beyond the distinct control values) that measure
#: the noise of a short recording well enough to judge it without a sigma column
REPLICATE_DOF = 10


def _short_unreplicated(rec) -> bool:
    """Fewer than :data:`~knotmech.diagnose.noisefloor.SHORT_ROWS` rows, no ``sigma``
    column and fewer than :data:`REPLICATE_DOF` replicate rows (repeated control values,
    whose scatter measures the noise: the capstan yarn rig's 22 holds at 7 angles have 15)."""
    if rec.n >= SHORT_ROWS or rec.sigma is not None:
        return False
    return rec.n - np.unique(rec.x).size < REPLICATE_DOF


def _noise_floor_check(rec, final, starts, rng, alpha):
    """A would-be ``none`` judged against the high-frequency noise floor.

    See :mod:`knotmech.diagnose.noisefloor`. Returns the floor, the verdict (``none``,
    ``unexplained`` or ``undetermined``), the reason and the regions (for
    ``unexplained``: located under white noise at the high-frequency level).
    """
    resid = rec.y - final.mean
    # enough white draws to resolve alpha (a counted p is at least 1/(B + 1)); fewer on
    # long recordings, where each draw costs n normal deviates
    draws = int(np.ceil(3.0 / alpha)) + (200 if rec.n <= 20_000 else 0)
    floor = noise_floor(
        resid, rec.x, rec.trial, final.noise, final.mean, starts, rng, draws=max(draws, 199)
    )
    verdict, reason = noise_floor_verdict(floor, alpha)
    if (verdict == "none" and _short_unreplicated(rec)) or (
        rec.sigma is not None and rec.n < SHORT_ROWS
    ):
        # a short recording: its stated sigma decides, or it is undetermined without one
        verdict, reason = short_recording_verdict(resid, rec.sigma, floor, len(final.p), alpha)
    regions = []
    k = UNDETERMINED_SMOOTH_KNOTS
    if verdict == "undetermined" and k and rec.n >= UNDETERMINED_ROWS_PER_KNOT * k:
        # the floor cannot tell a smooth mismatch from correlated noise; a smooth basis
        # fitted together with the noise can, on recordings long enough to estimate both
        # (its p-value counted from up to 3/alpha draws, no fitted tail)
        mis = smooth_mismatch(
            rec.x,
            resid,
            final.mean,
            starts,
            rec.trial,
            given_sigma=rec.sigma,
            n_knots=k,
            rng=rng,
            decide_at=alpha,
            counted=True,
        )
        if mis.p_value < alpha and mis.regions:
            return floor, "unexplained", _SMOOTH_REASON.format(mis.shape, mis.p_value), mis.regions
    if verdict == "unexplained":
        white = NoiseModel(floor.sigma_hf, 0.0, 0.0, 1.0)
        mis = flexible_mismatch(
            rec.x, resid, final.mean, white, starts, rec.trial, rng=rng, decide_at=alpha
        )
        regions = mis.regions or [(float(np.min(rec.x)), float(np.max(rec.x)))]
    return floor, verdict, reason, regions


def _power_law_check(rec, base, final, accepted, unexplained, fin_mis, data, starts, gs, seed,
                     alpha, only):  # fmt: skip
    """Whether 1/f-type noise fitted to the high frequencies explains what the AR(1) null
    calls structure (:mod:`knotmech.diagnose.powerlaw`).

    Tried when the remainder is at most :data:`~knotmech.diagnose.noisefloor.NONE_LEVEL_MAX`
    high-frequency sd (a larger one is a mismatch whatever the noise) and the fitted
    exponent lies in :data:`POWER_LAW_BETA_RANGE` (white-like or AR(1)-like high
    frequencies leave the AR(1) null in charge); for named effects also when a power law
    fits the whole spectrum of the final or the baseline's remainder at least as well as an
    AR(1) (:func:`_whole_spectrum_power_law`). For ``unexplained`` the structure test of the final
    remainder is repeated with power-law draws; for named effects each accepted effect's
    bootstrap is repeated, in the order accepted, with the null's draws power-law noise.
    Returns None when not tried, else a dict for the report (``explains``: the
    power-law null explains it, so the verdict is ``undetermined``; ``reason``).
    """
    resid = rec.y - final.mean
    # the spectrum of the final remainder, standardised by its sd: an accepted effect
    # takes its own broadband power (a step's leaks to every frequency) out of it, and a
    # spurious one, fitted to the wander of 1/f noise, leaves the high frequencies as they were
    # a named effect: its remainder and the baseline's are both asked which noise they are
    gate = _power_law_fit(rec, final, starts, None if unexplained else base)
    if gate is None:
        return None
    fit, level = gate
    rng = np.random.default_rng([seed, 14])
    out = {"beta": round(fit.beta, 3), "c": float(f"{fit.c:.4g}"),
           "band_cycles_per_row": [F_HIGH, 0.5], "ordinates": fit.n_ordinates,
           "level_hf_sd": round(level, 3)}  # fmt: skip
    if unexplained:
        noise = PowerLawNoise.from_noise(final.noise, fit)
        mis = flexible_mismatch(rec.x, resid, final.mean, noise, starts, rec.trial,
                                given_sigma=gs, rng=rng, decide_at=alpha)  # fmt: skip
        out.update(tested="unexplained", p_value=float(f"{mis.p_value:.3g}"))
        out["explains"] = bool(mis.p_value >= alpha)
        what = f"a located mismatch ({fin_mis.shape}, p = {fin_mis.p_value:.2g} under AR(1) noise)"
        p_pl = mis.p_value
    else:
        _, _, alpha_each = _tested_effects(rec, only, alpha)
        cur, p_pl, what = base, 0.0, ""
        out["tested"] = []
        for eff, ev, _ in accepted:
            alt = fit_with_effect(cur, eff, data, starts, given_sigma=gs)
            null_c = _null_under(cur, alt, data, starts, gs)
            lr = 2.0 * (alt.loglik - null_c.loglik)
            pl_null = replace(null_c, noise=PowerLawNoise.from_noise(null_c.noise, fit))
            p, b = _bootstrap_p(pl_null, eff, lr, data, starts, gs, rng, alpha_each)
            out["tested"].append({"effect": eff.name, "p_value": float(f"{p:.3g}"),
                                  "bootstrap_draws": int(b)})  # fmt: skip
            if p >= alpha_each:
                p_pl = p
                what = f"{eff.name} (p = {ev['p_value']:.2g} under AR(1) noise)"
                break
            cur = alt
        out["explains"] = bool(what)
    out["reason"] = (
        f"{what} is within power-law noise of exponent {fit.beta:.2g} fitted to the high "
        f"frequencies (p = {p_pl:.2g}); this recording's {rec.n} rows cannot tell 1/f-type "
        "noise from a smooth mismatch: record replicate trials or more rows"
        if out["explains"]
        else ""
    )
    return out


def _leftover_check(rec, final, starts, seed, alpha):
    """The remainder of an accepted effect judged by the noise floor, as a ``none`` is.

    An accepted effect can leave a large structured remainder (a second, uncatalogued
    mismatch); the structure test of step 4 may miss it when the fitted noise absorbs
    it. Returns the floor's numbers, reason and located regions when the floor calls
    the remainder ``unexplained`` (white high-frequency noise, remainder above it and
    not described by the noise model), else None. Its own random stream (seeded from
    ``seed``), so the verdict's draws do not change.
    """
    rng = np.random.default_rng([int(seed), 14])
    floor, verdict, reason, regions = _noise_floor_check(rec, final, starts, rng, alpha)
    if verdict != "unexplained":
        return None
    return {
        **floor.describe(),
        "verdict": verdict,
        "reason": reason,
        "regions": [{"start": float(a), "end": float(b)} for a, b in regions],
    }


def _tested_effects(rec, only, alpha):
    """The catalogue effects the selection tests on ``rec`` (those applicable, within
    ``only`` when given), the skipped ones with their reasons, and the per-effect level
    ``alpha / (number tested)``."""
    ok, skipped = applicable_effects(rec)
    if only is not None:
        ok = [e for e in ok if e in only]
    return ok, skipped, alpha / max(len(ok), 1)


def _select_closed_form(base, rec, data, starts, gs, rng, alpha, effects, max_effects,
                        pl_rng=None):  # fmt: skip
    """Forward selection over the catalogue with the parametric bootstrap.

    A candidate that passes the AR(1) bootstrap and the held-out check is also judged
    against power-law draws (:func:`_power_law_candidate`, drawn from ``pl_rng``) when its
    remainder's high frequencies are 1/f-like; it is accepted only if both nulls reject.
    """
    n = rec.n
    ok, skipped, alpha_each = _tested_effects(rec, effects, alpha)
    err_cur, block = heldout_errors(base, data, rec.trial)
    held_before = _rms(err_cur)
    held_cur = held_before
    current = base
    accepted = []
    tested = []
    steps = []
    for _ in range(max_effects):
        cands = []
        for eff in ok:
            count = current.model.effects.count(eff.name)
            if count and not eff.repeatable:
                continue
            if count >= _MAX_REPEATS:
                continue
            alt = fit_with_effect(current, eff, data, starts, given_sigma=gs)
            null_c = _null_under(current, alt, data, starts, gs)
            lr = 2.0 * (alt.loglik - null_c.loglik)
            k = _n_new(current, alt, eff)
            # rank by each augmented model's own BIC (its likelihood at its own noise
            # estimate): the common-noise ratios differ in their noise from candidate
            # to candidate and do not compare across candidates
            rank = _own_bic(alt, k, n)
            cands.append((lr - k * np.log(n), eff, alt, lr, null_c, rank))
        cands.sort(key=lambda c: -c[5])
        steps.append({c[1].name: float(f"{c[0]:.4g}") for c in cands})
        step = None
        for dbic, eff, alt, lr, null_c, _ in cands[:2]:
            if dbic <= 0:
                continue
            p, b = _bootstrap_p(null_c, eff, lr, data, starts, gs, rng, alpha_each)
            err_alt, _ = heldout_errors(alt, data, rec.trial)
            held_alt = _rms(err_alt)
            # the held-out criterion on whitened one-step-ahead prediction errors (both
            # models under the augmented model's noise): under correlated noise the raw
            # RMS hardly moves for a sharp mismatch of a few noise sd
            inn_cur = heldout_innovation_rms(err_cur, block, alt.noise, alt.mean, starts)
            inn_alt = heldout_innovation_rms(err_alt, block, alt.noise, alt.mean, starts)
            # an effect with no new free parameter (finite_thickness reinterprets mu to
            # meet the prior) need not improve the curve, only not spoil it (1 %)
            # either held-out measure may show it: a block holding a sharp peak is
            # predicted badly by both models, which can raise the innovations while
            # the raw RMS falls
            tol = 1.01 if _n_new(current, alt, eff) == 0 else 1.0
            held_ok = inn_alt < inn_cur * tol or held_alt < held_cur * tol
            prior_z = _prior_check(current, alt, eff, data, starts, gs)
            if prior_z is not None:
                # such an effect improves the prediction of the held-out prior or is not
                # claimed (the curve alone cannot show it: issue 26)
                held_ok = held_ok and abs(prior_z[1]) < abs(prior_z[0])
            ev = {
                "effect": eff.name,
                "delta_bic": float(f"{dbic:.4g}"),
                "likelihood_ratio": float(f"{lr:.4g}"),
                "p_value": float(f"{p:.3g}"),
                "bootstrap_draws": b,
                **_p_provenance(p, b, lr),
                "heldout_rms_before": float(f"{held_cur:.4g}"),
                "heldout_rms": float(f"{held_alt:.4g}"),
                "heldout_innovation_rms": [float(f"{inn_cur:.4g}"), float(f"{inn_alt:.4g}")],
                **({"heldout_prior_z": [float(f"{z:.4g}") for z in prior_z]} if prior_z else {}),
                "accepted": bool(p < alpha_each and held_ok),
            }
            if ev["accepted"] and pl_rng is not None:
                pl = _power_law_candidate(rec, alt, current, null_c, eff, lr, data, starts, gs,
                                          pl_rng, alpha_each)  # fmt: skip
                if pl is not None:
                    ev["power_law"] = pl
                    ev["accepted"] = bool(pl["p_value"] < alpha_each)
            tested.append(ev)
            if ev["accepted"]:
                step = (eff, alt, ev, held_alt, err_alt)
                break
        if step is None:
            break
        eff, alt, ev, held_alt, err_cur = step
        accepted.append((eff, ev, lr_gain(current, alt)))
        current, held_cur = alt, held_alt
    return current, accepted, tested, steps, skipped, held_before, held_cur


def _own_bic(fit, k, n) -> float:
    """Minus the BIC of a candidate model, up to a constant common to the candidates.

    ``2 loglik - (k + g) log(n)``: ``k`` the effect's new free parameters and ``g`` = 1
    when the fit's noise grows with the signal (``growth > 0``), the noise parameter
    that :func:`~knotmech.diagnose.stats.estimate_noise` charges ``log(n)/2`` of
    log-likelihood for (Schwarz 1978, Ann. Statist. 6, 461-464); the scale and rho are
    fitted in every candidate. Without ``g`` a candidate whose mean makes the growth
    worth fitting gains its likelihood free of charge against one whose fit kept the
    noise constant (held-out 103029: an adhesion of 10 noise sd, AR(1) noise; contact
    flattening fitted with growth 1 ranked 1.8 above adhesion, fitted with growth 0,
    and was accepted first).

    Parameters
    ----------
    fit : Fit
        The candidate (augmented) model's fit.
    k : int
        Its free parameters beyond the current model's.
    n : int
        Rows of the recording.

    Returns
    -------
    float
        ``2 loglik - (k + g) log n`` (dimensionless; larger is better).
    """
    g = 1 if fit.noise.growth > 0 else 0
    return 2.0 * fit.loglik - (k + g) * np.log(n)


def _power_law_fit(rec, model, starts, without=None):
    """The gate of the power-law null on ``model``'s remainder, shared by
    :func:`_power_law_candidate` and :func:`_power_law_check`.

    The remainder ``rec.y - model.mean`` must be at most
    :data:`~knotmech.diagnose.noisefloor.NONE_LEVEL_MAX` high-frequency sd (a larger one
    is a mismatch whatever the noise), and the Whittle exponent of its high frequencies,
    standardised by ``model``'s sd (:func:`~knotmech.diagnose.powerlaw.fit_power_law`),
    must lie in :data:`POWER_LAW_BETA_RANGE`. With ``without`` (the fit without the
    effect judged) a power law must also describe the whole spectrum of one of the two
    standardised remainders, ``model``'s or ``without``'s, at least as well as an AR(1)
    does (:func:`_whole_spectrum_power_law`).

    Returns
    -------
    tuple or None
        ``(fit, level)``: the power-law fit and the remainder's RMS in high-frequency sd
        (dimensionless); None when a gate fails.
    """
    resid = rec.y - model.mean
    sd_hf = hf_sigma(resid, rec.x, rec.trial)
    level = float(np.sqrt(np.mean(resid**2)) / sd_hf) if sd_hf > 0 else math.inf
    if not level <= NONE_LEVEL_MAX:
        return None
    fit = fit_power_law(resid / model.noise.sd(model.mean), starts)
    lo, hi = POWER_LAW_BETA_RANGE
    if fit is None or not lo <= fit.beta <= hi:
        return None
    if without is not None and not _whole_spectrum_power_law(rec, (model, without), starts):
        return None
    return fit, level


def _whole_spectrum_power_law(rec, fits, starts) -> bool:
    """Whether a power law describes the whole spectrum of any of ``fits``' standardised
    remainders at least as well as an AR(1) does
    (:func:`~knotmech.diagnose.powerlaw.whittle_ar1_minus_power_law` >= 0).

    AR(1) noise at rho 0.9 has a high-frequency exponent within
    :data:`POWER_LAW_BETA_RANGE` 8-16 % of the time (section 9 of the issue-26 note); a
    power law fitted there extrapolates far more low-frequency wander than it has, and its
    draws swallow a smooth effect (held-out 103035: a contact flattening of 10 noise sd,
    p 3e-24 under the AR(1) null, 0.006 under the power law; the whole spectrum prefers
    the AR(1) by 1.4 with the effect and 2.6 without it). The remainder without the
    effect is asked too: an effect fitted to the wander of 1/f noise takes the lowest
    frequencies out of its own remainder, which then looks like AR(1) noise, while the
    remainder without it keeps them (tune nulls 8394 and 8400, 1/f noise: the power law
    is preferred by 6.1 and 2.4 without the spurious effect, the AR(1) by 0.2 and 0.6
    with it).

    Parameters
    ----------
    rec : Recording
    fits : sequence of Fit
        The fits whose remainders ``rec.y - fit.mean`` are asked, each standardised by its
        own noise model's sd.
    starts : (n,) bool array
        Trial starts.

    Returns
    -------
    bool
    """
    for f in fits:
        u = (rec.y - f.mean) / f.noise.sd(f.mean)
        if not whittle_ar1_minus_power_law(u, starts) < 0:
            return True
    return False


def _power_law_candidate(rec, alt, current, null_c, eff, lr, data, starts, gs, rng, alpha_each):
    """A candidate effect judged against power-law (1/f-type) noise before it is accepted.

    The spectrum of the candidate's remainder (``rec.y - alt.mean``, standardised by the
    augmented model's sd) is fitted on the high frequencies
    (:func:`~knotmech.diagnose.powerlaw.fit_power_law`; Whittle 1953, Robinson 1995). When
    its exponent lies in :data:`POWER_LAW_BETA_RANGE` and the remainder is at most
    :data:`~knotmech.diagnose.noisefloor.NONE_LEVEL_MAX` high-frequency sd (the gates of
    :func:`_power_law_check`), the candidate's parametric bootstrap is repeated with the
    null's draws power-law noise of that exponent
    (:class:`~knotmech.diagnose.powerlaw.PowerLawNoise`): a wander of 1/f noise that an
    effect fits is then not significant. A real effect takes its own broadband power out
    of the remainder and stays significant under both nulls.

    Returns
    -------
    dict or None
        None when not tried; else ``beta``, ``p_value`` and ``bootstrap_draws`` of the
        power-law bootstrap (the candidate is accepted only if ``p_value < alpha_each``).
    """
    gate = _power_law_fit(rec, alt, starts, current)
    if gate is None:
        return None
    fit = gate[0]
    pl_null = replace(null_c, noise=PowerLawNoise.from_noise(null_c.noise, fit))
    p, b = _bootstrap_p(pl_null, eff, lr, data, starts, gs, rng, alpha_each)
    return {"beta": round(fit.beta, 3), "p_value": float(f"{p:.3g}"), "bootstrap_draws": int(b)}


def _prior_check(current, alt, eff, data, starts, gs):
    """(z before, z after) of the held-out prior (:func:`prior_heldout_z`) for an effect
    that adds no free parameter and so acts through the ``mu_nominal`` prior; None for
    other effects or without a prior."""
    if data.mu_nominal is None or _n_new(current, alt, eff) != 0:
        return None
    z_cur = prior_heldout_z(current, data, starts, given_sigma=gs)
    z_alt = prior_heldout_z(alt, data, starts, given_sigma=gs)
    return z_cur, z_alt


def _prior_text(ev) -> str:
    """The held-out prior check of a candidate, for the summary ('' when not run)."""
    z = ev.get("heldout_prior_z")
    if not z:
        return ""
    return f", mu_nominal predicted from the data at z = {z[0]} -> {z[1]} sd"


def _p_provenance(p, draws, lr) -> dict:
    """Where a bootstrap p-value comes from, and what the draws alone can claim.

    With ``k`` of ``B`` simulated statistics at or above the observed one the counted
    p-value is ``(1 + k)/(B + 1)`` (Davison & Hinkley 1997, eq. 4.11); with none the
    draws only show ``p < 1/(B + 1)`` and a smaller ``p`` is the fitted tail's.
    """
    bound = 1.0 / (draws + 1)
    if p < bound * (1 - 1e-9):
        return {
            "p_value_method": (
                f"scaled chi-square tail fitted to {draws} parametric-bootstrap draws "
                f"(none reached the observed likelihood ratio {lr:.4g})"
            ),
            "p_value_counted_bound": float(f"{bound:.3g}"),
        }
    return {"p_value_method": f"counted: (1 + exceedances) / ({draws} + 1) bootstrap draws"}


def _p_text(ev) -> str:
    """``p = ...`` with its provenance, never claiming more than the draws show."""
    if ev.get("bootstrap_draws", 0) == 0:
        return f"p = {ev['p_value']} (asymptotic LR, no bootstrap)"
    if "p_value_counted_bound" in ev:
        return (
            f"p = {ev['p_value']} (tail fit; by count p < {ev['p_value_counted_bound']} "
            f"from {ev['bootstrap_draws']} draws)"
        )
    return f"p = {ev['p_value']} ({ev['bootstrap_draws']} draws)"


def _rms(err) -> float:
    return float(np.sqrt(np.mean(err**2)))


def lr_gain(current, alt) -> float:
    return 2.0 * (alt.loglik - current.loglik)


def _null_under(null, alt, data, starts, gs):
    """The null model refitted under the augmented model's noise (held fixed).

    The likelihood ratio ``2 (l(alt) - l(null_c))`` compares both means under one noise
    model, the one estimated with the effect in the mean; a noise model estimated under
    the null alone absorbs smooth structure into a larger lag-one correlation (or sd)
    and hides the effect behind it.
    """
    return fit_model(null.model, data, [null.p], alt.noise, starts, given_sigma=gs, rounds=0)


def _bootstrap_p(current, effect, lr, data, starts, gs, rng, decide_at):
    # long recordings: draws of every k-th row (fitting.thinned_null)
    current, data, starts, gs = thinned_null(current, data, starts, gs)
    rec = current.model.rec
    mu0 = current.params["mu"]

    def draw(m):
        out = np.empty(m)
        for i in range(m):
            ystar = current.mean + current.noise.sample(current.mean, starts, rng)
            mu_nom = None
            if data.mu_nominal is not None:
                mu_nom = mu0 + data.mu_sigma * rng.standard_normal()
            d = Data(ystar, mu_nom, data.mu_sigma)
            null = fit_model(current.model, d, [current.p], current.noise, starts, given_sigma=gs)
            alt = fit_with_effect(null, effect, d, starts, given_sigma=gs)
            out[i] = 2.0 * (alt.loglik - _null_under(null, alt, d, starts, gs).loglik)
        return out

    del rec
    return monte_carlo_pvalue(lr, draw, decide_at=decide_at, extend=_EXTEND_DRAWS)


def _effect_regions(rec, base, final, effects):
    lo, hi = float(np.min(rec.x)), float(np.max(rec.x))
    if any(e.acts_everywhere for e in effects):
        return [(lo, hi)]
    diff = final.mean - base.mean
    sd = final.noise.sd(final.mean)
    mask = np.abs(diff) > sd
    if not np.any(mask):
        mask = np.abs(diff) >= 0.5 * np.max(np.abs(diff))
    return regions_from_mask(rec.x, mask)


def _fmt(v, digits=3):
    return f"{v:.{digits}g}"


def _verdict_line(report: Report, rec, fin_mis, effect) -> str:
    v = report.verdict
    held = ""
    if report.heldout_rms_before > 0:
        change = 100.0 * (report.heldout_rms_after / report.heldout_rms_before - 1.0)
        held = f"; held-out RMS {change:+.0f} %"
    p = report.final["parameters"]
    if v == "none":
        return (
            f"none: the {report.details['baseline_model']} baseline explains the data within its "
            f"noise (mu = {_fmt(p['mu'])}, rms = {_fmt(report.final['rms'])})"
        )
    reason = (report.details.get("short_recording", {}).get("reason")
              or report.details.get("noise_floor", {}).get("reason")
              or report.details.get("power_law", {}).get("reason"))  # fmt: skip
    if v in ("unexplained", "undetermined") and reason:
        return f"{v}: {reason}"
    if v == "unexplained":
        where = ", ".join(f"[{_fmt(a)}, {_fmt(b)}]" for a, b in report.regions)
        return (
            f"unexplained: a real mismatch at {rec.columns[0]} in {where} ({fin_mis.shape}, "
            f"p = {_fmt(fin_mis.p_value, 2)}) that no catalogue effect explains"
        )
    return effect.sentence(p, rec) + held


def _summary(report: Report, rec, fin_mis, base_mis, effect) -> str:
    lines = [_verdict_line(report, rec, fin_mis, effect)]
    lines.append(
        f"  baseline: rms {_fmt(report.baseline['rms'])}, residual structure p = "
        f"{_fmt(base_mis.p_value, 2)} ({base_mis.shape}); noise rho = "
        f"{report.details['noise']['baseline']['rho']}"
    )
    for ev in report.details["candidates"]:
        lines.append(
            f"  tested {ev['effect']}: delta BIC {ev['delta_bic']}, {_p_text(ev)}, "
            f"held-out rms {ev['heldout_rms']}{_prior_text(ev)} -> "
            f"{'accepted' if ev['accepted'] else 'rejected'}"
        )
    for name, why in report.details["skipped_effects"].items():
        lines.append(f"  skipped {name}: {why}")
    valid = report.details.get("validity")
    if valid:
        lines.append(
            f"  closed form judged {valid['rows_judged']} of {valid['rows']} rows "
            f"({valid['reason']})"
        )
    reached = report.details.get("der", {}).get("rows_judged")
    if reached:
        lines.append(
            f"  DER baseline judged {reached['rows_used']} of {reached['rows']} rows "
            f"({reached['reason']})"
        )
    out = report.details.get("outliers")
    if out:
        shown = ", ".join(
            f"row {i} ({rec.columns[1]} = {_fmt(v)}, {_fmt(z, 2)} sd)"
            for i, v, z in zip(out["rows"], out[rec.columns[1]], out["size_sd"], strict=True)
        )
        lines.append(f"  outliers left out of the fit: {len(out['rows'])}: {shown}")
    lo = report.details.get("leftover")
    if lo:
        where = ", ".join(f"[{_fmt(r['start'])}, {_fmt(r['end'])}]" for r in lo["regions"])
        lines.append(
            f"  warning: the accepted effects leave an unexplained remainder at "
            f"{rec.columns[0]} in {where}: {lo['reason']}"
        )
    nf = report.details.get("noise_floor")
    if nf:
        lines.append(
            f"  noise floor: rms {_fmt(nf['level'])} x the high-frequency noise "
            f"{_fmt(nf['sigma_hf'])} (p = {_fmt(nf['p_level'], 2)}); innovations' lag-one "
            f"correlation {_fmt(nf['innovation_lag1'], 2)} (p = {_fmt(nf['p_model'], 2)}); "
            f"{_fmt(nf['n_eff'])} independent stretches"
        )
    lines.append(
        f"  final: rms {_fmt(report.final['rms'])}, held-out rms {_fmt(report.heldout_rms_before)}"
        f" -> {_fmt(report.heldout_rms_after)}"
    )
    return "\n".join(lines)
