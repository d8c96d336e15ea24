r"""Closed-form models of the three experiments, with their effect augmentations.

A :class:`Model` is one experiment's baseline plus a tuple of effects from the
catalogue (:mod:`knotmech.diagnose.effects`). Each effect adds named parameters
(or, for ``finite_thickness``, changes the meaning of ``mu``); the mean functions
below implement every augmentation of an experiment, so effects compose freely.

Baselines (``shared/spec/recordings.md`` section 2):

.. math::
    \text{capstan\_pull:}\quad T_\mathrm{high} = \min\bigl(T_\mathrm{low} + k\max(u-\delta_0, 0),
        \; T_\mathrm{low} e^{\mu\theta}\bigr)

    \text{pinch:}\quad F_t = 2\mu F_n

    \text{tension\_profile:}\quad T(s) = T_\mathrm{high}\, e^{-\mu s/R},\quad R = (D+d)/2

Augmentations (symbols as in :mod:`knotmech.diagnose.effects`):

- ``static_friction`` (capstan_pull): the rod sticks until the stick line reaches
  :math:`T_\mathrm{low}e^{\mu_s\theta}`, then the tension relaxes to the kinetic
  plateau as :math:`T_k + (T_s - T_k) e^{-(u-u_p)/\ell}`.
- ``finite_thickness``: :math:`\mu \to \mu_\mathrm{eff}(\mu, D/d)` (clove-hitch
  paper, eq. 3), ``mu`` is the material coefficient carrying the ``mu_nominal`` prior.
- ``displacement_offset`` (capstan_pull): the slack :math:`\delta_0 \ge 0` is replaced
  by a signed shift, :math:`u - \delta_0 \to u + u_\mathrm{off}`; a pre-stretch
  (:math:`u_\mathrm{off} > 0`, tension above T_low at zero displacement) is what the
  baseline cannot fit.
- ``rate_dependent_friction``: :math:`\mu \to \mu + \beta \ln(v/v_\mathrm{ref})`,
  :math:`v_\mathrm{ref}` the geometric mean speed.
- ``adhesion`` (pinch): :math:`F_t \to F_t + F_a`.
- ``contact_flattening`` (pinch): beyond :math:`F_c = x_c\,\pi E d D/4` the slope is
  multiplied by ``slope_ratio`` :math:`r \in [0, 1]`:
  :math:`F_t = 2\mu(F_n - (1-r)\max(F_n - F_c, 0))`.
- ``self_contact_nip`` (tension_profile): :math:`T \to T\prod_j (1 - f_j H(s - s_j))`.

The DER baseline plugs in through :func:`get_baseline`: a baseline is any object
with ``name`` and ``check(recording)``; ``closed-form`` is the default, ``der``
needs :mod:`knotmech.scenes.capstan` (see :func:`get_baseline`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from knotmech.analytic.capstan import mu_eff
from knotmech.analytic.pinch import pinch_load_parameter
from knotmech.diagnose.recording import Recording
from knotmech.errors import InputError

__all__ = ["Model", "build_model", "get_baseline", "BASELINES", "pinch_load_parameter"]


@dataclass
class Model:
    """A baseline plus effects, with free and fixed parameters.

    Attributes
    ----------
    rec : Recording
    effects : tuple of str
        Effects in the order they were added (``self_contact_nip`` may repeat).
    names : list of str
        Free parameter names (the order of parameter vectors).
    lower, upper : arrays
        Bounds of the free parameters.
    fixed : dict
        Parameters held fixed (nip positions, ``delta0_m`` under displacement_offset).
    """

    rec: Recording
    effects: tuple
    names: list
    lower: np.ndarray
    upper: np.ndarray
    fixed: dict = field(default_factory=dict)

    def params(self, p: np.ndarray) -> dict:
        d = dict(self.fixed)
        d.update(zip(self.names, (float(v) for v in p), strict=True))
        return d

    def mean(self, p: np.ndarray) -> np.ndarray:
        return MEANS[self.rec.experiment](self.rec, self.params(p), self.effects)

    @property
    def n_free(self) -> int:
        return len(self.names)


def _ln_speed(rec: Recording) -> np.ndarray:
    v = rec.speed
    return np.log(v) - np.mean(np.log(v))


def reference_speed(rec: Recording) -> float:
    """Geometric-mean sliding speed [m/s] (the speed at which ``mu`` is reported)."""
    return float(np.exp(np.mean(np.log(rec.speed))))


def _mu_rows(rec, p, effects):
    mu = p["mu"]
    if "rate_dependent_friction" in effects:
        return np.maximum(mu + p["dmu_dlnv"] * _ln_speed(rec), 0.0)
    return mu


def _apparent(rec, mu, effects):
    if "finite_thickness" in effects:
        d = rec.meta("rod_diameter_m")
        D = rec.meta("post_diameter_m")
        return mu_eff(np.maximum(mu, 0.0), D / d)
    return mu


def _capstan_mean(rec, p, effects):
    u = rec.x
    t_low = rec.meta("T_low_N")
    theta = rec.meta("wrap_angle_rad")
    mu = _mu_rows(rec, p, effects)
    plateau = t_low * np.exp(_apparent(rec, mu, effects) * theta)
    if "displacement_offset" in effects:
        xs = u + p["offset_m"]
    else:
        xs = u - p["delta0_m"]
    k = p["k_N_per_m"]
    stick = t_low + k * np.maximum(xs, 0.0)
    if "static_friction" not in effects:
        return np.minimum(stick, plateau)
    peak = t_low * np.exp(_apparent(rec, mu + p["dmu_static"], effects) * theta)
    u_peak = (peak - t_low) / k
    ell = p["decay_length_m"]
    after = plateau + (peak - plateau) * np.exp(-np.maximum(xs - u_peak, 0.0) / ell)
    return np.where(xs < u_peak, stick, after)


def _pinch_mean(rec, p, effects):
    fn = rec.x
    mu = _mu_rows(rec, p, effects)
    load = fn
    if "contact_flattening" in effects:
        fc = p["onset_load_parameter"] * (
            np.pi
            * rec.meta("youngs_modulus_Pa")
            * rec.meta("rod_diameter_m")
            * rec.meta("pinch_diameter_m")
            / 4.0
        )
        load = fn - (1.0 - p["slope_ratio"]) * np.maximum(fn - fc, 0.0)
    out = 2.0 * mu * load
    if "adhesion" in effects:
        out = out + p["adhesion_force_N"]
    return out


def _tension_mean(rec, p, effects):
    s = rec.x
    r = 0.5 * (rec.meta("post_diameter_m") + rec.meta("rod_diameter_m"))
    mu = _apparent(rec, p["mu"], effects)
    out = rec.meta("T_high_N") * np.exp(-mu * s / r)
    j = 0
    while f"nip_position_{j}" in p:
        out = out * np.where(s > p[f"nip_position_{j}"], 1.0 - p[f"nip_drop_{j}"], 1.0)
        j += 1
    return out


MEANS = {
    "capstan_pull": _capstan_mean,
    "pinch": _pinch_mean,
    "tension_profile": _tension_mean,
}


def build_model(rec: Recording, effects: tuple = (), fixed: dict | None = None) -> Model:
    """Model of ``rec``'s experiment with ``effects`` (free parameters and bounds)."""
    span = float(np.ptp(rec.x)) or 1.0
    ymax = float(np.max(np.abs(rec.y))) or 1.0
    names, lo, hi = ["mu"], [0.0], [5.0]
    fixed = dict(fixed or {})
    exp = rec.experiment
    if exp == "capstan_pull":
        names += ["k_N_per_m"]
        lo += [1e-12]
        hi += [np.inf]
        if "displacement_offset" in effects:
            # signed, so that the model nests the baseline (offset_m = -delta0_m <= 0)
            names += ["offset_m"]
            lo += [-(float(np.max(rec.x)) if np.max(rec.x) > 0 else span)]
            hi += [span]
        else:
            names += ["delta0_m"]
            lo += [0.0]
            hi += [float(np.max(rec.x)) if np.max(rec.x) > 0 else span]
        if "static_friction" in effects:
            dx = np.diff(np.unique(rec.x))
            names += ["dmu_static", "decay_length_m"]
            lo += [0.0, 0.5 * float(np.median(dx)) if dx.size else 1e-4 * span]
            hi += [3.0, span]
    if exp == "pinch":
        if "adhesion" in effects:
            names += ["adhesion_force_N"]
            lo += [0.0]
            hi += [ymax]
        if "contact_flattening" in effects:
            xl = pinch_load_parameter(
                rec.x,
                youngs_modulus=rec.meta("youngs_modulus_Pa"),
                rod_diameter=rec.meta("rod_diameter_m"),
                pinch_diameter=rec.meta("pinch_diameter_m"),
            )
            names += ["onset_load_parameter", "slope_ratio"]
            lo += [float(np.min(xl)), 0.0]
            hi += [float(np.max(xl)), 1.0]
    if "rate_dependent_friction" in effects:
        names += ["dmu_dlnv"]
        lo += [-2.0]
        hi += [2.0]
    if exp == "tension_profile":
        j = 0
        while f"nip_position_{j}" in fixed:
            names += [f"nip_drop_{j}"]
            lo += [0.0]
            hi += [0.95]
            j += 1
    return Model(rec, tuple(effects), names, np.array(lo, float), np.array(hi, float), fixed)


