"""``knotmech hold`` for the cow (girth) hitch: aliases, the closed form, API == CLI, --simulate.

The cow hitch is two turns on the post in opposite senses with the bight over both legs.
Its load is on one leg and ``free_end_load`` on the other. The ideal rope (zero thickness:
a capstan of its 4 pi of wrap whatever the sense of the turns, K = exp(4 pi mu)) slips at
any load with one leg free and holds up to K times the lighter leg; no thick-nip model is
derived for it. The DER scene, its table and ``--simulate`` model one leg loaded, the
other free.
"""

import json
import math

import pytest

import knotmech
from knotmech import knots
from knotmech.cli.main import main
from knotmech.verdict import knot_key


@pytest.mark.parametrize(
    "name", ["cow-hitch", "cow hitch", "Cow", "girth hitch", "girth_hitch", "lark's head",
             "Lark\u2019s head", "larks-head", "lark's foot"],
)  # fmt: skip
def test_aliases(name):
    assert knot_key(name) == "cow-hitch"


def _api(d, D, mu, load, free, mat):
    return knotmech.hold("cow-hitch", rod_diameter=d * 1e-3, post_diameter=D * 1e-3, mu=mu,
                         load=load, free_end_load=free, material=mat)  # fmt: skip


def _cli(d, D, mu, load, free, mat, capsys, knot="girth hitch"):
    args = ["hold", knot, "--rod-diameter", f"{d}mm", "--post-diameter", f"{D}mm", "--mu",
            repr(mu), "--load", f"{load!r}N", "--free-end-load", f"{free!r}N"]  # fmt: skip
    if mat:
        args += ["--material", mat]
    assert main(args + ["--json", "-"]) == 0
    return _strict(capsys.readouterr().out)


def _strict(text):
    """The JSON, refusing NaN and Infinity (the verdict's JSON is strict)."""

    def refuse(name):
        raise AssertionError(f"non-strict JSON constant {name}")

    return json.loads(text, parse_constant=refuse)


CASES = [
    # (d, D) mm, mu, load N, free N, material
    (4, 80, 0.3, 1.0, 0.0, None),  # thin rope, one leg free, no E: the ideal rope slips
    (4, 80, 0.3, 1.0, 1.0, None),  # both legs at 1 N: holds up to 43.4 N
    (4, 80, 0.3, 50.0, 1.0, None),  # 50 N against 1 N: above exp(4 pi 0.3) = 43.4
    (4, 30, 0.3, 1.0, 0.0, None),  # d/D 0.133: the ideal rope outside its validity
    (4, 30, 0.5, 0.3, 0.0, "vps32"),  # the DER (table or --simulate) for one leg free
    (6, 40, 0.4, 200.0, 0.0, "nylon"),
    (6, 40, 0.4, 200.0, 150.0, "nylon"),
]


@pytest.mark.parametrize("case", CASES)
def test_api_and_cli_give_the_same_verdict(case, capsys):
    v = _api(*case).to_dict()
    c = _cli(*case, capsys)
    assert c["knot"] == "cow-hitch"
    for k in ("holds", "verdict", "decided_by", "margin", "next_step", "der", "creep"):
        assert c[k] == v[k], (case, k)


def test_closed_form_numbers(capsys):
    K = math.exp(4 * math.pi * 0.3)  # 43.376
    c = _cli(4, 80, 0.3, 1.0, 0.0, None, capsys)
    assert c["holds"] is False and c["decided_by"] == "ideal-rope" and c["margin"] == -1.0
    ideal = c["answers"][0]
    assert [a["model"] for a in c["answers"]] == ["ideal-rope"]  # no thick-nip model
    assert any("slips at any load" in n for n in ideal["notes"])
    c = _cli(4, 80, 0.3, 1.0, 1.0, None, capsys)
    assert c["holds"] is True and c["margin"] == pytest.approx(K - 1, rel=1e-12)
    c = _cli(4, 80, 0.3, 50.0, 1.0, None, capsys)
    assert c["holds"] is False and c["margin"] == pytest.approx(K / 50 - 1, rel=1e-12)


def test_thick_rope_without_a_table_answer_is_undecided_with_the_command(capsys):
    # d/D = 0.133: the ideal rope is outside its validity and there is no thick-nip model
    c = _cli(4, 30, 0.3, 1.0, 0.0, None, capsys)
    assert c["holds"] is None and c["decided_by"] is None
    assert "--material or --youngs-modulus" in c["next_step"] or "--simulate" in c["next_step"]
    # both legs loaded on the thick post: no model inside its validity either, and the DER
    # covers one leg free only: test the knot
    c = _cli(4, 30, 0.3, 1.0, 1.0, "vps32", capsys)
    assert c["holds"] is None and "T_low = 0" in c["der"]["message"]


def test_simulate_runs_the_cow_hitch_scene(monkeypatch, capsys):
    """--simulate calls simulate_point with knot="cow-hitch" (stubbed: no DER here); the
    answer says which loading the scene models."""
    from knotmech.verdict import build as phase_table

    seen = {}

    def fake(**kw):
        seen.update(kw)
        return {"holds": False, "verdict": "slip", "creep": 0.01, "creep_speed": 0.5,
                "ran_to_end": True, "wall_s": 1.0, "message": "", "creep_window_s": 0.75,
                "reason": "crept faster than the limit"}  # fmt: skip

    monkeypatch.setattr(phase_table, "simulate_point", fake)
    args = ["hold", "lark's head", "--rod-diameter", "4mm", "--post-diameter", "30mm", "--mu",
            "0.3", "--load", "0.3N", "--material", "vps32", "--simulate"]  # fmt: skip
    assert main(args + ["--json", "-"]) == 0
    data = _strict(capsys.readouterr().out)
    assert seen["knot"] == "cow-hitch" and seen["d_over_2R"] == pytest.approx(4 / 34)
    assert data["holds"] is False and data["decided_by"] == "DER-simulation"
    assert data["creep"]["window_s"] == 0.75 and "0.75 s" in data["der"]["criterion"]
    der_answer = next(a for a in data["answers"] if a["model"] == "DER-simulation")
    assert knots.get("cow-hitch").loading in der_answer["assumptions"]
    # both legs loaded (issue 25): the scene's asymmetric loading, T_low on the other leg
    assert main(args + ["--free-end-load", "0.3N", "--json", "-"]) == 0
    assert seen["t_low_fraction"] == pytest.approx(1.0)
    assert _strict(capsys.readouterr().out)["decided_by"] == "DER-simulation"
