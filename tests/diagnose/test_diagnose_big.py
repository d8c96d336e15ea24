"""Long recordings (issue 14 part 3): nip positions at 2e3-1e6 rows, the O(n log n)
gap scan, thinned bootstrap draws and the reader's fast path."""

from __future__ import annotations

import numpy as np
import pytest

from knotmech.diagnose import diagnose, fitting, get_effect, parse_recording, recording_from_arrays
from knotmech.diagnose.effects.self_contact_nip import _step_sums
from knotmech.diagnose.fitting import thinned_noise, thinned_rows, whiten_columns
from knotmech.diagnose.stats import NoiseModel, trial_starts
from knotmech.errors import RecordingError

META = {"T_high_N": 10.0, "rod_diameter_m": 0.004, "post_diameter_m": 0.016}


def _nip_recording(n, seed=0):
    """T = 10 N exp(-0.3 s / 0.01 m), a 3 % drop at s = 0.05 m, 0.01 N white noise
    (the step is 6.7 noise sd), s from 0 to 0.1 m."""
    rng = np.random.default_rng(seed)
    x = np.linspace(0.0, 0.1, n)
    t = 10.0 * np.exp(-0.3 * x / 0.01) * np.where(x > 0.05, 0.97, 1.0)
    return recording_from_arrays(
        "tension_profile", x, t + 0.01 * rng.standard_normal(n), metadata=META
    )


@pytest.mark.parametrize("rho", [0.0, 0.6, 0.97, -0.3])
def test_step_sums_equal_the_whitened_step_columns(rho):
    """The O(n log n) sums equal products of the explicit (n, M) whitened step columns."""
    rng = np.random.default_rng(1)
    n = 300
    s = rng.uniform(0.0, 1.0, n)
    starts = trial_starts(np.repeat([0, 1, 2], 100))
    g, w = rng.normal(size=n), rng.normal(size=n)
    cuts = np.sort(rng.uniform(0.0, 1.0, 50))
    cols = g[:, None] * (s[:, None] > cuts[None, :])
    e = whiten_columns(NoiseModel(1.0, 0.0, rho, 1.0), np.ones(n), starts, cols)
    (lin,), quad = _step_sums(s, g, [w], rho, starts, cuts)
    np.testing.assert_allclose(lin, w @ e, rtol=1e-10, atol=1e-10)
    np.testing.assert_allclose(quad, np.sum(e * e, axis=0), rtol=1e-10, atol=1e-10)


@pytest.mark.parametrize("n", [2000, 30_000, 100_000])
def test_nip_position_found_at_any_row_count(n):
    """A 3 % drop at s = 0.05 m is found within 3 gaps and named (before: 67 gaps off at
    3e4 rows and 360 at 1e5, both `unexplained`)."""
    rep = diagnose(_nip_recording(n), seed=0)
    assert rep.verdict == "self_contact_nip"
    pos = rep.final["parameters"]["positions_m"]
    assert len(pos) == 1
    gap = 0.1 / (n - 1)
    assert abs(pos[0] - 0.05) <= 3 * gap + 5e-7  # + the report's 6 significant digits
    assert rep.final["parameters"]["drop_fractions"][0] == pytest.approx(0.03, abs=0.003)


@pytest.mark.slow
def test_nip_position_found_at_a_million_rows():
    n = 1_000_000
    rep = diagnose(_nip_recording(n), seed=0)
    assert rep.verdict == "self_contact_nip"
    (pos,) = rep.final["parameters"]["positions_m"]
    assert abs(pos - 0.05) <= 3 * 0.1 / (n - 1) + 5e-7


def test_thinned_rows_keep_trial_starts_and_ar1_thins_to_rho_power_k():
    trial = np.repeat([0, 1, 2], [5000, 3001, 2000])
    starts = trial_starts(trial)
    rows, k = thinned_rows(starts, 4000)
    assert k == 3
    assert set(np.flatnonzero(starts)) <= set(rows)
    assert np.all(np.diff(rows)[~starts[rows][1:]] == 3)
    assert rows.size == 1667 + 1001 + 667
    # AR(1) of rho 0.9, every 3rd row: lag-one correlation 0.729
    rng = np.random.default_rng(3)
    noise = NoiseModel(1.0, 0.0, 0.9, 1.0)
    z = noise.sample(np.zeros(200_000), trial_starts(np.zeros(200_000)), rng)
    rows, k = thinned_rows(trial_starts(np.zeros(200_000)), 20_000)
    zt = z[rows]
    assert thinned_noise(noise, rows, k).rho == pytest.approx(0.9**10)
    r1 = np.corrcoef(zt[1:], zt[:-1])[0, 1]
    assert r1 == pytest.approx(0.9**10, abs=0.03)
    assert thinned_rows(starts, 20_000)[1] == 1


def _csv(rows):
    head = (
        "# knotmech-recording: 1\n# experiment: tension_profile\n# T_high_N: 10\n"
        "# rod_diameter_m: 0.004\n# post_diameter_m: 0.016\narclength_m,tension_N,sigma\n"
    )
    return head + "\n".join(rows) + "\n"


