"""``hold --simulate --bisect N``: DER runs that bisect a hitch's slip load (issue 23).

The bisection itself (:func:`knotmech.verdict.capacity.bisect_slip`) is checked against a
known threshold; the wiring through :func:`knotmech.hold` and the CLI with the DER run
stubbed by a rule "holds below a threshold", so the answer is known exactly. One slow test
runs the real DER (the clove hitch at mu = 0.1, which slips at every load of its table).
"""

import json
import math

import pytest

from knotmech import hold
from knotmech.cli.main import main
from knotmech.errors import InputError
from knotmech.verdict.capacity import BISECT_CEILING, MAX_BISECT_RUNS, bisect_slip

EA = 1.26e6 * math.pi * 0.004**2 / 4  # VPS32, d = 4 mm: 15.83 N


@pytest.mark.parametrize("threshold", [1.3, 2.0, 7.9, 15.9])
def test_bisection_halves_the_log_width_and_keeps_the_threshold(threshold):
    band, probes = bisect_slip(lambda f: f < threshold, low=1.0, high=16.0, runs=5,
                               ceiling=100.0, source="s")  # fmt: skip
    assert len(probes) == 5
    assert band.low <= threshold <= band.high
    # each run halves log(high/low): log2(16) = 4 -> 4 / 2^5
    assert math.log2(band.high / band.low) == pytest.approx(4 / 32)
    assert band.value == pytest.approx(math.sqrt(band.low * band.high))
    assert band.source.startswith("s; bisection: 4 N ")


def test_an_open_band_is_probed_at_the_ceiling_first():
    band, probes = bisect_slip(lambda f: f < 50.0, low=1.0, high=math.inf, runs=3,
                               ceiling=100.0, source="s")  # fmt: skip
    assert [f for f, _ in probes][:2] == [100.0, 10.0]
    assert band.low == pytest.approx(10 * 10**0.5) and band.high == 100.0
    # a hold at the ceiling leaves it open and stops
    band, probes = bisect_slip(lambda f: True, low=1.0, high=math.inf, runs=4, ceiling=100.0,
                               source="s")  # fmt: skip
    assert probes == [(100.0, True)] and band.low == 100.0 and math.isinf(band.high)
    assert not band.bounded
    # already at or above the ceiling: no run
    band, probes = bisect_slip(lambda f: 1 / 0, low=200.0, high=math.inf, runs=4,
                               ceiling=100.0, source="s")  # fmt: skip
    assert probes == [] and band.low == 200.0 and band.source == "s"


def test_a_failed_run_ends_the_bisection_and_keeps_the_band():
    answers = iter([True, None, False])
    band, probes = bisect_slip(lambda f: next(answers), low=1.0, high=16.0, runs=3,
                               ceiling=100.0, source="s")  # fmt: skip
    assert [h for _, h in probes] == [True, None]
    assert (band.low, band.high) == (4.0, 16.0) and "4 N held, 8 N failed" in band.source


@pytest.mark.parametrize(
    "kw, words",
    [
        ({"low": 2.0, "high": 1.0}, "low <= high"),
        ({"low": -1.0}, "low <= high"),
        ({"ceiling": 0.0}, "ceiling > 0"),
        ({"runs": 0}, "1 to 8 runs"),
        ({"runs": MAX_BISECT_RUNS + 1}, "1 to 8 runs"),
    ],
)
def test_bisect_slip_refuses_bad_input_in_one_line(kw, words):
    args = {"low": 1.0, "high": 2.0, "runs": 2, "ceiling": 10.0, "source": "s", **kw}
    with pytest.raises(InputError, match=words) as e:
        bisect_slip(lambda f: True, **args)
    assert "\n" not in str(e.value)


def _stub(monkeypatch, threshold_N):
    """DER runs (the first and the bisection's) that hold below ``threshold_N``."""
    from knotmech.verdict import build

    loads = []

    def fake(**kw):
        load = kw["t_over_EA"] * EA
        loads.append(load)
        holds = load < threshold_N
        return {"holds": holds, "verdict": "hold" if holds else "slip",
                "creep_speed": 1e-6 if holds else math.nan, "ran_to_end": holds,
                "wall_s": 1.0, "message": "", "reason": "" if holds else "ran off"}  # fmt: skip

    monkeypatch.setattr(build, "simulate_point", fake)
    return loads


def _ask(load, bisect, **kw):
    return hold("clove-hitch", rod_diameter=4e-3, post_diameter=36e-3, mu=0.3, load=load,
                material="vps32", simulate=True, bisect=bisect, **kw)  # fmt: skip


