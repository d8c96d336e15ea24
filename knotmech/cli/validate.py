"""``knotmech validate``: run the validation cases and write an index page.

The cases live in the top-level ``validation/`` folder of a source checkout (it is
not part of the wheel); each module ``validation/<name>.py`` exposes
``run(quick=True, out_dir=...) -> dict`` (see ``validation/__init__.py``). This
command runs them one after another with a progress bar, writes
``DIR/<name>.json`` and the figures, and ``DIR/index.html`` listing every figure
with its verdict. Exit status: 0 when every case passes, 1 when one fails or
raises, 2 on bad usage (for example no ``validation/`` folder).
"""

from __future__ import annotations

import html
import importlib
import importlib.util
import inspect
import json
import os
import shutil
import sys
import time
import traceback
import types
from pathlib import Path

from knotmech.errors import InputError

__all__ = [
    "register",
    "validation_dir",
    "discover_cases",
    "load_case",
    "run_case",
    "run_cases",
    "write_index",
]


def validation_dir(override=None) -> Path:
    """The folder of validation cases: ``override`` or ``<checkout>/validation``.

    Raises
    ------
    InputError
        When the folder does not exist (an installed wheel has no cases).
    """
    if override is not None:
        root = Path(override).resolve()
        if not root.is_dir():
            raise InputError(f"--cases-dir {str(override)!r} is not a folder")
        return root
    import knotmech

    root = Path(knotmech.__file__).resolve().parent.parent / "validation"
    if not root.is_dir():
        raise InputError(
            f"no validation/ folder next to the knotmech package (looked in {root}); the "
            "validation cases ship with the source checkout, not the wheel: run from a "
            "git clone installed with 'pip install -e .', or pass --cases-dir DIR"
        )
    return root


def discover_cases(root=None) -> list[str]:
    """Names of the case modules in ``root`` (``*.py`` not starting with ``_``), sorted."""
    root = validation_dir(root)
    return sorted(p.stem for p in root.glob("*.py") if not p.stem.startswith("_"))


def _package(root: Path) -> str:
    """Register ``root`` as an importable package named after the folder; return the name."""
    name = root.name
    if not name.isidentifier():
        raise InputError(f"validation folder name {name!r} is not a valid Python identifier")
    existing = sys.modules.get(name)
    if existing is not None:
        paths = [Path(p).resolve() for p in getattr(existing, "__path__", [])]
        if root in paths:
            return name
        raise InputError(
            f"cannot load validation cases from {root}: a different module named {name!r} "
            "is already imported"
        )
    init = root / "__init__.py"
    if init.is_file():
        spec = importlib.util.spec_from_file_location(
            name, init, submodule_search_locations=[str(root)]
        )
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        try:
            spec.loader.exec_module(module)
        except BaseException:
            del sys.modules[name]
            raise
    else:
        module = types.ModuleType(name)
        module.__path__ = [str(root)]
        sys.modules[name] = module
    return name


def load_case(name: str, root=None) -> types.ModuleType:
    """Import the case module ``name`` from the validation folder.

    Parameters
    ----------
    name : str
        Module name without ``.py`` (e.g. ``"coating"``).
    root : path, optional
        Validation folder; default ``<checkout>/validation``.
    """
    root = validation_dir(root)
    if name not in discover_cases(root):
        raise InputError(
            f"no validation case {name!r} in {root}; available: {', '.join(discover_cases(root))}"
        )
    package = _package(root)
    module = importlib.import_module(f"{package}.{name}")
    if not callable(getattr(module, "run", None)):
        raise InputError(f"validation case {name!r} has no run(quick, out_dir) function")
    return module


