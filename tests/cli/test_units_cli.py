"""Issue 13 / issue 10 part 4 through `knotmech hold`: inputs that were read wrongly are
refused with one line (exit 2); the README's inputs still answer."""

import pytest

from knotmech.cli.main import main

BASE = {"--rod-diameter": "4mm", "--post-diameter": "30mm", "--mu": "0.3", "--load": "1.47N",
        "--free-end-load": "0N"}  # fmt: skip


def _argv(knot="clove-hitch", **over):
    opts = dict(BASE)
    opts.update({"--" + k.lstrip("-").replace("_", "-"): v for k, v in over.items()})
    return ["hold", knot, *[x for kv in opts.items() for x in kv]]


@pytest.mark.parametrize("option, value, message", [
    ("--rod-diameter", "4,0mm", "comma"),  # was 40 mm
    ("--rod-diameter", "4", "--rod-diameter 4: give a unit, e.g. 4mm"),  # was 4 m
    ("--post-diameter", "30", "--post-diameter 30: give a unit, e.g. 30mm"),
    ("--load", "1.47", "--load 1.47: give a unit, e.g. 1.47N"),
    ("--mu", "0.3 deg", "--mu: give a plain number"),  # was 0.0052
    ("--mu", "\uff10.3", "non-ASCII digit"),  # fullwidth 0
    ("--load", "1_0N", "'_'"),  # was 10 N
    ("--rod-diameter", "\u22124mm", "diameter"),  # U+2212 is a minus (was +4 mm): refused
])  # fmt: skip
def test_hold_refuses_what_was_read_wrongly(option, value, message, capsys):
    assert main(_argv(**{option.lstrip("-"): value})) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and "\n" not in err


def test_hold_capstan_bare_wrap_angle_is_refused(capsys):
    # issue 10: `--wrap-angle 360` was 360 rad (57 turns) and a margin of 2e42 %
    argv = _argv("capstan", load="5N", free_end_load="1N") + ["--wrap-angle", "360"]
    assert main(argv) == 2
    assert "--wrap-angle 360: give a unit, e.g. 360deg" in capsys.readouterr().err


def test_hold_readme_capstan_still_answers(capsys):
    argv = _argv("capstan", load="5N", free_end_load="1N") + ["--wrap-angle", "360deg"]
    assert main(argv) == 0
    assert "HOLDS" in capsys.readouterr().out  # e^(mu_eff 2pi) = 5.196 > 5
