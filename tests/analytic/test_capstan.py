"""Capstan closed forms: reference values, limits (hypothesis), inverses, independent ODE checks."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from knotmech.analytic.capstan import (
    bending_parameter,
    capstan_end_factors,
    capstan_high_tension_nonlinear,
    capstan_ratio,
    capstan_ratio_bending,
    capstan_ratio_nonlinear,
    capstan_ratio_thick,
    capstan_ratio_thick_ends,
    capstan_tension_profile,
    liftoff_angle,
    mu_eff,
    mu_from_capstan_test,
    mu_from_mu_eff,
)
from knotmech.errors import InputError

mus = st.floats(1e-3, 3.0)
angles = st.floats(0.0, 6 * math.pi)
ratios = st.floats(1e-3, 1e3)
FAST = settings(max_examples=60, deadline=None)


# --------------------------------------------------------------------------- reference values
@pytest.mark.parametrize(("Dt", "expected"), [(1, 0.147), (2, 0.196), (5, 0.247), (10, 0.271)])
def test_mu_eff_reference_values(Dt, expected):
    # clove-hitch paper (Extreme Mech. Lett. 2022), eq. (3), values quoted in issue 2 for mu = 0.3
    assert float(mu_eff(0.3, Dt)) == pytest.approx(expected, abs=5e-4)


def test_capstan_ratio_one_turn():
    assert float(capstan_ratio(0.3, 2 * math.pi)) == pytest.approx(
        math.exp(0.6 * math.pi), rel=1e-15
    )


def test_capstan_profile_ends_and_rate():
    R, mu, th = 0.017, 0.3, 2 * math.pi
    s = np.array([0.0, R * th])
    T = capstan_tension_profile(s, high_tension=2.0, mu=mu, radius=R)
    assert T[0] == 2.0
    assert T[0] / T[1] == pytest.approx(float(capstan_ratio(mu, th)), rel=1e-14)


def test_mu_from_capstan_test_coated_rod_method():
    # a measured 1.5 turn ratio of e^(0.5*3pi) must give mu = 0.5 back
    th = 3 * math.pi
    assert float(mu_from_capstan_test(math.exp(0.5 * th), 1.0, th)) == pytest.approx(0.5, rel=1e-14)
    with pytest.raises(InputError, match="high_tension"):
        mu_from_capstan_test(1.0, 2.0, th)


# --------------------------------------------------------------------------- ideal capstan limits
@FAST
@given(angles)
def test_mu_zero_gives_ratio_one(theta):
    assert float(capstan_ratio(0.0, theta)) == 1.0
    assert float(capstan_ratio(1e-12, theta)) == pytest.approx(1.0, abs=1e-10)


@FAST
@given(mus, angles, angles)
def test_ratio_is_multiplicative_in_wrap(mu, t1, t2):
    lhs = float(capstan_ratio(mu, t1 + t2))
    rhs = float(capstan_ratio(mu, t1) * capstan_ratio(mu, t2))
    assert lhs == pytest.approx(rhs, rel=1e-12)


@FAST
@given(mus, st.floats(0.1, 6 * math.pi), st.floats(1.0, 5.0))
def test_capstan_test_round_trip(mu, theta, t_low):
    ratio = float(capstan_ratio(mu, theta))
    assert float(mu_from_capstan_test(ratio * t_low, t_low, theta)) == pytest.approx(mu, rel=1e-9)


# --------------------------------------------------------------------------- thick rod
@FAST
@given(mus, ratios)
def test_mu_eff_below_mu(mu, Dt):
    assert 0 < float(mu_eff(mu, Dt)) < mu


@FAST
@given(mus)
def test_mu_eff_tends_to_mu_for_large_post(mu):
    assert float(mu_eff(mu, 1e9)) == pytest.approx(mu, rel=1e-7)


@FAST
@given(mus, st.floats(1e-9, 1e-5))
def test_mu_eff_small_post_is_mu_times_Dt(mu, Dt):
    # a = d/(D+d) -> 1: mu_eff = mu*Dt*(1 + O(Dt))
    assert float(mu_eff(mu, Dt)) == pytest.approx(mu * Dt, rel=10 * Dt * (1 + mu**2))


@FAST
@given(mus, ratios, st.floats(1.001, 2.0))
def test_mu_eff_monotone_in_both_arguments(mu, Dt, factor):
    assert float(mu_eff(mu * factor, Dt)) > float(mu_eff(mu, Dt))
    assert float(mu_eff(mu, Dt * factor)) > float(mu_eff(mu, Dt))


@FAST
@given(mus, ratios)
def test_mu_eff_inverse_round_trip(mu, Dt):
    me = mu_eff(mu, Dt)
    assert float(mu_from_mu_eff(me, Dt)) == pytest.approx(mu, rel=1e-8)


def test_mu_eff_zero_mu_and_vectorised():
    out = mu_eff(np.array([0.0, 0.3]), np.array([[1.0], [10.0]]))
    assert out.shape == (2, 2)
    assert np.all(out[:, 0] == 0.0)
    assert out[1, 1] == pytest.approx(0.2707, abs=1e-4)


def test_mu_from_mu_eff_refuses_impossible_values():
    with pytest.raises(InputError, match="sqrt"):
        mu_from_mu_eff(1.5, 2.0)  # sup of mu_eff at D/d = 2 is sqrt(2)


@FAST
@given(mus, angles)
def test_thick_capstan_reduces_to_ideal(mu, theta):
    # mu - mu_eff ~ mu (1 + mu^2) / Dt, so the ratio differs by ~ theta mu (1 + mu^2) / Dt
    assert float(capstan_ratio_thick(mu, theta, 1e10)) == pytest.approx(
        float(capstan_ratio(mu, theta)), rel=1e-6
    )


# --------------------------------------------------------------------------- bending rigidity
def test_bending_zero_stiffness_is_ideal_exactly():
    r = capstan_ratio_bending(
        0.3, 2 * math.pi, bending_stiffness=0.0, low_tension=1.0, high_tension=5.0, radius=0.02
    )
    assert float(r) == float(capstan_ratio(0.3, 2 * math.pi))


@FAST
@given(mus, st.floats(math.pi / 2, 4 * math.pi), st.floats(1e-10, 1e-7))
def test_bending_correction_is_second_order_and_lowers_ratio(mu, theta, B):
    T_low, T_high, R = 1.0, 3.0, 0.02
    r = float(
        capstan_ratio_bending(
            mu, theta, bending_stiffness=B, low_tension=T_low, high_tension=T_high, radius=R
        )
    )
    ideal = math.exp(mu * theta)
    # derivations/capstan_ode.py: ratio = e^{mu theta}[1 - (1+mu^2)/2 (B/R^2)(1/T_low - 1/T_high)]
    predicted = ideal * (1 - (1 + mu**2) / 2 * B / R**2 * (1 / T_low - 1 / T_high))
    assert r < ideal
    eps2 = B / (T_low * R**2)
    assert abs(r - predicted) <= 2 * ideal * (1 + mu) ** 3 * eps2**1.5


def test_bending_parameter_value():
    eps = bending_parameter(bending_stiffness=4e-6, tension=1.0, radius=0.02)
    assert float(eps) == pytest.approx(0.1, rel=1e-14)


def test_liftoff_angle_solves_the_elastica():
    """Shoot the free elastica B phi'' = T sin(phi) from lift-off: it must decay to 0."""
    B, T, R = 2e-5, 0.5, 0.017
    eps = float(bending_parameter(bending_stiffness=B, tension=T, radius=R))
    phi0 = float(liftoff_angle(eps))
    lam = math.sqrt(B / T)

    def rhs(s, y):
        return [y[1], T / B * math.sin(y[0])]

    # leaving the post the tangent straightens: phi decreases from phi0 with phi' = -1/R
    sol = solve_ivp(rhs, (0, 8 * lam), [phi0, -1.0 / R], rtol=1e-11, atol=1e-13)
    assert abs(sol.y[0, -1]) < 2e-3 * phi0
    # a 1 % error in the angle makes the shot diverge
    sol_bad = solve_ivp(rhs, (0, 8 * lam), [1.01 * phi0, -1.0 / R], rtol=1e-11, atol=1e-13)
    assert abs(sol_bad.y[0, -1]) > 0.05 * phi0


def test_bending_refuses_rods_too_stiff_to_wrap():
    with pytest.raises(InputError, match="epsilon"):
        liftoff_angle(2.5)
    with pytest.raises(InputError, match="wrap_angle"):
        capstan_ratio_bending(
            0.3, 0.1, bending_stiffness=1e-6, low_tension=1.0, high_tension=1.1, radius=0.01
        )


# --------------------------------------------------------------------------- nonlinear friction
@FAST
@given(st.floats(0.05, 1.0), angles, st.floats(0.1, 10.0), st.floats(0.005, 0.1))
def test_howell_reduces_to_ideal(a, theta, T_low, R):
    kw = dict(low_tension=T_low, wrap_angle=theta, friction_coefficient=a, radius=R)
    exact = capstan_ratio_nonlinear(friction_exponent=1.0, **kw)
    assert float(exact) == pytest.approx(float(capstan_ratio(a, theta)), rel=1e-12)
    near = capstan_ratio_nonlinear(friction_exponent=1 - 1e-7, **kw)
    assert float(near) == pytest.approx(float(exact), rel=1e-4)


@pytest.mark.parametrize("n", [0.5, 0.67, 0.9])
def test_howell_matches_ode(n):
    a, R, T_low, theta = 0.4, 0.02, 0.7, 3 * math.pi
    sol = solve_ivp(
        lambda th, T: a * R ** (1 - n) * T**n, (0, theta), [T_low], rtol=1e-11, atol=1e-12
    )
    T_high = capstan_high_tension_nonlinear(
        low_tension=T_low, wrap_angle=theta, friction_coefficient=a, friction_exponent=n, radius=R
    )
    assert float(T_high) == pytest.approx(sol.y[0, -1], rel=1e-8)


def test_howell_ratio_grows_slower_than_exponential_at_high_tension():
    kw = dict(wrap_angle=2 * math.pi, friction_coefficient=0.3, friction_exponent=0.7, radius=0.02)
    r_low = float(capstan_ratio_nonlinear(low_tension=0.1, **kw))
    r_high = float(capstan_ratio_nonlinear(low_tension=100.0, **kw))
    assert r_high < r_low


# --------------------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: capstan_ratio(-0.1, 1.0), "mu"),
        (lambda: capstan_ratio(0.3, float("nan")), "wrap_angle"),
        (lambda: mu_eff(0.3, 0.0), "D_over_d"),
        (lambda: capstan_tension_profile(1.0, high_tension=1, mu=0.3, radius=-1), "radius"),
        (
            lambda: capstan_high_tension_nonlinear(
                low_tension=1,
                wrap_angle=1,
                friction_coefficient=0.3,
                friction_exponent=1.5,
                radius=0.1,
            ),
            "friction_exponent",
        ),
    ],
)
def test_bad_input_names_the_argument(call, name):
    with pytest.raises(InputError, match=name):
        call()


# --------------------------------------------------------------------------- end layers
@given(mus, st.floats(0.05, 1e3))
@FAST
def test_end_factors_bounds_and_fast_root(mu, Dt):
    entry, exit_ = capstan_end_factors(mu, Dt)
    assert entry >= 1.0 and 0.0 < exit_ <= 1.0
    # the exit factor is |l2| / (|l2| + mu_eff), l2 the negative root of the quadratic whose
    # positive root is mu_eff: mu a l^2 + l - mu (1 - a) = 0, a = d / (D + d)
    a = 1.0 / (1.0 + Dt)
    roots = np.roots([mu * a, 1.0, -mu * (1.0 - a)])
    l2, l1 = sorted(roots.real)
    assert l1 == pytest.approx(float(mu_eff(mu, Dt)), rel=1e-8)
    assert exit_ == pytest.approx(-l2 / (-l2 + l1), rel=1e-9)


@given(mus)
@FAST
def test_end_factors_vanish_for_thin_rods(mu):
    entry, exit_ = capstan_end_factors(mu, 1e9)
    assert abs(entry - 1.0) < 1e-6 and abs(exit_ - 1.0) < 1e-6
    assert capstan_end_factors(0.0, 1.0) == (1.0, 1.0)


def test_end_factors_against_der():
    # DER capstan with surface friction, mu = 0.5, D/d = 1, mesh converged: entry 1.0875,
    # exit 0.9491, sliding ratio +3.1 % above exp(mu_eff theta) at theta = pi/2 and pi
    # (tests/scenes/test_capstan.py::test_D_over_d_1_excess_is_an_end_layer_factor)
    entry, exit_ = capstan_end_factors(0.5, 1.0)
    assert entry == pytest.approx(1.0875, rel=1e-2)
    assert exit_ == pytest.approx(0.9491, rel=1e-2)
    excess = capstan_ratio_thick_ends(0.5, math.pi, 1.0) / capstan_ratio_thick(0.5, math.pi, 1.0)
    assert math.log(excess) == pytest.approx(0.031, abs=4e-3)


def test_end_factors_reject_bad_input():
    with pytest.raises(InputError, match="D_over_d"):
        capstan_end_factors(0.3, -1.0)
    with pytest.raises(InputError, match="mu"):
        capstan_end_factors(float("nan"), 1.0)
