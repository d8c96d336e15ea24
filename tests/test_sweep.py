"""knotmech.sweep: ordering, on-disk cache, error reporting, local processes and Dask."""

import functools
import os
import time
import uuid

import numpy as np
import pytest

from knotmech.errors import InputError
from knotmech.sweep import SweepTaskError, TaskFailure, param_grid, param_hash, sweep


def square_and_mark(x, marker_dir, delay=0.0):
    """Square x; leave one file per call in marker_dir so tests can count calls."""
    if delay:
        time.sleep(delay)
    name = f"{x}_{os.getpid()}_{uuid.uuid4().hex}"
    with open(os.path.join(marker_dir, name), "w") as fh:
        fh.write("called")
    return {"x": x, "x2": x * x, "pid": os.getpid()}


def fails_on_three(x):
    if x == 3:
        raise ValueError(f"x={x} is unlucky")
    return x


def weighted(a, b, w=1.0):
    return w * a + b


def n_calls(marker_dir):
    return len(os.listdir(marker_dir))


@pytest.fixture
def markers(tmp_path):
    d = tmp_path / "markers"
    d.mkdir()
    return str(d)


def test_param_grid_order_last_key_fastest():
    grid = param_grid({"a": [1, 2], "b": np.array([10.0, 20.0, 30.0]), "c": "fixed"})
    assert len(grid) == 6
    assert grid[0] == {"a": 1, "b": 10.0, "c": "fixed"}
    assert grid[1] == {"a": 1, "b": 20.0, "c": "fixed"}
    assert grid[3] == {"a": 2, "b": 10.0, "c": "fixed"}
    assert all(type(p["b"]) is float for p in grid)  # numpy scalars become plain floats


def test_results_in_input_order_with_processes(markers):
    # later tasks are faster, so they finish first: order must still be the input order
    xs = [5, 4, 3, 2, 1, 0]
    params = [{"x": x, "marker_dir": markers, "delay": 0.02 * x} for x in xs]
    res = sweep(square_and_mark, params, processes=2, progress=False)
    assert [r["x2"] for r in res] == [x * x for x in xs]
    assert res.params == params
    assert res.n_computed == 6 and res.n_cached == 0
    assert n_calls(markers) == 6
    # really ran in worker processes, not here
    assert os.getpid() not in {r["pid"] for r in res}


def test_cache_second_run_computes_nothing(markers, tmp_path):
    cache = tmp_path / "cache"
    grid = {"x": [1, 2, 3, 4], "marker_dir": markers}
    first = sweep(square_and_mark, grid, processes=2, cache_dir=cache, progress=False)
    assert n_calls(markers) == 4
    second = sweep(square_and_mark, grid, processes=2, cache_dir=cache, progress=False)
    assert n_calls(markers) == 4  # no new call
    assert second.n_computed == 0 and second.n_cached == 4
    assert [r["x2"] for r in second] == [r["x2"] for r in first] == [1, 4, 9, 16]
    # a grown grid computes only the new points
    third = sweep(
        square_and_mark,
        {"x": [1, 2, 3, 4, 5, 6], "marker_dir": markers},
        processes=1,
        cache_dir=cache,
        progress=False,
    )
    assert n_calls(markers) == 6
    assert third.n_computed == 2 and third.n_cached == 4
    # a new version tag invalidates
    sweep(square_and_mark, grid, processes=1, cache_dir=cache, progress=False, version="2")
    assert n_calls(markers) == 10


def test_hash_is_stable_and_discriminating():
    h = param_hash(weighted, {"a": 1.0, "b": 2.0})
    assert h == param_hash(weighted, {"b": 2.0, "a": 1.0})  # key order is irrelevant
    assert h == param_hash(weighted, {"a": np.float64(1.0), "b": 2.0})  # numpy scalar
    assert h != param_hash(weighted, {"a": 1.0, "b": 2.0000001})
    assert h != param_hash(fails_on_three, {"a": 1.0, "b": 2.0})  # other function
    assert h != param_hash(weighted, {"a": 1.0, "b": 2.0}, version="1")
    # a partial's bound keywords are part of the key
    assert param_hash(functools.partial(weighted, w=2.0), {"a": 1.0, "b": 2.0}) != param_hash(
        functools.partial(weighted, w=3.0), {"a": 1.0, "b": 2.0}
    )
    assert len(h) == 64


def test_task_error_is_reported_with_its_parameters(tmp_path):
    with pytest.raises(SweepTaskError) as info:
        sweep(fails_on_three, {"x": [1, 2, 3, 4]}, processes=2, cache_dir=tmp_path, progress=False)
    err = info.value
    assert "1 of 4 tasks failed" in str(err)
    assert "x=3" in str(err) and "ValueError" in str(err) and "unlucky" in str(err)
    assert [f.index for f in err.failures] == [2]
    assert "fails_on_three" in err.failures[0].traceback
    # the other tasks finished and were cached: a rerun computes only the failed one
    res = sweep(
        fails_on_three,
        {"x": [1, 2, 3, 4]},
        processes=1,
        cache_dir=tmp_path,
        progress=False,
        on_error="return",
    )
    assert res.n_cached == 3 and res.n_computed == 0
    assert isinstance(res[2], TaskFailure) and not res.ok
    assert [res[0], res[1], res[3]] == [1, 2, 4]


def test_bad_inputs_are_input_errors(tmp_path):
    with pytest.raises(InputError, match="processes"):
        sweep(weighted, [{"a": 1, "b": 2}], processes=0, progress=False)
    with pytest.raises(InputError, match="JSON"):
        sweep(weighted, [{"a": object(), "b": 2}], cache_dir=tmp_path, progress=False)
    with pytest.raises(InputError, match="module-level"):
        sweep(lambda a: a, [{"a": 1}, {"a": 2}], processes=2, progress=False)
    with pytest.raises(InputError, match="list of dicts"):
        sweep(weighted, 3, progress=False)


def test_serial_path_accepts_lambdas():
    res = sweep(lambda a: 2 * a, {"a": [1, 2, 3]}, processes=1, progress=False)
    assert list(res) == [2, 4, 6]


def test_dask_local_cluster(markers, tmp_path):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        processes=False, n_workers=1, threads_per_worker=2, dashboard_address=None
    ) as cluster:
        grid = {"x": [3, 1, 2], "marker_dir": markers}
        res = sweep(
            square_and_mark,
            grid,
            scheduler=cluster.scheduler_address,
            cache_dir=tmp_path / "c",
            progress=False,
        )
        assert [r["x2"] for r in res] == [9, 1, 4]
        assert n_calls(markers) == 3
        with pytest.raises(SweepTaskError, match="x=3"):
            sweep(
                fails_on_three, {"x": [2, 3]}, scheduler=cluster.scheduler_address, progress=False
            )
    # the cache is shared between backends
    again = sweep(square_and_mark, grid, processes=2, cache_dir=tmp_path / "c", progress=False)
    assert again.n_cached == 3 and n_calls(markers) == 3


def test_missing_dask_is_a_clear_input_error(monkeypatch):
    import builtins

    real_import = builtins.__import__

    def no_distributed(name, *args, **kwargs):
        if name == "distributed" or name.startswith("distributed."):
            raise ImportError("no distributed here")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_distributed)
    with pytest.raises(InputError, match=r"knotmech\[dask\]"):
        sweep(weighted, [{"a": 1, "b": 2}], scheduler="tcp://127.0.0.1:1", progress=False)
