"""Issue 27 in the scenes: every run's cost bounded before it starts, ``success`` only with
numbers, a run that stops in settling reported ``failed`` with its reason and state, and
a centreline reader that answers bad files with one line (never a traceback).

Every refusal here happens before anything large is allocated: the tests run in well
under a second each, except the quarter circle (a real run, about 3 s of CPU).
"""

import numpy as np
import pytest

from knotmech import rod
from knotmech.errors import InputError
from knotmech.scenes import bend, read_centreline, two_half_hitches
from knotmech.scenes._common import MAX_MEMORY, check_memory, check_numbers, pair_check_bytes
from knotmech.scenes.capstan import capstan
from knotmech.scenes.centreline import centreline
from knotmech.scenes.clove_hitch import clove_hitch
from knotmech.scenes.overhand import overhand
from knotmech.scenes.pinch import pinch

ROD = dict(rod_diameter=4e-3, youngs_modulus=1e6, density=1100.0, mu_rod_rod=0.3)


def _line(n=21, length=0.1):
    return np.column_stack([np.linspace(0, length, n), np.zeros(n), np.zeros(n)])


def _quarter_circle(n=20, radius=0.05):
    phi = np.linspace(0.0, 0.5 * np.pi, n)
    return np.column_stack([radius * np.cos(phi), radius * np.sin(phi), np.zeros(n)])


def _one_line(exc) -> str:
    msg = str(exc.value)
    assert "\n" not in msg
    return msg


# -- (a) cost bounded up front -------------------------------------------------------------


def test_bend_with_1e8_nodes_is_refused_with_its_estimate():
    # issue 27: `simulate bend --n-nodes 100000000` allocated 853 PiB until it failed
    with pytest.raises(InputError, match="node-steps") as exc:
        bend("reef", n_nodes=100_000_000)
    msg = _one_line(exc)
    assert "2e+08 nodes" in msg and "n_nodes" in msg


def test_bend_whose_overlap_watch_would_not_fit_in_memory_is_refused():
    # 2 x 5000 nodes: 6e6 node-steps pass, but the all-pairs watch needs 112 (1e4)^2 B
    with pytest.raises(InputError, match="memory") as exc:
        bend("reef", n_nodes=5000, dt=0.1)
    msg = _one_line(exc)
    assert "11.3 GB" in msg and "n_nodes" in msg


def test_centreline_with_1e6_nodes_is_refused_before_resampling():
    # issue 27: `simulate centreline --n-nodes 1000000` asked for 21.8 TiB
    with pytest.raises(InputError, match="node-steps") as exc:
        centreline(_line(), ends=[("fixed", "pull")], n_nodes=1_000_000, **ROD)
    assert "1e+06 nodes" in _one_line(exc)
    with pytest.raises(InputError, match="memory"):
        centreline(_line(), ends=[("fixed", "pull")], n_nodes=10_000, dt=0.5, **ROD)


def test_hitch_with_more_nodes_than_memory_is_refused():
    with pytest.raises(InputError, match=r"4\.48 TB of memory") as exc:
        clove_hitch(n_nodes=200_000)
    assert "n_nodes" in _one_line(exc)


def test_overhand_frames_are_bounded():
    with pytest.raises(InputError, match="memory"):
        overhand(1, 0.3, n_frames=10**9)


def test_every_scene_bounds_the_solver_memory():
    # 1e7 nodes held for two steps pass the node-steps bound (2e7) but need 160 GB
    with pytest.raises(InputError, match=r"160 GB of memory for the solver") as exc:
        capstan(wrap_angle=np.pi, mu=0.3, rod_diameter=4e-3, post_diameter=30e-3,
                youngs_modulus=1.26e6, t_low=0.1, mode="hold", t_high=0.1,
                n_elements=10**7, dt=1.0, hold_time=1.0)  # fmt: skip
    assert "n_elements" in _one_line(exc)


def test_memory_estimates():
    # the all-pairs check: 112 bytes per pair of edges (the temporaries of _edge_distances)
    assert pair_check_bytes(1000) == 1.12e8
    assert check_memory(1e9, what="x", hint="y") == 1e9
    with pytest.raises(InputError, match="4 GB"):
        check_memory(MAX_MEMORY * 1.01, what="x", hint="y")
    with pytest.raises(InputError, match="unbounded"):
        check_memory(float("inf"), what="x", hint="y")


# -- (b) success means every number is a number --------------------------------------------


def test_capstan_hold_with_t_high_below_t_low_is_refused():
    # issue 27: exited 0 with `status success; T_high/T_low = nan`
    with pytest.raises(InputError, match=r"t_high \(0\.5 N\) must be >= t_low \(1 N\)") as exc:
        capstan(wrap_angle=np.pi, mu=0.3, rod_diameter=4e-3, post_diameter=30e-3,
                youngs_modulus=1.26e6, t_low=1.0, mode="hold", t_high=0.5)  # fmt: skip
    _one_line(exc)


