"""The held-out prior check of an effect that acts through ``mu_nominal`` (issue 26).

``finite_thickness`` adds no free parameter: with mu free the baseline fits the smaller
mu_eff and the curve's held-out error cannot move (measured: 0.04401 -> 0.04396 on
seed 19). The check that can show it predicts the independently measured mu from the
data alone: :func:`knotmech.diagnose.fitting.prior_heldout_z`.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from knotmech.analytic.capstan import mu_eff
from knotmech.diagnose import diagnose
from knotmech.diagnose.effects import get_effect
from knotmech.diagnose.experiments import get_experiment
from knotmech.diagnose.fitting import Data, fit_baseline, fit_with_effect, prior_heldout_z
from knotmech.diagnose.stats import trial_starts
from knotmech.diagnose.synth import make_recording


def _fits(rec):
    data = Data(rec.y, rec.mu_nominal, rec.mu_nominal_sigma)
    starts = trial_starts(rec.trial)
    base = fit_baseline(rec, data, starts)
    alt = fit_with_effect(base, get_effect("finite_thickness"), data, starts)
    return data, starts, base, alt


def _null_like(rec, truth, seed):
    """The same rig and prior, the tension made with mu = mu_nominal (no thickness)."""
    exp = get_experiment("tension_profile")
    mean = exp.mean(rec, {"mu": truth["mu"]}, ())
    rng = np.random.default_rng(seed)
    md = dict(rec.metadata, mu_nominal=truth["mu"])
    return replace(rec, y=mean + truth["noise_sd"] * rng.standard_normal(rec.n), metadata=md)


def test_the_prior_is_predicted_within_its_sd_with_finite_thickness():
    """Planted at 8 prior sd: the baseline's data-only mu (= mu_eff) misses mu_nominal by
    about 8 sd, the effect's material mu by less than 1 sd."""
    rec, truth = make_recording("tension_profile", "finite_thickness", size=8.0, seed=19, n=200)
    data, starts, base, alt = _fits(rec)
    z_base = prior_heldout_z(base, data, starts)
    z_alt = prior_heldout_z(alt, data, starts)
    d_over_d = rec.meta("post_diameter_m") / rec.meta("rod_diameter_m")
    shift = (truth["mu"] - float(mu_eff(truth["mu"], d_over_d))) / rec.mu_nominal_sigma
    assert shift == pytest.approx(8.0, rel=1e-6)
    assert z_base == pytest.approx(-8.0, abs=1.0)
    assert abs(z_alt) < 1.0


def test_finite_thickness_is_claimed_with_the_improvement_in_its_evidence():
    rec, _ = make_recording("tension_profile", "finite_thickness", size=8.0, seed=19, n=200)
    rep = diagnose(rec, seed=19)
    assert rep.verdict == "finite_thickness"
    ev = next(c for c in rep.details["candidates"] if c["effect"] == "finite_thickness")
    z0, z1 = ev["heldout_prior_z"]
    assert ev["accepted"] and abs(z1) < 1.0 < 6.0 < abs(z0)
    assert "mu_nominal predicted from the data" in rep.summary
    # the claim carries its held-out proof in the report's own evidence
    assert rep.effects[0]["evidence"]["heldout_prior_z"] == [z0, z1]


def test_a_null_with_a_true_prior_is_not_claimed():
    """The same rig with no thickness effect (the tension made at mu_nominal): the
    effect's data-only material mu overshoots the prior, the check fails and nothing is
    named."""
    rec, truth = make_recording("tension_profile", "finite_thickness", size=8.0, seed=19, n=200)
    null = _null_like(rec, truth, seed=5)
    data, starts, base, alt = _fits(null)
    z_base = prior_heldout_z(base, data, starts)
    z_alt = prior_heldout_z(alt, data, starts)
    assert abs(z_base) < 2.0 and abs(z_alt) > abs(z_base) + 5.0
    rep = diagnose(null, seed=5)
    assert rep.verdict == "none"
    for c in rep.details["candidates"]:
        assert not (c["effect"] == "finite_thickness" and c["accepted"])


def test_no_prior_no_check():
    rec, _ = make_recording("tension_profile", None, seed=7, n=60)
    data = Data(rec.y, None, None)
    starts = trial_starts(rec.trial)
    assert prior_heldout_z(fit_baseline(rec, data, starts), data, starts) is None
