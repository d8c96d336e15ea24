"""The public names other tools call (issue 2) stay importable from ``knotmech`` and
give the published numbers."""

import inspect

import numpy as np
import pytest

import knotmech


def test_required_names_and_signatures():
    expected = {
        "capstan_ratio": ["mu", "wrap_angle"],
        "mu_eff": ["mu", "D_over_d"],
        "film_thickness_plate": ["viscosity", "speed", "surface_tension", "density"],
        "film_thickness_fibre": ["radius", "viscosity", "speed", "surface_tension"],
        "pinch_load_parameter": [
            "normal_force",
            "youngs_modulus",
            "rod_diameter",
            "pinch_diameter",
        ],
        "overhand_pull_force": [
            "end_to_end_shortening",
            "turns",
            "mu",
            "rod_radius",
            "bending_stiffness",
        ],
    }
    for name, params in expected.items():
        func = getattr(knotmech, name)
        assert list(inspect.signature(func).parameters)[: len(params)] == params, name


def test_mu_eff_reference_values():
    # clove-hitch paper (Extreme Mech. Lett. 2022) eq. 3; values quoted in issue 2
    got = knotmech.mu_eff(0.3, np.array([1.0, 2.0, 5.0, 10.0]))
    np.testing.assert_allclose(got, [0.147, 0.196, 0.247, 0.271], atol=5e-4)


def test_capstan_euler_value():
    # exp(0.5 pi) = 4.810, the ratio quoted in issue 4 for mu = 0.5, theta = pi
    assert knotmech.capstan_ratio(0.5, np.pi) == pytest.approx(4.8105, rel=1e-4)


def test_pinch_load_parameter_definition():
    # x = 4 F_n / (pi E d D): F_n = pi E d D / 40 must give exactly 0.1
    E, d, D = 1.26e6, 4e-3, 8e-3
    assert knotmech.pinch_load_parameter(np.pi * E * d * D / 40, E, d, D) == pytest.approx(0.1)


def test_lazy_subpackages_and_errors():
    assert callable(knotmech.simulate)
    assert callable(knotmech.diagnose_recording)
    with pytest.raises(AttributeError):
        knotmech.no_such_name  # noqa: B018
    with pytest.raises(knotmech.InputError, match="D_over_d"):
        knotmech.mu_eff(0.3, -1.0)
