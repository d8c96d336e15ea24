"""The tied pulls' stop at the rod model's strain limit (issue 25): a pulled end whose first
free edge reaches 10 % strain (tension 0.1 EA) ends the pull, and a knot that has not
slipped by then *held to at least* the pull force there, a lower bound of its slip load.

Default suite: the grip edges' strain and the stop on a straight rod stretched by hand, the
words of the result and of ``hold --simulate`` (well under a second). Slow: the
figure-eight bend at mu = 1, which locks and held to the strain limit (about 15 s of CPU,
71 s without the stop).
"""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from knotmech import rod
from knotmech.scenes.bends import (
    STRAIN_LIMIT,
    GripEdgeStrains,
    StrainStop,
    _grip,
    bend,
    held_note,
    held_words,
    inner_edge,
    pull_summary,
)
from knotmech.verdict.inputs import STRAIN_LIMIT as VERDICT_STRAIN_LIMIT

D = 4e-3


def _rope(n=11):
    x = np.zeros((n, 3))
    x[:, 0] = np.linspace(0.0, 0.1, n)  # rest edge 10 mm
    r = rod.Rod(positions=x, radius=0.5 * D, youngs_modulus=1e6, density=1100.0,
                natural="straight")  # fmt: skip
    return rod.RodSystem([r]), x


def _stretch(x, edge, strain):
    """``x`` with edge ``edge`` (nodes edge, edge + 1) stretched to ``strain``, the rest
    moved rigidly."""
    y = x.copy()
    y[edge + 1 :, 0] += strain * (x[edge + 1, 0] - x[edge, 0])
    return y


def test_one_strain_limit_for_the_stop_and_the_verdict():
    assert STRAIN_LIMIT == VERDICT_STRAIN_LIMIT == 0.1


def test_inner_edge_is_the_first_free_edge_next_to_either_grip():
    system, _ = _rope()
    start, end = _grip(system, 0, "start"), _grip(system, 0, "end")
    assert (start[1], inner_edge(system, start)) == (0, 1)
    assert (end[1], inner_edge(system, end)) == (9, 8)


def test_grip_edge_strains_of_a_five_node_rod_with_one_edge_stretched_by_one_percent():
    """5 nodes 25 mm apart along x, gripped at both ends (end edges 0 and 3): the edges
    read are 1 and 2. Edge 1 stretched by 1 % (to 25.25 mm, the nodes after it moved
    rigidly): strains (0.01, 0) by hand, tension EA x 0.01 = 1e6 Pa x pi (2 mm)^2 x 0.01
    = 0.04 pi N; the stop reads the larger, 0.01, and edge 2 stretched instead swaps them."""
    system, x = _rope(n=5)
    grips = (_grip(system, 0, "start"), _grip(system, 0, "end"))
    strains = GripEdgeStrains(system, grips)
    assert strains.edges.tolist() == [1, 2]
    assert strains(x) == pytest.approx([0.0, 0.0], abs=1e-12)
    y = x.copy()
    y[2:, 0] += 0.25e-3
    assert np.linalg.norm(y[2] - y[1]) == pytest.approx(25.25e-3, rel=1e-12)
    assert strains(y) == pytest.approx([0.01, 0.0], rel=1e-12, abs=1e-12)
    assert strains.ea * strains(y) == pytest.approx([0.04 * math.pi, 0.0], rel=1e-12, abs=1e-12)
    assert StrainStop(system, grips, lambda x: False).strain(y) == pytest.approx(0.01)
    assert strains(_stretch(x, 2, 0.01)) == pytest.approx([0.0, 0.01], rel=1e-12, abs=1e-12)


def test_stop_at_ten_percent_strain_of_a_pulled_ends_first_free_edge():
    system, x = _rope()
    grips = (_grip(system, 0, "start"), _grip(system, 0, "end"))
    stop = StrainStop(system, grips, tail_out=lambda x: False)
    assert stop.strain(x) == pytest.approx(0.0, abs=1e-12)
    # the end edges are rigid in a pull: their strain is not read; the middle's neither
    assert not stop(_stretch(x, 0, 0.5)) and not stop(_stretch(x, 5, 0.5))
    assert not stop.reached
    assert not stop(_stretch(x, 8, 0.099))
    assert stop.strain(_stretch(x, 8, 0.099)) == pytest.approx(0.099)
    assert stop(_stretch(x, 1, 0.1001)) and stop.reached
    assert stop(_stretch(x, 8, 0.1001)) and stop.reached


