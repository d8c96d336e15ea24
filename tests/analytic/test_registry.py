"""Sweep every registered closed form: finite on valid input, broadcasting, InputError, limits."""

import numpy as np
import pytest

from knotmech.analytic import registry
from knotmech.errors import InputError

NAMES = registry.names()
REQUIRED = [
    "film_thickness_plate",
    "film_thickness_fibre",
    "pinch_load_parameter",
    "overhand_pull_force",
    "coated_rod_mu",
    "coated_rod_volume_fraction",
]


def test_required_names_are_registered():
    for name in REQUIRED:
        assert name in registry.REGISTRY
    try:
        from knotmech.analytic import capstan
    except ImportError:
        return
    for name in ("capstan_ratio", "mu_eff"):
        if hasattr(capstan, name):
            assert name in registry.REGISTRY


@pytest.mark.parametrize("name", NAMES)
def test_finite_on_sample_and_documented(name):
    cf = registry.get(name)
    value = cf()
    assert np.all(np.isfinite(value)), f"{name} not finite at its sample {dict(cf.sample)}"
    assert cf.func.__doc__ and len(cf.func.__doc__.strip()) > 20


@pytest.mark.parametrize("name", NAMES)
def test_broadcasts_over_arrays(name):
    cf = registry.get(name)
    args = cf.positive + cf.nonnegative
    for arg in args:
        out = cf(**{arg: np.full(3, cf.sample[arg])})
        assert out.shape == (3,), f"{name}: {arg} as an array of 3 gave shape {out.shape}"
        np.testing.assert_allclose(out, cf(), rtol=1e-12)


@pytest.mark.parametrize("name", NAMES)
def test_nan_and_negative_input_raise(name):
    cf = registry.get(name)
    for arg in cf.positive + cf.nonnegative:
        sample = np.asarray(cf.sample[arg], dtype=float)
        for bad in (np.nan, -1.0 * max(float(sample), 1.0)):
            with pytest.raises(InputError):
                cf(**{arg: bad})
    for arg in cf.positive:
        with pytest.raises(InputError):
            cf(**{arg: 0.0})


@pytest.mark.parametrize("name", [n for n in NAMES if registry.get(n).limits])
def test_known_limits(name):
    cf = registry.get(name)
    for limit in cf.limits:
        np.testing.assert_allclose(
            cf(**limit.overrides),
            limit.expected,
            rtol=limit.rtol,
            atol=0,
            err_msg=limit.description,
        )


def test_register_and_lookup():
    @registry.register(sample={"x": 2.0}, positive=("x",), name="_toy")
    def toy(x):
        """Toy closed form used by this test only."""
        return np.sqrt(x)

    try:
        assert registry.evaluate("_toy") == pytest.approx(np.sqrt(2.0))
        assert registry.evaluate("_toy", x=9.0) == pytest.approx(3.0)
        assert toy(4.0) == 2.0  # the decorator returns the function unchanged
    finally:
        del registry.REGISTRY["_toy"]
    with pytest.raises(KeyError, match="known"):
        registry.get("_toy")
