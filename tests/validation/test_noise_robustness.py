"""Issue 14's validation in quick mode: pinch, two out-of-catalogue shapes at 1-100 sd,
nulls of seven noise kinds, from a generator independent of ``diagnose.synth``."""

import numpy as np
import pytest

from knotmech.cli.validate import load_case

case = load_case("noise_robustness")


def test_generator_noises_have_their_stated_properties():
    rng_n, sd = 4000, 0.5
    sig = np.linspace(1.0, 2.0, rng_n)
    for kind, lag1 in (("white", 0.0), ("ar1", 0.8), ("ar2", 1.2 / 1.4), ("pink", None)):
        z = case._noise(kind, rng_n, sd, sig, np.random.default_rng(3))
        assert np.std(z) == pytest.approx(sd, rel=0.08 if kind != "pink" else 1e-9)
        r1 = float(np.corrcoef(z[1:], z[:-1])[0, 1])
        if lag1 is not None:
            # AR(2) phi = (1.2, -0.4): rho_1 = phi1 / (1 - phi2) = 0.857
            assert r1 == pytest.approx(lag1, abs=0.05)
        else:
            assert r1 > 0.5  # 1/f: most power at the lowest frequencies
    q = case._noise("quantised", rng_n, sd, sig, np.random.default_rng(3))
    assert np.allclose(np.round((sig + q) / (1.5 * sd)) * 1.5 * sd, sig + q)
    o = case._noise("outliers", rng_n, sd, sig, np.random.default_rng(3))
    assert int(np.sum(np.abs(o) > 8 * sd)) == pytest.approx(0.02 * rng_n, abs=3)


def test_quick_power_curve_and_nulls(tmp_path):
    # 17 recordings, 16 s on the loaded development machine
    res = case.run(quick=True, out_dir=tmp_path)
    assert res["verdict"] == "pass", res["checks"]
    power = res["numbers"]["power"]
    for shape in ("pinch/ripple", "pinch/tanh_step"):
        assert power[shape]["1.0"] == 0.0
        assert power[shape]["30.0"] == power[shape]["100.0"] == 1.0
    assert all(v == 0.0 for v in res["numbers"]["null_false_positive_rate"].values())
    assert (tmp_path / "noise_robustness_power.png").stat().st_size > 10_000
