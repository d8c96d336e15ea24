"""Validation case 1 (capstan decay): numbers of its JSON summary.

Closed forms: the clove-hitch paper's eq. 3 evaluated by hand. DER: the pulled
capstan scene must decay at mu_eff(mu, D/d) on the post (rod surface friction),
and at mu when the friction is applied at the centreline (control).
"""

import json
from pathlib import Path

import numpy as np
import pytest

from knotmech.cli.validate import load_case

case = load_case("capstan_decay")


@pytest.fixture(scope="module")
def closed(tmp_path_factory):
    return case.run(quick=True, out_dir=tmp_path_factory.mktemp("cd_closed"), der=False)


@pytest.fixture(scope="module")
def der(tmp_path_factory):
    pytest.importorskip("knotmech.scenes.capstan")
    # in this process: the numba kernels compile once per session, shared with other tests
    return case.run(quick=True, out_dir=tmp_path_factory.mktemp("cd_der"), der=True, processes=1)


def test_closed_form_verdict_and_outputs(closed):
    assert closed["verdict"] == "pass", closed["checks"]
    assert closed["numbers"]["profile_source"].startswith("closed form")
    assert len(closed["figures"]) == 2
    for png in closed["figures"]:
        assert Path(png).read_bytes()[:4] == b"\x89PNG"
    on_disk = json.loads((Path(closed["figures"][0]).parent / "capstan_decay.json").read_text())
    assert on_disk["numbers"] == closed["numbers"]


def test_mu_eff_numbers(closed):
    n = closed["numbers"]
    assert n["D_over_d"] == [1.0, 2.0, 7.5, 30.0]
    # clove-hitch paper eq. 3 evaluated by hand for mu = 0.3, D/d = 7.5 (D, d = 30, 4 mm):
    # (1 + 7.5) = 8.5; sqrt(8.5^2 + 4 * 0.09 * 7.5) = sqrt(74.95) = 8.65736...;
    # (8.65736684 - 8.5) / 0.6 = 0.262278
    assert n["mu_eff"][2] == pytest.approx(0.2622780, abs=2e-7)
    # D/d = 1: sqrt(4 + 0.36) = 2.088061; (2.088061 - 2) / 0.6 = 0.146769
    assert n["mu_eff"][0] == pytest.approx(0.1467688, abs=2e-7)
    # the ideal rope is recovered for a thin rod on a thick post
    assert n["mu_eff_at_D_over_d_1e4"] == pytest.approx(0.3, rel=1e-3)
    # one turn of an ideal rope with mu = 0.3 keeps exp(-0.6 pi) = 0.15184 of the tension
    assert n["T_over_T_high_one_turn_ideal"] == pytest.approx(0.151836, abs=1e-6)
    np.testing.assert_allclose(n["closed_form_fitted_rate"], n["mu_eff"], rtol=1e-9)


def test_fit_decay_rate_window_and_noise():
    rng = np.random.default_rng(1)
    s = np.linspace(0, 12, 400)
    t = np.exp(-0.25 * s) * (1 + 0.01 * rng.standard_normal(s.size))
    t[:20] *= 0.7  # a loading-end disturbance left out by the window
    assert case.fit_decay_rate(s, t, s_min=1.0) == pytest.approx(0.25, abs=2e-3)
    assert abs(case.fit_decay_rate(s, t) - 0.25) > 2e-3  # without the window it is biased


def test_der_profiles_decay_at_mu_eff(der):
    assert der["verdict"] == "pass", der["checks"]
    n = der["numbers"]
    assert n["profile_source"].startswith("DER") and n["der_failed"] == []
    # DER decay rates against eq. 3 (mu_eff = 0.1468, 0.1962, 0.2623, 0.2895): within 5 %
    np.testing.assert_allclose(n["der_fitted_rate"], n["mu_eff"], rtol=0.05)
    # and they separate from the ideal rope: at D/d = 1 the rate is half of mu = 0.3
    assert n["der_fitted_rate"][0] < 0.16
    # holding ratio over a half turn: exp(mu_eff pi) = 1.586 (D/d = 1) ... 2.483 (D/d = 30)
    np.testing.assert_allclose(
        n["der_ratio_T_high_over_T_low"], np.exp(np.array(n["mu_eff"]) * np.pi), rtol=0.05
    )
    # control: friction at the centreline (no couple) gives the ideal-rope rate mu = 0.3
    assert n["der_control_rate"] == pytest.approx(0.3, rel=0.05)
