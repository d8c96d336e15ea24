"""``knotmech hold KNOT --simulate --plot FILE`` for the knots one DER run answers (the
bends, the loops, the Prusik): the simulated knot's last frame is drawn (issue 25, item 4).
The runs are stubbed: a known centreline stands for the last frame, so what is drawn can be
checked against it."""

from types import SimpleNamespace

import numpy as np
import pytest

from knotmech.cli.main import main
from knotmech.errors import InputError
from knotmech.verdict.answer import Verdict
from knotmech.verdict.plot import plot_verdict
from knotmech.verdict.scope import ONE_RUN_KNOTS, check_plot_request

PNG = b"\x89PNG\r\n\x1a\n"


def _helix(n=40, radius=0.012, turns=2.0):
    s = np.linspace(0, 2 * np.pi * turns, n)
    return np.c_[radius * np.cos(s), radius * np.sin(s), 0.002 * s]


def _result(positions, **extra):
    base = dict(verdict="slips", slip_load=0.05, max_force=0.06, pull_speed=0.04,
                status="success", message="", stats={"wall_s": 1.0}, topology_preserved=True,
                positions=positions[None])  # fmt: skip
    return SimpleNamespace(**{**base, **extra})


def test_one_run_knots_are_the_bends_loops_and_prusik():
    assert {"reef", "sheet-bend", "double-fishermans", "bowline", "figure-eight-loop",
            "prusik"} <= set(ONE_RUN_KNOTS)  # fmt: skip
    assert "clove-hitch" not in ONE_RUN_KNOTS and "capstan" not in ONE_RUN_KNOTS


@pytest.mark.parametrize(
    "knot, simulate, free, match",
    [
        ("bowline", False, 0.0, r"the bowline has no table, give simulate"),
        ("prusik", False, 0.0, r"the prusik has no table"),
        ("cow-hitch", False, 1.0, r"the cow-hitch has no table, give simulate"),
        ("round-turn", True, 0.0, r"a hitch with a DER answer \(clove-hitch"),
        ("capstan", False, 0.0, r"a knot under simulate \(reef, granny"),
    ],
)
def test_a_plot_with_nothing_to_draw_is_refused_before_any_work(knot, simulate, free, match):
    with pytest.raises(InputError, match=match):
        check_plot_request(knot, simulate=simulate, free_end_load=free)


@pytest.mark.parametrize("knot", ["bowline", "sheet-bend", "prusik", "clove-hitch"])
def test_a_plot_with_a_run_or_a_table_is_accepted(knot):
    check_plot_request(knot, simulate=True, free_end_load=0.0)  # no error


def test_hold_plot_of_a_loop_without_simulate_is_one_line_exit_2(tmp_path, capsys):
    argv = ["hold", "bowline", "--rod-diameter", "4mm", "--pin-diameter", "20mm", "--mu", "0.3",
            "--load", "0.05N", "--youngs-modulus", "1MPa",
            "--plot", str(tmp_path / "b.png")]  # fmt: skip
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--plot draws the simulated knot" in err[0]
    assert not (tmp_path / "b.png").exists()


def _axes_lines(path_png, verdict):
    """Draw ``verdict`` and return the 3-D axes' line data and legend texts."""
    import matplotlib.pyplot as plt

    seen = {}
    real_close = plt.close

    def keep(fig=None):
        ax = fig.axes[0]
        seen["lines"] = [np.column_stack(ln.get_data_3d()) for ln in ax.get_lines()]
        legend = ax.get_legend()
        seen["legend"] = [t.get_text() for t in legend.get_texts()] if legend else []
        seen["zlabel"] = ax.get_zlabel()
        real_close(fig)

    plt.close = keep
    try:
        plot_verdict(verdict, path_png)
    finally:
        plt.close = real_close
    return seen


def _verdict(knot, shape):
    return Verdict(holds=False, margin=-0.5, decided_by="DER-simulation", inside_validity=True,
                   answers=(), knot=knot, shape=shape)  # fmt: skip


def test_a_bend_is_drawn_as_its_two_ropes(tmp_path):
    """Two ropes one after the other in the positions: two lines, each exactly its half of
    the nodes (in mm), labelled rope 1 and rope 2; no post is drawn."""
    a = _helix(30)
    b = a + [0.03, 0.0, 0.0]
    shape = {"positions": np.vstack([a, b]), "rod_diameter": 4e-3, "post_diameter": None,
             "support": "", "ropes": 2}  # fmt: skip
    seen = _axes_lines(tmp_path / "bend.png", _verdict("sheet-bend", shape))
    assert (tmp_path / "bend.png").read_bytes()[:8] == PNG
    assert seen["legend"] == ["rope 1", "rope 2"]
    assert len(seen["lines"]) == 2
    np.testing.assert_allclose(seen["lines"][0], a * 1e3)
    np.testing.assert_allclose(seen["lines"][1], b * 1e3)
    assert seen["zlabel"] == "z [mm]"


def test_a_loop_is_drawn_round_its_pin(tmp_path):
    """One rope and five rings of the pin's radius (10 mm for a 20 mm pin) about z."""
    shape = {"positions": _helix(40), "rod_diameter": 4e-3, "post_diameter": 20e-3,
             "support": "pin", "ropes": 1}  # fmt: skip
    seen = _axes_lines(tmp_path / "loop.png", _verdict("bowline", shape))
    rope, rings = seen["lines"][0], seen["lines"][1:]
    np.testing.assert_allclose(rope, _helix(40) * 1e3)
    assert len(rings) == 5
    for ring in rings:
        np.testing.assert_allclose(np.hypot(ring[:, 0], ring[:, 1]), 10.0)
    assert seen["zlabel"] == "z [mm] (pin axis)"


@pytest.mark.parametrize(
    "knot, module, attr, extra",
    [
        ("bowline", "knotmech.scenes.loops", "loop",
         ["--pin-diameter", "20mm", "--youngs-modulus", "1MPa", "--load", "0.05N"]),
        ("sheet-bend", "knotmech.scenes.bends", "bend",
         ["--youngs-modulus", "1MPa", "--load", "0.05N"]),
        ("prusik", "knotmech.scenes.axial", "axial_pull",
         ["--post-diameter", "12mm", "--material", "nylon", "--load", "100N"]),
    ],
)  # fmt: skip
def test_hold_simulate_plot_draws_the_simulated_knot(monkeypatch, tmp_path, knot, module, attr,
                                                     extra):  # fmt: skip
    """The stubbed run's last frame reaches the plot: a PNG of the knot is written."""
    import importlib

    helix = _helix(40)

    def fake(name, **kw):
        return _result(helix, knot=name, kind=name, wraps=kw.get("wraps", 3),
                       sliding_force=150.0, peak_force=160.0, slid=True,
                       slide_distance=kw["rod_diameter"], drag_speed=0.01,
                       pin_diameter=kw.get("pin_diameter", 0.02), slipped_by="tail",
                       tail_draw_in=np.array([0.0, 0.012]), eye_growth=np.zeros(2),
                       law="anchor", frames_checked=2)  # fmt: skip

    monkeypatch.setattr(importlib.import_module(module), attr, fake)
    out = tmp_path / f"{knot}.png"
    argv = ["hold", knot, "--rod-diameter", "4mm", "--mu", "0.3", *extra, "--simulate",
            "--plot", str(out)]  # fmt: skip
    assert main(argv) == 0
    assert out.read_bytes()[:8] == PNG and out.stat().st_size > 10000
