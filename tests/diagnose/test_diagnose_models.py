"""Baselines reproduce the spec's closed forms; effects at their no-effect values vanish."""

import numpy as np
import pytest

from knotmech.analytic.capstan import mu_eff
from knotmech.diagnose.baselines import MEANS, pinch_load_parameter
from knotmech.diagnose.recording import Recording
from knotmech.diagnose.stats import NoiseModel, estimate_noise, trial_starts, wilson_interval


def _rec(exp, x, meta, speed=None):
    return Recording(exp, x, np.zeros_like(x), meta, None, np.zeros(x.size, int), speed)


CAP = {
    "wrap_angle_rad": 4 * np.pi,
    "T_low_N": 1.0,
    "rod_diameter_m": 0.004,
    "post_diameter_m": 0.02,
    "youngs_modulus_Pa": 1.26e6,
}
PIN = {"rod_diameter_m": 0.004, "pinch_diameter_m": 0.008, "youngs_modulus_Pa": 1.26e6}
TEN = {"T_high_N": 10.0, "rod_diameter_m": 0.004, "post_diameter_m": 0.02}


def test_capstan_baseline_is_the_spec_formula():
    u = np.linspace(0, 0.05, 101)
    rec = _rec("capstan_pull", u, CAP)
    p = {"mu": 0.3, "k_N_per_m": 500.0, "delta0_m": 0.002}
    expect = np.minimum(1.0 + 500.0 * np.maximum(u - 0.002, 0), np.exp(0.3 * 4 * np.pi))
    assert np.allclose(MEANS["capstan_pull"](rec, p, ()), expect, rtol=1e-14)
    # finite thickness: the plateau is the capstan ratio at mu_eff(mu, D/d = 5)
    ft = MEANS["capstan_pull"](rec, p, ("finite_thickness",))
    assert ft[-1] == pytest.approx(np.exp(float(mu_eff(0.3, 5.0)) * 4 * np.pi), rel=1e-12)


def test_capstan_no_effect_values_give_the_baseline():
    u = np.linspace(0, 0.05, 101)
    rec = _rec("capstan_pull", u, CAP, speed=np.repeat([1e-3, 1e-2], [50, 51]))
    p = {"mu": 0.3, "k_N_per_m": 500.0, "delta0_m": 0.0}
    base = MEANS["capstan_pull"](rec, p, ())
    q = dict(p, dmu_static=0.0, decay_length_m=0.003, dmu_dlnv=0.0, offset_m=0.0)
    for eff in ("static_friction", "rate_dependent_friction", "displacement_offset"):
        assert np.allclose(MEANS["capstan_pull"](rec, q, (eff,)), base, rtol=1e-13)


def test_static_friction_peak_reaches_mu_static():
    u = np.linspace(0, 0.05, 2001)
    rec = _rec("capstan_pull", u, CAP)
    p = {
        "mu": 0.3,
        "k_N_per_m": 3000.0,
        "delta0_m": 0.0,
        "dmu_static": 0.02,
        "decay_length_m": 0.002,
    }
    t = MEANS["capstan_pull"](rec, p, ("static_friction",))
    assert t.max() == pytest.approx(np.exp(0.32 * 4 * np.pi), rel=2e-3)
    assert t[-1] == pytest.approx(np.exp(0.30 * 4 * np.pi), rel=1e-6)


def test_pinch_and_tension_baselines_and_effects():
    fn = np.linspace(0.1, 10, 50)
    rec = _rec("pinch", fn, PIN)
    assert np.allclose(MEANS["pinch"](rec, {"mu": 0.3}, ()), 0.6 * fn)
    x = pinch_load_parameter(fn, youngs_modulus=1.26e6, rod_diameter=0.004, pinch_diameter=0.008)
    assert x[-1] == pytest.approx(4 * 10 / (np.pi * 1.26e6 * 0.004 * 0.008))
    p = {"mu": 0.3, "adhesion_force_N": 0.0, "onset_load_parameter": 0.1, "slope_ratio": 1.0}
    assert np.allclose(MEANS["pinch"](rec, p, ("adhesion", "contact_flattening")), 0.6 * fn)
    s = np.linspace(0, 0.1, 60)
    rec = _rec("tension_profile", s, TEN)
    base = MEANS["tension_profile"](rec, {"mu": 0.3}, ())
    assert np.allclose(base, 10 * np.exp(-0.3 * s / 0.012))
    nip = MEANS["tension_profile"](
        rec, {"mu": 0.3, "nip_position_0": 0.05, "nip_drop_0": 0.25}, ("self_contact_nip",)
    )
    assert np.allclose(nip, np.where(s > 0.05, 0.75, 1.0) * base)


def test_noise_estimate_recovers_ar1_and_growth():
    rng = np.random.default_rng(1)
    mean = np.linspace(1.0, 10.0, 6000)
    starts = trial_starts(np.zeros(mean.size, int))
    true = NoiseModel(0.05, 0.0, 0.9, 10.0)
    est = estimate_noise(true.sample(mean, starts, rng), mean, starts)
    assert est.rho == pytest.approx(0.9, abs=0.02)
    assert est.growth == 0.0
    assert est.scale == pytest.approx(0.05, rel=0.1)
    grow = NoiseModel(0.01, 3.0, 0.0, 10.0)
    est = estimate_noise(grow.sample(mean, starts, rng), mean, starts)
    assert est.growth == pytest.approx(3.0, rel=0.7)
    assert abs(est.rho) < 0.05
    # whitening under the true model gives unit-variance innovations
    r = true.sample(mean, starts, rng)
    e = true.whiten(r, true.sd(mean), starts)
    assert np.var(e) == pytest.approx(1.0, abs=0.05)
    assert abs(np.corrcoef(e[1:], e[:-1])[0, 1]) < 0.05


def test_wilson_interval_known_values():
    # 0 of 20: upper limit z^2 / (n + z^2) (Wilson 1927)
    lo, hi = wilson_interval(0, 20)
    assert lo == 0.0 and hi == pytest.approx(1.959964**2 / (20 + 1.959964**2), rel=1e-9)
    lo, hi = wilson_interval(10, 20)
    assert lo + hi == pytest.approx(1.0, rel=1e-12)
