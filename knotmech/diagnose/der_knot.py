r"""The DER overhand knot as the baseline of ``knot_pull`` (``--baseline der``).

:class:`DERKnotLaw` runs :func:`knotmech.scenes.overhand.overhand` with the recording's
knot (``turns``, ``rod_radius_m``, ``youngs_modulus_Pa``, ``rod_length_m``, optional
``density_kg_m3``, ``poisson_ratio``, ``pull_speed_m_per_s``) on a coarse mesh, at a few
friction coefficients, and gives the pull force :math:`F(D;\mu)` at any end-to-end
distance D and any mu from a smooth surface fitted to every run: the raw DER force
carries a slow ripple of about 20 % rms at these settings (lag-one correlation 0.97
between frames; probably the coarse mesh passing through the knot and stick-slip of the
braid; a larger slip-speed tolerance did not reduce it), so each run is averaged over a window of
two edges in D and :math:`\ln F = P_3(\ln e) + (b_0 + b_1\ln e)\ln\mu` is fitted to
all runs together (:math:`e = L - D`; the coated-rod paper fitted mu by matching DER
pull curves; the Jawed law is :math:`\ln F = \ln f_n(e) + \ln\mu`).

:func:`der_recording` returns the recording with that law attached (``force_law``): the
:class:`~knotmech.diagnose.experiments.knot_pull.KnotPull` mean then uses it in place of
the closed form, and the whole closed-form engine applies unchanged, its parametric
bootstrap included: a bootstrap draw refits the interpolated DER law, which needs no
new simulation (the draws are calibrated on the DER surrogate itself, not on the
closed form). Effects under this baseline: ``displacement_offset`` (a shift of D) and
``rate_dependent_friction`` (mu per row), neither of which needs a new run.

Settings (chosen for speed; the pull is quasi-static):

- mesh: the coarsest the start-shape generator accepts at or above :math:`L/(8h)` nodes
  (an edge of at most a sixth of the braid's helix pitch);
- the start shape: the generator's knot at :math:`D_0 = \min D - 0.03L` with the
  braid strand length of the closed form at :math:`e_0 = L - D_0`; held 0.2 s, then both
  ends pulled apart to :math:`\max D + 0.01L` (half-way from :math:`\max D` to L when
  that is closer: a pull to tight);
- separation speed 0.06 m/s (0.03 m/s each end, the quick setting of the overhand tests)
  or the recording's ``pull_speed_m_per_s`` if larger; time step 10 ms;
- contact range 0.3125 h, slip-speed tolerance 1e-4 m/s (implicit-contact-model paper);
- density ``density_kg_m3`` or 1180 kg/m^3, Poisson ratio ``poisson_ratio`` or 0.5;
- mu grid: one run at the closed-form mu, then runs at 0.85 and 1.15 times the mu that
  matches the recording's level (F is close to proportional to mu; the first run is left
  out of the surface when far from it), more runs if the fit leaves the grid (at most
  :data:`DER_KNOT_MAX_RUNS`);
- a run whose force runs away (a coarse knot pulled too tight jams) is cut there, and a
  run whose solver fails keeps the frames it recorded; the baseline then judges the rows
  up to the end-to-end distance every run reached (:func:`reached_recording`: the report's
  ``details.der.rows_judged`` says how many, where and why), and
  :class:`~knotmech.errors.SolverError` only when fewer than 8 rows lie before it;
- a pull to tight (rows beyond the Jawed closure's validity, such as the coated-rod
  paper's whole pulls to 0.998 L): an edge of at most :data:`_TIGHT_EDGE_H` h (the
  coarse mesh's force near tight is 1.65x the 301-node one), a cubic B-spline in
  :math:`\ln e` in place of the cubic (:data:`_TIGHT_KNOTS` interior knots), the grid's
  first mu at least :data:`_TIGHT_FIRST_MU` and its second step from
  :math:`F \propto \mu^{1/2}` (:data:`_TIGHT_MU_POWER`). Measured on a 301-node pull at
  mu = 0.3 (``validation/_make_imc_pull.py``): mu = 0.286 from 4 runs of 299 nodes, 43 s
  of CPU in all (docs/notes/diagnose-noise-and-statistics/issue26-tight-pull-prior-ripple.md).

**The surrogate's own error.** Two runs of the same knot from slightly different start
shapes give smoothed curves 2-7 % apart in shape, so the surface is the DER knot's law
only to within a smooth error of that size; a recording with noise of a few % over
~100 rows sees it (measured: 5 of 83 DER-made nulls were not ``none`` at alpha = 0.01,
docs/notes/diag12.md). At the recording's shortenings that error is a cubic in
:math:`z = \ln e` (the surface at fixed mu is one), so the baseline carries it as a
random effect: :math:`\ln F = \ln F_{\rm surf}(D;\mu) + \sum_{j\le3} a_j\phi_j(z)`,
:math:`\phi_j` polynomials orthonormal over the recording's rows, with the Gaussian prior
:math:`a_j \sim N(0, \tau^2)`. :math:`\tau^2 = s^2(1 + 1/r)` is the error of the
surface as a prediction of another run: :math:`s^2` the scatter of each run's own cubic
(projected on the :math:`\phi_j`) about the surface, :math:`\sum_r\lVert c_r\rVert^2
/(4r - 6)` for r runs and the surface's 6 coefficients (:func:`surrogate_term`). The
coefficients are free parameters of every model fitted to the recording
(``surrogate_a0..3``, declared by the knot_pull kind with the prior as one whitened
residual :math:`a_j/\tau` each, like ``mu_nominal``): the baseline, every effect's fit,
every bootstrap draw's refits and the held-out folds refit them, so an effect is not
asked to fit around a correction fitted without it. A mismatch much larger than the runs'
scatter is left for the effects. :data:`SURROGATE_ERROR` turns the term on (see there).

Cost: 3 runs of about 7-10 s each for the IMC paper's rod (1 m, h = 1.6 mm, 79 nodes) on
one loaded core (``benchmarks/diagnose_speed.py``).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, fields

import numpy as np

from knotmech.analytic.knots import overhand_knot
from knotmech.diagnose.effects import PlantContext, get_effect
from knotmech.diagnose.experiments import get_experiment
from knotmech.diagnose.experiments.knot_pull import KnotPull
from knotmech.diagnose.fitting import Data, fit_baseline
from knotmech.diagnose.noisefloor import without_rows
from knotmech.diagnose.recording import Recording
from knotmech.diagnose.stats import trial_starts
from knotmech.errors import InputError, SolverError
from knotmech.materials import IMC_DENSITY

__all__ = [
    "DERKnotLaw",
    "DERKnotRecording",
    "der_recording",
    "extend_grid",
    "fit_knot_der_baseline",
    "reached_recording",
    "der_made_recording",
    "DER_KNOT_MAX_RUNS",
    "SURROGATE_NAMES",
    "surrogate_term",
]

DER_KNOT_SEPARATION_SPEED = 0.06
DER_KNOT_DT = 1e-2
DER_KNOT_WAIT = 0.2
DER_KNOT_MAX_RUNS = 6
_DEGREE = 3
#: a pull to tight (rows beyond the Jawed closure's validity): an edge of at most this
#: many rod radii (measured on the implicit-contact-model paper's rod at mu = 0.3, the
#: force near tight against its 301-node pull: 79 nodes (edge 7.9 h) 1.65x, 151 nodes
#: 1.2x, 201 nodes 1.08x, 301 nodes 1.00-1.015x; docs/notes/diagnose-noise-and-statistics/
#: issue26-tight-pull-prior-ripple.md)
_TIGHT_EDGE_H = 2.1
#: on a pull to tight F grows as mu to about this power (299 nodes, runs at mu = 0.2 and
#: 0.3: 0.43 at D = 0.99 L, 0.73 at 0.9 L); the grid's second step uses it
_TIGHT_MU_POWER = 0.5
#: on a pull to tight the grid's first mu is at least this: the closed form fitted to
#: such a pull gives mu ~ 1e-18 (clipped to 0.05), where the DER knot's force near tight
#: hardly depends on mu (299 nodes: F(0.05) about 0.75 F(0.3)) and one run cannot place
#: the level; from 0.05 the grid ended at 0.08-0.21 and the fit at mu = 0.17 for a pull
#: made at 0.3
_TIGHT_FIRST_MU = 0.2
#: interior knots of the surface's cubic spline in ln e on a pull to tight (a cubic in
#: ln e misses the rise to tight by up to 2x)
_TIGHT_KNOTS = 6
#: a simulated force this many times the median of the run's first half is a runaway
_RUNAWAY = 1e3
#: carry the surrogate's own error (module docstring: ``surrogate_a0..3`` with the prior
#: N(0, tau^2), refitted with every model); False: the surface alone. On by default
#: (issue 26): measured on DER-made recordings (benchmarks/der_knot_null_size.py,
#: docs/notes/diagnose-noise-and-statistics/issue26-campaign.md) nulls not ``none`` 0/16
#: with it against 1/16 without (earlier: 8/120 = 6.7 % without, nominal 1 %); 8-sd
#: displacement offsets found 6/8 with it (the misses: negative offsets of one-turn
#: knots, ``unexplained``), 8/8 without; fitted within -3..+21 %
SURROGATE_ERROR = True


@dataclass
class DERKnotRecording(Recording):
    """A knot_pull recording carrying the DER force law (``force_law(D, mu)`` -> F [N])."""

    force_law: object = None


class DERKnotLaw:
    """DER pull force of one recording's knot, :math:`F(D;\\mu)` by interpolation.

    Parameters
    ----------
    rec : Recording
        A ``knot_pull`` recording (its metadata set up the knot).
    n_nodes : int, optional
        Mesh (default: the coarsest accepted, see the module docstring).
    """

    def __init__(self, rec, *, n_nodes=None):
        md = rec.metadata
        self.turns = int(rec.meta("turns"))
        self.h = rec.meta("rod_radius_m")
        self.E = rec.meta("youngs_modulus_Pa")
        self.L = rec.meta("rod_length_m")
        self.rho = float(md["density_kg_m3"]) if "density_kg_m3" in md else IMC_DENSITY
        self.nu = float(md["poisson_ratio"]) if "poisson_ratio" in md else 0.5
        v = md.get("pull_speed_m_per_s")
        self.v = max(float(v), DER_KNOT_SEPARATION_SPEED) if v else DER_KNOT_SEPARATION_SPEED
        self.d0 = float(np.min(rec.x)) - 0.03 * self.L
        #: the end-to-end distance the runs must reach (the recording's last)
        self.d_need = float(np.max(rec.x))
        # pulled 1 % of L beyond it, or half-way to L when it is closer (a pull to tight)
        self.d1 = min(self.d_need + 0.01 * self.L, self.d_need + 0.5 * (self.L - self.d_need))
        #: rows beyond the Jawed closure's validity: a pull to tight (finer mesh, spline)
        self.tight = get_experiment("knot_pull").validity(rec) is not None
        self.B = self.E * np.pi * self.h**4 / 4.0
        self.braid = float(
            overhand_knot(
                end_to_end_shortening=self.L - self.d0,
                turns=self.turns,
                mu=0.3,
                rod_radius=self.h,
                bending_stiffness=self.B,
            ).braid_length
        )
        self.n_nodes = self._mesh() if n_nodes is None else int(n_nodes)
        self._raw: dict = {}  # mu -> raw (D, F) of the run (in the surface)
        self._dropped: dict = {}  # runs left out of the surface (far from the data's mu)
        #: mu -> (the largest end-to-end distance the run reached [m], why it stopped
        #: short or None)
        self.reach: dict = {}
        #: the rows judged when the runs stop short of the recording (None: all)
        self.rows_note = None
        self.seconds = 0.0
        #: the surrogate-error correction (:meth:`set_correction`), None: none
        self.correction = None

    def _mesh(self) -> int:
        # imported here for start-up speed: knotmech.scenes loads the numba solver
        from knotmech.scenes.curves import overhand_knot as knot_curve

        edge = _TIGHT_EDGE_H * self.h if self.tight else 8.0 * self.h
        n = max(int(round(self.L / edge)) + 1, 41)
        for _ in range(12):
            try:
                knot_curve(
                    self.turns,
                    rod_length=self.L,
                    rod_radius=self.h,
                    end_to_end_length=self.d0,
                    braid_length=self.braid,
                    n_nodes=n,
                )
                return n
            except InputError as exc:
                if "coarse" not in str(exc):
                    raise InputError(f"the DER knot cannot be set up: {exc}") from None
                n = int(np.ceil(1.2 * n))
        raise InputError("the DER knot needs more than ~10 000 nodes; use the closed form")

    def settings(self) -> dict:
        return {
            "n_nodes": self.n_nodes,
            "separation_speed_m_per_s": self.v,
            "dt_s": DER_KNOT_DT,
            "start_end_to_end_m": float(f"{self.d0:.6g}"),
            "start_braid_length_m": float(f"{self.braid:.6g}"),
            "mu_grid": [float(f"{m:.4g}") for m in self.grid],
            "simulations": len(self._raw) + len(self._dropped),
            "simulation_seconds": float(f"{self.seconds:.3g}"),
            **({"surrogate_error": self.correction.describe()} if self.correction else {}),
            **({"rows_judged": self.rows_note} if self.rows_note else {}),
        }

    @property
    def grid(self) -> np.ndarray:
        return np.array(sorted(self._raw))

    def run(self, mu: float):
        """Simulate the pull at ``mu``; returns the raw (D, F) of the run [m, N]."""
        mu = round(float(mu), 6)
        if mu in self._raw:
            return self._raw[mu]
        # imported here for start-up speed: the solver compiles numba kernels
        from knotmech.rod.solver import SolverOptions
        from knotmech.scenes.overhand import overhand

        t0 = time.perf_counter()
        pull = (self.d1 - self.d0) / self.v
        res = overhand(
            self.turns,
            mu,
            n_nodes=self.n_nodes,
            rod_length=self.L,
            rod_radius=self.h,
            youngs_modulus=self.E,
            density=self.rho,
            poisson_ratio=self.nu,
            end_to_end_length=self.d0,
            braid_length=self.braid,
            pull_speed=0.5 * self.v,
            pull_both_ends=True,
            wait_time=DER_KNOT_WAIT,
            pull_time=pull,
            dt=DER_KNOT_DT,
            contact_distance=0.3125 * self.h,
            slip_speed=1e-4,
            n_frames=max(int(pull / DER_KNOT_DT / 2), 40),
            n_snapshots=1,
            options=SolverOptions(throw=False, rtol=1e-6),
        )
        self.seconds += time.perf_counter() - t0
        d, f, why = self._usable(res)
        if d.size < 2 * (_DEGREE + 3):
            raise SolverError(
                f"DER knot baseline failed at mu = {mu:.4g} ({self.turns} turns, "
                f"{self.n_nodes} nodes): {why or 'too few frames'}"
            )
        self.reach[mu] = (float(np.max(d)), why)
        self._raw[mu] = (d, f)
        self._refit()
        return d, f

    def _usable(self, res):
        """The frames of a run the surface may use: (D [m], F [N], why it stopped short).

        The pull's start-up is left out; a run whose solver failed keeps the frames it
        recorded, and one whose force runs away (a coarse knot pulled too tight jams) is
        cut there. ``why`` is None when the run was not cut.
        """
        d = np.asarray(res.end_to_end, float)
        f = np.asarray(res.pull_force, float)
        keep = res.times > DER_KNOT_WAIT + 0.25 * (0.03 * self.L) / self.v
        d, f = d[keep], f[keep]
        why = None if res.status == "success" else f"the solver failed ({res.message})"
        ref = float(np.median(np.abs(f[: max(len(f) // 2, 1)]))) if f.size else 0.0
        bad = ~np.isfinite(f) | ~np.isfinite(d) | (np.abs(f) > _RUNAWAY * ref)
        if np.any(bad):
            cut = int(np.argmax(bad))
            d, f = d[:cut], f[:cut]
            why = why or "the contact force ran away (the coarse knot jams)"
        return d, f, why

    @property
    def d_reach(self) -> float:
        """The end-to-end distance every run of the surface reached [m] (the surface is
        judged on rows up to there)."""
        return min(self._reach_of(mu)[0] for mu in self._raw)

    def _reach_of(self, mu) -> tuple:
        """(largest D reached [m], why it stopped short or None) of the run at ``mu``
        (a run stored without its reach: the largest D among its frames)."""
        return self.reach.get(mu, (float(np.max(self._raw[mu][0])), None))

    def stop_reason(self) -> str | None:
        """Why the runs stopped short of the recording's last row (None: they did not)."""
        if self.d_reach >= self.d_need - 1e-9:
            return None
        mu, (dr, why) = min(((m, self._reach_of(m)) for m in self._raw), key=lambda t: t[1][0])
        return (
            f"the DER knot ({self.turns} turns, {self.n_nodes} nodes) stops at "
            f"end_to_end_m = {dr:.5g} at mu = {mu:.4g}: {why or 'the end of its pull'}"
        )

    def reached_rows(self, x) -> np.ndarray:
        """Bool mask of the rows at end-to-end distances ``x`` [m] the runs reached."""
        return np.asarray(x, float) <= self.d_reach + 1e-12

    def _boxcar(self, d, f) -> np.ndarray:
        """Force averaged over a window of two edges in D (the mesh passing the knot)."""
        w = 2.0 * self.L / (self.n_nodes - 1)
        c = np.concatenate([[0.0], np.cumsum(f)])
        lo = np.searchsorted(d, d - 0.5 * w, side="left")
        hi = np.searchsorted(d, d + 0.5 * w, side="right")
        return (c[hi] - c[lo]) / np.maximum(hi - lo, 1)

    def _refit(self) -> None:
        """Fit the surface ln F = P(ln e) + (b0 + b1 ln e) ln mu to every run.

        ``P`` a cubic (on a pull to tight a cubic B-spline, :meth:`_spline`); the
        boxcar-averaged positive forces of all runs enter with equal weight, so the
        ripple of one run is averaged with the others'.
        """
        zs, ms, ls = [], [], []
        for mu, (d, f) in self._raw.items():
            order = np.argsort(d)
            d, f = d[order], f[order]
            fa = self._boxcar(d, f)
            ok = fa > 0
            zs.append(np.log(self.L - d[ok]))
            ms.append(np.full(ok.sum(), np.log(mu)))
            ls.append(np.log(fa[ok]))
        z, lm, lf = (np.concatenate(v) for v in (zs, ms, ls))
        if z.size < 2 * (_DEGREE + 3):
            raise SolverError("DER knot baseline: the simulated pull force is not positive")
        self._zrange = (float(z.min()), float(z.max()))
        cols = [z**j for j in range(_DEGREE + 1)] if not self.tight else list(self._spline(z).T)
        if len(self._raw) >= 2:
            cols += [lm, lm * z]
        a = np.column_stack(cols)
        self._coef = np.linalg.lstsq(a, lf, rcond=None)[0]

    def _spline(self, z) -> np.ndarray:
        """(n, k) cubic B-spline basis in z = ln e over the runs' range (a pull to tight),
        :data:`_TIGHT_KNOTS` interior knots evenly spaced in z."""
        from scipy.interpolate import BSpline

        lo, hi = self._zrange
        inner = np.linspace(lo, hi, _TIGHT_KNOTS + 2)
        t = np.r_[[lo] * _DEGREE, inner, [hi] * _DEGREE]
        zz = np.clip(np.asarray(z, float), lo, hi)
        return BSpline.design_matrix(zz, t, _DEGREE).toarray()

    def log_force(self, d, mu) -> np.ndarray:
        """ln F of the fitted surface at distances ``d`` [m] and ``mu`` (scalar or per row)."""
        return self._log_surface(d, mu)

    def _z(self, d) -> np.ndarray:
        z = np.log(np.clip(self.L - np.asarray(d, float), 1e-6 * self.L, None))
        return np.clip(z, *self._zrange)  # flat beyond the simulated range

    def _log_surface(self, d, mu) -> np.ndarray:
        z = self._z(d)
        c = self._coef
        if self.tight:
            k = _TIGHT_KNOTS + _DEGREE + 1
            out = self._spline(z) @ c[:k]
        else:
            k = _DEGREE + 1
            out = sum(c[j] * z**j for j in range(k))
        if c.size > k:
            lm = np.log(np.maximum(np.asarray(mu, float), 1e-6))
            out = out + (c[k] + c[k + 1] * z) * lm
        return out

    def run_scatter(self, basis) -> tuple[float, int]:
        r"""(s^2, r): the runs' scatter about the surface in the cubic ``basis``.

        Each run of the surface, boxcar-averaged as in :meth:`_refit`, minus the surface
        at its mu over the basis's z range, is projected on the basis (least squares on
        the run's frames); :math:`s^2 = \sum_r \lVert c_r\rVert^2/(4r - 6)` (the
        surface's 6 coefficients fitted to r runs' 4; r = 2: the const and slope of
        each run are the surface's exactly, 2 left). 0 for one run.
        """
        r = len(self._raw)
        if r < 2:
            return 0.0, r
        total = 0.0
        for mu, (d, f) in self._raw.items():
            order = np.argsort(d)
            d, f = d[order], f[order]
            fa = self._boxcar(d, f)
            z = np.log(self.L - d)
            ok = (fa > 0) & (z >= basis.zlo) & (z <= basis.zhi)
            if ok.sum() < 2 * (_DEGREE + 1):
                continue
            resid = np.log(fa[ok]) - self._log_surface(d[ok], mu)
            c = np.linalg.lstsq(basis(z[ok]), resid, rcond=None)[0]
            total += float(np.dot(c, c))
        return total / max(4 * r - 6, 1), r

    def set_correction(self, correction) -> None:
        """Use ``correction`` (a :class:`SurrogateCorrection`, or None) from now on."""
        self.correction = correction

    def smooth_force(self, mu: float, d) -> np.ndarray:
        """Force of the fitted surface at ``mu`` and distances ``d`` [N]."""
        return np.exp(self.log_force(d, mu))

    def __call__(self, d, mu) -> np.ndarray:
        """F(D; mu) [N] of the fitted surface (``mu`` may be an array per row)."""
        return np.exp(self.log_force(d, mu))

    def fit_grid(self, rec, mu_closed: float) -> None:
        r"""Run the grid: at ``mu_closed``, then at 0.85 and 1.15 times the mu that matches
        ``rec``'s level (F close to proportional to mu; on a pull to tight to
        :math:`\mu^{1/2}`, :data:`_TIGHT_MU_POWER`); the first run is dropped from the
        surface when it lies outside [0.7, 1.4] times that mu."""
        self.run(mu_closed)
        ok = self.reached_rows(rec.x)
        f = self.smooth_force(mu_closed, rec.x[ok])
        ratio = float(np.dot(f, rec.y[ok]) / np.dot(f, f))
        power = _TIGHT_MU_POWER if self.tight else 1.0
        mu1 = float(np.clip(mu_closed * ratio ** (1.0 / power), 0.02, 3.0))
        for m in (0.85 * mu1, 1.15 * mu1):
            self.run(m)
        if not 0.7 * mu1 <= mu_closed <= 1.4 * mu1:
            self._dropped[round(float(mu_closed), 6)] = self._raw.pop(round(float(mu_closed), 6))
            self._refit()


