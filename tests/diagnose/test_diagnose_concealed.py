"""Concealed-effects validation, small sample (fixed seeds): targets of issue 5.

Targets: >= 90 % recovery where the effect is >= 3 noise sd at its strongest
point; <= 5 % false positives on nulls, AR(1) rho = 0.9 noise included. The quick
sample is small (28 effect recordings at >= 3 sd, 9 at 10 sd under AR(1) rho = 0.9
noise, 24 nulls), so the assertions allow for it: recovery >= 85 %, AR(1) at least
8 of 9, and at most one false positive (the full table,
``python -m validation.concealed_effects --full``, is in the README).
"""

import json

import pytest

from knotmech.cli.validate import load_case
from knotmech.diagnose.effects import CATALOGUE
from knotmech.diagnose.synth import SYNTH_EFFECTS

case = load_case("concealed_effects")
#: experiment kinds and (kind, effect) pairs of the sample: the table runs the kinds of
#: version 1 of the contract by default (3 kinds and 9 pairs when the thresholds were set)
KINDS = len(case.V1_KINDS)
PAIRS = sum(len(SYNTH_EFFECTS[k]) for k in case.V1_KINDS)


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    out = tmp_path_factory.mktemp("concealed")
    return case.run(quick=True, out_dir=out), out


def test_recovery_at_three_sigma(quick):
    result, _ = quick
    big = result["table"]["recovery_at_3_sigma_or_more_white"]
    assert big["n"] >= 28
    assert big["rate"] >= 0.85


def test_recovery_under_ar1_noise_at_ten_sigma(quick):
    # one recording per (experiment, effect) pair at 10 sd under AR(1) rho = 0.9; before
    # the likelihood ratio used the augmented model's noise, the full table found
    # contact flattening in 2 of 6 such recordings
    result, _ = quick
    rows = [r for r in result["results"] if r["noise"] == "ar1" and r["size"] == 10.0]
    assert len(rows) == PAIRS
    assert sum(r["verdict"] == r["effect"] for r in rows) >= PAIRS - 1


def test_false_positives_on_nulls_white_and_ar1(quick):
    result, _ = quick
    nulls = result["table"]["nulls"]
    assert nulls["white"]["n"] == 4 * KINDS and nulls["ar1"]["n"] == 4 * KINDS
    assert nulls["all"]["false_positives"] <= 1


def test_out_of_catalogue_is_never_given_a_catalogue_name(quick):
    result, _ = quick
    ooc = [r for r in result["results"] if r["effect"] == "out_of_catalogue"]
    assert len(ooc) == 4 * KINDS
    named = [r for r in ooc if r["verdict"] in CATALOGUE]
    assert len(named) <= 1
    white = [r for r in ooc if r["noise"] == "white"]
    assert sum(r["verdict"] == "unexplained" for r in white) >= len(white) - 1
    # under AR(1) rho = 0.9 at least half (issue 12 part 5; measured 4 of 6, was 0 of 6:
    # undetermined until the smooth test of undetermined recordings)
    ar1 = [r for r in ooc if r["noise"] == "ar1"]
    assert sum(r["verdict"] == "unexplained" for r in ar1) >= len(ar1) / 2


def test_json_and_plot_written(quick):
    result, out = quick
    data = json.loads((out / "concealed_effects.json").read_text())
    assert data["name"] == "concealed_effects"
    assert {"recovery", "nulls", "confusion", "out_of_catalogue"} <= set(data["table"])
    assert all(p.endswith(".png") for p in result["figures"])