# --- baselines: closed-form (default) and DER (plugs in when the scene exists) -------


@dataclass(frozen=True)
class ClosedFormBaseline:
    """The closed-form baselines of the spec, for every experiment."""

    name: str = "closed-form"

    def check(self, rec: Recording) -> None:
        return None


@dataclass(frozen=True)
class DERBaseline:
    """DER-simulated capstan baseline (kinetic friction only).

    Needs ``knotmech.scenes.capstan``; :func:`get_baseline` refuses it until the
    scene provides a fast force-displacement curve.
    """

    name: str = "der"

    def check(self, rec: Recording) -> None:
        if rec.experiment != "capstan_pull":
            raise InputError(
                f"--baseline der applies to capstan_pull recordings, not {rec.experiment}"
            )


BASELINES = {"closed-form": ClosedFormBaseline(), "der": DERBaseline()}


def get_baseline(name: str):
    """Baseline by name: ``closed-form`` or ``der``.

    Raises
    ------
    InputError
        Unknown name, or ``der`` while the DER capstan baseline is not available.
    """
    if name not in BASELINES:
        raise InputError(f"baseline must be one of {', '.join(BASELINES)}, got {name!r}")
    if name == "der":
        raise InputError(
            "baseline 'der' is not available in this version (needs a fast DER capstan "
            "force-displacement curve from knotmech.scenes.capstan); use closed-form"
        )
    return BASELINES[name]