class CubicBasis:
    r"""Polynomials of degree <= 3 in z = ln e, orthonormal over a recording's rows.

    :math:`\phi(z) = V(\xi) R^{-1}`, :math:`\xi` the rows' z mapped onto [-1, 1],
    V the Vandermonde matrix, :math:`V/\sqrt n = QR`: the mean over the rows of
    :math:`\phi_j\phi_k` is :math:`\delta_{jk}`. Beyond the rows' range the basis is
    held at its end values (z clipped).
    """

    def __init__(self, z_rows):
        z = np.asarray(z_rows, float)
        self.zlo, self.zhi = float(z.min()), float(z.max())
        v = self._vander(z) / np.sqrt(z.size)
        self._rinv = np.linalg.inv(np.linalg.qr(v, mode="r"))

    def _vander(self, z):
        xi = (2.0 * np.clip(z, self.zlo, self.zhi) - self.zlo - self.zhi) / (self.zhi - self.zlo)
        return np.vander(xi, _DEGREE + 1, increasing=True)

    def __call__(self, z) -> np.ndarray:
        """(n, 4) basis values at ``z``."""
        return self._vander(np.asarray(z, float)) @ self._rinv


#: names of the surrogate-error coefficients (free parameters of the baseline)
SURROGATE_NAMES = tuple(f"surrogate_a{j}" for j in range(_DEGREE + 1))


