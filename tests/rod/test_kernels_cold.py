"""knotmech.rod.kernels_cold: names real kernels and reads their numba caches."""

import importlib
import os
import subprocess
import sys
from pathlib import Path

from knotmech import rod
from knotmech.rod.kernels import _cold, simulation_kernels


def test_the_named_kernels_exist_and_are_caching_dispatchers():
    names = simulation_kernels(cylinder_contact=True, rod_contact=True)
    assert len(names) == 9 and len(simulation_kernels()) == 6
    for name in names:
        module, func = name.rsplit(".", 1)
        kernel = getattr(importlib.import_module(f"knotmech.rod._kernels.{module}"), func)
        assert kernel._cache._cache_file is not None  # @njit(cache=True)


def test_cold_with_an_empty_numba_cache(tmp_path):
    """A fresh cache folder (a first run): the kernels would compile."""
    root = Path(__file__).resolve().parents[2]
    code = "from knotmech import rod; print(rod.kernels_cold(cylinder_contact=True))"
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "numba"), "PYTHONPATH": str(root)}
    env.pop("NUMBA_DISABLE_JIT", None)
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "True"


def test_warm_after_a_simulation():
    r = rod.Rod.straight(length=0.05, n_nodes=6, radius=1e-3, youngs_modulus=1e6, density=1e3)
    system = rod.RodSystem([r])
    res = rod.simulate(system, t_end=0.004, dt=2e-3, constraints=[rod.clamp_end(system)])
    assert res.success
    # the elastic kernels are compiled and cached now (the band solver's may not be: a
    # plain rod uses LAPACK), so at least the three energy kernels are warm
    assert not any(_cold(n) for n in simulation_kernels()[:3])
