"""knotmech.plotting: the shared figures draw what they say, headless, and check inputs."""

import numpy as np
import pytest

from knotmech.analytic.capstan import mu_eff
from knotmech.errors import InputError
from knotmech.plotting import (
    capstan_ratio_plot,
    force_curve_plot,
    phase_diagram_plot,
    tension_decay_plot,
)


def test_tension_decay_curves_are_the_capstan_exponentials(tmp_path):
    s = np.linspace(0, 10, 50)
    prof = (s, np.exp(-0.25 * s))
    ax = tension_decay_plot(s, mu=0.3, D_over_d=(2.0, 7.5), profiles={7.5: prof})
    lines = ax.get_lines()
    assert len(lines) == 4  # ideal, two mu_eff curves, one profile
    np.testing.assert_allclose(lines[0].get_ydata(), np.exp(-0.3 * s))
    np.testing.assert_allclose(lines[1].get_ydata(), np.exp(-float(mu_eff(0.3, 2.0)) * s))
    assert ax.get_yscale() == "log"
    ax.figure.savefig(tmp_path / "t.png")  # works without pyplot or a display
    assert (tmp_path / "t.png").stat().st_size > 1000


def test_capstan_ratio_axis_in_turns():
    theta = np.linspace(0, 4 * np.pi, 20)
    ax = capstan_ratio_plot(theta, mu=0.3, D_over_d=(1.0,), measured={"m": ([2 * np.pi], [5.0])})
    ideal, thick, measured = ax.get_lines()
    np.testing.assert_allclose(ideal.get_xdata(), theta / (2 * np.pi))
    np.testing.assert_allclose(thick.get_ydata(), np.exp(0.14676884 * theta), rtol=1e-7)
    assert measured.get_xdata()[0] == pytest.approx(1.0)


def test_phase_diagram_splits_hold_and_slip():
    x = np.array([0.1, 0.2, 0.3])
    y = np.array([1.0, 2.0, 3.0])
    ax = phase_diagram_plot(
        x,
        y,
        np.array([True, False, True]),
        boundary=([0, 1], [0, 1]),
        theory={"ideal": ([0, 1], [np.inf, np.inf])},
        note="why",
    )
    holds, slips = ax.collections
    assert holds.get_offsets().shape == (2, 2) and slips.get_offsets().shape == (1, 2)
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert sorted(labels) == ["fitted boundary", "holds", "ideal", "slips"]


def test_bad_inputs():
    with pytest.raises(InputError, match="holds must be a boolean"):
        phase_diagram_plot([1.0], [1.0], [1])
    with pytest.raises(InputError, match="equal length"):
        phase_diagram_plot([1.0, 2.0], [1.0], np.array([True]))
    with pytest.raises(InputError, match="mu"):
        tension_decay_plot(np.linspace(0, 1, 3), mu=-0.1)
    with pytest.raises(InputError, match="D_over_d"):
        tension_decay_plot(np.linspace(0, 1, 3), mu=0.3, D_over_d=(0.0,))
    with pytest.raises(InputError, match="pair"):
        tension_decay_plot(np.linspace(0, 1, 3), mu=0.3, profiles={2.0: [1, 2, 3]})


def test_regions_are_shaded_and_force_curves_marked():
    s = np.linspace(0, 10, 20)
    ax = tension_decay_plot(s, mu=0.3, regions=[(0.5, 1.0), (6.0, 7.0)])
    spans = [p for p in ax.patches]
    assert len(spans) == 2
    with pytest.raises(InputError, match="regions"):
        tension_decay_plot(s, mu=0.3, regions=[(1.0,)])
    x = np.linspace(0.2, 0.3, 10)
    ax = force_curve_plot(
        {"mu = 0.2": (x, x**2), "theory": (x, x)}, markers={"inversion": ([0.25], [0.0625])}
    )
    solid, dashed, mark = ax.get_lines()
    assert solid.get_linestyle() == "-" and dashed.get_linestyle() == "--"
    assert mark.get_xdata()[0] == 0.25
    with pytest.raises(InputError, match="non-empty"):
        force_curve_plot({})


def test_rod_plots_draw_the_recorded_frames(tmp_path):
    """Snapshots and a node's track of a (hand-made) Result: what is drawn is the data."""
    from types import SimpleNamespace

    from knotmech.plotting import new_figure, node_track_plot, rod_snapshots_plot, save_figure

    t = np.linspace(0.0, 1.0, 5)
    s = np.linspace(0.0, 0.1, 4)
    # frame k: a straight rod along x drooping linearly, tip height -0.01 k
    pos = np.array([np.c_[s, 0 * s, -0.1 * k * s] for k in range(5)])
    res = SimpleNamespace(times=t, positions=pos)
    fig, (a1, a2) = new_figure(2)
    rod_snapshots_plot(res, n_frames=3, plane="xz", ax=a1)
    lines = a1.get_lines()
    assert len(lines) == 4  # frames 0, 2, 4 and the last one in black
    np.testing.assert_allclose(lines[1].get_ydata(), pos[2, :, 2])
    assert lines[-1].get_label() == "t = 1 s"
    (track,) = node_track_plot(res, node=-1, axis="z", ax=a2).get_lines()
    np.testing.assert_allclose(track.get_ydata(), -0.01 * np.arange(5))
    path = save_figure(fig, tmp_path / "sub" / "rod.png")
    assert path.stat().st_size > 1000
    with pytest.raises(InputError, match="plane"):
        rod_snapshots_plot(res, plane="xx")
    with pytest.raises(InputError, match="node"):
        node_track_plot(res, node=7)
