"""The diagnosis report: JSON of ``shared/spec/recordings.md`` section 4, summary."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

__all__ = ["Report", "public_parameters", "effect_parameters"]


def _round(v):
    if isinstance(v, (float, np.floating)):
        v = float(v)
        return float(f"{v:.6g}")
    if isinstance(v, (list, tuple)):
        return [_round(u) for u in v]
    return v


def public_parameters(params: dict, effects: tuple, rec) -> dict:
    """Fitted parameters under their report names (``mu_static``, ``positions_m``...).

    ``effects`` are the model's Effect objects: each hides its internal parameters and
    adds its public ones.
    """
    out = {k: v for k, v in params.items() if not any(e.is_internal(k) for e in effects)}
    for e in effects:
        e.public(params, rec, out)
    return {k: _round(v) for k, v in out.items()}


def effect_parameters(effect, public: dict) -> dict:
    """The subset of ``public`` parameters that belongs to ``effect`` (an Effect)."""
    return {k: public[k] for k in effect.report_keys if k in public}


@dataclass
class Report:
    """Result of :func:`knotmech.diagnose.diagnose`.

    ``to_dict()`` gives the JSON of the spec (plus added keys); the arrays are
    kept for plotting and notebooks.
    """

    experiment: str
    verdict: str
    effects: list
    regions: list
    baseline: dict
    final: dict
    heldout_rms_before: float
    heldout_rms_after: float
    summary: str
    details: dict = field(default_factory=dict)
    x: np.ndarray | None = None
    y: np.ndarray | None = None
    baseline_mean: np.ndarray | None = None
    final_mean: np.ndarray | None = None
    columns: tuple = ("x", "y")
    #: per row: the recording it belongs to (several recordings) and its trial; the plot
    #: draws one line per (recording, trial), each sorted by x
    row_recording: np.ndarray | None = None
    row_trial: np.ndarray | None = None

    @property
    def verdict_line(self) -> str:
        return self.summary.splitlines()[0]

    def to_dict(self) -> dict:
        out = {
            "knotmech_report": 1,
            "experiment": self.experiment,
            "verdict": self.verdict,
            "effects": self.effects,
            "regions": [{"start": _round(a), "end": _round(b)} for a, b in self.regions],
            "baseline": self.baseline,
            "final": self.final,
            "heldout_rms_before": _round(self.heldout_rms_before),
            "heldout_rms_after": _round(self.heldout_rms_after),
        }
        out["summary"] = self.summary
        out.update(self.details)
        return out

    def write_json(self, path) -> None:
        Path(path).write_text(json.dumps(self.to_dict(), indent=2) + "\n", encoding="utf-8")
