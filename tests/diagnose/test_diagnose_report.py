"""Honesty of the report and plot (issue 12 part 5): p-values say where they come from,
the plotted baseline is the best baseline fit, axes carry names and units."""

import numpy as np
import pytest

from knotmech.diagnose import diagnose, make_recording
from knotmech.diagnose.plot import axis_label, plot_report

META = {"rod_diameter_m": 0.004, "pinch_diameter_m": 0.008, "youngs_modulus_Pa": 1.26e6}


def test_p_values_never_claim_more_than_their_draws():
    rec, _ = make_recording("pinch", "adhesion", size=8.0, seed=15, n=200)
    rep = diagnose(rec, seed=15)
    ev = rep.effects[0]["evidence"]
    b = ev["bootstrap_draws"]
    assert b >= 39  # the first batch of 9 draws no longer decides that p is small
    if ev["p_value"] < 1.0 / (b + 1):
        assert ev["p_value_counted_bound"] == pytest.approx(1.0 / (b + 1), rel=1e-2)
        assert "tail fitted to" in ev["p_value_method"]
        assert f"by count p < {ev['p_value_counted_bound']} from {b} draws" in rep.summary
    else:
        assert ev["p_value_method"].startswith("counted")
    # the held-out improvement that let the effect in, in the effect's own evidence
    # (issue 26): raw held-out RMS before -> after, whitened one-step-ahead [before, after]
    assert ev["heldout_rms"] < ev["heldout_rms_before"]
    inn = ev["heldout_innovation_rms"]
    assert len(inn) == 2 and inn[1] < inn[0]


def test_plotted_baseline_is_the_best_baseline_fit():
    # the hand-made pinch recording: F_t = 0.6 F_n + 0.01 N, 2 % noise
    rng = np.random.default_rng(0)
    fn = np.linspace(0.01, 0.3, 40)
    ft = (0.6 * fn + 0.01) * (1 + 0.02 * rng.standard_normal(fn.size))
    rep = diagnose(experiment="pinch", x=fn, y=ft, metadata=META)
    assert rep.verdict == "adhesion"
    mu_ls = float(np.dot(fn, ft) / (2 * np.dot(fn, fn)))  # least squares through 0
    rms_ls = float(np.sqrt(np.mean((ft - 2 * mu_ls * fn) ** 2)))
    # no curve running below every point: at most 30 % worse than least squares, and
    # points on both sides of it
    assert rep.baseline["rms"] < 1.3 * rms_ls
    assert rep.baseline["parameters"]["mu"] == pytest.approx(mu_ls, rel=0.02)
    above = np.mean(ft > rep.baseline_mean)
    assert 0.1 < above < 0.9


def test_axes_have_names_and_units(tmp_path):
    assert axis_label("wrap_angle_rad") == "wrap angle [rad]"
    assert axis_label("T_N") == "T [N]"
    assert axis_label("k_N_per_m") == "k [N/m]"
    assert axis_label("arclength_m") == "arclength [m]"
    rec, _ = make_recording("pinch", "adhesion", size=8.0, seed=15, n=120)
    fig = plot_report(diagnose(rec, seed=15), tmp_path / "p.png")
    ax, axr = fig.axes
    assert ax.get_ylabel() == "tangential force [N]"
    assert axr.get_xlabel() == "normal force [N]" and axr.get_ylabel() == "residual [N]"
    labels = ax.get_legend_handles_labels()[1]
    assert "mismatch region" in labels
    assert "baseline" in labels


def _lines(fig, style):
    return [ln for ln in fig.axes[0].get_lines() if ln.get_linestyle() == style]


def _monotone(values) -> bool:
    return bool(np.all(np.diff(values) >= -1e-12 * np.max(np.abs(values))))


def test_joint_plot_draws_one_line_per_recording(tmp_path):
    # two capstan pulls of one rod (mu = 0.3) at other loads and wraps: at one
    # displacement the curves differ, so rows sorted across both would zigzag between them
    from knotmech.diagnose import diagnose_many
    from knotmech.diagnose.recording import recording_from_arrays

    rng = np.random.default_rng(4)
    u = np.linspace(0.0, 0.05, 60)
    recs = []
    for t_low, theta in ((1.0, 2 * np.pi), (1.5, 3 * np.pi)):
        plateau = t_low * np.exp(0.3 * theta)
        t = np.minimum(t_low + (plateau - t_low) / 0.02 * u, plateau)
        meta = {
            "wrap_angle_rad": theta,
            "T_low_N": t_low,
            "rod_diameter_m": 0.004,
            "post_diameter_m": 0.02,
            "youngs_modulus_Pa": 1.26e6,
        }
        y = t + 0.004 * plateau * rng.standard_normal(u.size)
        recs.append(recording_from_arrays("capstan_pull", u, y, metadata=meta))
    rep = diagnose_many(recs, seed=1)
    assert rep.verdict == "none"
    assert rep.final["parameters"]["mu"] == pytest.approx(0.3, rel=0.01)
    fig = plot_report(rep, tmp_path / "joint.png")
    for style in ("--", "-"):
        lines = _lines(fig, style)
        assert len(lines) == 2
        for ln in lines:
            assert _monotone(ln.get_xdata()) and _monotone(ln.get_ydata())
    # every row is on exactly one line, at its own model value
    xs = np.concatenate([ln.get_xdata() for ln in _lines(fig, "--")])
    assert xs.size == rep.x.size
    labels = fig.axes[0].get_legend_handles_labels()[1]
    assert labels.count("baseline") == 1


def test_plot_draws_each_speed_as_its_own_line(tmp_path):
    rec, _ = make_recording("capstan_pull", "rate_dependent_friction", size=8.0, seed=3, n=120)
    rep = diagnose(rec, seed=3)
    assert rep.verdict == "rate_dependent_friction"
    fig = plot_report(rep, tmp_path / "speeds.png")
    final = _lines(fig, "-")
    assert len(final) == 3  # one per speed
    plateaus = sorted(float(np.max(ln.get_ydata())) for ln in final)
    assert plateaus[-1] - plateaus[0] > 0  # the speeds' plateaus differ ...
    for ln in final:  # ... and no line jumps between them
        assert _monotone(ln.get_xdata()) and _monotone(ln.get_ydata())