def test_a_rod_too_thick_for_the_post_is_refused():
    # the two half hitches' start curve on a 1 mm post has strands 0.29 d apart
    with pytest.raises(InputError, match="cannot be tied") as exc:
        two_half_hitches(rod_diameter=4e-3, post_diameter=1e-3)
    assert "0.29 d apart" in _one_line(exc)


def test_check_numbers_names_the_first_quantity_that_is_not_a_number():
    assert check_numbers(ratio=1.5, creep=np.zeros(3)) is None
    assert check_numbers(ratio=1.5, creep=[0.0, np.nan]).startswith("creep is not a number")
    assert check_numbers(ratio=float("inf")).startswith("ratio")


def test_pinch_refusal_names_the_option_given():
    # issue 27: `simulate pinch --normal-load 1e9N` was told `pull_distance must be <= ...`
    with pytest.raises(InputError, match="normal_load = 1e.09 N") as exc:
        pinch(normal_load=1e9, mu=0.3)
    assert "pull_distance" not in _one_line(exc)


# -- (c) a run that stops in set-up or settling is failed, with its reason and state ---------


def test_a_run_that_fails_in_settling_is_failed_with_reason_and_state():
    opts = rod.SolverOptions(max_newton=1, rtol=1e-15, dt_min=1e-3, throw=False)
    res = centreline(_quarter_circle(), ends=[("fixed", "pull")], n_nodes=21,
                     settle_time=0.02, options=opts, **ROD)  # fmt: skip
    assert res.status == "failed"
    assert res.message.startswith("settle: ")
    assert res.verdict == ""
    assert res.times.size == 0 and res.pull_force.size == 0
    assert res.draw_in.shape == (0, 0)
    assert res.positions.shape == (1, 21, 3)  # the last good state (the start) is kept


# -- (d) the centreline reader and a plain smooth centreline -------------------------------


def test_reader_refuses_a_200000_character_field_in_one_line():
    text = "x,y,z\n" + "1" * 200_000 + ",0,0\n" + "\n".join(f"{k},0,0" for k in range(12))
    with pytest.raises(InputError, match="not a CSV of points") as exc:
        read_centreline(text)
    assert len(_one_line(exc)) < 200


def test_reader_refuses_a_long_non_number_in_a_short_line():
    text = "\n".join(["x" * 50_000 + ",0,0"] + [f"{k},0,0" for k in range(12)]) + "\n"
    with pytest.raises(InputError, match="is not numbers") as exc:
        read_centreline("x,y,z\n" + text)
    assert len(_one_line(exc)) < 200


def test_reader_and_scene_refuse_a_coordinate_of_1e300():
    text = "\n".join(f"{k},0,0" for k in range(11)) + "\n1e300,0,0\n"
    with pytest.raises(InputError, match=r"1e\+300 m from the origin"):
        read_centreline(text)
    x = _line()
    x[3, 1] = 1e300
    with pytest.raises(InputError, match="beyond the 1000 m"):
        centreline(x, ends=[("fixed", "pull")], **ROD)


def test_reader_refuses_a_file_that_is_not_text(tmp_path):
    f = tmp_path / "knot.csv"
    f.write_bytes(b"\xff\xfe\x00\x01" * 10)
    with pytest.raises(InputError, match="cannot read"):
        read_centreline(f)


def test_a_plain_quarter_circle_runs_with_default_options():
    # issue 27: failed in settling at t = 4.8e-6 s (100 nodes on a 78 mm arc: edges of
    # 0.2 d, whose near neighbours pushed against each other in the contact)
    res = centreline(_quarter_circle(), ends=[("fixed", "pull")], **ROD)
    assert res.status == "success", res.message
    assert res.verdict == "holds"
    assert np.all(np.isfinite(res.pull_force)) and res.max_force > 0
    assert res.topology_preserved


def test_a_hitch_that_fails_in_settling_gives_no_verdict():
    # before: a free-end hitch whose solver failed in settling read "slip" (creep nan)
    opts = rod.SolverOptions(max_newton=1, rtol=1e-15, dt_min=1e-3, throw=False)
    res = two_half_hitches(loading="free", t_high=0.3, n_nodes=100, settle_time=0.05,
                           load_time=0.05, hold_time=0.05, options=opts)  # fmt: skip
    assert res.status == "failed"
    assert res.message.startswith("settle: ")
    assert res.verdict == ""
    assert res.times[-1] < 0.05  # the last good state, inside the settling


def test_a_hitch_on_a_post_of_kilometres_is_refused_before_its_curve():
    """Issue 27: `hold ... --post-diameter 40km --simulate` allocated its start curve (6 GiB
    on a 40 km post: 0.05 d sampling round the post) before any cost check."""
    with pytest.raises(InputError, match=r"post_diameter / rod_diameter = 1e\+07 is above 1000"):
        clove_hitch(loading="free", t_high=1.0, rod_diameter=4e-3, post_diameter=40e3)
