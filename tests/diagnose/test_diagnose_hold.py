"""``capstan_hold`` (spec section 5): the kind, its effects, the yarn rig's recording.

Verification: the baseline is the ideal capstan in both directions; each effect at its
no-effect value is the baseline and at small amplitude matches its closed form in
:mod:`knotmech.analytic.capstan` (Howell's law exactly, the bending lift-off to O(B^2)).
Regression: the shipped yarn-rig recording is what the converter makes of the raw
streams, its holds agree with the rig's own summary, and its diagnosis.
"""

from pathlib import Path

import numpy as np
import pytest

from knotmech.analytic.capstan import capstan_high_tension_nonlinear, capstan_ratio_bending
from knotmech.diagnose import diagnose, make_recording, parse_recording, read_recording
from knotmech.diagnose.baselines import MEANS
from knotmech.diagnose.recording import Recording, recording_from_arrays
from knotmech.diagnose.rigs import capstan_yarn_rig, plateau_windows
from knotmech.errors import InputError, RecordingError

RIG = Path("/work/shared/reference/capstan-yarn-rig")
SHIPPED = Path(__file__).parents[2] / "knotmech" / "data" / "recordings" / "capstan_yarn_rig.csv"
TH = np.linspace(0.5, 6.0, 12)
W, R = 5.0, 0.02


def _rec(sign, meta=None):
    meta = {"load_N": W, "post_diameter_m": 2 * R, **(meta or {})}
    return Recording(
        "capstan_hold",
        TH,
        np.zeros_like(TH),
        meta,
        None,
        np.zeros(TH.size, int),
        None,
        extra={"direction": np.full(TH.size, sign)},
    )


def test_baseline_is_the_ideal_capstan_both_ways_and_no_effect_values_vanish():
    mean = MEANS["capstan_hold"]
    for s in (1.0, -1.0):
        rec = _rec(s)
        base = mean(rec, {"mu": 0.3}, ())
        assert np.allclose(base, W * np.exp(s * 0.3 * TH), rtol=1e-14)
        p = {"mu": 0.3, "bending_loss": 0.0, "bending_number": 0.0, "friction_exponent": 1.0}
        p["sensor_offset_N"] = 0.0
        for eff in ("bending_resistance", "bending_stiffness", "pressure_dependent_friction"):
            assert np.allclose(mean(rec, p, (eff,)), base, rtol=1e-13)
        assert np.allclose(mean(rec, p, ("sensor_offset",)), base, rtol=1e-13)


def test_pressure_dependent_friction_is_howells_capstan():
    # raise: T_low = W; dT/dtheta = mu W^(1-n) T^n is Howell's a R^(1-n) T^n with
    # a = mu (W/R)^(1-n) (analytic.capstan_high_tension_nonlinear)
    n, mu = 0.7, 0.3
    got = MEANS["capstan_hold"](
        _rec(1.0), {"mu": mu, "friction_exponent": n}, ("pressure_dependent_friction",)
    )
    want = capstan_high_tension_nonlinear(
        low_tension=W,
        wrap_angle=TH,
        friction_coefficient=mu * (W / R) ** (1 - n),
        friction_exponent=n,
        radius=R,
    )
    assert np.allclose(got, want, rtol=1e-12)


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_bending_stiffness_matches_the_lift_off_capstan_to_first_order(sign):
    mu = 0.3

    def errors(b):
        got = MEANS["capstan_hold"](
            _rec(sign), {"mu": mu, "bending_number": b}, ("bending_stiffness",)
        )
        lo, hi = (W, got) if sign > 0 else (got, W)
        exact = capstan_ratio_bending(
            mu, TH, bending_stiffness=b * R**2 * W, low_tension=lo, high_tension=hi, radius=R
        )
        ratio = hi / lo
        assert np.all(ratio < np.exp(mu * TH))  # stiff ropes grip less (Jung et al. 2008)
        return np.max(np.abs(ratio / exact - 1)), np.max(np.abs(ratio * np.exp(-mu * TH) - 1))

    # the first-order form misses the exact one by O(eps^3) = O(B^1.5) (the lift-off
    # angles are O(eps), eps^2 = B/(T R^2)): under 5 % of the O(B) change at b = 2e-3,
    # and the relative miss halves when B is quartered
    err, change = errors(2e-3)
    err4, change4 = errors(5e-4)
    assert err < 0.05 * change
    assert err4 / change4 == pytest.approx(0.5 * err / change, rel=0.15)


