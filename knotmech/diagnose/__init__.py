"""knotmech.diagnose: the mismatch engine.

Find where a recording and its baseline model differ, name the missing physics
from a catalogue of effects, add it, refit, and show the held-out error drop.

Public API::

    from knotmech.diagnose import diagnose, read_recording
    report = diagnose(read_recording("pull.csv"))          # or diagnose("pull.csv")
    report = diagnose(experiment="pinch", x=fn, y=ft, metadata={...})  # arrays
    print(report.summary); report.write_json("out.json"); plot_report(report, "fit.png")

Layout: one module per experiment kind in :mod:`knotmech.diagnose.experiments`
(:class:`Experiment`) and one per effect in :mod:`knotmech.diagnose.effects`
(:class:`Effect`), each registered once; :func:`get_experiment` and :func:`get_effect`
are the lookups by name; :mod:`knotmech.diagnose.der` holds the DER baseline
(:mod:`knotmech.diagnose.der_knot` that of knot_pull); :func:`diagnose_many`
(:mod:`knotmech.diagnose.joint`) diagnoses several recordings of one set-up together.
"""

from knotmech.diagnose.effects import CATALOGUE, Effect, applicable_effects, get_effect
from knotmech.diagnose.engine import diagnose
from knotmech.diagnose.experiments import EXPERIMENT_KINDS, Experiment, get_experiment
from knotmech.diagnose.joint import diagnose_many
from knotmech.diagnose.plot import plot_report
from knotmech.diagnose.recording import (
    EXPERIMENTS,
    Recording,
    parse_recording,
    read_recording,
    recording_from_arrays,
)
from knotmech.diagnose.report import Report
from knotmech.diagnose.synth import make_recording

__all__ = [
    "diagnose",
    "diagnose_many",
    "Report",
    "Recording",
    "read_recording",
    "parse_recording",
    "recording_from_arrays",
    "EXPERIMENTS",
    "CATALOGUE",
    "Effect",
    "get_effect",
    "EXPERIMENT_KINDS",
    "Experiment",
    "get_experiment",
    "applicable_effects",
    "plot_report",
    "make_recording",
]
