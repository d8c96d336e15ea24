"""Derivations (SymPy) against the numeric closed forms: LLD, Jawed braid law, Audoly loose knot.

Each derived expression is lambdified and compared at random points with the function of
knotmech.analytic, so a wrong formula on either side fails.
"""

import importlib.util
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import quad
from scipy.special import ellipe, ellipk

from knotmech.analytic import film, knots

DERIVATIONS = Path(__file__).resolve().parents[1] / "derivations"
ELLIPTIC = [{"elliptic_k": ellipk, "elliptic_e": ellipe}, "numpy"]


def _load(name):
    spec = importlib.util.spec_from_file_location(f"derivation_{name}", DERIVATIONS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def lld():
    return _load("lld")


@pytest.fixture(scope="module")
def jawed():
    return _load("jawed_braid")


@pytest.fixture(scope="module")
def audoly():
    return _load("audoly_loose_knot")


rng = np.random.default_rng(20151)


def test_lld_rescaling_and_constant(lld):
    assert lld.thin_film_rescaling() == (0, 0)
    c = lld.landau_levich_constant()
    assert c == pytest.approx(0.643, abs=5e-4)  # Landau & Levich 1942
    assert c == pytest.approx(film.LANDAU_LEVICH_CURVATURE, abs=1e-5)
    kappa, height = lld.static_meniscus_curvature_plate()
    assert sp.simplify(height - sp.sqrt(2)) == 0


def test_lld_laws_match_the_implementation(lld):
    h_plate, h_fibre = lld.film_thickness_laws(constant=film.LANDAU_LEVICH_CURVATURE)
    plate = sp.lambdify((lld.eta, lld.U, lld.gamma, lld.rho, lld.g), h_plate, "numpy")
    fibre = sp.lambdify((lld.r, lld.eta, lld.U, lld.gamma), h_fibre, "numpy")
    n = 20
    eta = 10 ** rng.uniform(-4, 0, n)
    u = 10 ** rng.uniform(-5, -1, n)
    gamma = rng.uniform(0.02, 0.08, n)
    rho = rng.uniform(700, 2000, n)
    r = 10 ** rng.uniform(-6, -2, n)
    np.testing.assert_allclose(
        film.film_thickness_plate(eta, u, gamma, rho),
        plate(eta, u, gamma, rho, film.STANDARD_GRAVITY),
        rtol=1e-12,
    )
    np.testing.assert_allclose(
        film.film_thickness_fibre(r, eta, u, gamma), fibre(r, eta, u, gamma), rtol=1e-12
    )


def test_helix_contact_force(jawed):
    p_exact, p_leading = jawed.helix_contact_force()
    assert sp.simplify(p_leading - jawed.B * jawed.a * jawed.k**4) == 0
    f = sp.lambdify((jawed.a, jawed.k, jawed.T, jawed.B), p_exact, "numpy")
    # untensioned, slender helix: exact -> B a k^4 as a k -> 0, error O((a k)^2)
    for ak in (1e-2, 1e-3):
        k = 100.0
        p = f(ak / k, k, 0.0, 1.0)
        assert p == pytest.approx(
            knots.braid_contact_force_per_length(
                wavenumber=k, rod_radius=ak / k, bending_stiffness=1.0
            ),
            rel=6 * ak**2,
        )


def test_braid_force_matches_eq4(jawed):
    expr = jawed.braid_force()
    f = sp.lambdify((jawed.mu, jawed.n, jawed.h, jawed.B, jawed.k), expr, "numpy")
    for _ in range(10):
        m, n, h, b, k = (
            rng.uniform(0, 1),
            rng.integers(1, 8),
            10 ** rng.uniform(-4, -2),
            10 ** rng.uniform(-6, 0),
            10 ** rng.uniform(0, 4),
        )
        assert f(m, n, h, b, k) == pytest.approx(
            knots.braid_friction_force(
                wavenumber=k, turns=n, mu=m, rod_radius=h, bending_stiffness=b
            ),
            rel=1e-12,
        )


def test_loop_closure_matches_and_integrates(jawed):
    residual, loop_len, braid_len = jawed.loop_closure()
    assert residual == 0
    lam = sp.lambdify(jawed.m, loop_len, ELLIPTIC)
    ell = sp.lambdify(jawed.m, braid_len, ELLIPTIC)
    for m in np.r_[rng.uniform(0.001, 0.999, 8), 1e-4, 0.9999]:
        l_r, lam_r = knots.loop_closure(m)
        assert lam(m) == pytest.approx(lam_r, rel=1e-12)
        # the closed form cancels as m -> 0 (l/R ~ pi m/4, error ~ 1e-15/m^2); the
        # implementation uses a series there
        assert ell(m) == pytest.approx(l_r, rel=max(1e-10, 1e-14 / m**2))

        def ds(t, m=m):
            return 1 / np.sqrt(1 - m * np.sin(t / 2) ** 2)

        # direct quadrature of the elastica, theta in [0, 2 pi], R = 1
        assert quad(ds, 0, 2 * np.pi, limit=200)[0] == pytest.approx(lam_r, rel=1e-9)
        chord = quad(lambda t, f=ds: np.cos(t) * f(t), 0, 2 * np.pi, limit=200)[0]
        assert -chord == pytest.approx(l_r, rel=max(1e-9, 1e-12 / m))
        side = quad(lambda t, f=ds: np.sin(t) * f(t), 0, 2 * np.pi, limit=200)[0]
        assert abs(side) < 1e-9  # the loop closes onto the braid axis


def test_master_curve_matches_solver(jawed):
    ratio_e, ratio_f = jawed.master_curve()
    fe = sp.lambdify((jawed.x, jawed.lam), ratio_e, "numpy")
    ff = sp.lambdify(jawed.x, ratio_f, "numpy")
    h, b = 1e-3, 2e-4
    for _ in range(8):
        n, m = int(rng.integers(1, 6)), rng.uniform(0.05, 1.0)
        e = n**2 * h * 10 ** rng.uniform(1.2, 4)
        kn = knots.overhand_knot(
            end_to_end_shortening=e, turns=n, mu=m, rod_radius=h, bending_stiffness=b
        )
        x = kn.braid_length / kn.loop_radius
        lam_r = kn.loop_length / kn.loop_radius
        assert fe(x, lam_r) == pytest.approx(n**2 * h / e, rel=1e-8)
        assert ff(x) == pytest.approx(n**2 * kn.force * h**2 / (m * b), rel=1e-8)


def test_audoly_loose_knot(audoly):
    force_e, force_r, scaled = audoly.loose_knot_force()
    eps = sp.symbols("epsilon", positive=True)
    assert sp.simplify(scaled - eps**4 / 2) == 0
    fe = sp.lambdify((audoly.B, audoly.e), force_e, "numpy")
    fr = sp.lambdify((audoly.B, audoly.R), force_r, "numpy")
    b = 10 ** rng.uniform(-6, 0, 10)
    e = 10 ** rng.uniform(-2, 1, 10)
    np.testing.assert_allclose(
        fe(b, e),
        knots.loose_knot_force_from_shortening(end_to_end_shortening=e, bending_stiffness=b),
        rtol=1e-12,
    )
    np.testing.assert_allclose(
        fr(b, e), knots.loose_knot_force(loop_radius=e, bending_stiffness=b), rtol=1e-12
    )
