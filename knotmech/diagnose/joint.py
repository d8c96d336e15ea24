r"""Several recordings of one set-up diagnosed together (spec section 5, "Several recordings
at once"): :func:`diagnose_many`.

Procedure (k recordings of one experiment kind, made on one set-up):

1. Each recording is diagnosed alone (:func:`knotmech.diagnose.diagnose`, its own
   calibrated forward selection): this decides which effects each recording shows, so
   an effect that appears in one recording only is reported for that one.
2. Joint fits: the recordings' baseline models (no effects) and their final models
   (each with its own accepted effects) are fitted together by generalised least
   squares, each recording whitened by its own noise model (the one its single fit
   estimated). The *material* parameters are fitted once for all: ``mu`` always, and an
   effect's parameters where the effect lists them in ``shared_parameters`` (e.g.
   ``rate_dependent_friction``'s ``dmu_dlnv``), shared among the recordings that have
   that effect; the rest (stick stiffness and slack of a capstan pull, offsets, nip
   positions, adhesion forces) per recording. A ``mu_nominal`` prior enters once (the
   first recording's that has one: one set-up, one independent measurement).
3. Leave-one-out: each recording in turn is left out, the shared parameters are fitted
   to the others, and the left-out recording is predicted with them (its own
   per-recording parameters, which the others cannot know, are fitted on it with the
   shared ones held fixed; a shared parameter of an effect that no other recording has is
   fitted on it too). The RMS of that prediction error is ``heldout_recordings``, before
   (baseline models) and after (final models).

The report keeps the keys of section 4 (``verdict``: the accepted effect with the
largest total likelihood gain over the recordings, else ``unexplained`` if any recording
is, else ``none``; ``baseline`` and ``final`` parameters are the shared ones of the joint
fits, ``rms`` and ``heldout_rms_*`` pooled over all rows) and adds ``recordings`` and
``heldout_recordings``. A single recording gives :func:`~knotmech.diagnose.diagnose`'s
report exactly.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from scipy.optimize import least_squares

from knotmech.diagnose.engine import diagnose
from knotmech.diagnose.fitting import Data
from knotmech.diagnose.recording import Recording, read_recording
from knotmech.diagnose.report import Report, effect_parameters, public_parameters
from knotmech.diagnose.stats import trial_starts
from knotmech.errors import InputError

__all__ = ["diagnose_many", "shared_names"]


def shared_names(model) -> set:
    """The parameters of ``model`` fitted once for all recordings: ``mu`` and the
    ``shared_parameters`` of its effects."""
    out = {"mu"}
    for e in model.effect_objects:
        out.update(n for n in getattr(e, "shared_parameters", ()) if n in model.names)
    return out


class _Joint:
    """Stacked whitened residuals of several fitted models with shared parameters.

    ``fits``: one Fit per recording (its model, its start, its noise); ``free_shared``:
    names of shared parameters fitted here (others given in ``fixed_shared``).
    """

    def __init__(self, fits, datas, free_shared, fixed_shared=None):
        self.fits, self.datas = fits, datas
        self.fixed_shared = dict(fixed_shared or {})
        self.shared = sorted(free_shared)
        self.slots = []  # per recording: (index into p or a fixed name) per model name
        lo, hi, p0 = [], [], []
        for name in self.shared:
            owners = [f for f in fits if name in f.model.names]
            lo.append(max(f.model.lower[f.model.names.index(name)] for f in owners))
            hi.append(min(f.model.upper[f.model.names.index(name)] for f in owners))
            p0.append(float(np.median([f.params[name] for f in owners])))
        for f in fits:
            slot = []
            for j, name in enumerate(f.model.names):
                if name in self.fixed_shared:
                    slot.append(name)
                elif name in self.shared:
                    slot.append(self.shared.index(name))
                else:
                    slot.append(len(p0))
                    lo.append(f.model.lower[j])
                    hi.append(f.model.upper[j])
                    p0.append(float(f.p[j]))
            self.slots.append(slot)
        self.lower, self.upper = np.array(lo, float), np.array(hi, float)
        span = np.where(np.isfinite(self.upper - self.lower), self.upper - self.lower, 1.0)
        eps = 1e-9 * span
        self.p0 = np.clip(np.array(p0, float), self.lower + eps, self.upper - eps)
        self.sds = [f.noise.sd(f.mean) for f in fits]
        self.starts = [trial_starts(f.model.rec.trial) for f in fits]
        self.prior = next(
            ((d.mu_nominal, d.mu_sigma) for d in datas if d.mu_nominal is not None), None
        )

    def vector(self, i, p) -> np.ndarray:
        """Parameter vector of recording ``i``'s model from the joint vector ``p``."""
        return np.array(
            [self.fixed_shared[s] if isinstance(s, str) else p[s] for s in self.slots[i]]
        )

    def resid(self, p) -> np.ndarray:
        out = []
        for i, f in enumerate(self.fits):
            m = f.model.mean(self.vector(i, p))
            out.append(f.noise.whiten(self.datas[i].y - m, self.sds[i], self.starts[i]))
        if self.prior is not None:
            mu = p[self.shared.index("mu")] if "mu" in self.shared else self.fixed_shared["mu"]
            out.append(np.atleast_1d((mu - self.prior[0]) / self.prior[1]))
        return np.concatenate(out)

    def fit(self) -> np.ndarray:
        if self.p0.size == 0:
            return self.p0
        res = least_squares(
            self.resid, self.p0, bounds=(self.lower, self.upper), method="trf", x_scale="jac"
        )
        return res.x

    def means(self, p) -> list:
        return [f.model.mean(self.vector(i, p)) for i, f in enumerate(self.fits)]