def test_hold_bisects_within_the_table_band(monkeypatch):
    # a rule slipping from 3 N: the first run (2 N) holds, then three runs bracket 3 N
    loads = _stub(monkeypatch, 3.0)
    v = _ask(2.0, 3)
    assert v.holds is True and len(loads) == 4 and loads[0] == pytest.approx(2.0)
    runs = v.der["bisection"]
    assert [r["load_N"] for r in runs] == pytest.approx(loads[1:])
    assert [r["holds"] for r in runs] == [r["load_N"] < 3.0 for r in runs]
    slip = v.capacity.slip
    assert slip.low < 3.0 <= slip.high and slip.high / slip.low < 2.0
    assert "bisection:" in slip.source
    # the table's column is open above (nothing slipped up to 0.3 EA) and the first run held
    # 2 N: the first probe is the ceiling, 0.3 EA; then the geometric mid-points
    lo, hi = 2.0, math.inf
    for r in runs:
        want = BISECT_CEILING * EA if math.isinf(hi) else math.sqrt(lo * hi)
        assert r["load_N"] == pytest.approx(want)
        lo, hi = (r["load_N"], hi) if r["holds"] else (lo, r["load_N"])
    assert (slip.low, slip.high) == pytest.approx((lo, hi))


def test_hold_bisection_from_a_first_run_that_slipped(monkeypatch):
    # the shipped table at d/2R = 0.1, mu 0.3: held at 1e-3 EA, nothing slipped above;
    # a rule slipping from 1 N: the first run (2 N) slips, the band is [1e-3 EA, 2 N] and
    # two runs at its geometric mid-points hold
    loads = _stub(monkeypatch, 1.0)
    v = _ask(2.0, 2)
    assert v.holds is False and len(loads) == 3
    lo = 1e-3 * EA
    assert loads[1] == pytest.approx(math.sqrt(lo * 2.0))
    assert loads[2] == pytest.approx(math.sqrt(loads[1] * 2.0))
    slip = v.capacity.slip
    assert (slip.low, slip.high) == pytest.approx((loads[2], 2.0))
    assert v.capacity.limited_by == "slip" and slip.low <= 1.0 <= slip.high


def test_cli_bisect_writes_the_runs_to_json(monkeypatch, capsys):
    _stub(monkeypatch, 3.0)
    args = ["hold", "clove-hitch", "--rod-diameter", "4mm", "--post-diameter", "36mm",
            "--mu", "0.3", "--load", "2N", "--material", "vps32", "--simulate",
            "--bisect", "2", "--json", "-"]  # fmt: skip
    assert main(args) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["der"]["bisection"]) == 2
    assert "bisection:" in data["capacity"]["slip"]["source"]


@pytest.mark.parametrize(
    "extra, words",
    [
        (["--bisect", "2"], "give --simulate as well"),
        (["--bisect", "9", "--simulate"], "--bisect must be 1 to 8 runs, got 9"),
        (["--bisect", "-1", "--simulate"], "--bisect must be 1 to 8 runs, got -1"),
    ],
)
def test_cli_bisect_refuses_in_one_line(extra, words, capsys):
    args = ["hold", "clove-hitch", "--rod-diameter", "4mm", "--post-diameter", "36mm",
            "--mu", "0.3", "--load", "2N", "--material", "vps32"]  # fmt: skip
    assert main(args + extra) == 2
    err = capsys.readouterr().err.strip()
    assert words in err and len(err.splitlines()) == 1


def test_bisect_is_refused_for_knots_whose_run_gives_the_slip_load():
    with pytest.raises(InputError, match="not to bowline"):
        hold("bowline", rod_diameter=4e-3, pin_diameter=20e-3, mu=0.3, load=1.0,
             material="vps32", simulate=True, bisect=2)  # fmt: skip
    with pytest.raises(InputError, match="whole number"):
        _ask(1.0, 1.5)


@pytest.mark.slow
def test_real_bisection_of_a_clove_hitch_that_slips_everywhere():
    """mu = 0.1 at the paper's size: the table's column slips at every load (band (0,
    1e-4 EA]); a real DER run at 1e-5 EA slips too (ideal-rope theory: a free end slips at
    any load), so the band narrows to (0, 1e-5 EA]. (A run at 1e-6 EA fails in the settle,
    the tunnelling guard at dt 2e-9 s: the bisection would stop there, saying so.)"""
    v = hold("clove-hitch", rod_diameter=4e-3, post_diameter=30e-3, mu=0.1, load=1.47,
             material="vps32", simulate=True, bisect=1)  # fmt: skip
    assert v.holds is False
    runs = v.der["bisection"]
    assert [r["t_over_EA"] for r in runs] == pytest.approx([1e-5])
    assert [r["holds"] for r in runs] == [False]
    assert v.capacity.slip.high == pytest.approx(1e-5 * EA) and v.capacity.slip.low == 0.0
    assert "0.000158 N slipped" in v.capacity.slip.source
