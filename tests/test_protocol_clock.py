"""The hold protocol runs on the rod's flexural clock, so a DER hold run (and a table) is
the same for every material: ``knotmech.scenes.phase_table.protocol_time_scale``."""

import math

import numpy as np
import pytest

from knotmech.errors import InputError
from knotmech.scenes import phase_table as pt


def test_time_scale_is_the_flexural_time_over_the_reference_rods():
    """s = d / (sqrt(kappa) sqrt(E/rho)) / t_ref with t_ref the VPS32 rod's 4 mm /
    sqrt(1.26 MPa / 1150 kg/m^3) = 0.1208 ms."""
    assert pt.REFERENCE_FLEXURAL_TIME == pytest.approx(4e-3 / math.sqrt(1.26e6 / 1150), rel=1e-12)
    assert pt.REFERENCE_FLEXURAL_TIME == pytest.approx(1.2085e-4, rel=1e-4)
    assert pt.protocol_time_scale() == 1.0
    nylon = dict(rod_diameter=6e-3, youngs_modulus=0.25e9, density=1140.0)
    s1 = pt.protocol_time_scale(**nylon)
    assert s1 == pytest.approx(1.5 * math.sqrt(1.26e6 / 1150 / (0.25e9 / 1140)), rel=1e-12)
    # kappa 0.01: bending waves ten times slower, so ten times the protocol seconds
    assert pt.protocol_time_scale(**nylon, bending_scale=0.01) == pytest.approx(10 * s1)
    for bad in (dict(rod_diameter=-1.0), dict(density=float("nan")), dict(bending_scale=0.0)):
        with pytest.raises(InputError):
            pt.protocol_time_scale(**bad)


def test_a_table_stores_creep_on_the_protocol_clock():
    r = {"creep_speed": 2e-3, "creep_window_s": 5.0, "time_scale": 10.0}
    out = pt._on_protocol_clock(r)
    assert out["creep_speed"] == pytest.approx(2e-2) and out["creep_window_s"] == pytest.approx(0.5)
    assert pt._on_protocol_clock({"creep_speed": 1e-3}) == {"creep_speed": 1e-3}


def test_two_materials_make_the_same_dimensionless_run():
    """A solid rod of nylon's E and density (0.25 GPa, 1140 kg/m^3) and the VPS32 rod, both 4
    mm, at d/2R 0.1176, 0.1 EA, mu 0.3: on the flexural clock (s = 0.0707 for the nylon)
    the loaded end follows the same path in rod diameters, frame by frame, and takes the
    same steps. In seconds (s = 1) the nylon rod rings with a drag 14 times weaker against
    its own elastic rate, and runs off."""
    kw = dict(d_over_2R=0.1176, t_over_EA=0.1, mu=0.3, n_nodes=120, hold_time=0.3,
              keep_result=True)  # fmt: skip
    sil = pt.simulate_point(**kw)
    nyl = pt.simulate_point(**kw, youngs_modulus=0.25e9, density=1140.0)
    assert nyl["time_scale"] == pytest.approx(math.sqrt(1.26e6 / 1150 / (0.25e9 / 1140)))
    a, b = sil["result"], nyl["result"]
    d = 4e-3
    ua, ub = np.asarray(a.end_displacement) / d, np.asarray(b.end_displacement) / d
    assert ua.shape == ub.shape and np.max(np.abs(ua)) > 5  # the hitch re-seats by > 5 d
    np.testing.assert_allclose(ub, ua, atol=1e-3)
    np.testing.assert_allclose(np.asarray(b.times) / nyl["time_scale"], a.times, rtol=1e-9)
    assert a.stats["steps"] == b.stats["steps"]
    assert sil["verdict"] == nyl["verdict"]
    assert nyl["creep_speed_protocol"] == pytest.approx(nyl["creep_speed"] * nyl["time_scale"])
    # in seconds the nylon rod's run is another run: its loaded end runs off the post
    sec = pt.simulate_point(**kw, youngs_modulus=0.25e9, density=1140.0, time_scale=1.0)
    assert sec["ran_to_end"] is False and sec["verdict"] == "slip"
