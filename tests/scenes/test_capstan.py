"""Capstan in simulation: sliding ratio against exp(mu_eff theta), hold without creep.

Theory: clove-hitch paper eq. (3) (mu_eff of a rod of finite thickness, Jung, Pan & Kang
2008) via knotmech.analytic.capstan.mu_eff. The runs use a rope-like bending stiffness
EI = 1e-4 EA R^2 so that the lift-off boundary layers are short (EI/(T R^2) <= 1e-2; the
bending correction -(1+mu^2)/2 EI/(T_low R^2) is then below 1 %).
"""

import numpy as np
import pytest

from knotmech.analytic.capstan import capstan_end_factors, mu_eff
from knotmech.scenes.capstan import capstan, capstan_two_loops

D_ROD = 4e-3
E = 1.26e6
EA = E * np.pi * D_ROD**2 / 4


def run(D_over_d, mu, theta, n_elements=80, **kw):
    D = D_over_d * D_ROD
    R = 0.5 * (D + D_ROD)
    kw.setdefault("t_low", 0.01 * EA)
    return capstan(
        wrap_angle=theta,
        mu=mu,
        rod_diameter=D_ROD,
        post_diameter=D,
        youngs_modulus=E,
        bending_stiffness=1e-4 * EA * R**2,
        n_elements=n_elements,
        **kw,
    )


def test_thick_rod_slides_at_exp_mu_eff_theta():
    r = run(2.0, 0.5, np.pi)
    assert r.status == "success", r.message
    expected = np.exp(mu_eff(0.5, 2.0) * np.pi)
    assert r.exp_mu_eff_theta == pytest.approx(expected)
    # measured: +1.5 % (80 and 240 elements alike)
    assert abs(r.ratio / expected - 1) < 0.02
    # and clearly not the thin-rope value exp(mu theta) = 4.81
    assert r.ratio / r.exp_mu_theta < 0.6
    # tension profile: T_low at the far end, decreasing along the wrap
    assert r.tension[-1] == pytest.approx(r.t_low, rel=0.01)
    assert r.tension[0] == pytest.approx(r.ratio * r.t_low, rel=0.02)


def test_friction_at_the_centreline_gives_exp_mu_theta():
    """Without the couple of the surface friction the thick rod slides at exp(mu theta)."""
    r = run(2.0, 0.5, np.pi, surface_friction=False)
    assert abs(r.ratio / r.exp_mu_theta - 1) < 0.02


def test_hold_below_the_limit_no_creep_and_slide_above():
    limit = 0.01 * EA * np.exp(mu_eff(0.5, 2.0) * np.pi)
    held = run(2.0, 0.5, np.pi, mode="hold", t_high=0.9 * limit, hold_time=1.0)
    assert held.status == "success"
    # after the 0.1 s ramp, half a second under constant loads: not a nanometre of creep
    assert held.creep < 1e-9
    slid = run(2.0, 0.5, np.pi, mode="hold", t_high=1.1 * limit, hold_time=1.0)
    assert slid.displacement[-1] > 5e-3  # slid off by more than a diameter (stopped early)


def test_static_peak_then_kinetic_plateau():
    """mu_s = 0.6 > mu_k = 0.4: T_high overshoots at the onset of sliding, then slides at
    exp(mu_eff(mu_k) theta) (measured: peak 2.83, plateau 2.681 vs 2.667)."""
    r = run(4.0, 0.6, np.pi, mu_kinetic=0.4)
    kinetic = np.exp(mu_eff(0.4, 4.0) * np.pi)
    assert abs(r.ratio / kinetic - 1) < 0.02
    assert r.t_high.max() / r.t_low > 1.03 * r.ratio


@pytest.mark.slow
@pytest.mark.parametrize(
    "D_over_d, mu, theta",
    [
        (2.0, 0.5, 0.5 * np.pi),
        (2.0, 0.2, np.pi),
        (4.0, 0.5, 1.5 * np.pi),
        (10.0, 0.5, np.pi),
        (10.0, 0.3, 2.5 * np.pi),
        (50.0, 0.5, np.pi),
    ],
)
def test_sliding_ratio_sweep(D_over_d, mu, theta):
    r = run(D_over_d, mu, theta, n_elements=None)
    assert abs(r.ratio / r.exp_mu_eff_theta - 1) < 0.02


@pytest.mark.slow
def test_limits_mu_eff_thick_and_mu_thin():
    """ln(ratio)/theta follows mu_eff(D/d) and tends to mu as D/d grows."""
    mus = []
    for Dd in (2.0, 50.0):
        r = run(Dd, 0.5, np.pi, n_elements=None)
        mus.append(np.log(r.ratio) / np.pi)
    assert mus[0] == pytest.approx(mu_eff(0.5, 2.0), rel=0.02)
    assert mus[1] == pytest.approx(0.5, rel=0.03)
    assert mus[1] > mus[0]