def _joint_fit(fits, datas):
    """Joint fit of ``fits``: (shared values, per-recording parameter dicts, means)."""
    shared = set().union(*(shared_names(f.model) for f in fits))
    j = _Joint(fits, datas, shared)
    p = j.fit()
    params = [f.model.params(j.vector(i, p)) for i, f in enumerate(fits)]
    values = {n: float(p[j.shared.index(n)]) for n in j.shared}
    return values, params, j.means(p)


def _leave_one_out(fits, datas) -> list:
    """Prediction error of each recording from the shared parameters of the others [y units]."""
    errs = []
    for i in range(len(fits)):
        others = [k for k in range(len(fits)) if k != i]
        of = [fits[k] for k in others]
        od = [datas[k] for k in others]
        theirs = set().union(*(shared_names(f.model) for f in of))
        values, _, _ = _joint_fit(of, od)
        mine = shared_names(fits[i].model)
        fixed = {n: values[n] for n in mine & theirs}
        j = _Joint([fits[i]], [datas[i]], mine - theirs, fixed_shared=fixed)
        # the prior is the set-up's: it is part of what the others predict with
        j.prior = None
        p = j.fit()
        errs.append(datas[i].y - j.means(p)[0])
    return errs


def _rms(r) -> float:
    return float(np.sqrt(np.mean(np.asarray(r) ** 2)))


def _g(v) -> float:
    return float(f"{v:.6g}")


def _merge(regions) -> list:
    out = []
    for a, b in sorted(regions):
        if out and a <= out[-1][1]:
            out[-1] = (out[-1][0], max(out[-1][1], b))
        else:
            out.append((a, b))
    return out


