"""Issue 27 item 5: an option given twice is refused (argparse would keep the last value)."""

import argparse

import pytest

from knotmech.cli.main import REPEATABLE, SUBCOMMANDS, build_parser, main, repeated_option


@pytest.mark.parametrize("argv", [
    ["hold", "clove-hitch", "--rod-diameter", "4mm", "--post-diameter", "30mm", "--mu", "0.3",
     "--load", "1N", "--mu", "0.5"],
    ["hold", "clove-hitch", "--rod-diameter", "4mm", "--post-diameter", "30mm", "--mu=0.3",
     "--load", "1N", "--load=2N"],
    ["simulate", "pinch", "--normal-load", "0.3N", "--mu", "0.3", "--mu", "0.4"],
])  # fmt: skip
def test_an_option_given_twice_is_refused(argv, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert "is given twice; give it once" in err and "\n" not in err


def test_what_may_repeat():
    assert repeated_option(["simulate", "centreline", "k.csv", "--ends", "free,pull",
                            "--ends", "pull,free"]) is None  # fmt: skip
    assert repeated_option(["x", "--", "--mu", "--mu"]) is None
    assert repeated_option(["x", "--mu", "1", "--mu=2"]) == "--mu"


def test_repeatable_is_every_append_option():
    """REPEATABLE names exactly the options that collect a list (append, extend)."""
    found = set()
    for name in SUBCOMMANDS:
        stack = [build_parser(name, listing=False)]
        while stack:
            p = stack.pop()
            for action in p._actions:
                if isinstance(action, argparse._SubParsersAction):
                    stack.extend(action.choices.values())
                elif isinstance(action, argparse._AppendAction | argparse._ExtendAction):
                    found.update(o for o in action.option_strings if o.startswith("--"))
    assert found == set(REPEATABLE)


def test_no_command_says_why_on_stderr(capsys):
    """Issue 27: `knotmech` alone exited 2 with an empty stderr."""
    assert main([]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert err.strip().splitlines()[-1] == (
        "knotmech: error: give a command (tour, hold, simulate, diagnose, validate)"
    )


def test_a_recording_given_twice_is_refused(tmp_path, capsys):
    """Issue 27: `diagnose pinch.csv pinch.csv` fitted the same data twice."""
    from knotmech.cli.diagnose import template_text

    rec = tmp_path / "pinch.csv"
    rec.write_text(template_text("pinch"), encoding="utf-8")
    argv = ["diagnose", str(rec), str(tmp_path / ".." / tmp_path.name / "pinch.csv"),
            "--json", str(tmp_path / "r.json")]  # fmt: skip
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert "the same recording is given twice" in err and "\n" not in err
    assert not (tmp_path / "r.json").exists()
