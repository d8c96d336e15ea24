"""``knotmech hold``: verdicts, JSON output, and one-line errors with exit status 2."""

import json
import math
import subprocess
import sys

import pytest

from knotmech.cli.main import main

CLOVE = [
    "hold",
    "clove-hitch",
    "--rod-diameter",
    "4mm",
    "--post-diameter",
    "30mm",
    "--mu",
    "0.3",
    "--load",
    "1.47N",
]


def test_issue_example_free_end(capsys, tmp_path):
    """Issue 2's example: the ideal rope slips (margin -100 %) but d/D = 0.13 lies outside
    its validity, so the DER phase table (inside its grid, clove-hitch paper Fig. 4:
    such hitches hold) decides, and the disagreement is printed."""
    out_json = tmp_path / "verdict.json"
    rc = main(CLOVE + ["--free-end-load", "0N", "--json", str(out_json)])
    assert rc == 0
    out = capsys.readouterr().out
    assert "verdict: HOLDS" in out
    assert "ideal-rope" in out and "T_low = 0" in out and "disagreement" in out
    data = json.loads(out_json.read_text())
    assert data["holds"] is True
    assert data["decided_by"] == "DER-table"
    ideal = next(a for a in data["answers"] if a["model"] == "ideal-rope")
    assert ideal["holds"] is False and ideal["margin"] == -1.0
    assert ideal["inside_validity"] is False
    assert data["inputs"]["rod_diameter"] == pytest.approx(0.004)


def test_thin_rope_free_end_slips_by_ideal_rope(capsys, tmp_path):
    """Inside the ideal rope's validity (d/D <= 0.1) it decides: a free end always slips."""
    out_json = tmp_path / "verdict.json"
    args = ["hold", "clove-hitch", "--rod-diameter", "2mm", "--post-diameter", "50mm", "--mu",
            "0.3", "--load", "1.47N", "--free-end-load", "0N", "--json", str(out_json)]  # fmt: skip
    assert main(args) == 0
    assert "verdict: SLIPS" in capsys.readouterr().out
    data = json.loads(out_json.read_text())
    assert data["holds"] is False
    assert data["decided_by"] == "ideal-rope"
    assert data["margin"] == -1.0
    assert data["inputs"]["rod_diameter"] == pytest.approx(0.002)
    assert data["inputs"]["load"] == pytest.approx(1.47)
    assert any(a["model"] == "thick-nip" for a in data["answers"])


def test_clove_hitch_with_tension_on_the_free_end_holds(capsys, tmp_path):
    out_json = tmp_path / "v.json"
    # ideal-rope K = exp(0.3*4pi) = 43.38: 1.47 N / 43.38 = 0.0339 N is the threshold
    rc = main(CLOVE + ["--free-end-load", "5gf", "--json", str(out_json)])
    assert rc == 0
    data = json.loads(out_json.read_text())
    assert data["holds"] is True
    K = math.exp(0.3 * 4 * math.pi)
    assert data["margin"] == pytest.approx(K * 5e-3 * 9.80665 / 1.47 - 1, rel=1e-9)


def test_capstan_uses_mu_eff_and_reports_the_ideal(capsys, tmp_path):
    out_json = tmp_path / "c.json"
    args = ["hold", "capstan", "--wrap-angle", "360deg", "--rod-diameter", "4mm"]
    args += ["--post-diameter", "30mm", "--mu", "0.3", "--load", "6N", "--free-end-load", "1N"]
    assert main(args + ["--json", str(out_json)]) == 0
    out = capsys.readouterr().out
    assert "SLIPS" in out and "ideal-capstan" in out and "mu_eff" in out
    data = json.loads(out_json.read_text())
    assert data["holds"] is False  # e^(mu_eff 2pi) = 5.196 < 6 < e^(0.3*2pi) = 6.586
    ideal = next(a for a in data["answers"] if a["model"] == "ideal-capstan")
    assert ideal["holds"] is True


@pytest.mark.parametrize("knot", ["two-half-hitches", "round-turn", "round-turn-two-half-hitches"])
def test_other_knots(knot, capsys):
    args = ["hold", knot, "--rod-diameter", "4mm", "--post-diameter", "30mm", "--mu", "0.3"]
    args += ["--load", "1N", "--free-end-load", "0.5N", "--mu-rr", "0.2"]
    assert main(args) == 0
    assert "verdict: HOLDS" in capsys.readouterr().out


def _run(argv):
    """main(argv), with argparse's own exit (SystemExit) turned into its status."""
    try:
        return main(argv)
    except SystemExit as exc:
        return exc.code


BAD = [
    (["--rod-diameter=-4mm"], "--rod-diameter"),
    (["--rod-diameter", "0mm"], "--rod-diameter"),
    (["--post-diameter", "4N"], "--post-diameter"),
    (["--mu", "-0.1"], "--mu"),
    (["--mu", "nan"], "--mu"),
    (["--load", "3mm"], "--load"),
    (["--load", "garbage"], "--load"),
    (["--free-end-load", "2N"], "--free-end-load"),
    (["--mu-rr", "-1"], "--mu-rr"),
    (["--mu"], "--mu"),  # argparse: expected one argument
    (["--wrap-angle", "1turn"], "--wrap-angle"),
]


@pytest.mark.parametrize(("extra", "name"), BAD)
def test_bad_input_one_line_exit_2(extra, name, capsys):
    base = dict(zip(CLOVE[2::2], CLOVE[3::2], strict=True))
    args = ["hold", "clove-hitch"]
    for key, value in base.items():
        if not any(e == key or e.startswith(key + "=") for e in extra):
            args += [key, value]
    rc = _run(args + extra)
    err = capsys.readouterr().err
    assert rc == 2
    assert name in err
    assert len(err.strip().splitlines()) == 1
    assert "Traceback" not in err


def test_unknown_knot_and_missing_wrap_angle(capsys):
    assert main(["hold", "granny-knot"] + CLOVE[2:]) == 2
    assert "knot" in capsys.readouterr().err
    assert main(["hold", "capstan"] + CLOVE[2:]) == 2
    assert "--wrap-angle" in capsys.readouterr().err


def test_subprocess_no_traceback():
    args = ["hold", "clove-hitch", "--rod-diameter", "4mm", "--mu", "0.3", "--load", "1N"]
    args += ["--post-diameter", "30 furlongs per fortnight"]  # a speed, not a length
    proc = subprocess.run(
        [sys.executable, "-m", "knotmech.cli.main", *args],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert proc.returncode == 2
    assert "--post-diameter" in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1


@pytest.mark.parametrize("knot", ["capstan", "clove-hitch"])
@pytest.mark.parametrize("free", ["0N", "0.1N"])
def test_huge_friction_does_not_overflow(knot, free, capsys):
    args = ["hold", knot, "--rod-diameter", "4mm", "--post-diameter", "30mm", "--mu", "1000"]
    args += ["--load", "1N", "--free-end-load", free, "--json", "-"]
    if knot == "capstan":
        args += ["--wrap-angle", "1turn"]
    assert main(args) == 0
    data = json.loads(capsys.readouterr().out)  # '--json -' prints only the JSON
    if knot == "clove-hitch" and free == "0N":
        # beyond the DER tables' friction range (0.2-0.5): the mu = 0.5 table holds at this
        # geometry, and more friction keeps a hold, so the DER decides (the ideal rope would
        # say it slips at any load)
        assert data["holds"] is True and data["decided_by"] == "DER-table"
        assert data["der"]["mu_tables"] == [0.5]
    else:
        assert data["holds"] is (free != "0N")