@dataclass
class SurrogateCorrection:
    r"""The surrogate-error term :math:`\sum_j a_j\phi_j(z)` in ln F: its basis and prior.

    The coefficients are free parameters of every model fitted to the recording
    (``surrogate_a0..3``, :data:`SURROGATE_NAMES`) with the prior
    :math:`a_j \sim N(0, \tau^2)` (one whitened residual :math:`a_j/\tau` each);
    ``coef`` holds the baseline's fitted values, for the report.
    """

    basis: CubicBasis
    coef: np.ndarray
    tau: float
    runs: int
    names: tuple = SURROGATE_NAMES

    def __call__(self, z) -> np.ndarray:
        return self.basis(z) @ self.coef

    def log_factor(self, law, x, a) -> np.ndarray:
        """ln of the term's factor at the recorded end-to-end distances ``x`` [m] for the
        coefficients ``a`` (the recorded rows, not an effect's shifted axis)."""
        return self.basis(law._z(x)) @ np.asarray(a, float)

    def describe(self) -> dict:
        """The prior sd, the baseline's coefficients and their rms effect on ln F."""
        return {
            "prior_sd_ln_force": float(f"{self.tau:.3g}"),
            "runs": self.runs,
            "coefficients": [float(f"{c:.3g}") for c in self.coef],
            # the basis is orthonormal over the rows: the rms over them is |a|
            "rms_ln_force": float(f"{np.sqrt(np.sum(self.coef**2)):.3g}"),
        }


