"""Every SymPy-derived expression in derivations/{capstan_ode,mu_eff,hitches}.py against the code.

Each derived expression is lambdified and compared with the numeric implementation at
random points, so a wrong formula in either place fails.
"""

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from knotmech.analytic import capstan, hitch

ROOT = Path(__file__).resolve().parents[1]
RNG = np.random.default_rng(20261122)
N = 25


def _load(name):
    path = ROOT / "derivations" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(f"_derivation_{name}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def mu_eff_mod():
    return _load("mu_eff")


@pytest.fixture(scope="module")
def ode_mod():
    return _load("capstan_ode")


@pytest.fixture(scope="module")
def hitches_mod():
    return _load("hitches")


# --------------------------------------------------------------------------- mu_eff
def test_derived_mu_eff_matches_code(mu_eff_mod):
    m = mu_eff_mod
    f = sp.lambdify((m.mu, m.Dt), m.derive_mu_eff(), "numpy")
    mu = RNG.uniform(0.01, 3.0, N)
    Dt = 10 ** RNG.uniform(-2, 3, N)
    np.testing.assert_allclose(f(mu, Dt), capstan.mu_eff(mu, Dt), rtol=1e-11)


def test_derived_mu_eff_is_the_papers_form(mu_eff_mod):
    m = mu_eff_mod
    assert sp.simplify(m.derive_mu_eff() - m.paper_form()) == 0


def test_derived_inverse_matches_code(mu_eff_mod):
    m = mu_eff_mod
    f = sp.lambdify((m.lam, m.Dt), m.derive_mu_from_mu_eff(), "numpy")
    Dt = 10 ** RNG.uniform(-1, 2, N)
    me = RNG.uniform(0.0, 0.95, N) * np.sqrt(Dt)
    np.testing.assert_allclose(f(me, Dt), capstan.mu_from_mu_eff(me, Dt), rtol=1e-10)


def test_balance_equations_vanish_at_the_codes_mu_eff(mu_eff_mod):
    """The force and moment balances hold with lam = mu_eff from the code (and not with mu)."""
    m = mu_eff_mod
    tangential, normal, moment = m.balance_equations()
    n0 = sp.solve(normal, m.N0)[0]
    resid = sp.lambdify((m.lam, m.mu, m.d, m.D, m.T0), tangential.subs(m.N0, n0), "numpy")
    for _ in range(N):
        mu, d, D = RNG.uniform(0.05, 2.0), RNG.uniform(1e-3, 1e-2), RNG.uniform(1e-3, 1e-1)
        me = float(capstan.mu_eff(mu, D / d))
        assert abs(resid(me, mu, d, D, 1.0)) < 1e-12
        assert abs(resid(mu, mu, d, D, 1.0)) > 1e-4  # friction at the centreline is wrong
    assert sp.simplify(moment) == 0


# --------------------------------------------------------------------------- capstan ODE
def test_derived_ideal_ratio_and_profile(ode_mod):
    m = ode_mod
    ratio = sp.lambdify((m.mu, m.theta), m.derive_ideal_ratio(), "numpy")
    mu, th = RNG.uniform(0, 2, N), RNG.uniform(0, 20, N)
    np.testing.assert_allclose(ratio(mu, th), capstan.capstan_ratio(mu, th), rtol=1e-13)
    prof = sp.lambdify((m.s, m.mu, m.R, m.T_high), m.derive_profile(), "numpy")
    s, R, Th = RNG.uniform(0, 1, N), RNG.uniform(0.01, 1, N), RNG.uniform(0.1, 10, N)
    np.testing.assert_allclose(
        prof(s, mu, R, Th),
        capstan.capstan_tension_profile(s, high_tension=Th, mu=mu, radius=R),
        rtol=1e-13,
    )


def test_derived_howell_matches_code(ode_mod):
    m = ode_mod
    f = sp.lambdify((m.T_low, m.a, m.n, m.R, m.theta), m.derive_nonlinear_high_tension(), "numpy")
    T0, a, n = RNG.uniform(0.1, 10, N), RNG.uniform(0.05, 1, N), RNG.uniform(0.3, 0.99, N)
    R, th = RNG.uniform(0.005, 0.5, N), RNG.uniform(0, 15, N)
    code = capstan.capstan_high_tension_nonlinear(
        low_tension=T0, wrap_angle=th, friction_coefficient=a, friction_exponent=n, radius=R
    )
    np.testing.assert_allclose(f(T0, a, n, R, th), code, rtol=1e-11)


def test_derived_liftoff_angle_matches_code(ode_mod):
    m = ode_mod
    assert m.elastica_first_integral_residual() == 0
    f = sp.lambdify(m.eps, m.derive_liftoff_angle(), "numpy")
    eps = RNG.uniform(0, 1.99, N)
    np.testing.assert_allclose(f(eps), capstan.liftoff_angle(eps), rtol=1e-9, atol=1e-12)


def test_derived_bending_ratio_matches_code(ode_mod):
    m = ode_mod
    f = sp.lambdify((m.mu, m.theta, m.phi_l, m.phi_h), m.derive_bending_ratio(), "numpy")
    for _ in range(N):
        mu, th = RNG.uniform(0, 1), RNG.uniform(2, 12)
        B, R = 10 ** RNG.uniform(-8, -5), RNG.uniform(0.01, 0.05)
        Tl = RNG.uniform(0.1, 1.0)
        Th = Tl * RNG.uniform(1, 5)
        eps_l = math.sqrt(B / (Tl * R**2))
        eps_h = math.sqrt(B / (Th * R**2))
        if eps_l > 1.5:
            continue
        phl, phh = float(capstan.liftoff_angle(eps_l)), float(capstan.liftoff_angle(eps_h))
        code = capstan.capstan_ratio_bending(
            mu, th, bending_stiffness=B, low_tension=Tl, high_tension=Th, radius=R
        )
        assert float(code) == pytest.approx(f(mu, th, phl, phh), rel=1e-12)


def test_derived_bending_series_is_the_docstring_form(ode_mod):
    m = ode_mod
    series = m.derive_bending_ratio_series()
    expected = 1 - (1 + m.mu**2) / 2 * (m.phi_l**2 - m.phi_h**2)
    assert sp.simplify(series - expected) == 0


# --------------------------------------------------------------------------- hitches
def test_derived_nip_factor_matches_code(hitches_mod):
    m = hitches_mod
    f = sp.lambdify((m.d, m.Ds), m.nip_factor(), "numpy")
    d, Ds = 10 ** RNG.uniform(-4, -1, N), 10 ** RNG.uniform(-4, -1, N)
    np.testing.assert_allclose(f(d, Ds), hitch.nip_factor(d, Ds), rtol=1e-12)


def _thick_values(mu, d, D):
    g = hitch.KNOTS["clove-hitch"]
    return {
        "m_post": float(capstan.mu_eff(mu, D / d)),
        "m_rope": float(capstan.mu_eff(mu, 1.0)),
        "G": 2 * mu * float(hitch.nip_factor(d, D)),
        "G_r": 2 * mu * float(hitch.nip_factor(d, d)),
        "theta_in": g.post_wrap_in,
        "theta_out": g.post_wrap_out,
    }


def test_derived_clove_hitch_matches_code(hitches_mod):
    m = hitches_mod
    K = m.clove_hitch_ratio()
    f = sp.lambdify((m.m_post, m.G, m.theta_in, m.theta_out), K, "numpy")
    checked = 0
    for _ in range(4 * N):
        mu, d, D = RNG.uniform(0.0, 0.3), 10 ** RNG.uniform(-5, -3), 10 ** RNG.uniform(-2, -1)
        v = _thick_values(mu, d, D)
        code = float(hitch.thick_hitch_ratio("clove-hitch", mu, rod_diameter=d, post_diameter=D))
        lock = v["G"] * math.exp(v["m_post"] * v["theta_out"])
        if lock >= 1:
            assert math.isinf(code)
            continue
        assert code == pytest.approx(
            f(v["m_post"], v["G"], v["theta_in"], v["theta_out"]), rel=1e-11
        )
        checked += 1
    assert checked > 10
    ideal = sp.lambdify((m.m_post, m.theta_in, m.theta_out), m.ideal_limit(K), "numpy")
    mu = RNG.uniform(0, 1, N)
    np.testing.assert_allclose(
        ideal(mu, 2 * np.pi, 2 * np.pi), hitch.ideal_hitch_ratio("clove-hitch", mu), rtol=1e-13
    )


def test_derived_half_hitches_match_code(hitches_mod):
    m = hitches_mod
    K = m.two_half_hitches_ratio()
    f = sp.lambdify((m.m_post, m.m_rope, m.G_r, m.theta_p, m.theta_h), K, "numpy")
    checked = 0
    for _ in range(4 * N):
        mu, d, D = RNG.uniform(0.0, 0.25), 10 ** RNG.uniform(-4, -3), 10 ** RNG.uniform(-2, -1)
        v = _thick_values(mu, d, D)
        code = float(
            hitch.thick_hitch_ratio("two-half-hitches", mu, rod_diameter=d, post_diameter=D)
        )
        if v["G_r"] * math.exp(v["m_rope"] * 2 * math.pi) >= 1:
            assert math.isinf(code)
            continue
        expected = f(v["m_post"], v["m_rope"], v["G_r"], math.pi, 2 * math.pi)
        assert code == pytest.approx(expected, rel=1e-11)
        checked += 1
    assert checked > 10
    ideal = sp.lambdify((m.m_post, m.m_rope, m.theta_p, m.theta_h), m.ideal_limit(K), "numpy")
    mu, mrr = RNG.uniform(0, 1, N), RNG.uniform(0, 1, N)
    np.testing.assert_allclose(
        ideal(mu, mrr, np.pi, 2 * np.pi),
        hitch.ideal_hitch_ratio("two-half-hitches", mu, mrr),
        rtol=1e-13,
    )


def test_derived_clove_lock_condition(hitches_mod):
    m = hitches_mod
    assert sp.simplify(m.clove_hitch_lock_condition() - sp.exp(m.m_post * m.theta_out)) == 0


def test_derived_round_turn_matches_code(hitches_mod):
    m = hitches_mod
    f = sp.lambdify((m.m_post, m.theta_p), m.round_turn_ratio(), "numpy")
    mu = RNG.uniform(0, 1, N)
    np.testing.assert_allclose(
        f(mu, 2 * np.pi), hitch.ideal_hitch_ratio("round-turn", mu), rtol=1e-13
    )
    d, D = 2e-3, 3e-2
    np.testing.assert_allclose(
        f(capstan.mu_eff(mu, D / d), 2 * np.pi),
        hitch.thick_hitch_ratio("round-turn", mu, rod_diameter=d, post_diameter=D),
        rtol=1e-13,
    )