def test_reader_fast_path_equals_cell_by_cell_and_keeps_its_checks():
    rng = np.random.default_rng(0)
    x = np.linspace(0, 0.1, 2000)
    y = 10 * np.exp(-3 * x / 0.1) + 0.01 * rng.standard_normal(x.size)
    rows = [f" {a:.9g} ,{b:.9g},\t0.01" for a, b in zip(x, y, strict=True)]
    rows.insert(7, "   ")
    rec = parse_recording(_csv(rows))
    np.testing.assert_array_equal(rec.x, np.array([float(f"{a:.9g}") for a in x]))
    np.testing.assert_array_equal(rec.y, np.array([float(f"{b:.9g}") for b in y]))
    # a quote sends it down the cell-by-cell path: same numbers
    slow = parse_recording(_csv(rows[:-1] + ['"0.1",' + rows[-1].split(",", 1)[1]]))
    np.testing.assert_array_equal(slow.y, rec.y)
    # the checks, with the line of the bad row (header: line 6; row 1500: line 1507)
    bad = list(rows)
    bad[1500] = "0.05,1e5_0,0.01"
    with pytest.raises(RecordingError, match=r"line 1507: non-numeric cell '1e5_0'"):
        parse_recording(_csv(bad))
    bad = list(rows)
    bad[1500] = "0.05,nan,0.01"
    with pytest.raises(RecordingError, match=r"line 1507: NaN or infinite value in column"):
        parse_recording(_csv(bad))
    bad = list(rows)
    bad[1500] = "0.05,1.0"
    with pytest.raises(RecordingError, match=r"line 1507: expected 3 cells, got 2"):
        parse_recording(_csv(bad))
    bad = list(rows)
    bad[1500] = "0.05,1.0,-0.01"
    with pytest.raises(RecordingError, match=r"line 1507: sigma must be > 0"):
        parse_recording(_csv(bad))
    bad = list(rows)
    bad[1500] = "0.05,1.\u0661,0.01"
    with pytest.raises(RecordingError, match=r"line 1507: .*U\+0661 is not ASCII"):
        parse_recording(_csv(bad))


def test_nip_output_in_place_equals_the_product_of_steps():
    """The nips multiplied in place on the tail of ordered arc lengths (or by mask) give
    the same numbers, bit for bit, as the product of one step per nip."""
    rng = np.random.default_rng(4)
    nip = get_effect("self_contact_nip")
    p = {"nip_position_0": 0.07, "nip_position_1": 0.02, "nip_position_2": 0.05}
    p.update({"nip_drop_0": 0.3, "nip_drop_1": 0.11, "nip_drop_2": 0.013})
    for x in (np.linspace(0.0, 0.1, 1001), rng.uniform(0.0, 0.1, 1001)):
        rec = recording_from_arrays("tension_profile", x, 1.0 + x, metadata=META)
        value = 1.0 + rng.uniform(size=x.size)
        ref = value
        for j in range(3):
            ref = ref * np.where(x > p[f"nip_position_{j}"], 1.0 - p[f"nip_drop_{j}"], 1.0)
        np.testing.assert_array_equal(nip.output(rec, p, value), ref)
    # a row exactly at a nip is above none of it (s > position)
    rec = recording_from_arrays(
        "tension_profile", np.array([0.0, 0.02, 0.05, 0.1] * 2), np.arange(8.0) + 1, metadata=META
    )
    out = nip.output(rec, p, np.ones(8))
    np.testing.assert_allclose(out[:4], [1.0, 1.0, 0.89, 0.89 * 0.987 * 0.7])


def test_heldout_refits_on_thinned_rows_of_a_long_recording(monkeypatch):
    """Beyond FIT_ROWS the held-out refits use every k-th training row: the held-out RMS
    moves by far less than the effect of a nip on it (30 000 rows, k = 2)."""
    rec = _nip_recording(30_000)
    base = fitting.fit_baseline(rec, fitting.Data(rec.y, None, None), trial_starts(rec.trial))
    data = fitting.Data(rec.y, None, None)
    thin = fitting.heldout_rms(base, data, rec.trial)
    monkeypatch.setattr(fitting, "FIT_ROWS", 10**9)
    full = fitting.heldout_rms(base, data, rec.trial)
    assert thin == pytest.approx(full, rel=1e-4)
    # (the nip's 3 % drop raises the baseline's held-out RMS from 0.01 N to ~0.016 N)
    assert 0.012 < full < 0.03


@pytest.mark.slow
def test_ripple_of_thirty_sd_on_a_long_tension_profile_is_unexplained():
    """Issue 14: a 30-sd sinusoidal ripple (no catalogue effect) on 5e4 rows; its
    candidate nips are fitted on thinned rows (every 3rd) and refitted on all."""
    from validation.noise_robustness import make

    rec, _ = make("tension_profile", "ripple", 30.0, "white", 200, 50_000)
    rep = diagnose(rec, seed=200)
    assert rep.verdict == "unexplained"
    assert [e["name"] for e in rep.effects] == ["self_contact_nip"]
