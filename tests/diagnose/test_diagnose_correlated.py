"""Statistics of the engine under correlated (AR(1)) noise: issue 5's concealed-effect targets.

Non-centralities quoted below are those of the likelihood ratio when the true noise
(rho = 0.9) is known: contact flattening at 10 noise sd has 23-61 on the synthetic
recordings, static friction at 6 sd 50-68, against a 1 % critical value near 12.
"""

import numpy as np
import pytest
from scipy.stats import chi2

from knotmech.diagnose import diagnose, make_recording
from knotmech.diagnose.fitting import heldout_innovation_rms
from knotmech.diagnose.stats import (
    NoiseModel,
    _tail_p,
    monte_carlo_pvalue,
    trial_starts,
    wilson_interval,
)


@pytest.mark.parametrize(
    ("experiment", "effect", "size", "seed"),
    [
        # both were `none` when the likelihood ratio used the null's own noise estimate
        # (rho 0.975-0.985: the bend was absorbed into the correlation)
        ("pinch", "contact_flattening", 10.0, 5000),
        ("pinch", "contact_flattening", 10.0, 5003),
        ("capstan_pull", "rate_dependent_friction", 10.0, 7000),
    ],
)
def test_effect_under_ar1_noise_is_found(experiment, effect, size, seed):
    rec, _ = make_recording(experiment, effect, size=size, noise="ar1", seed=seed, n=240)
    rep = diagnose(rec, seed=seed)
    assert rep.verdict == effect
    ev = rep.effects[0]["evidence"]
    assert ev["p_value"] < 0.005 and ev["delta_bic"] > 0


@pytest.mark.parametrize(("experiment", "seed"), [("capstan_pull", 7026), ("pinch", 7001)])
def test_ar1_null_stays_none(experiment, seed):
    # capstan 7026: its baseline noise estimate (rho 0.955) came from a poor first fit;
    # without the moderate-correlation second pass a displacement offset was "found"
    rec, _ = make_recording(experiment, None, noise="ar1", seed=seed, n=240)
    assert diagnose(rec, seed=seed).verdict == "none"


def test_heldout_innovations_weigh_a_sharp_mismatch_more_than_the_raw_rms():
    rng = np.random.default_rng(3)
    n = 2000
    starts = trial_starts(np.zeros(n, int))
    nm = NoiseModel(1.0, 0.0, 0.9, 1.0)
    mean = np.zeros(n)
    block = np.arange(n) // 40
    noise = nm.sample(mean, starts, rng)
    # pure AR(1) errors whitened with the true rho: unit innovation RMS
    assert heldout_innovation_rms(noise, block, nm, mean, starts) == pytest.approx(1.0, abs=0.04)
    # every 200 rows a 3 sd jump relaxing over 2 rows (a static-friction-like peak):
    # raw RMS +5.6 %, innovation RMS +11.8 % on this draw
    k = np.arange(n) % 200
    bump = np.where(k >= 100, 3.0 * np.exp(-(k - 100) / 2.0), 0.0)
    raw0, raw1 = np.sqrt(np.mean(noise**2)), np.sqrt(np.mean((noise + bump) ** 2))
    inn0 = heldout_innovation_rms(noise, block, nm, mean, starts)
    inn1 = heldout_innovation_rms(noise + bump, block, nm, mean, starts)
    assert inn1 / inn0 - 1 == pytest.approx(0.118, abs=0.01)
    assert raw1 / raw0 - 1 == pytest.approx(0.056, abs=0.01)


def test_tail_fit_of_boundary_draws_is_not_overconfident():
    # nested test on the boundary: most draws 0, a few small positive ones
    sims = np.array([0.0, 0.4, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1e-9])
    p = _tail_p(12.0, sims)
    # mixture: (1 + 1)/(9 + 1) * P(chi2_2 > 12) = 0.2 * exp(-6); a normal tail of these
    # draws would give ~1e-170
    assert p == pytest.approx(0.2 * np.exp(-6.0), rel=1e-9)
    # non-nested statistic (mostly negative draws): normal tail of the draws
    neg = np.array([-3.0, -2.0, -1.0, -2.5, 0.5, -1.5, -2.2, -0.8, -1.1])
    z = (1.0 - neg.mean()) / neg.std()
    from scipy.stats import norm

    assert _tail_p(1.0, neg) == pytest.approx(norm.sf(z))


