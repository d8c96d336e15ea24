"""The package's import layering, as stated by the import-linter contracts in pyproject.toml.

``lint-imports`` checks three contracts (``[tool.importlinter]``): the package's layers
(``cli`` -> ``diagnose | hold | plotting`` -> scenes -> ``sweep`` -> ``rod`` -> closed
forms, materials, units -> ``errors``), the layers inside ``knotmech.diagnose``, and no
import cycle between sibling modules anywhere (function-level imports count). The last two
tests plant an upward import and a cycle in a copy of the package and check that the
contracts break, so the first cannot pass by checking nothing.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
LINT = shutil.which("lint-imports")

pytestmark = pytest.mark.skipif(LINT is None, reason="import-linter is not installed")


def _lint(root: Path) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(root))
    return subprocess.run(
        [LINT, "--no-cache", "--config", str(root / "pyproject.toml")],
        cwd=root,
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
    )


def _copy(tmp_path: Path) -> Path:
    shutil.copytree(
        ROOT / "knotmech",
        tmp_path / "knotmech",
        ignore=shutil.ignore_patterns("__pycache__", "data"),
    )
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    return tmp_path


def _append(path: Path, line: str) -> None:
    path.write_text(path.read_text() + f"\n\ndef _planted():\n    {line}\n")


def test_contracts_kept():
    res = _lint(ROOT)
    assert res.returncode == 0, res.stdout[-4000:] + res.stderr[-2000:]
    assert "3 kept, 0 broken" in res.stdout


def test_an_upward_import_breaks_the_layers(tmp_path):
    root = _copy(tmp_path)
    # the rod solver reaching up into the command line, inside a function
    _append(root / "knotmech" / "rod" / "results.py", "import knotmech.cli.main  # noqa")
    res = _lint(root)
    assert res.returncode == 1
    assert "knotmech layers" in res.stdout and "BROKEN" in res.stdout
    assert "knotmech.rod.results -> knotmech.cli.main" in res.stdout


def test_a_cycle_in_diagnose_breaks_the_contracts(tmp_path):
    root = _copy(tmp_path)
    # the old cycle: the model reaching the effect registry by name
    _append(root / "knotmech" / "diagnose" / "model.py", "import knotmech.diagnose.effects  # noqa")
    res = _lint(root)
    assert res.returncode == 1
    assert "No cycles are allowed in knotmech.diagnose" in res.stdout
    assert "diagnose layers" in res.stdout


if __name__ == "__main__":  # pragma: no cover
    sys.exit(_lint(ROOT).returncode)
