"""Shared strings and helpers of the catalogue modules."""

from __future__ import annotations

import numpy as np

CLOVE = (
    "clove-hitch paper: Exploring the inner workings of the clove hitch knot, "
    "Extreme Mech. Lett. (2022), doi:10.1016/j.eml.2022.101788"
)


def fmt(v, digits=3) -> str:
    """``v`` with ``digits`` significant digits."""
    return f"{v:.{digits}g}"


def ln_speed(rec) -> np.ndarray:
    """ln(v / v_ref) per row, v_ref the geometric-mean speed."""
    v = rec.speed
    return np.log(v) - np.mean(np.log(v))


def reference_speed(rec) -> float:
    """Geometric-mean sliding speed [m/s] (the speed at which ``mu`` is reported)."""
    return float(np.exp(np.mean(np.log(rec.speed))))


def amplitude_for_size(mean_of, mean0, sd, size, a0) -> float:
    """Amplitude ``a`` of an effect whose largest change ``max |mean_of(a) - mean0| / sd``
    equals ``size`` (secant steps from ``a0``; the change is nearly linear in ``a``)."""
    a = float(a0)
    for _ in range(3):
        change = float(np.max(np.abs(mean_of(a) - mean0) / sd))
        if change <= 0:
            return a
        a = a * size / change
    return a


def amplitude_beyond_mu(mean_of, baseline_of_mu, mu0, sd, size, a0) -> float:
    """Amplitude ``a`` whose change *beyond what a refitted mu absorbs* is ``size`` sd.

    For an effect that mu can partly mimic (a curvature of ln T in the wrap angle, a
    level at zero wrap), the size that the data can show is the largest
    ``|mean_of(a) - baseline_of_mu(mu*)| / sd`` with ``mu*`` the least-squares mu (in
    units of sd) of the baseline fitted to ``mean_of(a)``; the change is nearly linear in
    ``a``, so three secant steps from ``a0`` find it.
    """
    from scipy.optimize import minimize_scalar

    def change(a):
        target = mean_of(a)
        res = minimize_scalar(
            lambda mu: float(np.sum(((target - baseline_of_mu(mu)) / sd) ** 2)),
            bounds=(max(mu0 - 0.5, 0.0), mu0 + 0.5),
            method="bounded",
            options={"xatol": 1e-10},
        )
        return float(np.max(np.abs(target - baseline_of_mu(res.x)) / sd))

    a = float(a0)
    for _ in range(3):
        c = change(a)
        if c <= 0:
            return a
        a = a * size / c
    return a