def test_recording_columns_words_and_metadata():
    text = "\n".join(
        ["# experiment: capstan_hold", "# load_N: 4.0", "wrap_angle_rad,T_N,direction"]
        + [
            f"{a},{4 * np.exp(s * 0.2 * a):.5f},{w}"
            for a in (1, 2, 3)
            for s, w in ((1, "raise"), (-1, "Lower"))
        ]
    )
    rec = parse_recording(text + "\n")
    assert rec.n == 6 and list(rec.extra["direction"]) == [1, -1] * 3
    with pytest.raises(RecordingError, match="line 4: column direction must read raise or lower"):
        parse_recording(text.replace("raise", "up", 1) + "\n")
    with pytest.raises(RecordingError, match="needs '# direction: raise'"):
        parse_recording(
            text.replace(",direction", "").replace(",raise", "").replace(",Lower", "") + "\n"
        )
    with pytest.raises(RecordingError, match="needs '# load_N: ...' metadata or a load_N column"):
        parse_recording(text.replace("# load_N: 4.0\n", "") + "\n")
    short = "\n".join(text.splitlines()[:6]) + "\n"
    with pytest.raises(RecordingError, match="3 data rows; a recording needs at least 5"):
        parse_recording(short)
    rec = recording_from_arrays(
        "capstan_hold",
        [1, 2, 3, 4, 5],
        [3, 2.5, 2, 1.6, 1.3],
        metadata={"load_N": 4.0},
        columns={"direction": ["lower"] * 5},
    )
    assert np.all(rec.extra["direction"] == -1)
    # 6 readings at 2 wrap angles: the reader refuses a control variable with fewer than 3
    # values before the engine would count 2 holds (fewer than the 5 a hold recording needs)
    with pytest.raises(InputError, match="only 2 distinct values of wrap_angle_rad"):
        recording_from_arrays(
            "capstan_hold",
            [1, 1, 1, 2, 2, 2],
            [3, 3.1, 3, 2.5, 2.4, 2.5],
            metadata={"load_N": 4.0},
            columns={"direction": ["lower"] * 6},
        )
    rec = recording_from_arrays(
        "capstan_hold",
        [1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4],
        [3, 3.1, 3, 2.5, 2.4, 2.5, 2.0, 2.1, 2.0, 1.6, 1.7, 1.6],
        metadata={"load_N": 4.0},
        columns={"direction": ["lower"] * 12},
    )
    with pytest.raises(InputError, match="12 readings of 4 holds .* at least 5 holds"):
        diagnose(rec)


@pytest.mark.parametrize(
    ("effect", "seed"),
    [
        ("bending_resistance", 31),
        ("sensor_offset", 32),
        ("bending_stiffness", 33),
        ("pressure_dependent_friction", 34),
    ],
)
def test_hold_effects_are_named(effect, seed):
    rec, truth = make_recording("capstan_hold", effect, size=8.0, seed=seed, n=240)
    rep = diagnose(rec, seed=seed)
    assert rep.verdict == effect
    par = rep.effects[0]["parameters"]
    name = next(iter(k for k in truth if k in par))
    assert par[name] == pytest.approx(truth[name], rel=0.35, abs=0.02 * abs(truth[name]) + 1e-9)


def _sensor_resolution(seed, *, quantum, n_outliers):
    rec, truth = make_recording("capstan_hold", None, noise="ar1", rho=0.9, seed=seed, n=240)
    sd = float(np.median(truth["noise_sd"]))
    y = np.round(rec.y / (quantum * sd)) * quantum * sd
    rng = np.random.default_rng(seed)
    idx = rng.choice(rec.n, n_outliers, replace=False)
    y[idx] += 12 * sd * rng.choice([-1.0, 1.0], n_outliers)
    return Recording(
        rec.experiment, rec.x, y, rec.metadata, None, rec.trial, None, "<q>", rec.columns, rec.extra
    )


@pytest.mark.parametrize("seed", [200, 201, 202])
def test_quantised_correlated_null_with_outliers_is_none(seed):
    # readings on a grid of 1.5 noise sd (a sensor at its resolution), AR(1) rho = 0.9,
    # three spikes of 12 sd
    rec = _sensor_resolution(seed, quantum=1.5, n_outliers=3)
    assert np.unique(rec.y).size < 0.7 * rec.n
    rep = diagnose(rec, seed=seed)
    assert rep.verdict == "none"


@pytest.mark.skipif(not RIG.exists(), reason="the rig's raw streams are not on this machine")
def test_yarn_rig_converter_reproduces_the_shipped_recording_and_the_rig_summary():
    text, rows = capstan_yarn_rig(RIG)
    assert text == SHIPPED.read_text(encoding="utf-8")
    assert len(rows) == 22  # 7 angles x 3 loadings, and a fourth loading at 270 degrees
    summary = np.genfromtxt(RIG / "capstan_summary.csv", delimiter=",", names=True)
    for deg, mid in zip(
        summary["nominal_wrap_deg"], summary["hold_force_N_midrange_all_trials"], strict=True
    ):
        mine = [r["force_N"] for r in rows if r["nominal_deg"] == int(deg)]
        # the rig's value: midrange of its 10 s windows, +-0.03-0.18 N; at 270 degrees it
        # left out one of the four loadings (mean 3.493 with it, 3.429 without)
        assert np.mean(mine) == pytest.approx(mid, abs=0.07)
    t = np.arange(0, 30, 0.02)
    f = np.where((t > 5) & (t < 25), 3.0, 0.0) + 0.0066 * np.round(np.sin(7 * t))
    holds = plateau_windows(t, f, window_s=10.0)
    assert len(holds) == 1 and holds[0].window == pytest.approx((10.0, 20.0), abs=0.05)


def test_yarn_rig_diagnosis():
    rec = read_recording(SHIPPED)
    assert rec.n == 22 and rec.meta("load_N") == pytest.approx(7.8829, abs=1e-3)
    rep = diagnose(rec, seed=0)
    # one mu for all angles: 0.179 (least squares of ln(W/T) on theta gives 0.1790)
    assert rep.baseline["parameters"]["mu"] == pytest.approx(0.178, abs=0.002)
    # the per-angle means scatter about the capstan curve beyond the replicate scatter
    # (classical lack-of-fit F = 4.9 on (6, 15) dof, p = 0.006) in no catalogue shape: no
    # effect is accepted, and the structure test sits near alpha (p = 0.0013-0.021 over
    # bootstrap seeds 0-5; at seed 0 p = 0.0024 and the verdict is unexplained)
    assert all(not ev["accepted"] for ev in rep.details["candidates"])
    assert rep.details["located"]["baseline_residuals"]["p_value"] < 0.03
    assert rep.verdict in ("unexplained", "none")
