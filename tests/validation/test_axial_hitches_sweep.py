"""validation._axial_hitches --sweep: the (mu, kappa) table, figure and checks, with the
drags replaced by rows of known numbers (the real drags are in the note; 3-20 s each)."""

import json

import validation._axial_hitches as ah


def _fake(knot, normal_load, *, mu=0.3, bending_scale=1.0):
    # a sliding force linear in mu, a fibre rope (kappa 0.01) at half of it; held at mu 0.6
    f = 10.0 * mu * (0.5 if bending_scale != 1.0 else 1.0)
    return {"knot": knot, "normal_load": normal_load, "mu": mu, "bending_scale": bending_scale,
            "sliding_force": f, "peak_force": 2 * f, "slid": mu < 0.6, "topology_preserved": True,
            "cpu_s": 1.0}  # fmt: skip


def test_sweep_drags_each_hitch_at_every_mu_and_kappa(tmp_path, monkeypatch):
    monkeypatch.setattr(ah, "drag_row", _fake)
    res = ah.sweep(tmp_path, knots=("clove-hitch", "prusik"))
    assert res["verdict"] == "pass"
    got = json.loads((tmp_path / "axial_hitches_mu_kappa.json").read_text())
    # [sliding force or None (held within the drag), peak, CPU]
    assert got["numbers"]["prusik"] == {
        "mu 0.1, kappa 1": [1.0, 2.0, 1.0],
        "mu 0.3, kappa 1": [3.0, 6.0, 1.0],
        "mu 0.6, kappa 1": [None, 12.0, 1.0],
        "mu 0.3, kappa 0.01": [1.5, 3.0, 1.0],
    }
    assert ah._sweep_point(got["rows"][2]) == 12.0  # held: drawn at its peak
    assert len(got["rows"]) == 2 * len(ah.SWEEP) == 8
    assert all(r["normal_load"] == ah.SWEEP_LOAD == 0.5 for r in got["rows"])
    assert (tmp_path / "axial_hitches_mu_kappa.png").stat().st_size > 10_000


def test_sweep_fails_when_a_drag_changed_its_knot_type(tmp_path, monkeypatch):
    def broken(knot, normal_load, **kw):
        row = _fake(knot, normal_load, **kw)
        row["topology_preserved"] = kw.get("mu") != 0.6
        return row

    monkeypatch.setattr(ah, "drag_row", broken)
    res = ah.sweep(tmp_path, knots=("clove-hitch",))
    assert res["verdict"] == "fail" and res["checks"]["topology_kept"] is False
