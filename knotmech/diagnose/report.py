"""The diagnosis report: JSON of ``shared/spec/recordings.md`` section 4, summary."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

__all__ = ["Report", "public_parameters", "effect_parameters"]

#: internal parameter names -> report names (others are reported as they are)
_INTERNAL = {"dmu_static"}


def _round(v):
    if isinstance(v, (float, np.floating)):
        v = float(v)
        return float(f"{v:.6g}")
    if isinstance(v, (list, tuple)):
        return [_round(u) for u in v]
    return v


def public_parameters(params: dict, effects: tuple, rec) -> dict:
    """Fitted parameters under their report names (``mu_static``, ``positions_m``...)."""
    from knotmech.analytic.capstan import mu_eff
    from knotmech.diagnose.baselines import reference_speed

    out = {}
    for k, v in params.items():
        if k in _INTERNAL or k.startswith("nip_"):
            continue
        out[k] = v
    if "static_friction" in effects:
        out["mu_static"] = params["mu"] + params["dmu_static"]
        out["mu_kinetic"] = params["mu"]
    if "finite_thickness" in effects:
        dd = rec.meta("post_diameter_m") / rec.meta("rod_diameter_m")
        out["mu_eff"] = float(mu_eff(params["mu"], dd))
    if "self_contact_nip" in effects:
        j, pos, drops = 0, [], []
        while f"nip_position_{j}" in params:
            pos.append(params[f"nip_position_{j}"])
            drops.append(params[f"nip_drop_{j}"])
            j += 1
        order = np.argsort(pos)
        out["positions_m"] = [float(pos[i]) for i in order]
        out["drop_fractions"] = [float(drops[i]) for i in order]
    if "rate_dependent_friction" in effects:
        out["reference_speed_m_per_s"] = reference_speed(rec)
    return {k: _round(v) for k, v in out.items()}


#: report parameters that belong to each effect
_EFFECT_KEYS = {
    "static_friction": ("mu_static", "mu_kinetic", "decay_length_m"),
    "finite_thickness": ("mu", "mu_eff"),
    "contact_flattening": ("onset_load_parameter", "slope_ratio"),
    "adhesion": ("adhesion_force_N",),
    "self_contact_nip": ("positions_m", "drop_fractions"),
    "displacement_offset": ("offset_m",),
    "rate_dependent_friction": ("dmu_dlnv", "reference_speed_m_per_s"),
}


def effect_parameters(name: str, public: dict) -> dict:
    """The subset of ``public`` parameters that belongs to effect ``name``."""
    return {k: public[k] for k in _EFFECT_KEYS[name] if k in public}


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