def surrogate_term(drec):
    r"""The surrogate-error term of ``drec``'s DER law: its basis over the recording's
    rows and its prior sd :math:`\tau = \sqrt{s^2(1 + 1/r)}` from
    :meth:`DERKnotLaw.run_scatter` (module docstring). None when the runs give no
    scatter (fewer than two)."""
    law = drec.force_law
    basis = CubicBasis(np.log(law.L - drec.x))
    s2, r = law.run_scatter(basis)
    if s2 <= 0.0:
        return None
    tau = float(np.sqrt(s2 * (1.0 + 1.0 / r)))
    return SurrogateCorrection(basis, np.zeros(_DEGREE + 1), tau, r)


def der_recording(rec, mu_closed: float) -> DERKnotRecording:
    """``rec`` with the DER force law of its knot attached (the grid already run).

    Parameters
    ----------
    rec : Recording
        A ``knot_pull`` recording.
    mu_closed : float
        The closed-form fit's mu (the first run of the grid).
    """
    law = DERKnotLaw(rec)
    law.fit_grid(rec, mu_closed)
    vals = {f.name: getattr(rec, f.name) for f in fields(Recording)}
    return DERKnotRecording(**vals, force_law=law)


def extend_grid(rec: DERKnotRecording, mu: float) -> bool:
    """Run one more grid point when ``mu`` lies outside the grid (returns True if run)."""
    law = rec.force_law
    g = law.grid
    if len(law._raw) >= DER_KNOT_MAX_RUNS or g[0] * 1.02 <= mu <= g[-1] / 1.02:
        return False
    law.run(1.15 * mu if mu > g[-1] else mu / 1.15)
    return True


