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
    "format_number",
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
    module = None
    try:
        module = load_case(name, root)
        params = inspect.signature(module.run).parameters
        accepts_all = any(p.kind is p.VAR_KEYWORD for p in params.values())
        kwargs = {k: v for k, v in options.items() if accepts_all or k in params}
        result = dict(module.run(quick=quick, out_dir=out, **kwargs))
        result.setdefault("summary", _summary_of(module))
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
            "summary": _summary_of(module) if module is not None else "",
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


_BADGE_CLASS = {"pass": "pass", "fail": "fail", "error": "error"}

#: at most this many items of a list are shown; the rest are in the case's JSON
_MAX_ITEMS = 8
#: at most this many rows of a table of rows (a list of equal-length lists)
_MAX_ROWS = 12


def format_number(x, digits: int = 4) -> str:
    """A number as a reviewer reads it: ``digits`` significant digits, integers exact.

    ``1091.0`` -> ``"1091"``, ``0.262278431`` -> ``"0.2623"``, ``3.1e-06`` -> ``"3.1e-6"``,
    booleans as ``yes``/``no``; anything else is returned as ``str(x)``.
    """
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, int):
        return str(x)
    if isinstance(x, float):
        if x != x or x in (float("inf"), float("-inf")):
            return str(x)
        if x.is_integer() and abs(x) < 1e6:
            return str(int(x))
        text = f"{x:.{digits}g}"
        if "e" in text:
            mant, exp = text.split("e")
            text = f"{mant}e{int(exp)}"
        return text
    return str(x)


def _is_scalar(v) -> bool:
    return v is None or isinstance(v, bool | int | float | str)


def _more(shown: int, total: int, text: str, colspan: int | None = None) -> str:
    """The table row saying how many items there are in all, when some are not shown."""
    if total <= shown:
        return ""
    span = f' colspan="{colspan}"' if colspan is not None else ""
    return f'<tr><td{span} class="more">&hellip; {total} {text} in all</td></tr>'


def _dict_cell(v: dict, depth: int) -> str:
    """HTML of a dict: a two-column table of its keys and their values."""
    esc = html.escape
    if depth >= 3:
        return esc(f"({len(v)} entries, see the JSON)")
    rows = "".join(
        f"<tr><th>{esc(str(k))}</th><td>{_cell(x, depth + 1)}</td></tr>" for k, x in v.items()
    )
    return f'<table class="sub">{rows}</table>'


def _scalars_cell(v) -> str:
    """HTML of a list of scalars: the first ``_MAX_ITEMS``, comma-separated."""
    shown = [format_number(x) if x is not None else "\u2014" for x in v[:_MAX_ITEMS]]
    more = (
        f' <span class="more">&hellip; {len(v)} values in all</span>' if len(v) > _MAX_ITEMS else ""
    )
    return html.escape(", ".join(shown)) + more


def _is_row_table(v) -> bool:
    """True for a list of equal-length lists of scalars, at most 8 columns wide."""
    rowlike = all(isinstance(x, list | tuple) and all(_is_scalar(y) for y in x) for x in v)
    return rowlike and len({len(x) for x in v}) == 1 and len(v[0]) <= 8


def _rows_cell(v) -> str:
    """HTML of a table of rows: the first ``_MAX_ROWS`` rows."""
    rows = "".join(
        "<tr>" + "".join(f"<td>{_cell(y)}</td>" for y in x) + "</tr>" for x in v[:_MAX_ROWS]
    )
    more = _more(_MAX_ROWS, len(v), "rows", colspan=len(v[0]))
    return f'<table class="sub">{rows}{more}</table>'


def _list_cell(v, depth: int) -> str:
    """HTML of a list: scalars inline, a table of rows, else one row per item."""
    if all(_is_scalar(x) for x in v):
        return _scalars_cell(v)
    if _is_row_table(v):
        return _rows_cell(v)
    if depth >= 3:
        return html.escape(f"({len(v)} items, see the JSON)")
    rows = "".join(f"<tr><td>{_cell(x, depth + 1)}</td></tr>" for x in v[:_MAX_ROWS])
    return f'<table class="sub">{rows}{_more(_MAX_ROWS, len(v), "items")}</table>'


