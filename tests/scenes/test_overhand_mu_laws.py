"""The table of validation/_overhand_mu_laws.py: forces read from a saved pull."""

import json

import numpy as np
import pytest

from validation import _overhand_mu_laws as om


def _save(path, e, f, t, **meta):
    base = dict(law="anchor", mu=0.3, turns=3, cpu_s=1.5, status="success", steps=10,
                newton_iterations=20, rejected_steps=1)  # fmt: skip
    np.savez(path, end_to_end=e, pull_force=f, times=t, meta=json.dumps({**base, **meta}))


def test_row_reads_the_tight_phase_mean_and_the_force_at_a_length(tmp_path):
    t = np.linspace(0.0, 9.5, 96)
    e = 0.18 + 0.03 * np.clip(t - 0.5, 0.0, None)  # pulled at 30 mm/s after the wait
    f = 0.1 * e  # [N] linear in the length
    _save(tmp_path / "a.npz", e, f, t)
    r = om.row(str(tmp_path / "a.npz"))
    lo, hi = om.WINDOWS[3]
    sel = (t > 0.7) & (e >= lo) & (e <= hi)
    assert r["mean_mN"] == pytest.approx(round(100.0 * e[sel].mean(), 2))
    assert r["force_at_mN"] == pytest.approx(100.0 * om.AT[3], abs=0.01)
    assert (r["steps"], r["rejected"], r["cpu_s"]) == (10, 1, 1.5)


def test_row_without_the_fixed_length_reached(tmp_path):
    t = np.linspace(0.0, 2.0, 21)
    e = 0.18 + 0.03 * np.clip(t - 0.5, 0.0, None)
    _save(tmp_path / "b.npz", e, 0.1 * e, t)
    r = om.row(str(tmp_path / "b.npz"))
    assert r["force_at_mN"] is None and r["mean_mN"] is None
