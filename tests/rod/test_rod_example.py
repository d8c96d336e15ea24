"""The README example (examples/cantilever.py) runs and settles where statics says."""

import importlib.util
from pathlib import Path

import numpy as np
import pytest

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "cantilever.py"


def test_cantilever_example_settles_with_the_clamp_carrying_the_weight(tmp_path):
    spec = importlib.util.spec_from_file_location("cantilever_example", EXAMPLE)
    ex = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(ex)
    res, system = ex.result, ex.system
    assert res.status == "success"
    weight = 9.81 * system.mass[system.node_dofs[:, 2]].sum()
    assert res.reactions[-1, :, 2].sum() == pytest.approx(weight, rel=5e-3)
    # nearly settled: the tip moved less than 2 mm (1 % of L) over the last 0.3 s
    assert np.ptp(res.positions[-15:, -1, 2]) < 2e-3
    assert ex.main(tmp_path / "c.png").stat().st_size > 10_000
