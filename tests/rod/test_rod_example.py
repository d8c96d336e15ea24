"""The README example (examples/cantilever.py) runs, settles where statics says, prints the
numbers the README quotes, and writes its figure to a scratch folder (never the tracked
docs/img/cantilever.png unless asked)."""

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "cantilever.py"


@pytest.fixture(scope="module")
def example():
    spec = importlib.util.spec_from_file_location("cantilever_example", EXAMPLE)
    ex = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(ex)
    system, result = ex.simulate()
    return ex, system, result


def test_cantilever_example_settles_with_the_clamp_carrying_the_weight(example, tmp_path):
    ex, system, res = example
    assert res.status == "success"
    weight = 9.81 * system.mass[system.node_dofs[:, 2]].sum()
    # 1200 kg/m^3 * pi (1 mm)^2 * 0.2 m * 9.81 m/s^2 = 7.397e-3 N
    assert weight == pytest.approx(1200 * np.pi * 1e-6 * 0.2 * 9.81, rel=1e-12)
    assert res.reactions[-1, :, 2].sum() == pytest.approx(weight, rel=5e-3)
    # nearly settled: the tip moved less than 2 mm (1 % of L) over the last 0.3 s
    assert np.ptp(res.positions[-15:, -1, 2]) < 2e-3
    assert ex.plot(res, tmp_path / "c.png").stat().st_size > 10_000


def test_cantilever_prints_the_numbers_the_readme_quotes(example):
    """The README's comments on the example quote these lines; keep both in step."""
    ex, system, res = example
    lines = ex.summary_lines(system, res)
    assert lines[0].startswith("success: 1000 steps, ")
    # Newton iterations of this run (README: "1445 Newton iterations"); a band, not the
    # exact count, so that a different BLAS may differ by a few iterations
    its = res.stats["newton_iterations"]
    assert 1400 <= its <= 1500, its
    assert f"{its} Newton iterations" in lines[0]
    assert lines[1] == "tip at t = 2 s: [0.151, 0.000, -0.121] m"
    assert lines[2].startswith("clamp force: [")
    assert "7.40" in lines[2].split("]")[0]  # z: 7.40e-03 or 7.41e-03 N
    assert "(the rod's weight: 7.397e-03 N)" in lines[2]


def test_cantilever_writes_to_a_scratch_folder_by_default(tmp_path):
    """Run as a user does: the figure lands in ./knotmech-examples, docs/img is untouched."""
    tracked = ROOT / "docs" / "img" / "cantilever.png"
    before = tracked.stat().st_mtime_ns if tracked.exists() else None
    out = subprocess.run(
        [sys.executable, str(EXAMPLE)],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg"},
    )
    assert out.returncode == 0, out.stderr
    assert (tmp_path / "knotmech-examples" / "cantilever.png").stat().st_size > 10_000
    assert "wrote knotmech-examples/cantilever.png" in out.stdout
    assert (tracked.stat().st_mtime_ns if tracked.exists() else None) == before


def test_cantilever_out_that_is_a_file_is_refused_before_the_run(tmp_path):
    f = tmp_path / "file.png"
    f.write_text("x")
    out = subprocess.run(
        [sys.executable, str(EXAMPLE), "--out", str(f)],
        capture_output=True,
        text=True,
        timeout=60,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    assert out.returncode == 2
    assert out.stderr.strip().count("\n") == 0 and "is not a folder" in out.stderr
