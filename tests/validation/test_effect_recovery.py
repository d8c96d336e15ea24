"""Issue 12 part 5's validation: the two generators of validation/effect_recovery.py
differ from each other (and from synth.py) in grids, noise code and shapes."""

import numpy as np
import pytest

from knotmech.cli.validate import load_case

case = load_case("effect_recovery")


def test_generators_keep_apart():
    full, quick = case.cases(False), case.cases(True)
    seeds = {g: {c[-1] for c in full + quick if c[0] == g} for g in ("tune", "heldout")}
    assert not seeds["tune"] & seeds["heldout"]
    assert {c[0] for c in quick} == {"heldout"}  # the quick run judges, never tunes
    # 9 (kind, effect) pairs x 3 sizes x 2 reps x 2 noises + 36 nulls + 24 shapes each
    assert len(full) == 2 * (108 + 36 + 24)


@pytest.mark.parametrize("g", ["tune", "heldout"])
def test_noise_level_and_correlation_are_as_stated(g):
    # AR(1) unit noise of each implementation: unit sd, lag-one correlation rho
    z = case._Noise(g, 11).unit(20_000, 0.9)
    assert np.std(z) == pytest.approx(1.0, rel=0.06)
    assert float(np.corrcoef(z[1:], z[:-1])[0, 1]) == pytest.approx(0.9, abs=0.01)
    w = case._Noise(g, 12).unit(20_000, 0.0)
    assert abs(float(np.corrcoef(w[1:], w[:-1])[0, 1])) < 0.03


def test_planted_sizes_and_grids():
    # adhesion of 6 sd: 6 x the baseline's noise sd, 0.5 % of its largest F_t = 2 mu F_n
    rec, truth = case.make("tune", "pinch", "adhesion", 6.0, "white", 3)
    assert rec.n == 200 and np.allclose(np.diff(rec.x), np.diff(rec.x)[0])
    sd0 = 0.005 * 2 * truth["mu"] * rec.x[-1]
    assert truth["adhesion_force_N"] == pytest.approx(6.0 * sd0, rel=1e-12)
    rec, truth = case.make("heldout", "pinch", None, 0.0, "white", 50_003)
    assert 150 <= rec.n <= 260
    gaps = np.diff(rec.x)
    assert np.std(gaps) > 0.3 * np.mean(gaps)  # a jittered grid, not a linspace
    # a nip of 8 sd drops the tension by 8 sd (tune: a sharp step)
    rec, truth = case.make("tune", "tension_profile", "self_contact_nip", 8.0, "white", 5)
    assert 1 <= len(truth["positions_m"]) <= 2


def test_size_check_of_the_quick_run_is_an_exact_test():
    # 6 nulls: one flag is what an engine of exactly 1 % size shows 5.9 % of the time
    # (1 - 0.99**6), so it passes; two (p = 0.0015) fail. The full run keeps Wilson's bound.
    assert case._size_ok(case._rate(0, 6), quick=True)
    assert case._size_ok(case._rate(1, 6), quick=True)
    assert not case._size_ok(case._rate(2, 6), quick=True)
    assert not case._size_ok(case._rate(1, 6), quick=False)  # Wilson lower bound 0.030
    assert case._size_ok(case._rate(1, 36), quick=False)
