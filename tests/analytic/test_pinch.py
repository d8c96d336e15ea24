"""Pinch: Amontons on two faces, load parameter, Hertz contact (scaling and a Boussinesq check)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from knotmech.analytic import pinch
from knotmech.errors import InputError
from knotmech.materials import VPS32_YOUNGS_MODULUS as E_VPS32

force = st.floats(1e-3, 1e3)
modulus = st.floats(1e5, 1e11)
size = st.floats(1e-4, 1e-1)


@settings(max_examples=50, deadline=None)
@given(force, modulus, size, size, st.floats(0.01, 5.0))
def test_load_parameter_and_sliding_force_linear_in_normal_force(fn, e, d, dd, factor):
    x1 = pinch.pinch_load_parameter(fn, e, d, dd)
    x2 = pinch.pinch_load_parameter(factor * fn, e, d, dd)
    assert x2 == pytest.approx(factor * x1, rel=1e-12)
    assert x1 == pytest.approx(4 * fn / (np.pi * e * d * dd), rel=1e-12)
    assert pinch.pinch_sliding_force(0.3, factor * fn) == pytest.approx(
        factor * pinch.pinch_sliding_force(0.3, fn), rel=1e-12
    )
    assert pinch.pinch_sliding_force(2 * 0.3, fn) == pytest.approx(2 * 0.6 * fn, rel=1e-12)


def test_clove_hitch_paper_pinch_threshold():
    """Clove-hitch paper, sec. 9: VPS32 rod d = 4 mm, E = 1.26 MPa, pinching cylinders
    D = 8 mm; Amontons-Coulomb holds for 4 F_n/(pi E d D) below about 0.1, i.e. F_n up to
    0.1 * pi * 1.26e6 * 4e-3 * 8e-3 / 4 = 3.167 N."""
    f_limit = 0.1 * np.pi * E_VPS32 * 4e-3 * 8e-3 / 4
    assert f_limit == pytest.approx(3.167, rel=1e-3)
    ok = pinch.pinch_amontons_applies([0.99 * f_limit, 1.01 * f_limit], E_VPS32, 4e-3, 8e-3)
    assert list(ok) == [True, False]
    # the paper's clove hitch sits at x ~ 0.05: half that load
    assert pinch.pinch_load_parameter(0.5 * f_limit, E_VPS32, 4e-3, 8e-3) == pytest.approx(0.05)


@settings(max_examples=40, deadline=None)
@given(force, size, modulus)
def test_hertz_circular_scaling(p, r, es):
    c1 = pinch.hertz_circular_contact(normal_force=p, radius=r, contact_modulus=es)
    c8 = pinch.hertz_circular_contact(normal_force=8 * p, radius=r, contact_modulus=es)
    assert c8.semi_major == pytest.approx(2 * c1.semi_major, rel=1e-12)  # a ~ F^(1/3)
    assert c8.peak_pressure == pytest.approx(2 * c1.peak_pressure, rel=1e-12)
    assert c8.approach == pytest.approx(4 * c1.approach, rel=1e-12)  # delta ~ F^(2/3)
    # load = integral of the Hertz pressure, (2/3) pi a^2 p0
    assert 2 / 3 * np.pi * c1.semi_major**2 * c1.peak_pressure == pytest.approx(p, rel=1e-12)


@settings(max_examples=30, deadline=None)
@given(force, size, st.floats(1.0, 30.0), st.floats(1e5, 1e9), st.floats(0.0, 0.5))
def test_crossed_cylinders_scaling_and_equal_radius_case(p, r1, ratio, e, nu):
    kw = {"radius_1": r1, "radius_2": ratio * r1, "youngs_modulus": e, "poisson_ratio": nu}
    c1 = pinch.hertz_crossed_cylinders(normal_force=p, **kw)
    c8 = pinch.hertz_crossed_cylinders(normal_force=8 * p, **kw)
    assert c8.semi_major == pytest.approx(2 * c1.semi_major, rel=1e-9)
    assert c8.semi_minor == pytest.approx(2 * c1.semi_minor, rel=1e-9)
    assert c1.semi_minor <= c1.semi_major * (1 + 1e-12)
    # Johnson's rule of thumb b/a ~ (A/B)^(2/3) = ratio^(-2/3), to a few per cent for B/A <= 5
    if ratio <= 5:
        assert c1.semi_minor / c1.semi_major == pytest.approx(ratio ** (-2 / 3), rel=0.03)
    eq = pinch.hertz_crossed_cylinders(normal_force=p, **{**kw, "radius_2": r1})
    circ = pinch.hertz_circular_contact(
        normal_force=p, radius=r1, contact_modulus=pinch.effective_modulus(e, nu)
    )
    assert eq.semi_major == pytest.approx(circ.semi_major, rel=1e-9)
    assert eq.approach == pytest.approx(circ.approach, rel=1e-9)


def _boussinesq_displacement(px, py, a, b, p0, es, n_phi=4000):
    """Surface displacement at (px, py) under p0 sqrt(1 - x^2/a^2 - y^2/b^2), by quadrature.

    u = 1/(pi E*) int p dA / |P - Q|; in polar coordinates about P the radial integral of
    sqrt(alpha - 2 beta rho - gamma rho^2) over [0, rho_max] is done in closed form.
    """
    phi = np.linspace(0.0, 2 * np.pi, n_phi, endpoint=False)
    c, s = np.cos(phi), np.sin(phi)
    gam = c**2 / a**2 + s**2 / b**2
    beta = px * c / a**2 + py * s / b**2
    alpha = 1 - px**2 / a**2 - py**2 / b**2
    disc = np.sqrt(beta**2 + alpha * gam)
    r_max, r_min = (-beta + disc) / gam, (-beta - disc) / gam
    c0, r0 = 0.5 * (r_max + r_min), 0.5 * (r_max - r_min)

    def prim(u):
        return 0.5 * (u * np.sqrt(np.maximum(r0**2 - u**2, 0)) + r0**2 * np.arcsin(u / r0))

    inner = np.sqrt(gam) * (prim(r0) - prim(-c0))
    return p0 / (np.pi * es) * inner.mean() * 2 * np.pi


def test_crossed_cylinder_contact_reproduces_the_gap_by_boussinesq():
    """Independent check of the elliptical solution: the displacement field of its pressure
    must equal delta - A x^2 - B y^2 inside the patch (rod d = 4 mm on a pinch D = 8 mm)."""
    r1, r2, p, e, nu = 2e-3, 4e-3, 1.5, E_VPS32, 0.5
    c = pinch.hertz_crossed_cylinders(
        normal_force=p, radius_1=r1, radius_2=r2, youngs_modulus=e, poisson_ratio=nu
    )
    es = pinch.effective_modulus(e, nu)
    a, b, p0 = float(c.semi_major), float(c.semi_minor), float(c.peak_pressure)
    coef_a, coef_b = 1 / (2 * r2), 1 / (2 * r1)  # x along the smaller curvature
    for px, py in [(0, 0), (0.5 * a, 0), (0, 0.5 * b), (0.3 * a, 0.4 * b)]:
        u = _boussinesq_displacement(px, py, a, b, p0, es)
        assert u == pytest.approx(float(c.approach) - coef_a * px**2 - coef_b * py**2, rel=1e-6)


@pytest.mark.parametrize("bad", [np.nan, -1.0])
def test_bad_input_raises(bad):
    with pytest.raises(InputError):
        pinch.pinch_load_parameter(bad, 1e6, 1e-3, 1e-2)
    with pytest.raises(InputError):
        pinch.pinch_sliding_force(bad, 1.0)
    with pytest.raises(InputError):
        pinch.hertz_crossed_cylinders(
            normal_force=1.0, radius_1=bad, radius_2=1e-3, youngs_modulus=1e6, poisson_ratio=0.3
        )
    with pytest.raises(InputError, match="poisson_ratio"):
        pinch.effective_modulus(1e6, 0.6)
