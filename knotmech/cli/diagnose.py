"""``knotmech diagnose``: where a recording and its baseline model differ, and why.

Example::

    knotmech diagnose pull.csv --json report.json --plot report.png
    knotmech diagnose n1.csv n2.csv n3.csv --json joint.json   # one set-up, fitted together
    knotmech diagnose --template pinch > my_pinch.csv

Reads and validates the recording (``docs/recordings.md``), runs
:func:`knotmech.diagnose.diagnose`, writes the JSON report, prints the one-line
verdict and a short summary; several recordings go to
:func:`knotmech.diagnose.diagnose_many`. ``--baseline der`` uses the DER capstan
(capstan_pull, :class:`knotmech.diagnose.der.DERCurves`) or the DER overhand knot
(knot_pull, :mod:`knotmech.diagnose.der_knot`) as the baseline. ``--template
KIND`` prints a valid example recording of that kind (``knotmech/data/templates``).
The output paths (``--json``, ``--plot`` and its format) are checked before any work
starts. Exit status 0 once the report is written (whatever the verdict); 2 on a bad
recording or bad options (one line, no traceback).
"""

from __future__ import annotations

import sys
from importlib import resources
from pathlib import Path

from knotmech.cli._paths import check_output_path, plot_formats, writing
from knotmech.errors import InputError

__all__ = ["register", "run", "template_kinds", "template_text"]


def template_kinds() -> tuple[str, ...]:
    """Experiment kinds with an example recording in ``knotmech/data/templates``."""
    folder = resources.files("knotmech") / "data" / "templates"
    if not folder.is_dir():
        return ()
    return tuple(
        sorted(p.name[: -len(".csv")] for p in folder.iterdir() if p.name.endswith(".csv"))
    )


def template_text(kind: str) -> str:
    """The example recording of ``kind`` (raises InputError for a kind without one)."""
    kinds = template_kinds()
    if kind not in kinds:
        raise InputError(f"--template: no template for {kind!r}; kinds: {', '.join(kinds)}")
    path = resources.files("knotmech") / "data" / "templates" / f"{kind}.csv"
    return path.read_text(encoding="utf-8")


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "diagnose",
        help="find where a recording differs from its baseline model and name the missing physics",
        description=(
            "Fit the closed-form baseline of the recording's experiment, locate systematic "
            "residuals, add catalogue effects one at a time while they are significant "
            "(parametric bootstrap) and improve the held-out error, and report the verdict. "
            "The recording format: docs/recordings.md; an example of each kind: --template KIND."
        ),
    )
    p.add_argument(
        "recording",
        metavar="REC.csv",
        nargs="*",
        help="recording file(s) (CSV with # metadata); several: one set-up, fitted together",
    )
    p.add_argument("--json", metavar="OUT.json", help="write the report here (required)")
    p.add_argument(
        "--plot", metavar="FILE", default=None, help="also draw the fit (PNG, PDF, SVG...)"
    )
    p.add_argument(
        "--template",
        metavar="KIND",
        default=None,
        help=(
            "print a valid example recording of this experiment kind and exit "
            f"({', '.join(template_kinds()) or 'none installed'}); e.g. "
            "knotmech diagnose --template pinch > pinch.csv"
        ),
    )
    p.add_argument(
        "--baseline",
        choices=("closed-form", "der"),
        default="closed-form",
        help=(
            "baseline model family (default closed-form); der: capstan_pull (the DER capstan "
            "with kinetic friction only, rope-like EI, 40 elements, ~17 runs of ~0.3 s; "
            "static_friction re-runs it with mu_s > mu_k, decided by the asymptotic "
            "likelihood ratio) or knot_pull (3 DER overhand pulls on a coarse mesh, a smooth "
            "surface in mu as the baseline, the usual bootstrap on it)"
        ),
    )
    p.add_argument("--seed", type=int, default=0, help="seed of the bootstrap, >= 0 (default 0)")
    p.add_argument(
        "--alpha", type=float, default=0.01, help="family-wise significance level (default 0.01)"
    )
    p.set_defaults(func=run)


def run(args) -> int:
    if args.template is not None:
        if args.recording or args.json or args.plot:
            raise InputError("--template KIND prints an example recording; give it alone")
        sys.stdout.write(template_text(args.template))
        return 0
    if not args.recording or not args.json:
        missing = [n for n, v in (("REC.csv", args.recording), ("--json", args.json)) if not v]
        raise InputError(
            f"missing {' and '.join(missing)}: knotmech diagnose REC.csv [REC2.csv ...] "
            "--json OUT.json (or --template KIND for an example recording)"
        )
    _check_distinct(args.recording)
    json_path, plot_path = _output_paths(args)
    # imported here, not at the top, for start-up speed: `knotmech --help` and the other
    # commands do not load SciPy and the engine
    from knotmech.diagnose import diagnose_many, plot_report, read_recording

    recs = [read_recording(path) for path in args.recording]
    report = diagnose_many(recs, baseline=args.baseline, seed=args.seed, alpha=args.alpha)
    with writing(json_path, option="--json"):
        report.write_json(json_path)
    if plot_path is not None:
        with writing(plot_path, option="--plot"):
            plot_report(report, plot_path)
    print(report.summary)
    print(f"  report: {args.json}" + (f", plot: {args.plot}" if args.plot else ""))
    return 0


def _check_distinct(paths) -> None:
    """Refuse a recording named twice: fitting the same data twice would count it twice."""
    seen = {}
    for path in map(Path, paths):
        key = path.resolve() if path.exists() else path
        if key in seen:
            raise InputError(
                f"{path}: the same recording is given twice (as {seen[key]} too); give it once"
            )
        seen[key] = path


def _output_paths(args):
    """``--json`` and ``--plot`` (None when not given), checked before any work starts:
    writable, a known plot format, and not one of the recordings."""
    json_path = check_output_path(args.json, option="--json")
    plot_path = None
    if args.plot is not None:
        plot_path = check_output_path(args.plot, formats=plot_formats(), option="--plot")
    for source in map(Path, args.recording):
        for option, out in (("--json", json_path), ("--plot", plot_path)):
            if out is not None and source.exists() and out.resolve() == source.resolve():
                raise InputError(
                    f"{option} {out}: is the recording itself ({source}); give another file name"
                )
    return json_path, plot_path
