"""Clove hitch: Darboux vector of analytic curves (default run); tied and loaded (slow)."""

import numpy as np
import pytest

from knotmech.errors import InputError
from knotmech.scenes.clove_hitch import clove_hitch, darboux_profile


def helix_with_frenet_frame(n, a=1.0, c=0.5, turns=2.0):
    t = np.linspace(0.0, 2 * np.pi * turns, n)
    x = np.column_stack([a * np.cos(t), a * np.sin(t), c * t])
    mid = 0.5 * (t[1:] + t[:-1])
    normal = -np.column_stack([np.cos(mid), np.sin(mid), 0 * mid])  # principal normal
    return x, normal


def test_darboux_of_helix_is_curvature_and_torsion():
    """Frenet frame of a helix: Omega = (0, kappa, tau), kappa = a/(a^2+c^2), tau = c/(a^2+c^2)."""
    a, c = 1.0, 0.5
    kappa, tau = a / (a * a + c * c), c / (a * a + c * c)
    errs = []
    ns = [101, 201, 401, 801]
    for n in ns:
        x, m1 = helix_with_frenet_frame(n, a, c)
        _, om = darboux_profile(x, m1)
        err = np.max(np.abs(om - [0.0, kappa, tau]))
        errs.append(err)
    assert errs[-1] < 1e-4 * kappa
    # second-order convergence in the edge length
    rate = np.polyfit(np.log(1.0 / (np.array(ns) - 1)), np.log(errs), 1)[0]
    assert rate == pytest.approx(2.0, abs=0.2)


def test_darboux_of_twisted_straight_rod():
    n, w = 51, 3.0
    s = np.linspace(0.0, 1.0, n)
    x = np.column_stack([0 * s, 0 * s, s])
    mid = 0.5 * (s[1:] + s[:-1])
    m1 = np.column_stack([np.cos(w * mid), np.sin(w * mid), 0 * mid])
    s_nodes, om = darboux_profile(x, m1)
    assert np.allclose(om[:, :2], 0.0, atol=1e-12)
    assert np.allclose(om[:, 2], w, rtol=1e-12)
    assert np.allclose(s_nodes, s[1:-1])


def test_bad_input():
    with pytest.raises(InputError):
        clove_hitch(loading="twisted")
    with pytest.raises(InputError):
        clove_hitch(loading="asymmetric")  # t_low missing
    with pytest.raises(InputError):
        clove_hitch(loading="free", t_low=0.5)
    with pytest.raises(InputError):
        clove_hitch(rod_length=0.1)
