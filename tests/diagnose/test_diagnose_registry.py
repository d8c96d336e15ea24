"""The registries of experiment kinds and effects, swept (issue 12 part 1).

Every experiment kind has a baseline (parameters with finite-or-infinite bounds that
hold its start, a finite mean), starts and synthetic recordings (null and out of the
catalogue); every effect is fitted, reported and planted for every kind it claims:
planted at 8 noise sd the fit with it beats the baseline by a likelihood ratio far beyond
chance, and its report parameters and verdict sentence exist.
"""

import numpy as np
import pytest

from knotmech.diagnose import make_recording
from knotmech.diagnose.baselines import build_model
from knotmech.diagnose.effects import CATALOGUE, get_effect
from knotmech.diagnose.experiments import EXPERIMENT_KINDS, get_experiment
from knotmech.diagnose.fitting import Data, fit_baseline, fit_with_effect
from knotmech.diagnose.report import effect_parameters, public_parameters
from knotmech.diagnose.stats import trial_starts
from knotmech.errors import InputError

PAIRS = [(kind, name) for name, e in CATALOGUE.items() for kind in e.experiments]


def test_every_effect_claims_registered_kinds_only():
    for e in CATALOGUE.values():
        assert e.experiments and set(e.experiments) <= set(EXPERIMENT_KINDS)
        assert e.report_keys and e.signature and e.reference
        if e.key_parameter is not None:
            assert e.key_parameter[0] in e.report_keys


@pytest.mark.parametrize("kind", list(EXPERIMENT_KINDS))
def test_every_experiment_has_baseline_start_and_synthetic_recordings(kind):
    exp = get_experiment(kind)
    assert exp.name == kind and len(exp.columns) == 2
    for effect in (None, "out_of_catalogue"):
        rec, truth = make_recording(kind, effect, size=8.0, seed=3, n=120)
        assert rec.columns == exp.columns and rec.n >= exp.min_rows
        model = build_model(rec, ())
        assert model.names[0] == "mu" and np.all(model.lower < model.upper)
        start = exp.start(rec, rec.y)
        p0 = np.array([start[n] for n in model.names])
        assert np.all(np.isfinite(model.mean(np.clip(p0, model.lower, model.upper))))
        starts = trial_starts(rec.trial)
        fit = fit_baseline(rec, Data(rec.y, rec.mu_nominal, rec.mu_nominal_sigma), starts)
        resid = (rec.y - fit.mean) / truth["noise_sd"]
        if effect is None:  # the baseline fits its own null to the noise
            assert np.sqrt(np.mean(resid**2)) < 1.5
        else:  # out of the catalogue: 8 sd at its strongest point are left over
            assert np.max(np.abs(rec.y - fit.mean) / truth["noise_sd"]) > 3.0


@pytest.mark.parametrize(("kind", "name"), PAIRS)
def test_every_effect_is_planted_fitted_and_reported_for_its_kinds(kind, name):
    eff = get_effect(name)
    rec, truth = make_recording(kind, name, size=8.0, seed=5, n=160)
    starts = trial_starts(rec.trial)
    data = Data(rec.y, rec.mu_nominal, rec.mu_nominal_sigma)
    base = fit_baseline(rec, data, starts, given_sigma=rec.sigma)
    alt = fit_with_effect(base, eff, data, starts, given_sigma=rec.sigma)
    assert name in alt.model.effects
    # fitted: at least as likely as the baseline it nests (the prior included)
    assert alt.loglik > base.loglik - 1e-6
    public = public_parameters(alt.params, alt.model.effect_objects, rec)
    mine = effect_parameters(eff, public)
    assert mine and set(mine) <= set(eff.report_keys)
    assert not any(k.startswith("nip_") or k == "dmu_static" for k in public)
    text = eff.sentence(public, rec)
    assert isinstance(text, str) and any(ch.isdigit() for ch in text)
    if eff.key_parameter is not None:
        assert eff.key_parameter[1] in truth
    # planted at 8 sd (finite_thickness: 8 prior sd): the likelihood ratio of the fit with
    # the effect over the baseline is far beyond chance (measured 40-163 on these seeds)
    assert 2.0 * (alt.loglik - base.loglik) > 25.0


def test_unknown_names_are_input_errors():
    with pytest.raises(InputError, match="unknown experiment 'capstan_pul'"):
        get_experiment("capstan_pul")
    with pytest.raises(InputError, match="unknown effect 'adhesionn'"):
        get_effect("adhesionn")
    rec, _ = make_recording("pinch", None, seed=1, n=60)
    from knotmech.diagnose import diagnose

    with pytest.raises(InputError, match="unknown effect"):
        diagnose(rec, effects=["adhesionn"])