def test_a_tail_running_out_wins_over_the_strain_limit():
    system, x = _rope()
    stop = StrainStop(system, [_grip(system, 0, "start")], tail_out=lambda x: True)
    assert stop(_stretch(x, 1, 0.2)) and not stop.reached


def test_the_words_of_a_hold_to_the_strain_limit():
    r = SimpleNamespace(verdict="holds", max_force=1.1376, held_to_strain_limit=True,
                        slip_load=math.nan, stats={"steps": 3}, positions=np.zeros((2, 5, 3)),
                        status="success", message="", frames_checked=4)  # fmt: skip
    assert held_words(r) == "HOLDS to at least 1.138 N (0.1 EA, the rod model's strain limit)"
    assert held_note(1.1376).startswith("holds to at least 1.138 N (0.1 EA, the rod model's")
    assert pull_summary(r)["held_to_strain_limit"] is True
    r.held_to_strain_limit = False
    assert held_words(r) == "HOLDS up to 1.138 N (the pull ended)"


def test_hold_simulate_reads_a_hold_to_the_strain_limit_as_a_lower_bound():
    from knotmech.verdict.answer import Verdict
    from knotmech.verdict.bend import _pull_outcome, der_slip_band

    r = SimpleNamespace(verdict="holds", max_force=1.14, slip_load=math.nan, message="",
                        held_to_strain_limit=True)  # fmt: skip
    holds, cap, msg = _pull_outcome("figure-eight-bend", r, 1.0)
    assert (holds, cap) == (True, 1.14) and "holds to at least 1.14 N (0.1 EA" in msg
    holds, cap, msg = _pull_outcome("figure-eight-bend", r, 2.0)
    assert holds is None and math.isnan(cap)
    assert "the load 2 N is above it" in msg and "not decided" in msg
    # the capacity: open above from the held-to load, not a point slip load
    dec = SimpleNamespace(capacity=1.14, decides=True)
    v = SimpleNamespace(deciding=dec, der={"verdict": "holds", "held_to_strain_limit": True})
    band = der_slip_band(v, "bend")
    assert (band.low, band.value, band.high) == (1.14, math.inf, math.inf)
    assert band.source == (
        "the DER pull of the bend stopped at the rod model's strain limit, 0.1 EA"
    )
    from knotmech.verdict.answer import _slip_words

    assert _slip_words(band) == (
        "no slip up to 1.14 N (the DER pull of the bend stopped at "
        "the rod model's strain limit, 0.1 EA)"
    )
    # a load above the held-to force: undecided, the bound still given
    v = SimpleNamespace(deciding=None, der={"verdict": "holds", "max_force": 1.14,
                                            "held_to_strain_limit": True})  # fmt: skip
    assert der_slip_band(v, "loop").low == 1.14
    v.deciding, v.der = dec, {"verdict": "slips"}
    band = der_slip_band(v, "bend")
    assert (band.low, band.value, band.high) == (1.14, 1.14, 1.14)
    assert Verdict  # the verdict module imports with the scenes'


@pytest.mark.slow
def test_figure_eight_bend_at_mu_one_holds_to_the_strain_limit():
    """The figure-eight bend locks at mu = 1 (``knotmech simulate figure-eight-bend --mu
    1``): the pull stops when an end reaches 10 % strain, 9 d into the 20 d pull (measured
    14.8 s of CPU, was 71 s pulling on to 7.2 N = 57 % strain); it held to at least
    1.14 N, the mean of the two grips' pull forces there (measured 1.138 N), and no edge
    of either rope is strained beyond the limit by more than a step's worth."""
    r = bend("figure-eight-bend", mu_rod_rod=1.0)
    assert r.status == "success", r.message
    assert r.verdict == "holds" and r.held_to_strain_limit and r.topology_preserved
    assert 1.0 < r.max_force < 0.1 * 1e6 * math.pi * D * D / 4
    assert r.pull_displacement[-1] < 15 * D  # stopped before the 20 d pull's end
    assert r.message.startswith("holds to at least")
    assert r.to_dict()["held_to_strain_limit"] is True
    x0, x = r.positions[0], r.positions[-1]
    rest = np.linalg.norm(np.diff(x0, axis=0), axis=1)
    strain = np.linalg.norm(np.diff(x, axis=0), axis=1) / rest - 1
    n = len(x) // 2
    strain[n - 1] = 0.0  # the joint between the two ropes' rows is no edge
    assert 0.1 <= strain.max() < 0.102
