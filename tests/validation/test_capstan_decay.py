"""Validation case 1 (capstan decay): numbers of its JSON summary."""

import json
from pathlib import Path

import numpy as np
import pytest

from knotmech.cli.validate import load_case

case = load_case("capstan_decay")


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    return case.run(quick=True, out_dir=tmp_path_factory.mktemp("capstan_decay"))


def test_verdict_and_outputs(result):
    assert result["verdict"] == "pass", result["checks"]
    assert len(result["figures"]) == 2
    for png in result["figures"]:
        with open(png, "rb") as fh:
            assert fh.read(4) == b"\x89PNG"
    on_disk = json.loads((Path(result["figures"][0]).parent / "capstan_decay.json").read_text())
    assert on_disk["numbers"] == result["numbers"]


def test_mu_eff_numbers(result):
    n = result["numbers"]
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


def test_fitted_rates(result):
    n = result["numbers"]
    tol = 1e-9 if n["profile_source"].startswith("closed form") else 0.05
    np.testing.assert_allclose(n["fitted_rate"], n["mu_eff"], rtol=tol)


def test_fit_decay_rate_window_and_noise():
    rng = np.random.default_rng(1)
    s = np.linspace(0, 12, 400)
    t = np.exp(-0.25 * s) * (1 + 0.01 * rng.standard_normal(s.size))
    t[:20] *= 0.7  # a loading-end disturbance left out by the window
    assert case.fit_decay_rate(s, t, s_min=1.0) == pytest.approx(0.25, abs=2e-3)
    assert abs(case.fit_decay_rate(s, t) - 0.25) > 2e-3  # without the window it is biased