def fit_knot_der_baseline(rec, data, starts, gs):
    """The DER baseline of a knot_pull recording: the closed-form fit gives the first
    mu of the grid, then the DER law is fitted (one free parameter, mu), the grid
    extended while the fit leaves it.

    A whole pull to tight may end beyond what the DER knot's coarse mesh reaches (it
    jams a few millimetres short of tight): the baseline then judges the rows up to the
    end-to-end distance every run reached, and the report's ``details.der.rows_judged``
    says how many, up to where and why (:func:`reached_recording`). ``data``,
    ``starts`` and ``gs`` are those of ``rec``; the reduced recording's own are used.

    Returns
    -------
    rec : DERKnotRecording
        The recording with the DER law attached, cut to the rows the runs reached (use
        it for everything that follows).
    fit : Fit
    """
    if getattr(rec, "force_law", None) is not None:  # the law is already run
        drec = rec
    else:
        mu0 = _closed_form_mu(rec, gs)
        if get_experiment("knot_pull").validity(rec) is not None:  # a pull to tight
            mu0 = max(mu0, _TIGHT_FIRST_MU)
        drec = der_recording(rec, mu0)
    full = drec
    for _ in range(DER_KNOT_MAX_RUNS):
        drec = reached_recording(full)
        fit = _fit_reached(drec)
        if not extend_grid(full, float(fit.params["mu"])):
            break
    drec = reached_recording(full)
    fit = _fit_reached(drec)
    law = drec.force_law
    if SURROGATE_ERROR and law.correction is None:
        term = surrogate_term(drec)
        if term is not None:  # from now on every model carries the term, with its prior
            law.set_correction(term)
            fit = _fit_reached(drec)
            term.coef = np.array([fit.params[name] for name in term.names])
    return drec, fit


