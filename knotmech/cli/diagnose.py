"""``knotmech diagnose``: where a recording and its baseline model differ, and why.

Example::

    knotmech diagnose pull.csv --json report.json --plot report.png

Reads and validates the recording (``shared/spec/recordings.md``), runs
:func:`knotmech.diagnose.diagnose`, writes the JSON report, prints the one-line
verdict and a short summary. ``--baseline der`` (capstan_pull) uses the DER capstan
as the baseline, see :class:`knotmech.diagnose.baselines.DERCurves`. Exit status 0 once
the report is written (whatever the verdict); 2 on a bad recording or bad options
(one line, no traceback).
"""

from __future__ import annotations

from knotmech.diagnose import diagnose_many, plot_report, read_recording

__all__ = ["register", "run"]


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "diagnose",
        help="find where a recording differs from its baseline model and name the missing physics",
        description=(
            "Fit the closed-form baseline of the recording's experiment, locate systematic "
            "residuals, add catalogue effects one at a time while they are significant "
            "(parametric bootstrap) and improve the held-out error, and report the verdict."
        ),
    )
    p.add_argument(
        "recording",
        metavar="REC.csv",
        nargs="+",
        help="recording file(s) (CSV with # metadata); several: one set-up, fitted together",
    )
    p.add_argument("--json", metavar="OUT.json", required=True, help="write the report here")
    p.add_argument("--plot", metavar="FILE", default=None, help="also draw the fit (PNG, PDF...)")
    p.add_argument(
        "--baseline",
        choices=("closed-form", "der"),
        default="closed-form",
        help=(
            "baseline model family (default closed-form); der: capstan_pull only, the DER "
            "capstan with kinetic friction only (rope-like EI, 40 elements, ~17 runs of ~0.3 s); "
            "static_friction re-runs it with mu_s > mu_k, decided by the asymptotic "
            "likelihood ratio (no bootstrap), BIC and the held-out check"
        ),
    )
    p.add_argument("--seed", type=int, default=0, help="seed of the bootstrap (default 0)")
    p.add_argument(
        "--alpha", type=float, default=0.01, help="family-wise significance level (default 0.01)"
    )
    p.set_defaults(func=run)


def run(args) -> int:
    recs = [read_recording(path) for path in args.recording]
    report = diagnose_many(recs, baseline=args.baseline, seed=args.seed, alpha=args.alpha)
    report.write_json(args.json)
    if args.plot:
        plot_report(report, args.plot)
    print(report.summary)
    print(f"  report: {args.json}" + (f", plot: {args.plot}" if args.plot else ""))
    return 0
