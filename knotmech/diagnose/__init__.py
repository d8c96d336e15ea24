"""knotmech.diagnose: the mismatch engine.

Find where a recording and its baseline model differ, name the missing physics
from a catalogue of effects, add it, refit, and show the held-out error drop.

Public API::

    from knotmech.diagnose import diagnose, read_recording
    report = diagnose(read_recording("pull.csv"))          # or diagnose("pull.csv")
    report = diagnose(experiment="pinch", x=fn, y=ft, metadata={...})  # arrays
    print(report.summary); report.write_json("out.json"); plot_report(report, "fit.png")
"""

from knotmech.diagnose.effects import CATALOGUE, Effect, applicable_effects
from knotmech.diagnose.engine import diagnose
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
    "Report",
    "Recording",
    "read_recording",
    "parse_recording",
    "recording_from_arrays",
    "EXPERIMENTS",
    "CATALOGUE",
    "Effect",
    "applicable_effects",
    "plot_report",
    "make_recording",
]
