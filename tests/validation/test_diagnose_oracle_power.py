"""The oracle noncentrality of validation/diagnose_oracle_power.py against closed forms,
and the generator's curve without the effect (validation/effect_recovery.make_means)."""

import numpy as np
import pytest
from scipy.stats import norm

from knotmech.cli.validate import load_case
from knotmech.errors import InputError

case = load_case("diagnose_oracle_power")
gen = load_case("effect_recovery")


def test_white_step_is_h_sqrt_n_over_sd():
    # a step of h = 0.37 on the last 57 of 200 rows, sd 0.021: delta = 0.37 sqrt(57)/0.021
    f = np.zeros(200)
    f[-57:] = 0.37
    delta = case.noncentrality(f, np.full(200, 0.021))
    assert delta == pytest.approx(0.37 * np.sqrt(57) / 0.021, rel=1e-12)
    assert delta == pytest.approx(133.0209, rel=1e-6)


@pytest.mark.parametrize(("n", "rho"), [(200, 0.9), (7, -0.5), (2, 0.3)])
def test_ar1_offset_matches_the_tridiagonal_closed_form(n, rho):
    # c^2/sd^2 (N - (N - 2) rho)/(1 + rho), from the precision (1/(1 - rho^2)) tridiag
    c, sd = 0.05, 0.021
    delta = case.noncentrality(np.full(n, c), np.full(n, sd), rho=rho)
    exact = c / sd * np.sqrt((n - (n - 2) * rho) / (1.0 + rho))
    assert delta == pytest.approx(exact, rel=1e-12)


def test_ar1_offset_at_rho_09_over_200_rows_is_a_third_of_white():
    # (200 - 198 * 0.9)/1.9 = 21.8/1.9: delta = (c/sd) sqrt(11.47...) against sqrt(200) white
    ratio = case.noncentrality(np.ones(200), np.ones(200), rho=0.9) / np.sqrt(200.0)
    assert ratio == pytest.approx(np.sqrt(21.8 / 1.9 / 200.0), rel=1e-12)
    assert ratio == pytest.approx(0.23951, rel=1e-4)


def test_independent_trials_add_and_heteroscedastic_sd_matches_a_dense_solve():
    rng = np.random.default_rng(4)
    n, rho = 60, 0.8
    f, sd = rng.normal(size=n), rng.uniform(0.5, 2.0, n)
    trial = np.repeat([0, 1, 2], 20)
    idx = np.arange(n)
    corr = rho ** np.abs(idx[:, None] - idx[None, :]) * (trial[:, None] == trial[None, :])
    dense = f @ np.linalg.solve(sd[:, None] * corr * sd[None, :], f)
    assert case.noncentrality(f, sd, trial, rho) ** 2 == pytest.approx(dense, rel=1e-10)
    parts = [case.noncentrality(f[trial == t], sd[trial == t], rho=rho) ** 2 for t in range(3)]
    assert case.noncentrality(f, sd, trial, rho) ** 2 == pytest.approx(sum(parts), rel=1e-12)


def test_power_is_alpha_at_zero_and_one_half_at_the_critical_value():
    assert case.oracle_power(0.0, 0.005) == pytest.approx(0.005, rel=1e-12)
    assert case.oracle_power(norm.isf(0.005), 0.005) == pytest.approx(0.5, abs=1e-15)
    # 3 sd at 0.005: Phi(3 - 2.5758) = 0.6643
    assert case.oracle_power(3.0, 0.005) == pytest.approx(0.66428, abs=1e-5)


@pytest.mark.parametrize(
    ("f", "sd", "kw"),
    [(np.ones(3), np.ones(4), {}), (np.ones(3), np.zeros(3), {}), (np.ones(3), np.ones(3),
     {"rho": 1.0}), (np.array([1.0, np.nan]), np.ones(2), {})],
)  # fmt: skip
def test_bad_input_is_refused(f, sd, kw):
    with pytest.raises(InputError):
        case.noncentrality(f, sd, **kw)


def test_make_means_plants_on_the_curve_without_the_effect():
    # a null: no effect; pinch adhesion: a constant of size x sd at the first row
    *_, mean, mean0, _, _, _, sd = gen.make_means("heldout", "pinch", None, 0.0, 97040)
    assert np.array_equal(mean, mean0)
    _, x, mean, mean0, _, _, truth, _ = gen.make_means("heldout", "pinch", "adhesion", 3.0, 97021)
    f = mean - mean0
    assert np.allclose(f, truth["adhesion_force_N"], rtol=0, atol=1e-15)
    sd0 = 0.003 * np.max(mean0) * (0.6 + 0.4 * mean0[0] / np.max(mean0))
    assert f[0] == pytest.approx(3.0 * sd0, rel=1e-12)


def test_finite_thickness_oracle_is_its_size():
    row = case.recording_oracle(("heldout", "tension_profile", "finite_thickness", 3.0,
                                 "ar1", None, 97045))  # fmt: skip
    assert row["delta"] == 3.0
    assert row["power"] == pytest.approx(0.66428, abs=1e-5)
    assert row["prior_pull"] == pytest.approx(2.57, abs=0.005)


def _pinch(x, y):
    meta = {"rod_diameter_m": 0.003, "pinch_diameter_m": 0.01, "youngs_modulus_Pa": 1.0e6}
    return gen.as_recording("pinch", meta, x, y, np.zeros(x.size, int), None)


def test_refit_of_pinch_adhesion_removes_its_part_along_x():
    # baseline 2 mu x, linear in mu: an offset c keeps only its part orthogonal to x,
    # delta^2 = (c/sd)^2 (N - (sum x)^2 / sum x^2)
    x = np.linspace(0.2, 3.0, 80)
    mean0, c, sd = 0.6 * x, 0.01, np.full(80, 0.004)
    rec = _pinch(x, mean0)
    delta, misfit = case.refitted_noncentrality("pinch", rec, mean0 + c, mean0, sd,
                                                np.zeros(80, int), 0.0)  # fmt: skip
    exact = c / 0.004 * np.sqrt(80 - x.sum() ** 2 / (x @ x))
    assert delta == pytest.approx(exact, rel=1e-8)
    assert misfit < 1e-12


def test_refit_in_ar1_noise_equals_the_linear_projection_for_a_linear_baseline():
    x = np.linspace(0.2, 3.0, 80)
    mean0 = 0.6 * x
    sd = 0.004 * (0.6 + 0.4 * x / 3.0)
    f = 0.01 * np.tanh(x - 1.5)
    trial = np.zeros(80, int)
    delta, _ = case.refitted_noncentrality("pinch", _pinch(x, mean0), mean0 + f, mean0, sd,
                                           trial, 0.9)  # fmt: skip
    linear = case.profiled_noncentrality(f, sd, trial, 0.9, 2.0 * x[:, None])
    assert delta == pytest.approx(linear, rel=1e-8)
    assert delta < case.noncentrality(f, sd, trial, 0.9)


def test_a_finite_thickness_curve_is_a_baseline_curve_with_another_mu():
    row = case.recording_oracle(("heldout", "capstan_pull", "finite_thickness", 3.0,
                                 "white", None, 97006))  # fmt: skip
    assert row["delta_curve"] > 100.0  # the mu change is hundreds of sd on the curve
    assert row["delta_curve_profiled"] < 1e-9 * row["delta_curve"]  # and no evidence


def test_a_missing_campaign_folder_is_one_line(tmp_path, capsys):
    assert case.main(["--out", str(tmp_path), "--results", str(tmp_path / "none")]) == 2
    out = capsys.readouterr().out.strip()
    assert out.count("\n") == 0 and "no campaign cache" in out