@pytest.mark.slow
def test_two_loops_of_the_clove_hitch_paper():
    """theta = 4 pi, d = 4 mm, D = 30 mm, E = 1.26 MPa, mu = 0.32, T_low = 0.069 N (solid rod:
    EI/(T_low R^2) = 0.8, so the plateau lies well below exp(mu_eff theta) = 33.4)."""
    r = capstan_two_loops()
    assert r.status == "success", r.message
    assert 1.0 < r.ratio < r.exp_mu_eff_theta


def _interior_fit(r, lo=0.2, hi=0.8):
    """Fit log T = c0 - k phi on the wrap's polar angles lo..hi of theta (final frame).

    Returns the polynomial (slope, intercept) in the polar angle phi of the edge midpoints.
    """
    R = 0.5 * (r.post_diameter + r.rod_diameter)
    mid = 0.5 * (r.positions[-1][1:] + r.positions[-1][:-1])
    ang = np.arctan2(mid[:, 1], mid[:, 0])
    ang = np.where(ang < -0.5, ang + 2 * np.pi, ang)
    inner = (ang > lo * r.wrap_angle) & (ang < hi * r.wrap_angle)
    inner &= np.hypot(mid[:, 0], mid[:, 1]) < 1.05 * R
    return np.polyfit(ang[inner], np.log(r.tension[inner]), 1)


def test_D_over_d_1_excess_is_an_end_layer_factor():
    """At D/d = 1 the sliding ratio is +3.1 % above exp(mu_eff theta) (mu = 0.5), outside the
    2 % of the thicker rods, and this is the thick-rod model's end layers, not an error of
    the decay rate or of the mesh. Eq. (3) of the clove-hitch paper holds "away from the
    loading ends": in the wrap the friction couple (d/2) f is carried by a shear force
    Q = (d/2) f, which must build up where the rod comes onto the post and vanish where it
    leaves, and these two layers (about 0.3 rad each) multiply the ratio by a factor
    (measured: 1.0875 at the entry, 0.949 at the exit, product 1.031; a rope-limit model,
    :func:`~knotmech.analytic.capstan_end_factors`, gives 1.0853 and 0.9472, +2.8 %)
    that does not depend
    on theta and grows with d/(D+d) and mu (-0.1, +0.5, +1.5, +3.1, +5.5 % at
    D/d = 10, 4, 2, 1, 0.5, theta = pi; +0.9 % at D/d = 1, mu = 0.2).
    Measured at D/d = 1: interior rate 0.2358 vs mu_eff = 0.2361; excess +3.16 %
    (theta = pi/2), +3.14 % (pi); +3.25, +3.14, +3.11, +3.11 % at 100, 200, 400, 800
    elements; +3.08 .. +3.25 % for a contact stiffness 1/4 .. 4 times the default;
    +3.0 .. +3.2 % for leads of R .. 4 R; +2.5, +3.1, +3.3, +3.3 % for
    EI/(T_low R^2) = 0.04, 0.01, 0.0025, 0.000625 (a finite limit as the rod becomes a rope).
    """
    me = mu_eff(0.5, 1.0)
    half = run(1.0, 0.5, 0.5 * np.pi, n_elements=None)
    full = run(1.0, 0.5, np.pi, n_elements=None)
    fine = run(1.0, 0.5, np.pi, n_elements=400)
    for r in (half, full, fine):
        assert r.status == "success", r.message
    # the decay rate in the middle of the wrap is mu_eff (within 0.5 %)
    assert -_interior_fit(full)[0] == pytest.approx(me, rel=5e-3)
    assert -_interior_fit(fine)[0] == pytest.approx(me, rel=5e-3)
    # the end layers against the rope-limit model (1.0853 and 0.9472; measured 1.0875, 0.9491;
    # the model is approximate: inextensible, EI -> 0; over D/d = 0.5 .. 4 and mu = 0.2 .. 0.8
    # its factors are within about 1 % of the simulated ones)
    fit = _interior_fit(full)
    entry, exit_ = capstan_end_factors(0.5, 1.0)
    t_high = full.ratio * full.t_low
    assert t_high / np.exp(np.polyval(fit, 0.0)) == pytest.approx(entry, rel=1e-2)
    assert np.exp(np.polyval(fit, np.pi)) / full.t_low == pytest.approx(exit_, rel=1e-2)
    # the same end factor at theta = pi/2 and pi: their ratio is exp(mu_eff pi/2) to 0.3 %
    assert np.log(full.ratio / half.ratio) == pytest.approx(me * 0.5 * np.pi, rel=3e-3)
    # the excess itself: about +3.1 %, the same at both angles and at twice the resolution
    excess = [np.log(r.ratio / r.exp_mu_eff_theta) for r in (half, full, fine)]
    for e in excess:
        assert 0.027 < e < 0.035
    assert abs(excess[2] - excess[1]) < 2e-3
    # and it is an end effect of the surface friction: at the centreline, exp(mu theta)
    centre = run(1.0, 0.5, np.pi, n_elements=None, surface_friction=False)
    assert abs(centre.ratio / centre.exp_mu_theta - 1) < 5e-3