def test_first_small_batch_does_not_decide_a_borderline_case():
    # the 9 draws that once gave p = 2.3e-6 for LR = 12.15 on an AR(1) null (the tail
    # fitted to them); the first batch now decides only below decide_at / 1e6
    first = np.array([0.0, 0.4, 0.07, 0.11, 0.26, 2.08, 1.95, 0.0, 0.26])
    calls = []

    def draw(m):
        calls.append(m)
        if len(calls) == 1:
            return first
        return np.random.default_rng(len(calls)).chisquare(3.0, m)

    p, b = monte_carlo_pvalue(12.15, draw, decide_at=0.005)
    assert calls[0] == 9 and b == 199
    assert p >= 0.005  # not significant at 0.005; chi2_3 draws: P(chi2_3 > 12.15) = 0.0069


def _scripted_draws(exceed_at, observed, total=999):
    """A draw function handing out ``total`` chi2_3 draws below ``observed`` in order,
    except at the rows ``exceed_at`` (above it), and the batch sizes it was asked for."""
    sims = np.minimum(np.random.default_rng(3).chisquare(3.0, total), observed - 1.0)
    sims[list(exceed_at)] = observed + 1.0
    calls = []

    def draw(m):
        a = sum(calls)
        calls.append(m)
        return sims[a : a + m]

    return draw, calls


def test_undecided_bootstrap_draws_on_until_the_level_is_outside_its_interval():
    # one exceedance in the first 199 draws: p = 2/200 = 0.01 cannot go below 0.005;
    # 800 more draws without one give p = 2/1000 (99 % Wilson interval of 1/699
    # reaches 0.0121, of 1/999 0.0085: still undecided, so every batch is drawn)
    draw, calls = _scripted_draws([50], 15.0)
    p, b = monte_carlo_pvalue(15.0, draw, decide_at=0.005)
    assert (p, b, calls) == (0.01, 199, [9, 30, 60, 100])
    draw, calls = _scripted_draws([50], 15.0)
    p, b = monte_carlo_pvalue(15.0, draw, decide_at=0.005, extend=(200, 300, 300))
    assert (p, b, calls) == (pytest.approx(0.002), 999, [9, 30, 60, 100, 200, 300, 300])


def test_decided_bootstrap_draws_no_more():
    # four exceedances in 199 draws: the 99 % Wilson interval of 4/199 is 0.0060-0.065,
    # above 0.005, so the extension is not drawn and p = 5/200
    draw, calls = _scripted_draws([10, 60, 100, 150], 15.0)
    p, b = monte_carlo_pvalue(15.0, draw, decide_at=0.005, extend=(200, 300, 300))
    assert (p, b, calls) == (0.025, 199, [9, 30, 60, 100])


def _rejections(rates, decide_at, seed):
    """Runs of the extended test on chi2_3 draws, one per true p in ``rates`` (the
    observed statistic's exceedance probability): how many reject at ``decide_at``, and
    how many of those stopped the extension early (between 199 and 999 draws)."""
    rng = np.random.default_rng(seed)
    rejected = early = 0
    for rate in rates:
        p, b = monte_carlo_pvalue(
            float(chi2.isf(rate, 3.0)),
            lambda m: rng.chisquare(3.0, m),
            decide_at=decide_at,
            extend=(200, 300, 300),
        )
        rejected += p < decide_at
        early += p < decide_at and 199 < b < 999
    return rejected, early


@pytest.mark.parametrize(("decide_at", "fixed_size"), [(0.005, 0.004), (0.0025, 0.002)])
def test_undecided_bootstrap_keeps_its_level(decide_at, fixed_size):
    # the extension rejects only at 999 draws (the 99 % Wilson upper bound of 0/B,
    # z^2/(B + z^2), is 0.0094 at B = 699, above the level), so its level is that of
    # the fixed 999-draw test, (1 + k)/1000 < decide_at: k <= 3 (0.004) at 0.005, k <= 1
    # (0.002) at 0.0025, plus the tail-fit decisions of the first 199 draws. Under the
    # null the true p is uniform; above 0.02 no run rejects (P(Bin(999, 0.02) <= 3) ~ 1e-5)
    u = np.random.default_rng(31).uniform(0.0, 0.02, 2000)
    rej, early = _rejections(u, decide_at, 32)
    assert early == 0
    lo, hi = wilson_interval(rej, 2000, 3.29)
    assert 0.02 * lo <= decide_at and 0.02 * hi >= fixed_size


def test_undecided_bootstrap_gains_power_at_half_the_level():
    # a true p of 0.0025 at the level 0.005: 199 draws reject only with no exceedance,
    # (1 - 0.0025)^199 = 0.608 of the time; drawn on to 999, P(Bin(999, 0.0025) <= 3) =
    # 0.758
    rej, _ = _rejections(np.full(400, 0.0025), 0.005, 23)
    lo, _ = wilson_interval(rej, 400, 3.29)
    assert lo > (1 - 0.0025) ** 199
