"""AR(p) noise for the noise floor (issue 14 part 2): order by BIC under a bound on the
rows, Ljung-Box whiteness, independent stretches from the largest characteristic root.

Reference values: an AR(2) with phi = (1.2, -0.4) has complex roots of modulus
sqrt(0.4) = 0.632 (z^2 - 1.2 z + 0.4 = 0); the Ljung-Box statistic of white noise is
chi-square with h degrees of freedom (Ljung & Box 1978).
"""

from __future__ import annotations

import numpy as np
import pytest

from knotmech.diagnose import diagnose
from knotmech.diagnose.arnoise import fit_ar, max_order
from knotmech.diagnose.noisefloor import NoiseFloor, noise_floor_verdict
from knotmech.diagnose.recording import recording_from_arrays

PINCH_META = {"rod_diameter_m": 0.004, "pinch_diameter_m": 0.008, "youngs_modulus_Pa": 1.26e6}


def _ar(phi, n, rng, burn=300):
    e = rng.standard_normal(n + burn)
    z = np.zeros(n + burn)
    for i in range(len(phi), n + burn):
        z[i] = sum(p * z[i - k - 1] for k, p in enumerate(phi)) + e[i]
    return z[burn:]


def test_max_order_is_twenty_rows_per_coefficient():
    assert [max_order(n) for n in (8, 39, 40, 120, 160, 10_000)] == [1, 1, 2, 6, 8, 8]


def test_ar2_recovered_with_its_roots():
    rng = np.random.default_rng(0)
    n = 4000
    fit = fit_ar(_ar((1.2, -0.4), n, rng), np.zeros(n, int))
    assert fit.order == 2
    assert fit.phi == pytest.approx((1.2, -0.4), abs=0.05)
    assert fit.root_modulus == pytest.approx(np.sqrt(0.4), abs=0.03)
    r = fit.root_modulus
    assert fit.n_eff == pytest.approx(n * (1 - r) / (1 + r))
    assert fit.p_white > 0.001


def test_white_noise_is_order_zero_and_ljung_box_holds_its_size():
    rng = np.random.default_rng(1)
    n = 200
    seg = np.zeros(n, int)
    fits = [fit_ar(rng.standard_normal(n), seg) for _ in range(300)]
    assert np.mean([f.order == 0 for f in fits]) > 0.9
    zero = [f for f in fits if f.order == 0]
    assert all(f.n_eff == n for f in zero)
    rate = float(np.mean([f.p_white < 0.05 for f in zero]))
    # binomial(~290, 0.05): sd 1.3 %; 5 +- 4 %
    assert 0.01 <= rate <= 0.09


def test_segments_restart_the_recursion():
    rng = np.random.default_rng(2)
    # two trials of AR(1) 0.5; a jump between them must not look like correlation
    a, b = _ar((0.5,), 1000, rng), _ar((0.5,), 1000, rng) + 50.0
    u = np.concatenate([a, b - 50.0])
    seg = np.repeat([0, 1], 1000)
    fit = fit_ar(u, seg)
    assert fit.order == 1 and fit.phi[0] == pytest.approx(0.5, abs=0.06)


@pytest.mark.parametrize("seed", range(3))
def test_ar2_null_of_120_rows_is_none(seed):
    """AR(2) (1.2, -0.4) noise, 120 rows, pinch: was `undetermined` (the AR(1) model's
    innovations stay correlated), now `none` with the AR(2) found by the floor."""
    rng = np.random.default_rng(40 + seed)
    n = 120
    z = _ar((1.2, -0.4), n, rng)
    x = np.linspace(0.2, 10.0, n)
    rec = recording_from_arrays("pinch", x, 0.6 * x + 0.01 * z / np.std(z), metadata=PINCH_META)
    rep = diagnose(rec, seed=0)
    assert rep.verdict == "none", rep.summary


