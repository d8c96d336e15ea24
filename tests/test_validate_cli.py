"""`knotmech validate`: discovery, JSON + PNG + index.html, verdicts and exit codes."""

import json
import textwrap
import uuid
from pathlib import Path

import pytest

import knotmech
from knotmech.cli import validate as cli_validate
from knotmech.cli.main import main
from knotmech.errors import InputError

PASSING = """
import matplotlib.figure
from ._common import finish, save_figure

SUMMARY = "A line from y = 0 to 1 against the identity (made up)."

def run(quick=True, out_dir=".", scheduler=None):
    fig = matplotlib.figure.Figure()
    fig.add_subplot().plot([0, 1], [0, 1])
    png = save_figure(fig, out_dir, "good_line")
    return finish("good", out_dir=out_dir, checks={"one is one": True},
                  numbers={"answer": 42.0, "quick": quick, "scheduler": scheduler},
                  figures=[png], quick=quick)
"""

FAILING = """
\"\"\"Two is three, against arithmetic.

More text that is not the summary.
\"\"\"
from ._common import finish

def run(quick=True, out_dir="."):
    return finish("bad", out_dir=out_dir, checks={"two is three": False},
                  numbers={"x": 1.5}, figures=[])
"""

RAISING = """
def run(quick=True, out_dir="."):
    raise RuntimeError("boom in the case")
"""


@pytest.fixture
def cases(tmp_path):
    """A folder of three fake cases sharing the real validation/_common.py helpers."""
    root = tmp_path / f"cases_{uuid.uuid4().hex[:8]}"
    root.mkdir()
    common = Path(knotmech.__file__).resolve().parents[1] / "validation" / "_common.py"
    (root / "_common.py").write_text(common.read_text())
    (root / "good.py").write_text(textwrap.dedent(PASSING))
    (root / "bad.py").write_text(textwrap.dedent(FAILING))
    (root / "broken.py").write_text(textwrap.dedent(RAISING))
    return root


def test_discovery_skips_private_modules(cases):
    assert cli_validate.discover_cases(cases) == ["bad", "broken", "good"]


def test_real_validation_folder_is_found():
    names = cli_validate.discover_cases()
    assert "capstan_decay" in names
    assert all(not n.startswith("_") for n in names)


def test_run_all_writes_json_png_index_and_exit_1(cases, tmp_path, capsys):
    out = tmp_path / "out"
    rc = main(["validate", "--quick", "--out", str(out), "--cases-dir", str(cases)])
    assert rc == 1  # one case fails, one raises
    good = json.loads((out / "good.json").read_text())
    assert good["verdict"] == "pass" and good["numbers"]["answer"] == 42.0
    assert good["numbers"]["quick"] is True and good["numbers"]["scheduler"] is None
    assert (out / "good_line.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert json.loads((out / "bad.json").read_text())["verdict"] == "fail"
    broken = json.loads((out / "broken.json").read_text())
    assert broken["verdict"] == "error" and "boom in the case" in broken["notes"][0]
    page = (out / "index.html").read_text()
    assert '<img src="good_line.png"' in page
    assert "1 of 3 cases pass" in page
    # what each case checks: its SUMMARY, else the first paragraph of its docstring
    assert good["summary"] == "A line from y = 0 to 1 against the identity (made up)."
    assert json.loads((out / "bad.json").read_text())["summary"] == (
        "Two is three, against arithmetic."
    )
    assert page.count("A line from y = 0 to 1 against the identity (made up).") == 2
    assert '<a href="good_line.png" title="open full size">' in page
    for word in ("PASS", "FAIL", "ERROR"):
        assert word in page
    text = capsys.readouterr().out
    assert "good: pass" in text and "bad: fail" in text and "broken: error" in text


def test_only_full_and_scheduler_are_passed_on(cases, tmp_path):
    out = tmp_path / "out"
    rc = main(
        [
            "validate",
            "--full",
            "--only",
            "good",
            "--out",
            str(out),
            "--cases-dir",
            str(cases),
            "--scheduler",
            "tcp://example:8786",
        ]
    )
    assert rc == 0
    good = json.loads((out / "good.json").read_text())
    assert good["numbers"]["quick"] is False
    assert good["numbers"]["scheduler"] == "tcp://example:8786"
    assert not (out / "bad.json").exists()


def test_unknown_case_and_missing_folder_exit_2(cases, tmp_path, capsys):
    assert (
        main(["validate", "--only", "nope", "--out", str(tmp_path), "--cases-dir", str(cases)]) == 2
    )
    assert "unknown validation case(s) nope" in capsys.readouterr().err
    assert main(["validate", "--out", str(tmp_path), "--cases-dir", str(tmp_path / "absent")]) == 2
    assert main(["validate", "--cases-dir", str(cases)]) == 2  # --out is required
    # argparse: mutually exclusive options (main returns argparse's status, 2)
    assert main(["validate", "--quick", "--full", "--out", str(tmp_path)]) == 2


def test_checkout_without_validation_folder_is_a_clear_error(monkeypatch, tmp_path):
    fake_pkg = tmp_path / "site-packages" / "knotmech"
    fake_pkg.mkdir(parents=True)
    monkeypatch.setattr(knotmech, "__file__", str(fake_pkg / "__init__.py"))
    with pytest.raises(InputError, match="source checkout"):
        cli_validate.validation_dir()


def test_list(cases, capsys):
    assert main(["validate", "--list", "--cases-dir", str(cases)]) == 0
    assert capsys.readouterr().out.split() == ["bad", "broken", "good"]


def test_one_case_command_prints_checks_and_short_numbers(tmp_path, capsys):
    """``python -m validation.<name>``: verdict, each check marked, numbers to 4 digits."""
    import importlib.util
    import sys

    path = Path(knotmech.__file__).resolve().parents[1] / "validation" / "_common.py"
    spec = importlib.util.spec_from_file_location("_validation_common_under_test", path)
    common = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = common
    spec.loader.exec_module(common)

    def run(quick=True, out_dir="."):
        return common.finish(
            "demo",
            out_dir=out_dir,
            checks={"ratio within 1 %": True, "order near 2": False},
            numbers={"ratio": 1.0012345678, "grid": list(range(40)), "n": 7},
            figures=[],
            quick=quick,
        )

    assert common.main(run, ["--out", str(tmp_path)]) == 1  # one check fails
    text = capsys.readouterr().out.splitlines()
    assert text[0] == "demo: FAIL"
    assert "  [pass] ratio within 1 %" in text and "  [FAIL] order near 2" in text
    assert "  ratio = 1.001" in text and "  n = 7" in text
    grid = next(line for line in text if line.startswith("  grid = "))
    assert len(grid) <= 2 + len("grid = ") + 72 and grid.endswith("...")
    assert json.loads((tmp_path / "demo.json").read_text())["numbers"]["ratio"] == 1.0012345678
