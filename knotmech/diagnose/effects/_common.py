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
    equals ``size`` (two secant steps from ``a0``; the change is nearly linear in ``a``)."""
    a = float(a0)
    for _ in range(3):
        change = float(np.max(np.abs(mean_of(a) - mean0) / sd))
        if change <= 0:
            return a
        a = a * size / change
    return a