def diagnose_many(
    recordings,
    *,
    baseline: str = "closed-form",
    seed: int = 0,
    alpha: float = 0.01,
    max_effects: int = 6,
    effects=None,
) -> Report:
    """Diagnose several recordings of one set-up together (see the module docstring).

    Parameters
    ----------
    recordings : sequence of Recording or path
        Recordings of one experiment kind (at least one). One recording: the report
        of :func:`~knotmech.diagnose.diagnose` exactly.
    baseline : {"closed-form", "der"}
        ``der``: knot_pull only here (each recording's DER knot law is run once).
    seed, alpha, max_effects, effects
        As in :func:`~knotmech.diagnose.diagnose` (recording ``i`` is diagnosed with
        seed ``seed + i``).

    Returns
    -------
    Report
        With ``details["recordings"]`` (per recording: ``file``, ``verdict``,
        ``effects``, ``regions``, ``parameters``, ``rms_before``, ``rms_after``) and
        ``details["heldout_recordings"]`` (``file``, ``rms_before``, ``rms_after``).

    Raises
    ------
    InputError
        No recordings, recordings of different kinds, or a combination not supported.
    """
    recs = _as_recordings(recordings)
    opts = {"seed": seed, "alpha": alpha, "max_effects": max_effects, "effects": effects}
    if len(recs) == 1:
        return diagnose(recs[0], baseline=baseline, **opts)
    kind = _one_kind(recs, baseline)
    singles = [
        diagnose(r, baseline=baseline, **dict(opts, seed=seed + i)) for i, r in enumerate(recs)
    ]
    names = _file_names(recs)
    datas = [_data(s.fits["recording"]) for s in singles]
    base_fits = [s.fits["baseline"] for s in singles]
    final_fits = [s.fits["final"] for s in singles]
    b_shared, _, b_means = _joint_fit(base_fits, datas)
    f_shared, f_params, f_means = _joint_fit(final_fits, datas)
    held_b = _leave_one_out(base_fits, datas)
    held_f = _leave_one_out(final_fits, datas)
    per, held = [], []
    gains: dict = {}
    effects_out: dict = {}
    for i, s in enumerate(singles):
        rec = s.fits["recording"]
        public = public_parameters(f_params[i], final_fits[i].model.effect_objects, rec)
        _gather_effects(s, final_fits[i].model, public, names[i], effects_out, gains)
        per.append(
            {
                "file": names[i],
                "verdict": s.verdict,
                "effects": [e["name"] for e in s.effects],
                "regions": [{"start": _g(a), "end": _g(b)} for a, b in s.regions],
                "parameters": public,
                "rms_before": _g(_rms(datas[i].y - b_means[i])),
                "rms_after": _g(_rms(datas[i].y - f_means[i])),
            }
        )
        held.append(
            {"file": names[i], "rms_before": _g(_rms(held_b[i])), "rms_after": _g(_rms(held_f[i]))}
        )
    _shared_values(effects_out)
    y_all = np.concatenate([d.y for d in datas])
    details = {
        "baseline_model": baseline,
        "recordings": per,
        "heldout_recordings": held,
        "shared_parameters": sorted(f_shared),
        "single_reports": [s.to_dict() for s in singles],
        "alpha": alpha,
        "seed": seed,
    }
    report = Report(
        experiment=kind,
        verdict=_joint_verdict(gains, singles),
        effects=list(effects_out.values()),
        regions=_merge([tuple(r) for s in singles for r in s.regions]),
        baseline={
            "parameters": {k: _g(v) for k, v in b_shared.items()},
            "rms": _g(_rms(y_all - np.concatenate(b_means))),
        },
        final={
            "parameters": {k: _g(v) for k, v in f_shared.items()},
            "rms": _g(_rms(y_all - np.concatenate(f_means))),
        },
        heldout_rms_before=_rms(np.concatenate(held_b)),
        heldout_rms_after=_rms(np.concatenate(held_f)),
        summary="",
        details=details,
        x=np.concatenate([s.x for s in singles]),
        y=y_all,
        baseline_mean=np.concatenate(b_means),
        final_mean=np.concatenate(f_means),
        columns=singles[0].columns,
    )
    report.summary = _summary(report, singles)
    # which recording each row of the concatenated arrays belongs to (for plotting)
    report.row_recording = np.concatenate(
        [np.full(d.y.size, i, dtype=int) for i, d in enumerate(datas)]
    )
    report.row_trial = np.concatenate([s.row_trial for s in singles])
    return report