def _fit_reached(rec):
    """The baseline fitted to ``rec`` with its own data, trial starts and sigma."""
    data = Data(rec.y, rec.mu_nominal, rec.mu_nominal_sigma)
    return fit_baseline(rec, data, trial_starts(rec.trial), given_sigma=rec.sigma)


def reached_recording(drec):
    """``drec`` cut to the rows its DER runs reached, the law's ``rows_note`` set.

    Raises
    ------
    SolverError
        Fewer than the kind's ``min_rows`` rows were reached.
    """
    law = drec.force_law
    ok = law.reached_rows(drec.x)
    law.rows_note = None
    if np.all(ok):
        return drec
    k = int(np.sum(ok))
    need = get_experiment("knot_pull").min_rows
    why = law.stop_reason()
    if k < need:
        raise SolverError(
            f"DER knot baseline: {why}; only {k} of {drec.n} rows lie before it (at least "
            f"{need} needed); use the closed-form baseline"
        )
    law.rows_note = {
        "rows_used": k,
        "rows": int(drec.n),
        "judged_range_m": [float(np.min(drec.x[ok])), float(np.max(drec.x[ok]))],
        "stopped_at_end_to_end_m": float(f"{law.d_reach:.6g}"),
        "reason": f"{drec.n - k} rows beyond it left out: {why}",
    }
    return without_rows(drec, np.flatnonzero(~ok))