def test_ar_path_needs_correlated_high_frequency_noise():
    base = dict(
        sigma_hf=0.01,
        level=6.0,
        p_level=0.002,
        rho_needed=0.9,
        innovation_lag1=0.4,
        p_model=1e-6,
        hf_lag1=-0.1,
        n_eff=20.0,
        n=120,
    )
    from knotmech.diagnose.arnoise import ARFit

    good = ARFit(2, (1.2, -0.4), 1.0, 0.632, 27.0, 5.0, 10, 0.6, 6)
    # correlated high-frequency noise and a whitening AR(2) with 20 stretches: noise
    assert noise_floor_verdict(NoiseFloor(p_hf_white=0.001, ar=good, **base), 0.01)[0] == "none"
    # white high-frequency noise: the excess is structure whatever an AR(p) says
    assert noise_floor_verdict(NoiseFloor(p_hf_white=0.5, ar=good, **base), 0.01)[0] == (
        "unexplained"
    )
    # too few stretches (the engine's AR(1) count is the smaller): too short to tell
    short = {**base, "n_eff": 3.0}
    v, why = noise_floor_verdict(NoiseFloor(p_hf_white=0.001, ar=good, **short), 0.01)
    assert v == "undetermined"
    assert "best AR(p) noise model (p = 2 by BIC, at most 6 for 120 rows)" in why
    assert "too short for its noise" in why
    # the AR(1) consistency check no longer vetoes the AR(p) rescue (issue 26's AR(2)
    # nulls: the AR(1) draws were the wrong model for them) ...
    v, _ = noise_floor_verdict(
        NoiseFloor(p_hf_white=0.001, ar=good, p_consistent=0.004, **base), 0.01
    )
    assert v == "none"
    # ... the AR(p) model's own draws do: the reason names that check, not the stretches
    v, why = noise_floor_verdict(
        NoiseFloor(p_hf_white=0.001, ar=good, p_consistent=0.004, p_consistent_ar=0.004, **base),
        0.01,
    )
    assert v == "undetermined"
    assert "do not give the level with these high frequencies (p = 0.004)" in why
    assert "too short for its noise" not in why
    bad = ARFit(2, (1.2, -0.4), 1.0, 0.632, 27.0, 40.0, 10, 1e-5, 6)
    v, why = noise_floor_verdict(NoiseFloor(p_hf_white=0.001, ar=bad, **base), 0.01)
    assert v == "undetermined" and "Ljung-Box p = 1e-05" in why


def test_ar2_null_with_the_heldout_phi_is_none():
    """AR(2) noise of phi (0.7, 0.15) (issue 26's held-out generator), 200 rows, pinch,
    unit marginal sd x 0.01: the consistency check drew AR(1) noise and vetoed the AR(2)
    rescue (p_consistent 0.004 < 0.01: ``undetermined``); the AR(2) model's own draws
    agree with the level and the high frequencies (p_consistent_ar 0.61): ``none``."""
    from scipy.signal import lfilter

    n = 200
    rng = np.random.default_rng([0, 26])
    z = lfilter([1.0], [1.0, -0.7, -0.15], rng.standard_normal(n + 300))[300:]
    x = np.linspace(0.2, 10.0, n)
    rec = recording_from_arrays("pinch", x, 0.6 * x + 0.01 * z / np.std(z), metadata=PINCH_META)
    rep = diagnose(rec, seed=0)
    assert rep.verdict == "none", rep.summary
    nf = rep.details["noise_floor"]
    assert nf["p_consistent"] < 0.01 and nf["p_consistent_ar"] == pytest.approx(0.607, abs=0.01)
    assert nf["ar"]["order"] == 2 and nf["ar"]["p_white"] >= 0.01


@pytest.mark.parametrize(("noise", "size", "kind", "seed", "verdict"), [
    ("ar1", 10.0, "pinch", 0, "undetermined"),
    ("ar1", 10.0, "tension_profile", 1, "unexplained"),
    ("ar2", 30.0, "pinch", 0, "unexplained"),
    ("pink", 30.0, "pinch", 0, "unexplained"),
])  # fmt: skip
def test_narrow_bumps_on_coloured_noise_stay_flagged(noise, size, kind, seed, verdict):
    """``noise_robustness`` Gaussian bumps (sd 4 % of the range) on AR(1) 0.8, AR(2) and
    1/f noise, 120 rows: the AR(p) rescue judged by its own draws and the power-law
    rescue leave them as they were (36 such bumps, 10 and 30 sd: 35 unchanged, one 10-sd
    bump on 1/f noise now ``none``, issue26-campaign.md section 5)."""
    from validation.noise_robustness import make

    rec, _ = make(kind, "bump", size, noise, seed, 120)
    assert diagnose(rec, seed=seed).verdict == verdict