def run_case(name: str, *, quick: bool = True, out_dir, root=None, **options) -> dict:
    """Run one case and return its summary; an exception becomes verdict ``"error"``.

    Options (``scheduler``, ``progress``) are passed on only when the case's
    ``run`` accepts them. The summary gains ``seconds`` (wall time) and is written
    to ``<out_dir>/<name>.json``.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    try:
        module = load_case(name, root)
        params = inspect.signature(module.run).parameters
        accepts_all = any(p.kind is p.VAR_KEYWORD for p in params.values())
        kwargs = {k: v for k, v in options.items() if accepts_all or k in params}
        result = dict(module.run(quick=quick, out_dir=out, **kwargs))
        missing = {"name", "verdict", "figures", "numbers"} - set(result)
        if missing:
            raise InputError(f"case {name!r} returned no {', '.join(sorted(missing))}")
        if result["verdict"] not in ("pass", "fail"):
            raise InputError(f"case {name!r} returned verdict {result['verdict']!r}")
    except Exception as exc:
        result = {
            "name": name,
            "verdict": "error",
            "quick": bool(quick),
            "figures": [],
            "numbers": {},
            "checks": {},
            "notes": [f"{type(exc).__name__}: {exc}"],
            "traceback": traceback.format_exc(),
        }
    result["seconds"] = round(time.perf_counter() - start, 3)
    # figures outside the output folder are copied in, so the index is self-contained
    figures = []
    for fig in result.get("figures", []):
        path = Path(fig)
        if path.is_file() and path.resolve().parent != out.resolve():
            target = out / path.name
            shutil.copyfile(path, target)
            path = target
        figures.append(str(path))
    result["figures"] = figures
    (out / f"{name}.json").write_text(json.dumps(result, indent=2, default=str) + "\n")
    return result


def run_cases(
    names=None, *, quick: bool = True, out_dir, root=None, progress: bool = True, **options
) -> list[dict]:
    """Run several cases (default: all) with a progress bar; write the index page."""
    from tqdm.auto import tqdm

    available = discover_cases(root)
    names = list(names) if names else available
    unknown = [n for n in names if n not in available]
    if unknown:
        raise InputError(
            f"unknown validation case(s) {', '.join(unknown)}; available: {', '.join(available)}"
        )
    results = []
    bar = tqdm(names, desc="validate", unit="case", disable=not progress)
    for name in bar:
        bar.set_postfix_str(name)
        results.append(run_case(name, quick=quick, out_dir=out_dir, root=root, **options))
    write_index(out_dir, results, quick=quick)
    return results


_COLOURS = {"pass": "#1a7f37", "fail": "#cf222e", "error": "#8250df"}


def write_index(out_dir, results, *, quick: bool = True) -> Path:
    """Write ``<out_dir>/index.html``: a summary table, then every figure with its verdict."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    esc = html.escape
    rows, sections = [], []
    for r in results:
        colour = _COLOURS.get(r["verdict"], "#57606a")
        badge = f'<b style="color:{colour}">{esc(r["verdict"].upper())}</b>'
        rows.append(
            f'<tr><td><a href="#{esc(r["name"])}">{esc(r["name"])}</a></td><td>{badge}</td>'
            f"<td>{r.get('seconds', '')}</td><td>{len(r.get('figures', []))}</td></tr>"
        )
        nums = "".join(
            f"<tr><td>{esc(str(k))}</td><td>{esc(json.dumps(v))}</td></tr>"
            for k, v in r.get("numbers", {}).items()
        )
        checks = "".join(
            f"<li>{'&#10003;' if ok else '&#10007;'} {esc(str(k))}</li>"
            for k, ok in r.get("checks", {}).items()
        )
        notes = "".join(f"<li>{esc(str(n))}</li>" for n in r.get("notes", []))
        figs = "".join(
            f'<figure><img src="{esc(Path(f).name)}" alt="{esc(Path(f).name)}">'
            f"<figcaption>{esc(Path(f).name)} &mdash; {badge}</figcaption></figure>"
            for f in r.get("figures", [])
        )
        tb = f"<pre>{esc(r['traceback'])}</pre>" if r.get("traceback") else ""
        sections.append(
            f'<section id="{esc(r["name"])}"><h2>{esc(r["name"])}: {badge}</h2>'
            f'{figs}<h3>Numbers</h3><table class="n">{nums}</table>'
            f"<h3>Checks</h3><ul>{checks}</ul><h3>Notes</h3><ul>{notes}</ul>{tb}"
            f'<p><a href="{esc(r["name"])}.json">{esc(r["name"])}.json</a></p></section>'
        )
    n_pass = sum(r["verdict"] == "pass" for r in results)
    mode = "quick" if quick else "full"
    page = f"""<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>knotmech validation</title>
<style>
body {{ font-family: sans-serif; max-width: 1100px; margin: 2em auto; }}
table {{ border-collapse: collapse; }} td, th {{ border: 1px solid #ccc; padding: 3px 8px; }}
figure {{ display: inline-block; margin: 0.5em; }} img {{ max-width: 520px; }}
table.n td:last-child {{ font-family: monospace; }}
</style></head><body>
<h1>knotmech validation ({mode})</h1>
<p>{n_pass} of {len(results)} cases pass.</p>
<table><tr><th>case</th><th>verdict</th><th>seconds</th><th>figures</th></tr>
{"".join(rows)}</table>
{"".join(sections)}
</body></html>
"""
    path = out / "index.html"
    path.write_text(page)
    return path


def _main(args) -> int:
    root = validation_dir(args.cases_dir)
    if args.list:
        for name in discover_cases(root):
            print(name)
        return 0
    if args.out is None:
        raise InputError("--out DIR is required (the folder for JSON, PNG and index.html)")
    _make_out_dir(args.out)  # before any case runs
    options = {}
    if args.scheduler:
        options["scheduler"] = args.scheduler
    results = run_cases(
        args.only, quick=not args.full, out_dir=args.out, root=root, progress=True, **options
    )
    for r in results:
        line = f"{r['name']}: {r['verdict']} ({r['seconds']:.1f} s)"
        if r["verdict"] == "error":
            line += f" {r['notes'][0]}"
        print(line)
    print(f"index: {Path(args.out) / 'index.html'}")
    return 0 if all(r["verdict"] == "pass" for r in results) else 1


def _make_out_dir(text) -> Path:
    """Create the output folder ``--out`` now (a case may run for minutes before writing)."""
    path = Path(text)
    if path.exists() and not path.is_dir():
        raise InputError(f"--out {text}: exists and is not a folder")
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"--out {text}: cannot create the folder ({exc.strerror})") from None
    if not os.access(path, os.W_OK | os.X_OK):
        raise InputError(f"--out {text}: the folder is not writable")
    return path


def register(subparsers) -> None:
    """Add the ``validate`` subcommand."""
    p = subparsers.add_parser(
        "validate",
        help="run the validation cases (theory vs simulation), write PNG, JSON and index.html",
        description=__doc__.split("\n\n")[0],
    )
    mode = p.add_mutually_exclusive_group()
    mode.add_argument("--quick", action="store_true", default=True, help="quick runs (default)")
    mode.add_argument("--full", action="store_true", help="full resolution: every figure")
    p.add_argument("--out", metavar="DIR", help="output folder (created if needed)")
    p.add_argument(
        "--only", metavar="NAME", nargs="+", action="extend", help="run only these cases"
    )
    p.add_argument("--list", action="store_true", help="list the cases and exit")
    p.add_argument(
        "--scheduler", metavar="ADDRESS", help="Dask scheduler (tcp://host:8786) for the sweeps"
    )
    p.add_argument(
        "--cases-dir", metavar="DIR", help="folder of cases (default: <checkout>/validation)"
    )
    p.set_defaults(func=_main)
