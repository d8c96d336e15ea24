"""Parallel parameter sweeps with an on-disk cache.

Phase diagrams and friction fits run many independent evaluations of one
function at different parameters. :func:`sweep` runs them

- on local processes (:class:`concurrent.futures.ProcessPoolExecutor`) by default,
- in the calling process when ``processes=1`` (or when one task is left to do),
- on a Dask cluster when ``scheduler`` is a scheduler address such as
  ``"tcp://10.0.0.5:8786"`` or a ``distributed.Client`` (optional extra
  ``pip install "knotmech[dask]"``),

with a tqdm progress bar, and stores every result on disk under a stable hash of
(function qualified name, JSON-canonical parameters, version tag, knotmech
version), so a rerun with a grown grid only computes the new points.

Example
-------
>>> from knotmech.sweep import sweep
>>> res = sweep(my_simulation, {"mu": [0.2, 0.3], "T_high": [1.0, 2.0]},
...             cache_dir="cache/hitch")            # doctest: +SKIP
>>> res.params[0], res[0]                            # doctest: +SKIP

The cache is keyed on the function's *name*, not its code: after changing what a
function computes, bump its version (``version=`` or a ``__sweep_version__``
attribute on the function) or delete the cache folder.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import itertools
import json
import os
import pickle
import tempfile
import traceback
from collections.abc import Callable, Iterable, Mapping, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path
from typing import Any

import numpy as np

from knotmech.errors import InputError, KnotmechError

__all__ = [
    "sweep",
    "param_grid",
    "param_hash",
    "SweepResult",
    "SweepTaskError",
    "TaskFailure",
]

_CACHE_FORMAT = 1


class SweepTaskError(KnotmechError, RuntimeError):
    """One or more tasks of a sweep raised.

    Attributes
    ----------
    failures : list of TaskFailure
        Every failed task (index, parameters, exception text, traceback).
    result : SweepResult
        The partial result; failed entries hold their :class:`TaskFailure`.
        Successful results are cached as usual, so a rerun after a fix only
        recomputes the failed points.
    """

    def __init__(self, message: str, failures: list[TaskFailure], result: SweepResult):
        super().__init__(message)
        self.failures = failures
        self.result = result


@dataclasses.dataclass(frozen=True)
class TaskFailure:
    """A task that raised: where, with which parameters, and why."""

    index: int
    params: dict
    error: str  # "ExceptionType: message"
    traceback: str

    def __str__(self) -> str:
        return f"task {self.index} {_short(self.params)} raised {self.error}"


@dataclasses.dataclass
class SweepResult(Sequence):
    """Results of a sweep, in the order of the parameter list.

    Behaves as a read-only sequence of the results; also carries the parameters
    and counts.

    Attributes
    ----------
    params : list of dict
        The parameter sets, one per result.
    results : list
        ``func(**params[i])`` for each i (a :class:`TaskFailure` where the task
        raised and ``on_error="return"``).
    n_computed, n_cached : int
        How many results were computed in this call and how many came from the cache.
    failures : list of TaskFailure
    """

    params: list
    results: list
    n_computed: int = 0
    n_cached: int = 0
    failures: list = dataclasses.field(default_factory=list)

    def __len__(self) -> int:
        return len(self.results)

    def __getitem__(self, i):
        return self.results[i]

    @property
    def ok(self) -> bool:
        """True when no task failed."""
        return not self.failures


# --------------------------------------------------------------------------- parameters


def param_grid(grid: Mapping[str, Any]) -> list[dict]:
    """Cartesian product of a mapping ``name -> values`` as a list of dicts.

    Keys keep their insertion order and the last key varies fastest. A value
    that is a scalar (or a string) is a fixed parameter; lists, tuples, ranges
    and 1-D arrays are axes.

    >>> param_grid({"a": [1, 2], "b": [10, 20], "c": "x"})[:2]
    [{'a': 1, 'b': 10, 'c': 'x'}, {'a': 1, 'b': 20, 'c': 'x'}]
    """
    if not isinstance(grid, Mapping):
        raise InputError(f"grid must be a mapping name -> values, got {type(grid).__name__}")
    names = list(grid)
    axes = []
    for name in names:
        if not isinstance(name, str):
            raise InputError(f"grid keys must be parameter names (str), got {name!r}")
        values = grid[name]
        if isinstance(values, np.ndarray):
            if values.ndim > 1:
                raise InputError(f"grid axis {name!r} must be 1-D, got shape {values.shape}")
            values = values.tolist() if values.ndim == 1 else [values.item()]
        elif isinstance(values, list | tuple | range):
            values = list(values)
        else:
            values = [values]
        if not values:
            raise InputError(f"grid axis {name!r} is empty")
        axes.append(values)
    return [dict(zip(names, combo, strict=True)) for combo in itertools.product(*axes)]


def _as_param_list(param_grid_or_list) -> list[dict]:
    if isinstance(param_grid_or_list, Mapping):
        return param_grid(param_grid_or_list)
    if isinstance(param_grid_or_list, str | bytes) or not isinstance(param_grid_or_list, Iterable):
        raise InputError(
            "param_grid_or_list must be a mapping name -> values or a list of dicts, "
            f"got {type(param_grid_or_list).__name__}"
        )
    out = []
    for i, p in enumerate(param_grid_or_list):
        if not isinstance(p, Mapping):
            raise InputError(f"parameter set {i} must be a dict of keyword arguments, got {p!r}")
        out.append(dict(p))
    return out


def _jsonable(obj):
    """``json.dumps`` default: numpy, paths and dataclasses to plain JSON."""
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, np.ndarray):
        return {"__ndarray__": obj.tolist(), "dtype": str(obj.dtype)}
    if isinstance(obj, Path):
        return str(obj)
    if isinstance(obj, set | frozenset):
        return sorted(obj, key=repr)
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return {"__dataclass__": type(obj).__qualname__, **dataclasses.asdict(obj)}
    raise TypeError(type(obj).__name__)


def _canonical(obj) -> str:
    try:
        return json.dumps(obj, sort_keys=True, separators=(",", ":"), default=_jsonable)
    except (TypeError, ValueError) as exc:
        raise InputError(
            f"sweep parameters must be JSON-serialisable (numbers, strings, lists, dicts, "
            f"numpy arrays, dataclasses); cannot encode {exc}"
        ) from None


def _func_name(func: Callable) -> str:
    if isinstance(func, functools.partial):
        inner = _func_name(func.func)
        return f"partial({inner},{_canonical([list(func.args), func.keywords])})"
    module = getattr(func, "__module__", None) or "?"
    qualname = getattr(func, "__qualname__", None) or type(func).__qualname__
    return f"{module}.{qualname}"


def param_hash(func: Callable, params: Mapping, version: str | None = None) -> str:
    """Stable hash of one task: function name, canonical parameters, version tags.

    Parameters
    ----------
    func : callable
        The function (its module and qualified name enter the key; a
        :class:`functools.partial` adds its bound arguments).
    params : dict
        Keyword arguments; serialised as JSON with sorted keys, so the key order
        does not matter, but ``1`` and ``1.0`` differ.
    version : str, optional
        User version tag; defaults to ``func.__sweep_version__`` or ``"0"``.

    Returns
    -------
    str
        64 hexadecimal digits (SHA-256).
    """
    from knotmech import __version__

    if version is None:
        version = str(getattr(func, "__sweep_version__", "0"))
    payload = _canonical(
        {
            "func": _func_name(func),
            "params": dict(params),
            "version": str(version),
            "knotmech": __version__,
            "format": _CACHE_FORMAT,
        }
    )
    return hashlib.sha256(payload.encode()).hexdigest()


# --------------------------------------------------------------------------- cache


class _Cache:
    def __init__(self, cache_dir):
        self.dir = Path(cache_dir)
        try:
            self.dir.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise InputError(f"cache_dir {str(cache_dir)!r} cannot be created: {exc}") from None

    def _path(self, key: str) -> Path:
        return self.dir / key[:2] / f"{key}.pkl"

    def get(self, key: str):
        """Return (True, value) when cached, else (False, None); unreadable entries are misses."""
        path = self._path(key)
        if not path.is_file():
            return False, None
        try:
            with open(path, "rb") as fh:
                entry = pickle.load(fh)
            return True, entry["result"]
        except Exception:  # a truncated or foreign file: recompute it
            return False, None

    def put(self, key: str, func_name: str, params: dict, result) -> None:
        path = self._path(key)
        path.parent.mkdir(exist_ok=True)
        entry = {"func": func_name, "params": params, "result": result}
        fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
        try:
            with os.fdopen(fd, "wb") as fh:
                pickle.dump(entry, fh, protocol=pickle.HIGHEST_PROTOCOL)
            os.replace(tmp, path)  # atomic: a reader never sees half a file
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise


# --------------------------------------------------------------------------- execution


def _run_one(func, params):
    """Worker side: call and capture any exception as text (picklable everywhere)."""
    try:
        return True, func(**params), None
    except Exception as exc:
        return False, f"{type(exc).__name__}: {exc}", traceback.format_exc()


def _short(params: Mapping, limit: int = 120) -> str:
    text = ", ".join(f"{k}={v!r}" for k, v in params.items())
    return "(" + (text if len(text) <= limit else text[: limit - 3] + "...") + ")"


def _iter_local(func, todo, n_workers):
    """Yield (index, outcome) as tasks finish on a process pool."""
    try:
        pickle.dumps(func)
    except Exception:
        raise InputError(
            f"func {_func_name(func)} cannot be sent to worker processes (it must be a "
            "module-level function); define it at module level or pass processes=1"
        ) from None
    with ProcessPoolExecutor(max_workers=n_workers) as pool:
        futures = {pool.submit(_run_one, func, params): i for i, params in todo}
        for fut in as_completed(futures):
            yield futures[fut], fut.result()


def _iter_serial(func, todo):
    for i, params in todo:
        yield i, _run_one(func, params)


def _iter_dask(func, todo, scheduler):
    try:
        from distributed import Client
        from distributed import as_completed as dask_as_completed
    except ImportError:
        raise InputError(
            "a Dask scheduler was given but dask.distributed is not installed; "
            'install it with: pip install "knotmech[dask]"'
        ) from None
    own_client = False
    if isinstance(scheduler, Client):
        client = scheduler
    elif isinstance(scheduler, str):
        try:
            client = Client(scheduler, timeout="30s", set_as_default=False)
        except Exception as exc:  # OSError / TimeoutError from distributed
            raise InputError(f"cannot reach Dask scheduler {scheduler!r}: {exc}") from None
        own_client = True
    else:
        raise InputError(
            "scheduler must be an address such as 'tcp://host:8786' or a distributed.Client, "
            f"got {type(scheduler).__name__}"
        )
    try:
        futures = {}
        for i, params in todo:
            fut = client.submit(_run_one, func, params, pure=False)
            futures[fut] = i
        with client.as_current():
            for fut in dask_as_completed(list(futures)):
                yield futures[fut], fut.result()
    finally:
        if own_client:
            client.close()


def _check_sweep_args(func, on_error, processes) -> None:
    """One-line InputErrors for a non-callable ``func``, a bad ``on_error`` or ``processes``."""
    if not callable(func):
        raise InputError(f"func must be callable, got {type(func).__name__}")
    if on_error not in ("raise", "return"):
        raise InputError(f"on_error must be 'raise' or 'return', got {on_error!r}")
    if processes is not None and (
        isinstance(processes, bool) or not isinstance(processes, int | np.integer) or processes < 1
    ):
        raise InputError(f"processes must be an integer >= 1, got {processes!r}")


def _from_cache(func, params_list, cache, version):
    """(results with the cached ones filled in, cache keys, tasks to run as (index, params),
    number cached)."""
    n = len(params_list)
    results: list = [None] * n
    keys: list = [None] * n
    todo = []
    n_cached = 0
    for i, params in enumerate(params_list):
        if cache is not None:
            keys[i] = param_hash(func, params, version)
            hit, value = cache.get(keys[i])
            if hit:
                results[i] = value
                n_cached += 1
                continue
        else:
            _canonical(params)  # same input check with or without a cache
        todo.append((i, params))
    return results, keys, todo, n_cached


def _outcomes(func, todo, scheduler, processes):
    """(index, (ok, value, traceback)) as the tasks finish: on a dask ``scheduler``, local
    worker processes, or in this process (one worker or one task)."""
    if scheduler is not None:
        return _iter_dask(func, todo, scheduler)
    n_workers = int(processes) if processes is not None else (os.cpu_count() or 1)
    n_workers = min(n_workers, max(len(todo), 1))
    if n_workers <= 1 or len(todo) <= 1:
        return _iter_serial(func, todo)
    return _iter_local(func, todo, n_workers)


def sweep(
    func: Callable,
    param_grid_or_list,
    *,
    processes: int | None = None,
    scheduler=None,
    cache_dir=None,
    progress: bool = True,
    version: str | None = None,
    on_error: str = "raise",
    desc: str | None = None,
) -> SweepResult:
    """Evaluate ``func(**params)`` for every parameter set, in parallel, with caching.

    Parameters
    ----------
    func : callable
        A module-level function taking keyword arguments (it is pickled to worker
        processes or Dask workers). Its return value must be picklable.
    param_grid_or_list : mapping or sequence of dict
        A grid ``{"name": values, ...}`` (Cartesian product, see :func:`param_grid`)
        or an explicit list of keyword-argument dicts.
    processes : int, optional
        Local worker processes; default ``os.cpu_count()``. ``1`` runs everything
        in the calling process (no pickling; useful for debugging). Ignored when
        ``scheduler`` is given.
    scheduler : str or distributed.Client, optional
        Dask scheduler address (``"tcp://host:8786"``) or an existing client; the
        tasks then run on that cluster. Needs the optional extra ``knotmech[dask]``.
    cache_dir : path, optional
        Folder of the on-disk cache (one pickle per task, named by
        :func:`param_hash`). Without it nothing is cached.
    progress : bool
        Show a tqdm progress bar (on stderr).
    version : str, optional
        Version tag entering the cache key (default ``func.__sweep_version__`` or "0").
        Bump it when the function changes what it computes.
    on_error : {"raise", "return"}
        ``"raise"`` (default): let every task finish, then raise
        :class:`SweepTaskError` naming the failed parameters. ``"return"``: put a
        :class:`TaskFailure` in place of each failed result. Failures are never cached.
    desc : str, optional
        Label of the progress bar (default: the function name).

    Returns
    -------
    SweepResult
        Results in the order of the parameter list, with ``params``,
        ``n_computed`` and ``n_cached``.

    Raises
    ------
    InputError
        Bad arguments, unpicklable function, missing Dask, unreachable scheduler.
    SweepTaskError
        A task raised (``on_error="raise"``).
    """
    from tqdm.auto import tqdm

    _check_sweep_args(func, on_error, processes)
    params_list = _as_param_list(param_grid_or_list)
    name = _func_name(func)
    cache = _Cache(cache_dir) if cache_dir is not None else None

    n = len(params_list)
    results, keys, todo, n_cached = _from_cache(func, params_list, cache, version)

    failures: list[TaskFailure] = []
    label = desc or name.rsplit(".", 1)[-1]
    bar = tqdm(total=n, initial=n_cached, desc=label, disable=not progress)
    try:
        for i, (ok, value, tb) in _outcomes(func, todo, scheduler, processes):
            if ok:
                results[i] = value
                if cache is not None:
                    cache.put(keys[i], name, params_list[i], value)
            else:
                failure = TaskFailure(index=i, params=params_list[i], error=value, traceback=tb)
                failures.append(failure)
                results[i] = failure
            bar.update(1)
    finally:
        bar.close()

    failures.sort(key=lambda f: f.index)
    out = SweepResult(
        params=params_list,
        results=results,
        n_computed=len(todo) - len(failures),
        n_cached=n_cached,
        failures=failures,
    )
    if failures and on_error == "raise":
        first = failures[0]
        more = f" (and {len(failures) - 1} more)" if len(failures) > 1 else ""
        raise SweepTaskError(
            f"sweep of {name}: {len(failures)} of {n} tasks failed; first: {first}{more} "
            "(tracebacks in .failures)",
            failures,
            out,
        )
    return out
