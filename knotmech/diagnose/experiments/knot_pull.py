r"""``knot_pull``: an overhand knot in a rod pulled tight by its two ends (spec section 5).

Columns ``end_to_end_m`` (D, the distance between the pulled ends), ``force_N`` (F);
metadata ``knot`` (``overhand``), ``turns`` (n, 1-4), ``rod_radius_m`` (h),
``youngs_modulus_Pa`` (E), ``rod_length_m`` (L); optional ``density_kg_m3``,
``poisson_ratio``, ``pull_speed_m_per_s`` (used by the DER baseline).

Closed-form baseline: the braid law of Jawed, Dieleman, Audoly & Reis, PRL 115, 118302
(2015), Eqs. (3)-(5) with the loop closure
(:func:`knotmech.analytic.knots.overhand_pull_force`), at the shortening
:math:`e = L - D`:

.. math:: F(D) = \mu\, f_n(L - D), \qquad f_n(e) = 2\pi n h B k(e)^3,
          \quad B = E\pi h^4/4,

free parameter ``mu`` (rod-rod kinetic friction). The law is linear in mu, and
:math:`f_n` depends on the knot through one variable only: with :math:`t = e/(n^2h)`,

.. math:: f_n(e) = \frac{B}{n^2h^2}\,g(t), \qquad
          g = 2\pi\Big(\frac{2\pi}{8\sqrt3\pi^2}\Big)^3 x^3,
          \qquad t = \frac{8\sqrt3\pi^2\,(x + 4K(m))}{x^2},

:math:`x = \ell/R` the closure's braid length over loop radius
(:func:`knotmech.analytic.knots.loop_closure`; from :math:`R = 8\sqrt3\pi^2n^2h/x^2`,
:math:`k = 2\pi n/(xR)` and :math:`F = 2\pi\mu nhBk^3`). So :math:`\ln g` is
tabulated once against :math:`\ln t`, at nodes of the elastica parameter m (uniform in
logit m), and interpolated by a cubic spline (:func:`unit_law`): a recording of 1e6 rows
costs a spline evaluation per model call, not a bisection of the closure per row.
With ``--baseline der`` the force law
is the DER simulation of the same knot (:mod:`knotmech.diagnose.der_knot`), which the
recording carries as ``force_law``; the stages are the same.
"""

from __future__ import annotations

import functools

import numpy as np

from knotmech.analytic import knots
from knotmech.analytic.knots import JAWED_C
from knotmech.diagnose.experiments.base import Experiment, Stages

__all__ = ["KnotPull", "closure_limits", "unit_law", "UNIT_LAW_STEP"]

#: spacing of the table's nodes in logit m (the measured interpolation error at this step,
#: between nodes, is below 3e-11 relative: tests/diagnose/test_diagnose_knot_pull.py)
UNIT_LAW_STEP = 0.02
#: the table's range in logit m: wider than the closure's bisection bracket (-60, 36)
_LOGIT_RANGE = (-62.0, 40.0)

#: the knots this kind knows
KNOTS = ("overhand",)


def closure_limits() -> tuple[float, float]:
    """(smallest, largest) :math:`e/(n^2h)` the Jawed et al. closure represents [-]."""
    lo, hi = knots._shortening_bounds()
    return float(lo), float(hi)


def _closure_parametric(logit_m):
    """(ln t, ln g) of the closure at elastica parameters m = 1/(1 + exp(-logit_m)).

    1 - m is formed from the logit directly, as 1/(1 + exp(logit_m)), so K(m) stays accurate as
    m -> 1; below m = 1e-3 the braid ratio x uses the series of
    :func:`knotmech.analytic.knots.loop_closure` (cancellation in 8(K - E)/m - 4K).
    """
    from scipy.special import ellipe, ellipkm1

    u = np.asarray(logit_m, float)
    m = 1.0 / (1.0 + np.exp(-u))
    p = 1.0 / (1.0 + np.exp(u))  # 1 - m
    small = m < 1e-3
    ms, ps = np.where(small, 0.5, m), np.where(small, 0.5, p)
    series = np.pi * (
        m / 4 + 3 * m**2 / 16 + 75 * m**3 / 512 + 245 * m**4 / 2048 + 6615 * m**5 / 65536
    )
    x = np.where(small, series, 8.0 * (ellipkm1(ps) - ellipe(ms)) / ms - 4.0 * ellipkm1(ps))
    t = 8.0 * JAWED_C * (x + 4.0 * ellipkm1(p)) / x**2
    g = 2.0 * np.pi * (2.0 * np.pi / (8.0 * JAWED_C)) ** 3 * x**3
    return np.log(t), np.log(g)