def _cell(v, depth: int = 0) -> str:
    """HTML of one value of ``numbers``: scalars formatted, lists and dicts as tables.

    ``depth`` counts the tables this one is nested in; below three levels a dict or a list
    of non-scalars is summarised by its length (the full value is in the case's JSON).
    """
    if v is None:
        return '<span class="none">&mdash;</span>'
    if _is_scalar(v):
        return html.escape(format_number(v))
    if isinstance(v, dict | list | tuple) and not v:
        return '<span class="none">(none)</span>'
    if isinstance(v, dict):
        return _dict_cell(v, depth)
    if isinstance(v, list | tuple):
        return _list_cell(v, depth)
    return html.escape(str(v))


def _badge(verdict: str) -> str:
    cls = _BADGE_CLASS.get(verdict, "error")
    return f'<span class="badge {cls}">{html.escape(str(verdict).upper())}</span>'


def _summary_of(module) -> str:
    """The case's one-sentence summary: ``SUMMARY``, else its docstring's first line."""
    text = getattr(module, "SUMMARY", None)
    if not text:
        text = (inspect.getdoc(module) or "").strip().split("\n\n")[0].replace("\n", " ")
    return str(text).strip()


_CSS = """
body { font-family: system-ui, sans-serif; max-width: 1200px; margin: 1.5em auto;
       padding: 0 1em; line-height: 1.4; color: #1f2328; }
h1 { margin-bottom: 0.2em; } h2 { margin-top: 2em; border-bottom: 1px solid #d0d7de; }
table { border-collapse: collapse; } td, th { border: 1px solid #d0d7de; padding: 3px 8px;
  vertical-align: top; text-align: left; }
th { background: #f6f8fa; font-weight: 600; }
table.summary td.what { max-width: 640px; }
table.numbers th { font-family: ui-monospace, monospace; font-weight: normal; }
table.numbers td { font-family: ui-monospace, monospace; }
table.sub { margin: 0; font-size: 0.92em; } table.sub th, table.sub td { padding: 1px 5px; }
.badge { display: inline-block; padding: 1px 9px; border-radius: 10px; color: white;
  font-weight: 700; font-size: 0.85em; letter-spacing: 0.03em; }
.badge.pass { background: #1a7f37; } .badge.fail { background: #cf222e; }
.badge.error { background: #8250df; }
.what { margin: 0.3em 0 0.8em; } p.lead { font-size: 1.05em; }
figure { margin: 0.8em 0; } figure img { max-width: 100%; height: auto;
  border: 1px solid #d0d7de; } figcaption { font-size: 0.9em; color: #57606a; }
ul.checks { list-style: none; padding-left: 0.3em; } .ok { color: #1a7f37; font-weight: 700; }
.no { color: #cf222e; font-weight: 700; } .none, .more { color: #57606a; }
details { margin: 0.6em 0; } pre { background: #f6f8fa; padding: 0.6em; overflow-x: auto; }
"""


def _seconds(r: dict) -> str:
    """A case's run time for the summary table, or "" when it has none."""
    seconds = r.get("seconds")
    return f"{float(seconds):.1f}" if isinstance(seconds, int | float) else ""


def _summary_row(r: dict) -> str:
    """One row of the page's summary table: case, badge, sentence, checks, seconds."""
    esc = html.escape
    name = str(r["name"])
    checks = r.get("checks", {}) or {}
    n_ok = sum(bool(ok) for ok in checks.values())
    return (
        f'<tr><td><a href="#{esc(name)}">{esc(name)}</a></td><td>{_badge(r["verdict"])}</td>'
        f'<td class="what">{esc(str(r.get("summary") or ""))}</td>'
        f"<td>{n_ok} of {len(checks)}</td><td>{_seconds(r)}</td></tr>"
    )