def _as_recordings(recordings) -> list:
    """Recordings and paths as Recording objects (at least one)."""
    recs = []
    for r in recordings:
        if isinstance(r, Recording):
            recs.append(r)
        elif isinstance(r, (str, Path)):
            recs.append(read_recording(r))
        else:
            raise InputError(f"a recording must be a Recording or a path, got {type(r).__name__}")
    if not recs:
        raise InputError("diagnose_many needs at least one recording")
    return recs


def _one_kind(recs, baseline: str) -> str:
    """The one experiment kind of ``recs``, refused with the baselines it cannot take."""
    kinds = sorted({r.experiment for r in recs})
    if len(kinds) > 1:
        raise InputError(
            f"recordings diagnosed together must be of one experiment kind, got {', '.join(kinds)}"
        )
    if baseline == "der" and kinds[0] != "knot_pull":
        raise InputError(
            "several recordings with baseline 'der' are supported for knot_pull only; "
            "use closed-form, or diagnose them one at a time"
        )
    return kinds[0]


def _data(rec) -> Data:
    return Data(rec.y, rec.mu_nominal, rec.mu_nominal_sigma)


def _gather_effects(single, model, public, name, effects_out, gains) -> None:
    """Add one recording's accepted effects to ``effects_out`` (name -> entry with
    per-recording parameters and evidence) and their likelihood ratios to ``gains``."""
    for ev in single.effects:
        eff = next(e for e in model.effect_objects if e.name == ev["name"])
        entry = effects_out.setdefault(
            ev["name"],
            {"name": ev["name"], "parameters": {}, "evidence": {}, "recordings": []},
        )
        entry["recordings"].append(name)
        entry["parameters"][name] = effect_parameters(eff, public)
        entry["evidence"][name] = ev["evidence"]
        gains[ev["name"]] = gains.get(ev["name"], 0.0) + float(
            ev["evidence"].get("likelihood_ratio", ev["evidence"].get("delta_bic", 0.0))
        )


def _joint_verdict(gains: dict, singles) -> str:
    """The effect of the largest summed gain; else ``unexplained`` if any recording is,
    ``undetermined`` if all are, else ``none``."""
    if gains:
        return max(gains, key=gains.get)
    if any(s.verdict == "unexplained" for s in singles):
        return "unexplained"
    if all(s.verdict == "undetermined" for s in singles):
        return "undetermined"
    return "none"


def _shared_values(effects_out: dict) -> None:
    """An effect whose parameters are shared shows one value: that of the joint fit."""
    for entry in effects_out.values():
        first = entry["parameters"][entry["recordings"][0]]
        if all(entry["parameters"][r] == first for r in entry["recordings"]):
            entry["parameters"] = first


def _file_names(recs) -> list:
    """A name per recording: its file name, else ``recording <i>`` (made unique)."""
    out = []
    for i, r in enumerate(recs):
        name = r.source if r.source and not r.source.startswith("<") else f"recording {i + 1}"
        if name in out:
            name = f"{name} ({i + 1})"
        out.append(name)
    return out


def _summary(report, singles) -> str:
    shared = ", ".join(f"{k} = {v:.4g}" for k, v in report.final["parameters"].items())
    lines = [
        f"{report.verdict}: {len(singles)} {report.experiment} recordings fitted together "
        f"(shared: {shared})"
    ]
    pairs = zip(report.details["recordings"], report.details["heldout_recordings"], strict=True)
    for rec, held in pairs:
        lines.append(
            f"  {rec['file']}: {rec['verdict']}"
            f"{' (' + ', '.join(rec['effects']) + ')' if rec['effects'] else ''}; rms "
            f"{rec['rms_before']:.4g} -> {rec['rms_after']:.4g}; left out and predicted from "
            f"the others: rms {held['rms_before']:.4g} -> {held['rms_after']:.4g}"
        )
    lines.append(
        f"  pooled: rms {report.baseline['rms']:.4g} -> {report.final['rms']:.4g}, held-out "
        f"{report.heldout_rms_before:.4g} -> {report.heldout_rms_after:.4g}"
    )
    return "\n".join(lines)
