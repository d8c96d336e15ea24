"""Issue 26: no RuntimeWarning, no NaN or infinity from a zero standard deviation.

A remainder whose high-frequency sd is zero (more than half of its second differences
vanish: noise-free, constant or quantised readings) once divided by zero in the noise
floor (``noisefloor._level``), overflowed ``R**2`` (an ``OverflowError`` reported as a
numerical failure), or reached the engine's white noise model with sd 0 (a NaN in every
whitening of ``stats`` and ``locate._whiten_cols``). Now that sd is the engine noise
model's floor, 1e-7 of the model's largest value, flagged ``hf_floored``; a
:class:`NoiseModel` of zero scale is refused. The numbers below are exact (a floor of
1e-7, a root mean square computed by hand) or the engine's verdicts on 50-row recordings
before the change (where it gave one), run with every RuntimeWarning an error.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from knotmech.diagnose import diagnose, make_recording
from knotmech.diagnose.noisefloor import (
    HF_SD_FLOOR,
    _level,
    _log_level_z,
    _rho_needed,
    noise_floor,
)
from knotmech.diagnose.stats import NoiseModel, trial_starts
from knotmech.errors import DiagnoseError

pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")


def test_level_of_a_column_without_high_frequency_noise_is_zero_or_infinite():
    seg = np.zeros(9, int)
    zero = np.zeros((9, 1))
    kink = np.abs(np.arange(9.0) - 4.0)[:, None]  # one nonzero second difference of 7
    assert _level(zero, seg)[0] == 0.0
    assert _level(kink, seg)[0] == math.inf


def test_level_of_a_noisy_column_is_rms_over_hf_sd():
    # second differences of (0, 1, 0, 1, ...) alternate +2, -2: MAD 2, sd 1.4826 * 2 / sqrt 6
    u = np.tile([0.0, 1.0], 5)[:, None]
    sd = 1.482602218505602 * 2.0 / math.sqrt(6.0)
    assert _level(u, np.zeros(10, int))[0] == pytest.approx(math.sqrt(0.5) / sd, rel=1e-15)


def test_rho_needed_and_log_level_at_the_extremes():
    assert _rho_needed(1e200) == 1.0  # R**2 would overflow
    assert _rho_needed(math.inf) == 1.0
    assert _rho_needed(2.0) == pytest.approx(2.0 - math.sqrt(1.75), rel=1e-15)
    assert _log_level_z(0.0, np.array([1.0, 2.0]), 1.0) == -math.inf


@pytest.mark.parametrize("scale", [0.0, -1.0, math.nan, math.inf])
def test_noise_model_of_zero_or_non_finite_scale_is_refused(scale):
    with pytest.raises(DiagnoseError, match="noise model"):
        NoiseModel(scale, 0.0, 0.0, 1.0)


def test_noise_model_of_zero_reference_level_is_refused():
    with pytest.raises(DiagnoseError, match="noise model"):
        NoiseModel(1.0, 0.0, 0.0, 0.0)


def test_noise_model_of_a_zero_sigma_column_is_refused():
    with pytest.raises(DiagnoseError, match="sigma column"):
        NoiseModel(1.0, 0.0, 0.0, 1.0, np.array([1.0, 0.0, 1.0]))


def test_noise_floor_of_a_kinked_remainder_uses_the_floor():
    """A V-shaped remainder: high-frequency sd 0, so sigma_hf = 1e-7 * fref, and the level
    is its rms over that (rms of |i - 25| / 4 for i < 50: sqrt(sum / 50) / 4; quarters
    are exact in binary, so the second differences are exactly 0 but at the kink)."""
    n = 50
    x = np.arange(n, dtype=float)
    resid = 0.25 * np.abs(x - 25.0)
    trial = np.zeros(n, int)
    mean = np.full(n, 2.0)
    noise = NoiseModel(0.01, 0.0, 0.0, 2.0)
    nf = noise_floor(resid, x, trial, noise, mean, trial_starts(trial),
                     np.random.default_rng(0), draws=199)  # fmt: skip
    rms = 0.25 * math.sqrt(np.sum((x - 25.0) ** 2) / n)
    assert nf.hf_floored
    assert nf.sigma_hf == HF_SD_FLOOR * 2.0
    assert nf.level == pytest.approx(rms / 2e-7, rel=1e-14)
    assert nf.p_level == pytest.approx(1.0 / 200.0)
    out = nf.describe()
    assert out["hf_floored"] is True and out["sigma_hf"] == 2e-7
    json.dumps(out, allow_nan=False)


# --- the engine on extreme 50-row recordings ------------------------------------------


def _base(kind):
    rec, _ = make_recording(kind, n=50, seed=1)
    meta = {k: v for k, v in rec.metadata.items() if k != "experiment"}
    rep = diagnose(rec)
    r = rep.fits["recording"]
    return r.x, r.y, rep.fits["baseline"].mean, meta


def _y(how, y, fit):
    n = y.size
    if how == "exact_fit":  # the baseline's own mean: a remainder of round-off only
        return fit
    out = np.full(n, y[0])
    if how == "const_but_one":
        out[-1] = 1.5 * y[0]
    elif how == "const_but_mid":
        out[n // 2] = 1.5 * y[0]
    elif how == "zeros_but_one":
        out = np.r_[np.zeros(n - 1), 1.0]
    return out


#: (kind, readings, control, sigma column, verdict); the verdicts of the cases marked
#: "before" are those of the engine before issue 26 (the others were a numerical failure,
#: exit 2: an OverflowError of R**2 in noise_floor, or NaN from a white model of sd 0)
CASES = [
    ("pinch", "exact_fit", "x", None, "none"),  # before
    ("tension_profile", "exact_fit", "x", None, "none"),  # before
    ("capstan_pull", "exact_fit", "x", None, "none"),  # before
    ("pinch", "zeros_but_one", "x", None, "unexplained"),  # before
    ("tension_profile", "const_but_one", "offset", None, "undetermined"),  # before
    ("tension_profile", "const_but_mid", "offset", None, "unexplained"),  # was NaN
    ("capstan_pull", "const_but_mid", "x", None, "unexplained"),  # was OverflowError
    ("capstan_pull", "exact_fit", "x", 1.0, "none"),  # was OverflowError
    ("pinch", "const_but_one", "x", None, "adhesion"),  # was OverflowError
]


@pytest.fixture(scope="module")
def bases():
    return {k: _base(k) for k in ("capstan_pull", "pinch", "tension_profile")}


def _finite_or_null(obj, path="report"):
    if isinstance(obj, dict):
        for k, v in obj.items():
            _finite_or_null(v, f"{path}.{k}")
    elif isinstance(obj, list | tuple):
        for i, v in enumerate(obj):
            _finite_or_null(v, f"{path}[{i}]")
    elif isinstance(obj, float):
        assert math.isfinite(obj), path


@pytest.mark.parametrize(("kind", "how", "control", "sigma", "verdict"), CASES)
def test_extreme_recordings_give_finite_reports_without_warnings(
    bases, kind, how, control, sigma, verdict
):
    x, y, fit, meta = bases[kind]
    if control == "offset":
        x = x * 1e-3 + 1e3
    yy = _y(how, y, fit)
    sig = None if sigma is None else np.full(yy.size, sigma)
    rep = diagnose(experiment=kind, x=x, y=yy, metadata=meta, sigma=sig)
    assert rep.verdict == verdict
    out = rep.to_dict()
    _finite_or_null(out)
    json.dumps(out, allow_nan=False)
    floor = out.get("noise_floor")
    if floor is not None and floor.get("hf_floored"):
        fref = float(np.max(np.abs(rep.fits["final"].mean)))
        assert floor["sigma_hf"] == float(f"{HF_SD_FLOOR * fref:.3g}")