def _checks_html(checks: dict) -> str:
    """The heading and list of a case's checks, each ticked or crossed ("" if none)."""
    if not checks:
        return ""
    esc = html.escape
    n_ok = sum(bool(ok) for ok in checks.values())
    items = "".join(
        f'<li><span class="{"ok" if ok else "no"}">{"&#10003;" if ok else "&#10007;"}'
        f"</span> {esc(str(k))}</li>"
        for k, ok in checks.items()
    )
    return f'<h3>Checks ({n_ok} of {len(checks)} hold)</h3><ul class="checks">{items}</ul>'


def _figures_html(figures) -> str:
    """Each figure as a thumbnail linking to its full-size PNG beside the page."""
    esc = html.escape
    return "".join(
        f'<figure><a href="{esc(Path(f).name)}" title="open full size">'
        f'<img src="{esc(Path(f).name)}" alt="{esc(Path(f).stem)}" loading="lazy"></a>'
        f"<figcaption>{esc(Path(f).name)} (click for full size)</figcaption></figure>"
        for f in figures
    )


def _numbers_html(numbers: dict) -> str:
    """The case's numbers as a table, 4 significant digits ("" if none)."""
    esc = html.escape
    rows = "".join(
        f"<tr><th>{esc(str(k))}</th><td>{_cell(v)}</td></tr>" for k, v in numbers.items()
    )
    return f'<h3>Numbers</h3><table class="numbers">{rows}</table>' if rows else ""


def _section(r: dict) -> str:
    """One case's section: sentence, checks, figures, numbers, notes, traceback, JSON link."""
    esc = html.escape
    name = str(r["name"])
    what = str(r.get("summary") or "")
    notes = "".join(f"<li>{esc(str(n))}</li>" for n in r.get("notes", []))
    tb = r.get("traceback")
    parts = [
        f'<section id="{esc(name)}"><h2>{esc(name)} {_badge(r["verdict"])}</h2>',
        f'<p class="what">{esc(what)}</p>' if what else "",
        _checks_html(r.get("checks", {}) or {}),
        _figures_html(r.get("figures", [])),
        _numbers_html(r.get("numbers", {}) or {}),
        f"<h3>Notes</h3><ul>{notes}</ul>" if notes else "",
        f"<details><summary>traceback</summary><pre>{esc(tb)}</pre></details>" if tb else "",
        f'<p>All values, unrounded: <a href="{esc(name)}.json">{esc(name)}.json</a></p></section>',
    ]
    return "".join(parts)


def write_index(out_dir, results, *, quick: bool = True) -> Path:
    """Write ``<out_dir>/index.html``, the page a reviewer reads.

    A summary table (case, pass/fail badge, the sentence saying what the case checks and
    against what, checks passed, time), then one section per case: the sentence, its
    checks, its figures (each a link to the full-size PNG), its numbers as tables with 4
    significant digits (the full values are in ``<name>.json``) and its notes.

    Parameters
    ----------
    out_dir : str or Path
        Folder of the page (created if missing); the figures are expected beside it.
    results : list of dict
        One dict per case, as :func:`run_case` returns them.
    quick : bool
        Whether the cases ran in quick mode (said in the title).

    Returns
    -------
    Path
        The page written.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    rows = [_summary_row(r) for r in results]
    sections = [_section(r) for r in results]
    n_pass = sum(r["verdict"] == "pass" for r in results)
    mode = "quick" if quick else "full"
    overall = _badge("pass" if n_pass == len(results) and results else "fail")
    page = f"""<!doctype html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>knotmech validation ({mode})</title>
<link rel="icon" href="data:,">
<style>{_CSS}</style></head><body>
<h1>knotmech validation ({mode}) {overall}</h1>
<p class="lead">{n_pass} of {len(results)} cases pass. Each case puts a simulation or a
computation beside a reference (a closed form, a paper's measurement or figure) and passes
when every one of its checks holds. Figures open full size when clicked; numbers are shown
to 4 significant digits, the full values are in each case's JSON.</p>
<table class="summary"><tr><th>case</th><th>verdict</th><th>what it checks, against what</th>
<th>checks</th><th>seconds</th></tr>
{"".join(rows)}</table>
{"".join(sections)}
</body></html>
"""
    path = out / "index.html"
    path.write_text(page, encoding="utf-8")
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
