"""Oracle power of the campaign's planted effects: could any test have found them (issue 26)?

For each catalogue-effect recording of :mod:`validation.diagnose_campaign` (regenerated
with its own generator and seed, :func:`validation.effect_recovery.make_means`) this case
computes the power of the best test that knows everything: the effect's exact shape and
size, the baseline's exact parameters and the noise's exact covariance. Testing the
simple null "mean = mu0" against the simple alternative "mean = mu0 + f" (``f`` the
planted effect, the curve with minus the curve without it) in Gaussian noise of
covariance Sigma, the Neyman-Pearson most powerful test rejects on the GLS statistic
``f' Sigma^-1 (y - mu0) / delta``, which is N(0, 1) under the null and N(delta, 1) under
the alternative, with the noncentrality

    delta^2 = f' Sigma^-1 f,

so its power at level alpha is ``1 - Phi(z_(1 - alpha) - delta)`` (Lehmann & Romano,
*Testing Statistical Hypotheses*, 3rd ed. 2005, section 3.2, Theorem 3.2.1 and the
normal-mean example 3.2.1 after it). Sigma is the generator's own: white noise
``diag(sd^2)``; AR(1) noise ``D R D`` with ``D = diag(sd)`` (the heteroscedastic sd per
row) and ``R`` the stationary AR(1) correlation ``rho^|i - j|`` over the rows of each
trial (trials independent: the generator draws each trial's series anew), whose inverse
is tridiagonal, ``1/(1 - rho^2)`` times ``[1, -rho; -rho, 1 + rho^2, -rho; ...; -rho,
1]`` (Box, Jenkins & Reinsel, *Time Series Analysis*, 4th ed., section 7.1.4), so that

    g' R^-1 g = g_1^2 + sum_(i >= 2) (g_i - rho g_(i-1))^2 / (1 - rho^2),  g = f / sd.

``finite_thickness`` is special: it lowers mu to mu_eff, and a curve with mu_eff is a
curve of the baseline with another mu. Its only evidence is the prior ``mu_nominal``
(drawn N(mu, sigma^2), sigma = (mu - mu_eff)/size): even with the curve pinning mu_eff
exactly the test of the prior pull has ``delta = (mu - mu_eff)/sigma = size`` (the bound
used here; the simple-versus-simple ``f' Sigma^-1 f`` with mu known would be huge and
meaningless).

The level: the engine tests each applicable effect at ``alpha_each = 0.01/m`` (Bonferroni
over the m effects it tests on the recording, ``engine._tested_effects``): 0.0025-0.005
here. The table uses **alpha = 0.005**, the largest alpha_each (m = 2), so the oracle is
given the most lenient level any effect is tested at; the power at each recording's own
alpha_each is kept in the JSON as well. The engine knows neither the shape nor the
baseline's parameters (it refits them) nor the noise's covariance, so the oracle power is
an upper bound on any engine's power for that recording.

    python -m validation.diagnose_oracle_power [--full] [--out DIR]
        [--seed0 97000 ...] [--results DIR ...]

``--results``: folders holding ``diagnose_campaign_cache.jsonl`` of campaign runs on
those sets; each recording's ``found`` is joined by its case (the first folder holding a
case wins), and the found rate is tabulated by oracle-power bin.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np
from scipy.stats import norm

from knotmech.diagnose.effects import applicable_effects
from knotmech.diagnose.experiments import get_experiment
from knotmech.diagnose.stats import wilson_interval
from knotmech.errors import InputError

from . import diagnose_campaign as camp
from . import effect_recovery as gen
from ._common import finish, output_dir, save_figure

NAME = "diagnose_oracle_power"
#: one sentence for the validation page: what this case checks, and against what
SUMMARY = (
    "The power of the best test that knows each planted effect's shape and the noise's "
    "covariance (the noncentrality sqrt(f' Sigma^-1 f), checked against closed forms for "
    "a white step and an AR(1) offset), set against the campaign's found effects."
)

#: the level of the table (the largest per-effect level the engine uses, 0.01/2)
ALPHA = 0.005
#: the engine's family level (its per-effect level is this over the effects tested)
ENGINE_ALPHA = 0.01
#: the six held-out sets judged so far (issue 26, sections 2-11 of the campaign note)
HELDOUT_SETS = (97_000, 98_000, 99_000, 100_000, 101_000, 102_000)
#: power bins of the table: [lo, hi)
BINS = ((0.0, 0.5), (0.5, 0.9), (0.9, 0.99), (0.99, 1.0 + 1e-12))


# --------------------------------------------------------------------------- oracle
def noncentrality(f, sd, trial=None, rho: float = 0.0) -> float:
    """``sqrt(f' Sigma^-1 f)`` for heteroscedastic AR(1) noise over the rows of each trial.

    Parameters
    ----------
    f : array_like, shape (N,)
        The planted effect (mean with minus mean without), same units as ``sd`` [N].
    sd : array_like, shape (N,)
        Marginal noise sd per row [N], > 0.
    trial : array_like of int, shape (N,), optional
        Trial of each row; the noise of different trials is independent. Rows of a trial
        are taken in their order. Default: one trial.
    rho : float
        Lag-one correlation of the stationary AR(1) noise over rows, ``|rho| < 1``
        (0: white noise, ``Sigma = diag(sd^2)``).

    Returns
    -------
    float
        The noncentrality delta (dimensionless).
    """
    f = np.asarray(f, dtype=float)
    sd = np.asarray(sd, dtype=float)
    if f.ndim != 1 or sd.shape != f.shape:
        raise InputError(f"f and sd must be 1-D of one length, got {f.shape} and {sd.shape}")
    if not (np.all(np.isfinite(f)) and np.all(np.isfinite(sd)) and np.all(sd > 0)):
        raise InputError("f must be finite and sd finite and > 0 on every row")
    if not abs(rho) < 1.0:
        raise InputError(f"rho must lie in (-1, 1), got {rho}")
    trial = np.zeros(f.size, int) if trial is None else np.asarray(trial)
    if trial.shape != f.shape:
        raise InputError(f"trial must have one entry per row, got {trial.shape} for {f.shape}")
    return float(np.linalg.norm(_whiten(f, sd, trial, rho)))


def _whiten(a, sd, trial, rho):
    """Columns of ``a`` (N or N x k) mapped by L^-1, Sigma = L L' (AR(1) innovations per
    trial: row 1 as is, then ``(g_i - rho g_(i-1))/sqrt(1 - rho^2)``, g = a/sd)."""
    g = np.asarray(a, dtype=float) / (sd if np.ndim(a) == 1 else sd[:, None])
    out = g.copy()
    for t in np.unique(trial):
        rows = np.flatnonzero(trial == t)
        out[rows[1:]] = (g[rows[1:]] - rho * g[rows[:-1]]) / np.sqrt(1.0 - rho**2)
    return out


def profiled_noncentrality(f, sd, trial, rho: float, jac) -> float:
    """Noncentrality with a linear nuisance part projected out (a cross-check of
    :func:`refitted_noncentrality`, which it equals for a baseline linear in its
    parameters).

    ``sqrt(f' W f - f' W J (J' W J)^-1 J' W f)``, W = Sigma^-1, J the baseline mean's
    Jacobian in its free parameters [N x k]: the part of the effect no (linearised)
    change of the baseline's parameters can mimic.
    """
    u = _whiten(f, sd, trial, rho)
    v = _whiten(jac, sd, trial, rho)
    coef, *_ = np.linalg.lstsq(v, u, rcond=None)
    rest = u - v @ coef
    return float(np.sqrt(rest @ rest))


def _gls_fit(kind: str, rec, y, sd, trial, rho: float, starts):
    """Least squares of the engine's closed-form baseline to ``y`` in the whitened metric
    (``||L^-1 (y - m(p))||``, :func:`_whiten`) within the baseline's own bounds
    (``Experiment.parameters``: e.g. the capstan's slack ``delta0_m >= 0``), from each
    start; the best fit's parameters and its whitened residual norm."""
    from scipy.optimize import least_squares

    exp = get_experiment(kind)
    names, lo, hi = (np.asarray(v) for v in exp.parameters(rec))
    best = None
    for st in starts:
        p0 = np.clip([float(st[k]) for k in names], lo, hi)
        scale = np.maximum(np.abs(p0), 1e-9)

        def resid(q, scale=scale):
            p = dict(zip(names, q * scale, strict=True))
            return _whiten(y - exp.mean(rec, p), sd, trial, rho)

        fit = least_squares(resid, p0 / scale, bounds=(lo / scale, hi / scale), xtol=1e-14,
                            ftol=1e-14, gtol=1e-14)  # fmt: skip
        norm2 = float(fit.fun @ fit.fun)
        if best is None or norm2 < best[1]:
            best = (dict(zip(names, fit.x * scale, strict=True)), norm2)
    return best[0], float(np.sqrt(best[1]))


def refitted_noncentrality(kind: str, rec, mean, mean0, sd, trial, rho: float):
    """Noncentrality with the baseline's parameters refitted: ``min_p ||L^-1 (mean -
    m(p))||``, the distance of the mean with the effect from the baseline family in the
    noise's metric.

    This is the noncentrality of the likelihood-ratio test of "baseline" against
    "baseline + this effect" with the baseline's parameters free and the effect's shape
    known (Seber & Wild, *Nonlinear Regression*, Wiley 1989, section 5.9.1: the LR
    statistic's asymptotic noncentral chi^2 with this noncentrality; exact for a
    baseline linear in its parameters, e.g. pinch's ``2 mu x``). The baseline is the
    engine's closed form (:func:`knotmech.diagnose.experiments.get_experiment`), the
    family the generators plant on; fitted first to ``mean0`` (it must match to
    rounding: the returned misfit, whitened rms over the rows) and from there, and from
    the experiment's own start, to ``mean``.

    Returns
    -------
    delta : float
        The refitted noncentrality (dimensionless).
    misfit : float
        rms of the whitened residual of the baseline fitted to ``mean0`` (0 if the
        generator's baseline lies in the engine's family).
    """
    exp = get_experiment(kind)
    p_true, miss = _gls_fit(kind, rec, mean0, sd, trial, rho, [exp.start(rec, mean0)])
    _, delta = _gls_fit(kind, rec, mean, sd, trial, rho, [p_true, exp.start(rec, mean)])
    return delta, miss / np.sqrt(mean.size)


def oracle_power(delta, alpha: float = ALPHA):
    """Power ``1 - Phi(z_(1 - alpha) - delta)`` of the one-sided test of noncentrality delta."""
    if not 0.0 < alpha < 1.0:
        raise InputError(f"alpha must lie in (0, 1), got {alpha}")
    return norm.sf(norm.isf(alpha) - np.asarray(delta, dtype=float))


def recording_oracle(case) -> dict:
    """Oracle noncentrality and power of one campaign case (a catalogue effect)."""
    g, kind, eff, size, noise, rows, seed = case
    if eff in (None, "out_of_catalogue") or noise not in ("white", "ar1"):
        raise InputError(f"not a catalogue-effect recording of the campaign: {case}")
    meta, x, mean, mean0, trial, speed, truth, sd = gen.make_means(g, kind, eff, size, seed, rows)
    rho = gen.RHO if noise == "ar1" else 0.0
    curve = noncentrality(mean - mean0, sd, trial, rho)
    out = {"case": list(case), "kind": kind, "effect": eff, "size": size, "noise": noise}
    out["seed"], out["rows"], out["delta_curve"] = seed, int(x.size), curve
    if eff == "finite_thickness":  # the evidence is the prior pull (module docstring)
        out["delta"] = float(size)
        out["prior_pull"] = float((meta["mu_nominal"] - truth["mu_eff"]) / meta["mu_nominal_sigma"])
    else:
        out["delta"] = curve
    rec = gen.as_recording(kind, meta, x, mean, trial, speed)
    m = len(applicable_effects(rec)[0])
    out["alpha_engine"] = ENGINE_ALPHA / max(m, 1)
    if eff == "finite_thickness":  # this draw's prior: above the critical value or not
        out["prior_pull_above_critical"] = bool(out["prior_pull"] > norm.isf(out["alpha_engine"]))
    out["power"] = float(oracle_power(out["delta"], ALPHA))
    rec0 = gen.as_recording(kind, meta, x, mean0, trial, speed)
    out["delta_profiled"], out["baseline_misfit"] = refitted_noncentrality(
        kind, rec0, mean, mean0, sd, trial, rho
    )
    if eff == "finite_thickness":  # its curve is a baseline with another mu: prior only
        out["delta_curve_profiled"] = out["delta_profiled"]
        out["delta_profiled"] = float(size)
    out["power_profiled"] = float(oracle_power(out["delta_profiled"], ALPHA))
    out["power_engine_alpha"] = float(oracle_power(out["delta"], out["alpha_engine"]))
    out["power_profiled_engine_alpha"] = float(
        oracle_power(out["delta_profiled"], out["alpha_engine"])
    )
    return out


def effect_cases(seed0s=HELDOUT_SETS) -> list:
    """The campaign's catalogue-effect cases of the held-out generator for each set."""
    return [c for s in seed0s for c in camp.cases(False, ("heldout",), "effects", s)]


# --------------------------------------------------------------------------- checks
def closed_forms() -> dict:
    """The oracle against two closed forms (relative errors).

    White noise, a step of height h on n of N rows: ``delta = h sqrt(n) / sd``. AR(1)
    of lag-one correlation rho, a constant offset c on all N rows: from the tridiagonal
    precision, ``delta^2 = (c/sd)^2 (1 + (N - 1)(1 - rho)^2/(1 - rho^2))
    = (c/sd)^2 (N - (N - 2) rho)/(1 + rho)``.
    """
    h, sd, n_rows, n_step = 0.37, 0.021, 200, 57
    f = np.zeros(n_rows)
    f[-n_step:] = h
    white = noncentrality(f, np.full(n_rows, sd))
    white_exact = h * np.sqrt(n_step) / sd
    c, rho = 0.05, 0.9
    ar1 = noncentrality(np.full(n_rows, c), np.full(n_rows, sd), rho=rho)
    ar1_exact = c / sd * np.sqrt((n_rows - (n_rows - 2) * rho) / (1.0 + rho))
    return {
        "white_step": abs(white / white_exact - 1.0),
        "ar1_offset": abs(ar1 / ar1_exact - 1.0),
    }


def dense_check(row: dict) -> float:
    """Relative difference of :func:`noncentrality` from a dense Cholesky solve of
    ``f' Sigma^-1 f`` on one recording (Sigma built entry by entry)."""
    g, kind, eff, size, noise, rows, seed = row["case"]
    _, x, mean, mean0, trial, _, _, sd = gen.make_means(g, kind, eff, size, seed, rows)
    rho = gen.RHO if noise == "ar1" else 0.0
    idx = np.arange(x.size)
    corr = rho ** np.abs(idx[:, None] - idx[None, :]) * (trial[:, None] == trial[None, :])
    sigma = sd[:, None] * corr * sd[None, :]
    f = mean - mean0
    chol = np.linalg.cholesky(sigma)
    z = np.linalg.solve(chol, f)
    return abs(noncentrality(f, sd, trial, rho) / np.sqrt(z @ z) - 1.0)


# --------------------------------------------------------------------------- results
def load_found(dirs) -> dict:
    """``found`` per case from campaign caches (the first folder holding a case wins)."""
    out = {}
    for d in dirs:
        path = Path(d) / f"{camp.NAME}_cache.jsonl"
        if not path.exists():
            raise InputError(f"no campaign cache {path}")
        for line in path.read_text().splitlines():
            if line.strip():
                r = json.loads(line)
                out.setdefault(tuple(r["case"]), {"found": r["found"], "verdict": r["verdict"]})
    return out


def _rate(k: int, n: int) -> dict:
    lo, hi = wilson_interval(k, n) if n else (0.0, 1.0)
    return {"k": int(k), "n": int(n), "rate": (k / n) if n else None, "wilson95": [lo, hi]}


def _bin_label(lo, hi):
    return f"{lo:g} - {min(hi, 1.0):g}" if hi <= 1.0 else f">= {lo:g}"


def _by_power(joined: list, key: str) -> dict:
    """Found rate per bin of ``key`` (``power`` or ``power_profiled``), and at >= 0.9."""
    by_bin = {}
    for lo, hi in BINS:
        sub = [r for r in joined if lo <= r[key] < hi]
        by_bin[_bin_label(lo, hi)] = _rate(sum(r["found"] for r in sub), len(sub))
    strong = [r for r in joined if r[key] >= 0.9]
    misses = [r for r in joined if not r["found"]]
    return {
        # the sum of the powers: the most recordings any test finds on average (an upper
        # bound on the expected found count at this level)
        "expected_found_bound": float(sum(r[key] for r in joined)),
        "found_by_power": by_bin,
        "found_power_ge_0.9": _rate(sum(r["found"] for r in strong), len(strong)),
        "misses_power_lt_0.5": sum(r[key] < 0.5 for r in misses),
        "misses_power_ge_0.9": sum(r[key] >= 0.9 for r in misses),
    }


def tabulate(rows: list) -> dict:
    """Found rate by oracle-power bin (known baseline; refitted baseline), the misses."""
    joined = [r for r in rows if r.get("found") is not None]
    misses = [r for r in joined if not r["found"]]
    return {
        "found": _rate(sum(r["found"] for r in joined), len(joined)),
        "known_baseline": _by_power(joined, "power"),
        "refitted_baseline": _by_power(joined, "power_profiled"),
        "misses_prior_pull_below_critical": sum(
            r.get("prior_pull_above_critical") is False for r in misses
        ),
        "found_prior_pull_below_critical": sum(
            r.get("prior_pull_above_critical") is False for r in joined if r["found"]
        ),
        "misses": [
            f"{r['seed']} {r['kind']}/{r['effect']} {r['size']:g} sd {r['noise']}: "
            f"{r['verdict']}, delta {r['delta']:.2f} / refitted {r['delta_profiled']:.2f}, "
            f"oracle power {r['power']:.3f} / {r['power_profiled']:.3f}"
            + (f", prior pull {r['prior_pull']:.2f}" if "prior_pull" in r else "")
            for r in misses
        ],
    }


def _pct(v: dict) -> str:
    if not v["n"]:
        return "-"
    lo, hi = v["wilson95"]
    return f"{v['k']}/{v['n']} = {100 * v['rate']:.0f} % ({100 * lo:.0f}-{100 * hi:.0f} %)"


def markdown(table: dict, rows: list) -> str:
    """Recordings, found and missed per oracle-power bin (Wilson 95 %), for the oracle
    that knows the baseline and for the one that refits it."""
    lines = [
        f"| oracle power at alpha = {ALPHA:g} | known baseline: recordings | found (Wilson "
        "95 %) | missed | refitted baseline: recordings | found (Wilson 95 %) | missed |",
        "|---" * 7 + "|",
    ]
    kb, rb = table["known_baseline"], table["refitted_baseline"]

    def cells(v):
        return f" {v['n']} | {_pct(v)} | {v['n'] - v['k']} |"

    for label in kb["found_by_power"]:
        a, b = kb["found_by_power"][label], rb["found_by_power"][label]
        lines.append(f"| {label} |" + cells(a) + cells(b))
    a, b = kb["found_power_ge_0.9"], rb["found_power_ge_0.9"]
    lines.append("| **>= 0.9** |" + cells(a) + cells(b))
    a = table["found"]
    lines.append("| all |" + cells(a) + cells(a))
    e1, e2 = kb["expected_found_bound"], rb["expected_found_bound"]
    p1, p2 = 100 * e1 / a["n"], 100 * e2 / a["n"]
    lines.append(
        f"| sum of oracle powers (most found on average) | {e1:.1f} | {p1:.1f} % | "
        f"| {e2:.1f} | {p2:.1f} % | |"
    )
    return "\n".join(lines) + "\n"


def plot(rows: list):
    """Found (1) or missed (0) against the oracle noncentrality: baseline known (left)
    and refitted (right)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10.0, 3.6))
    joined = [r for r in rows if r.get("found") is not None]
    panels = (
        ("delta", "oracle: shape, baseline, noise known"),
        ("delta_profiled", "oracle: shape, noise known, baseline refitted"),
    )
    for i, (key, title) in enumerate(panels):
        ax = fig.add_subplot(1, 2, i + 1)
        rng = np.random.default_rng(0)
        for noise, mark in (("white", "o"), ("ar1", "s")):
            for size, col in ((3.0, "C3"), (6.0, "C1"), (10.0, "C0")):
                sub = [r for r in joined if r["noise"] == noise and r["size"] == size]
                if not sub:
                    continue
                d = np.array([r[key] for r in sub])
                y = np.array([float(r["found"]) for r in sub]) + rng.uniform(-0.06, 0.06, d.size)
                ax.scatter(d, y, s=12, marker=mark, color=col, alpha=0.6,
                           label=f"{size:g} sd, {noise}")  # fmt: skip
        for p in (0.5, 0.9, 0.99):
            d = norm.isf(ALPHA) - norm.isf(p)
            ax.axvline(d, color="k", ls=":", lw=0.8)
            ax.text(d, 0.5, f" power {p:g}", rotation=90, fontsize=7, va="center")
        ax.set_xscale("log")
        ax.set_yticks([0, 1], ["missed", "found"])
        ax.set_xlabel(f"noncentrality (power at alpha = {ALPHA:g})", fontsize=8)
        ax.set_title(title, fontsize=9)
        if i == 1:
            ax.legend(fontsize=6, ncol=2, loc="center right")
    fig.tight_layout()
    return fig


# --------------------------------------------------------------------------- run
def run(quick=True, out_dir=".", seed0s=None, results=()) -> dict:
    """Oracle powers of the sets' effect recordings; with ``results``, found by power bin.

    Quick: the first set only. Writes ``<out>/diagnose_oracle_power.json`` (rows and
    table), ``.md`` and ``.png``.
    """
    seed0s = tuple(seed0s or (HELDOUT_SETS[:1] if quick else HELDOUT_SETS))
    rows = [recording_oracle(c) for c in effect_cases(seed0s)]
    found = load_found(results) if results else {}
    for r in rows:
        hit = found.get(tuple(json.loads(json.dumps(r["case"]))))
        r.update(hit or {"found": None, "verdict": None})
    table = tabulate(rows)
    out = output_dir(out_dir)
    text = markdown(table, rows) if found else "no campaign results given\n"
    (out / f"{NAME}.md").write_text(text)
    figures = [save_figure(plot(rows), out_dir, NAME)] if found else []
    errors = closed_forms()
    dense = max(dense_check(r) for r in rows[:: max(1, len(rows) // 6)])
    checks = {
        "white step: delta = h sqrt(n)/sd to 1e-12": errors["white_step"] < 1e-12,
        "AR(1) offset: closed form to 1e-12": errors["ar1_offset"] < 1e-12,
        "tridiagonal form = dense Cholesky solve to 1e-9": dense < 1e-9,
        "every delta finite and > 0": all(np.isfinite(r["delta"]) and r["delta"] > 0 for r in rows),
    }
    if found:
        checks["every effect recording has a campaign result"] = all(
            r["found"] is not None for r in rows
        )
    numbers = {
        "sets": list(seed0s),
        "alpha": ALPHA,
        "closed_form_rel_errors": errors,
        "dense_rel_error_max": dense,
        **table,
        "rows": rows,
    }
    notes = [
        "oracle power = upper bound on any test's power (shape, baseline and noise "
        "covariance known); finite_thickness: delta = size (the prior pull)"
    ]
    return finish(NAME, out_dir=out_dir, checks=checks, numbers=numbers, figures=figures,
                  quick=bool(quick), extra={"table_markdown": text}, notes=notes)  # fmt: skip


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--full", action="store_true")
    p.add_argument("--out", default="validation-out")
    p.add_argument("--seed0", type=int, nargs="*", default=None, help="first seeds of the sets")
    p.add_argument("--results", nargs="*", default=(), help="campaign output folders")
    a = p.parse_args(argv)
    try:
        res = run(not a.full, a.out, a.seed0, tuple(a.results))
    except InputError as exc:
        print(f"{NAME}: {exc}")
        return 2
    print(res["table_markdown"])
    print("\n".join(res["numbers"]["misses"]))
    print(json.dumps(res["checks"], indent=1))
    print(f"{NAME}: {res['verdict']}")
    return 0 if res["verdict"] == "pass" else 1


if __name__ == "__main__":
    raise SystemExit(main())