@functools.cache
def unit_law():
    r"""The closure's force law :math:`\ln g(\ln t)` as a cubic spline (built once).

    :math:`F = \mu\,B/(n^2h^2)\,g(t)`, :math:`t = e/(n^2h)` (module docstring);
    nodes every :data:`UNIT_LAW_STEP` in logit m over :data:`_LOGIT_RANGE` (5101 nodes,
    t from below the closure's long-braid limit to 1e55). Returns a
    :class:`scipy.interpolate.CubicSpline` in ln t.
    """
    from scipy.interpolate import CubicSpline

    u = np.arange(_LOGIT_RANGE[0], _LOGIT_RANGE[1] + 0.5 * UNIT_LAW_STEP, UNIT_LAW_STEP)
    lt, lg = _closure_parametric(u)
    return CubicSpline(lt[::-1], lg[::-1])  # t decreases with m


def _number(v) -> bool:
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool)


class KnotPull(Experiment):
    name = "knot_pull"
    columns = ("end_to_end_m", "force_N")
    required_metadata = ("knot", "turns", "rod_radius_m", "youngs_modulus_Pa", "rod_length_m")
    control_nonnegative = True
    stages = (
        "friction(mu) -> mu per row; knot_shift(None) -> the true end-to-end distance "
        "per row (default the recorded one); output(F) -> the measured force"
    )

    def __init__(self):
        self._cache: dict = {}

    # --- recording -------------------------------------------------------------------
    def check(self, rec):
        md = rec.metadata
        if str(md.get("knot")).strip().lower() not in KNOTS:
            return f"metadata knot must be one of {', '.join(KNOTS)}, got {md.get('knot')!r}"
        n = md.get("turns")
        if not _number(n) or n != round(n) or not 1 <= n <= 4:
            return f"metadata turns must be a whole number 1-4, got {n!r}"
        for key in ("rod_radius_m", "youngs_modulus_Pa", "rod_length_m"):
            v = md.get(key)
            if not _number(v) or not np.isfinite(v) or v <= 0:
                return f"metadata {key} must be a number > 0, got {v!r}"
        length = rec.meta("rod_length_m")
        if np.max(rec.x) >= length:
            return (
                f"end_to_end_m must be below rod_length_m = {length:g} (the knot holds rod), "
                f"got {np.max(rec.x):g}"
            )
        return None

    def validity(self, rec):
        """Rows with more rod in the knot than the Jawed et al. closure's long-braid limit,
        :math:`L - D > t_{min} n^2 h` (a pull to tight ends beyond it)."""
        n = int(rec.meta("turns"))
        length = rec.meta("rod_length_m")
        lo, _ = closure_limits()
        e_min = lo * n**2 * rec.meta("rod_radius_m")
        ok = length - rec.x > e_min
        if np.all(ok):
            return None
        return ok, (
            f"end_to_end_m above {length - e_min:.6g} m leaves less rod in the knot than the "
            f"Jawed et al. closure allows (L - D must exceed {e_min:.4g} m for {n} turns)"
        )

    # --- baseline ----------------------------------------------------------------------
    def bending_stiffness(self, rec) -> float:
        """B = E pi h^4 / 4 [N m^2]."""
        return rec.meta("youngs_modulus_Pa") * np.pi * rec.meta("rod_radius_m") ** 4 / 4.0

    def unit_force(self, rec, d) -> np.ndarray:
        r"""Closed-form force at mu = 1 at end-to-end distances ``d`` [m] -> [N].

        ``d`` is clipped into the range the closure represents (a shifted axis may
        leave it while a fit explores). Evaluated from the tabulated law
        (:func:`unit_law`): within 1e-9 relative of
        :func:`~knotmech.analytic.knots.overhand_knot` for :math:`e/(n^2h) \ge 10`, which
        is the closure's own rounding (tests); closer to the long-braid limit, where
        ``overhand_knot`` forms 1 - m by subtraction, the table is the accurate one.
        """
        n = int(rec.meta("turns"))
        h = rec.meta("rod_radius_m")
        length = rec.meta("rod_length_m")
        b = self.bending_stiffness(rec)
        d = np.asarray(d, float)
        key = (n, h, length, b, d.tobytes())
        hit = self._cache.get(key)
        if hit is not None:
            return hit
        lo, hi = closure_limits()
        e = np.clip(length - d, lo * n**2 * h * (1 + 1e-6), min(hi * n**2 * h, length) * 0.999)
        out = b / (n * h) ** 2 * np.exp(unit_law()(np.log(e / (n**2 * h))))
        if len(self._cache) >= 8:  # a few axes (a fit's own); 1e6 rows are 16 MB each
            self._cache.pop(next(iter(self._cache)))
        self._cache[key] = out
        return out

    def start(self, rec, y) -> dict:
        law = getattr(rec, "force_law", None)
        if law is None:
            f, mu0 = self.unit_force(rec, rec.x), 1.0
        else:  # the DER law: scaled from the middle of its mu grid
            mu0 = float(np.median(law.grid))
            f = law(rec.x, mu0)
        return {"mu": max(mu0 * float(np.dot(f, y) / np.dot(f, f)), 1e-3), "offset_m": 0.0}

    def mean(self, rec, p, effects=()):
        st = Stages(rec, p, effects)
        mu = st.apply("friction", p["mu"])
        d = st.apply("knot_shift", None)
        if d is None:
            d = rec.x
        law = getattr(rec, "force_law", None)
        if law is None:
            force = mu * self.unit_force(rec, d)
        else:  # the DER law, times its surrogate-error term at the recorded rows
            force = law(d, mu)
            term = getattr(law, "correction", None)
            if term is not None:
                a = np.array([p.get(name, 0.0) for name in term.names])
                force = force * np.exp(term.log_factor(law, rec.x, a))
        return st.apply("output", force)

    def parameters(self, rec):
        """``mu``; under the DER law with its surrogate-error term
        (:data:`knotmech.diagnose.der_knot.SURROGATE_ERROR`) also the term's coefficients
        ``surrogate_a0..3``, within 10 prior sd."""
        names, lo, hi = super().parameters(rec)
        term = getattr(getattr(rec, "force_law", None), "correction", None)
        if term is not None:
            names += list(term.names)
            lo += [-10.0 * term.tau] * len(term.names)
            hi += [10.0 * term.tau] * len(term.names)
        return names, lo, hi

    def priors(self, rec) -> dict:
        """The surrogate-error coefficients' prior N(0, tau^2) (none without the term)."""
        term = getattr(getattr(rec, "force_law", None), "correction", None)
        return {} if term is None else dict.fromkeys(term.names, term.tau)

    # --- synthetic recordings ------------------------------------------------------------
    def synth_setup(self, rng, n, speeds):
        turns = int(rng.integers(1, 5))
        meta = {
            "knot": "overhand",
            "turns": float(turns),
            "rod_radius_m": 1.6e-3,
            "youngs_modulus_Pa": 0.18e6,
            "rod_length_m": 1.0,
        }
        # from a loose knot (e = 0.7 m) to where the slender-loop law stays valid
        e_tight = {1: 0.22, 2: 0.32, 3: 0.42, 4: 0.52}[turns]
        m = n // len(speeds)
        d1 = np.linspace(1.0 - 0.7, 1.0 - e_tight, m)
        x = np.tile(d1, len(speeds))
        params = {"mu": float(rng.uniform(0.2, 0.5))}
        trial = np.repeat(np.arange(len(speeds)), m)
        speed = np.repeat(speeds, m) if len(speeds) > 1 else None
        return meta, x, trial, speed, params, {}

    def synth_noise_scale(self, meta, mean0) -> float:
        """Noise sd [N]: 1 % of the median force (the force spans a decade)."""
        return 0.01 * float(np.median(np.abs(mean0)))

    def out_of_catalogue(self, x, meta, p, mean0, sd, size, rng):
        """A local force bump (a strand catching: Gaussian, 5 % of the span wide)."""
        span = x[-1] - x[0]
        c = x[0] + rng.uniform(0.3, 0.7) * span
        w = 0.05 * span
        i = int(np.argmin(np.abs(x - c)))
        return mean0 + size * sd[i] * np.exp(-0.5 * ((x - c) / w) ** 2)
