"""Helpers shared by the validation cases: figures, JSON summary, verdict.

A case builds its figures with :mod:`knotmech.plotting` (pyplot-free figures),
saves them with :func:`save_figure`, collects ``checks`` and ``numbers`` and ends
with :func:`finish`, which sets the verdict and writes ``<out_dir>/<name>.json``.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
from collections.abc import Callable, Mapping
from pathlib import Path

import numpy as np

__all__ = ["verdict", "save_figure", "finish", "to_jsonable", "output_dir", "main"]


def output_dir(out_dir) -> Path:
    """Create (if needed) and return the output folder."""
    path = Path(out_dir)
    path.mkdir(parents=True, exist_ok=True)
    return path


def verdict(checks: Mapping[str, bool]) -> str:
    """``"pass"`` when there is at least one check and every check is true, else ``"fail"``."""
    if not checks:
        return "fail"
    return "pass" if all(bool(v) for v in checks.values()) else "fail"


def save_figure(fig, out_dir, name: str, *, dpi: int = 120) -> str:
    """Save a matplotlib figure as ``<out_dir>/<name>.png``; return the path as a string."""
    path = output_dir(out_dir) / f"{name}.png"
    fig.savefig(path, dpi=dpi)
    try:  # free pyplot-managed figures; pyplot-free ones are collected normally
        import matplotlib.pyplot as plt

        plt.close(fig)
    except Exception:  # pragma: no cover - closing is best effort
        pass
    return str(path)


def to_jsonable(obj):
    """Numbers, arrays and dataclasses as plain JSON (NaN/inf become strings)."""
    if isinstance(obj, Mapping):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [to_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return to_jsonable(obj.tolist())
    if isinstance(obj, np.bool_ | bool):
        return bool(obj)
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.floating | float):
        x = float(obj)
        return x if math.isfinite(x) else str(x)
    if isinstance(obj, Path):
        return str(obj)
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return to_jsonable(dataclasses.asdict(obj))
    return obj


def finish(
    name: str,
    *,
    out_dir,
    checks: Mapping[str, bool],
    numbers: Mapping,
    figures: list,
    notes: list | None = None,
    quick: bool = True,
    extra: Mapping | None = None,
) -> dict:
    """Assemble a case summary, set its verdict and write ``<out_dir>/<name>.json``.

    Returns
    -------
    dict
        ``name, verdict, quick, figures, numbers, checks, notes`` and ``extra`` keys.
    """
    result = {
        "name": name,
        "verdict": verdict(checks),
        "quick": bool(quick),
        "figures": [str(f) for f in figures],
        "numbers": to_jsonable(dict(numbers)),
        "checks": {k: bool(v) for k, v in checks.items()},
        "notes": list(notes or []),
    }
    if extra:
        result.update(to_jsonable(dict(extra)))
    path = output_dir(out_dir) / f"{name}.json"
    path.write_text(json.dumps(result, indent=2, sort_keys=False) + "\n")
    return result


def main(run: Callable[..., dict], argv=None) -> int:
    """Command line of one case: ``python -m validation.<name> [--full] [--out DIR]``."""
    parser = argparse.ArgumentParser(description=(run.__module__ or "case") + ": run one case")
    parser.add_argument("--full", action="store_true", help="full resolution (default quick)")
    parser.add_argument("--out", default="validation-out", help="output folder")
    args = parser.parse_args(argv)
    result = run(quick=not args.full, out_dir=args.out)
    print(format_result(result))
    return 0 if result["verdict"] == "pass" else 1


def _short(value, width: int = 72) -> str:
    """A number to 4 significant digits, a list or dict cut to one line of ``width``."""
    if isinstance(value, bool) or value is None:
        return str(value)
    if isinstance(value, int | float):
        return f"{value:.4g}"
    if isinstance(value, list | tuple):
        text = "[" + ", ".join(_short(v, width) for v in value) + "]"
    elif isinstance(value, dict):
        text = "{" + ", ".join(f"{k}: {_short(v, width)}" for k, v in value.items()) + "}"
    else:
        text = str(value)
    return text if len(text) <= width else text[: width - 3] + "..."


def format_result(result: Mapping) -> str:
    """A case's summary for people: verdict, each check, the numbers (short), the figures."""
    lines = [f"{result['name']}: {result['verdict'].upper()}"]
    checks = result.get("checks", {})
    if checks:
        lines.append("checks:")
        lines += [f"  [{'pass' if ok else 'FAIL'}] {name}" for name, ok in checks.items()]
    numbers = result.get("numbers", {})
    if numbers:
        lines.append("numbers:")
        lines += [f"  {key} = {_short(value)}" for key, value in numbers.items()]
    lines += [f"figure: {fig}" for fig in result.get("figures", [])]
    lines += [f"note: {note}" for note in result.get("notes", [])]
    return "\n".join(lines)