#: the range the first mu of the DER grid is clipped into
_FIRST_MU = (0.05, 2.0)


def _closed_form_mu(rec, given_sigma) -> float:
    """The closed form's mu, the first of the DER grid: fitted to the rows inside the
    closure's validity (a pull to tight ends beyond it, where the clipped closure's force
    is far too large and would drag mu towards 0), clipped into :data:`_FIRST_MU` (a
    DER pull to tight fitted with the closed form gives mu ~ 1e-18: the closure's force
    rises far too fast near its limit; the grid's next runs start from the DER run's own
    match to the recording)."""
    valid = get_experiment("knot_pull").validity(rec)
    if valid is not None and np.sum(valid[0]) >= get_experiment("knot_pull").min_rows:
        rec = without_rows(rec, np.flatnonzero(~valid[0]))
        given_sigma = rec.sigma
    data = Data(rec.y, rec.mu_nominal, rec.mu_nominal_sigma)
    closed = fit_baseline(rec, data, trial_starts(rec.trial), given_sigma=given_sigma)
    return float(np.clip(closed.params["mu"], *_FIRST_MU))


#: speeds of the DER-made recordings with rate-dependent friction [m/s]
_SPEEDS = np.array([1e-4, 1e-3, 1e-2])


def der_made_recording(
    turns: int = 1,
    mu: float = 0.3,
    effect: str | None = None,
    *,
    size: float = 8.0,
    n: int = 90,
    seed: int = 0,
    noise_fraction: float = 0.03,
):
    """A knot_pull recording made by the DER knot (the IMC paper's rod), with an effect.

    The mean is the DER law (:class:`DERKnotLaw`, its surface fitted to runs at 0.85 and
    1.2 times ``mu``: a grid of its own, not the one the baseline runs) at ``mu`` (the
    ripple of the raw force is numerical), with ``effect`` planted at ``size``
    noise sd (as :func:`knotmech.diagnose.make_recording` plants it: the effect's
    ``plant`` with the DER law as the mean), plus white noise of ``noise_fraction`` of
    the local force plus a quarter of that of the median force (a force sensor's relative
    error and a floor).

    Parameters
    ----------
    turns : int
    mu : float
    effect : None, "displacement_offset" or "rate_dependent_friction"
    size : float
    n : int
        Rows (split over three speeds for rate-dependent friction).
    seed : int
    noise_fraction : float

    Returns
    -------
    rec : Recording
    truth : dict
        ``effect``, ``mu``, the planted parameters, ``noise_sd`` and ``law`` (the
        :class:`DERKnotLaw` holding the run at ``mu``).
    """
    rng = np.random.default_rng(seed)
    exp = get_experiment("knot_pull")
    meta = {
        "experiment": "knot_pull",
        "knot": "overhand",
        "turns": float(turns),
        "rod_radius_m": 1.6e-3,
        "youngs_modulus_Pa": 0.18e6,
        "rod_length_m": 1.0,
        "pull_speed_m_per_s": DER_KNOT_SEPARATION_SPEED,
    }
    # looser than the closed-form sets: the coarse DER knot jams near the law's limit
    e_tight = {1: 0.25, 2: 0.38, 3: 0.5, 4: 0.6}[int(turns)]
    eff = get_effect(effect) if effect is not None else None
    speeds = _SPEEDS if effect == "rate_dependent_friction" else _SPEEDS[:1]
    m = n // len(speeds)
    x = np.tile(np.linspace(1.0 - 0.7, 1.0 - e_tight, m), len(speeds))
    trial = np.repeat(np.arange(len(speeds)), m)
    speed = np.repeat(speeds, m) if len(speeds) > 1 else None
    cols = KnotPull.columns
    base = Recording("knot_pull", x, np.zeros_like(x), dict(meta), None, trial, speed, "", cols)
    law = DERKnotLaw(base)
    for m in (0.85 * mu, 1.2 * mu):  # a grid of its own, not the baseline's
        law.run(m)
    vals = {f.name: getattr(base, f.name) for f in fields(Recording)}
    made = DERKnotRecording(**vals, force_law=law)
    p = {"mu": float(mu)}
    mean0 = exp.mean(made, p, ())
    sd = noise_fraction * (mean0 + 0.25 * float(np.median(mean0)))
    truth = {"effect": effect or "none", "mu": float(mu), "size": float(size)}
    mean = mean0
    if eff is not None:
        ctx = PlantContext(
            experiment=exp,
            rec=made,
            meta=meta,
            x=x,
            speed=speed,
            p=dict(p),
            mean0=mean0,
            sd=sd,
            size=size,
            rng=rng,
        )
        p, planted = eff.plant("knot_pull", ctx)
        truth.update(planted)
        mean = exp.mean(made, p, (eff,))
    y = mean + sd * rng.standard_normal(x.size)
    truth["noise_sd"] = sd
    truth["law"] = law
    rec = Recording("knot_pull", x, y, meta, None, trial, speed, "<der-made>", cols)
    return rec, truth
