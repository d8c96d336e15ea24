r"""Power-law (1/f-type) noise: its spectrum fitted on the high frequencies, and draws.

The engine's noise model is AR(1) (:class:`knotmech.diagnose.stats.NoiseModel`). A
sensor's 1/f ("pink") noise is not: its power keeps rising towards the lowest
frequencies, where an AR(1) model fitted to the same rows flattens, so an AR(1) null
calls the low-frequency wander of 1/f noise a smooth mismatch. On the high frequencies
(:data:`F_HIGH` and up, where a mismatch of a few periods over the range has no power)
the two cannot be told apart on a short recording (Whittle fits of both to 120 rows of
pink or AR(1) noise prefer either about half the time), so a mismatch that an AR(1) null
finds but a power-law null fitted to the same high frequencies does not is
*undetermined*, not structure: :func:`knotmech.diagnose.diagnose` runs that second null
(:func:`power_law_reason`).

The spectrum of the standardised residual :math:`u = r/\sigma(f)` (per-row sd of the
fitted noise model) is modelled as :math:`S(f) = c\,f^{-\beta}` (:math:`f` in cycles
per row) and fitted by the Whittle likelihood (Whittle 1953; Robinson 1995 for the
long-memory case) on the periodogram ordinates of each trial above :data:`F_HIGH`,
:math:`\beta` over :data:`BETA_GRID` with :math:`c` profiled out. Draws
(:class:`PowerLawNoise`) are Gaussian series with that spectrum synthesised by FFT at
twice the trial's length and cut to it (so they are not circular), times the per-row sd.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from knotmech.diagnose.stats import NoiseModel

__all__ = [
    "F_HIGH",
    "BETA_GRID",
    "BETA_RANGE",
    "PowerLawFit",
    "PowerLawNoise",
    "fit_power_law",
    "power_law_draws",
    "whittle_ar1_minus_power_law",
]

#: lowest frequency [cycles per row] of the band the power law is fitted on
F_HIGH = 1.0 / 16.0
#: spectral exponents tried (0: white; 1: pink; 2: a random walk)
BETA_GRID = np.linspace(0.0, 3.0, 121)
#: fewest periodogram ordinates a fit needs (a trial of 64 rows gives 28)
MIN_ORDINATES = 24
#: the power-law null is tried when the remainder's high-frequency spectral exponent lies
#: in this range, that of flicker (1/f-type) noise: on 120 rows white noise fits 0-0.4
#: (90 % under 0.38), pink 0.57-1.33 (10-90 %), AR(1) at rho 0.8 1.15-1.78 and at rho 0.9
#: 1.6-1.8 (the engine's AR(1) null keeps those: a power law fitted to them would
#: extrapolate far more low-frequency power than they have)
BETA_RANGE = (0.3, 1.3)


#: lag-one correlations of the AR(1) spectrum fitted by :func:`whittle_ar1_minus_power_law`
AR1_RHO_GRID = np.linspace(-0.4, 0.995, 280)


@dataclass(frozen=True)
class PowerLawFit:
    """A Whittle fit of :math:`S(f) = c f^{-\\beta}` to a high-frequency band.

    Attributes
    ----------
    beta : float
        Spectral exponent.
    c : float
        Spectral level [units of u squared per (cycle/row)], ``E I(f) = c f^-beta``.
    n_ordinates : int
        Periodogram ordinates fitted.
    """

    beta: float
    c: float
    n_ordinates: int


def _segments(starts: np.ndarray):
    idx = np.flatnonzero(starts)
    return zip(idx, np.append(idx[1:], starts.size), strict=True)


def fit_power_law(u, starts, *, f_min: float = F_HIGH) -> PowerLawFit | None:
    """Whittle fit of a power law to the periodograms of ``u`` above ``f_min``.

    Parameters
    ----------
    u : (n,) array
        Standardised residuals (rows in recording order).
    starts : (n,) bool array
        Trial starts; each trial's periodogram is taken on its own (mean removed).
    f_min : float
        Lowest frequency fitted [cycles per row].

    Returns
    -------
    PowerLawFit or None
        None when fewer than :data:`MIN_ORDINATES` ordinates lie in the band.
    """
    f, p = _periodogram(np.asarray(u, float), starts, f_min)
    if f.size < MIN_ORDINATES or not np.all(np.isfinite(p)) or np.sum(p) <= 0:
        return None
    nll, c = _power_law_nll(f, p)
    i = int(np.argmin(nll))
    return PowerLawFit(float(BETA_GRID[i]), float(c[i]), int(f.size))


def _power_law_nll(f, p):
    """(profiled Whittle negative log-likelihood up to a constant, scale c) of
    :math:`c f^{-\\beta}` at each exponent of :data:`BETA_GRID`, fitted to the periodogram
    ordinates ``p`` at frequencies ``f`` > 0: c(beta) = mean(I f^beta), -loglik = sum(log c
    - beta log f)."""
    lf = np.log(f)
    g = p[:, None] * np.exp(BETA_GRID[None, :] * lf[:, None])
    c = np.mean(g, axis=0)
    return f.size * np.log(c) - BETA_GRID * np.sum(lf), c


def _periodogram(u, starts, f_min):
    """Frequencies [cycles per row] in ``[f_min, 0.5)`` and periodogram ordinates of each
    trial of ``u`` (mean removed; trials under 8 rows left out), concatenated."""
    fs, ps = [], []
    for a, b in _segments(np.asarray(starts, bool)):
        m = b - a
        if m < 8:
            continue
        z = u[a:b] - np.mean(u[a:b])
        per = np.abs(np.fft.rfft(z)) ** 2 / m
        f = np.fft.rfftfreq(m)
        keep = (f >= f_min) & (f < 0.5)  # the Nyquist ordinate has another distribution
        fs.append(f[keep])
        ps.append(per[keep])
    f = np.concatenate(fs) if fs else np.empty(0)
    p = np.concatenate(ps) if ps else np.empty(0)
    return f, p


def whittle_ar1_minus_power_law(u, starts) -> float:
    r"""How much better a power law describes ``u``'s whole spectrum than an AR(1) does.

    Both two-parameter spectra are fitted by the profiled Whittle likelihood (Whittle
    1953) to every periodogram ordinate of each trial, :math:`0 < f < 1/2` (not only the
    band above :data:`F_HIGH`): the power law :math:`c f^{-\beta}` over
    :data:`BETA_GRID`, the AR(1) :math:`c / (1 + \rho^2 - 2\rho\cos 2\pi f)` over
    :data:`AR1_RHO_GRID`. On the high frequencies alone the two cannot be told apart on a
    few hundred rows; below them an AR(1) flattens and a power law keeps rising. Measured
    on 300 series of 160-260 rows of each campaign generator (``validation.
    diagnose_campaign``, seeds 777000-777299) whose high-frequency exponent lies in
    :data:`BETA_RANGE`: AR(1) noise at rho 0.9 gives a positive value 16-26 % of the time,
    1/f noise 77-93 %.

    Parameters
    ----------
    u : (n,) array
        Standardised residuals (rows in recording order).
    starts : (n,) bool array
        Trial starts.

    Returns
    -------
    float
        Minimum negative log-likelihood of the AR(1) fit minus that of the power-law fit
        (dimensionless; > 0: the power law fits better); nan without ordinates.
    """
    f, p = _periodogram(np.asarray(u, float), starts, 0.0)
    f, p = f[f > 0], p[f > 0]
    if f.size == 0 or not np.all(np.isfinite(p)) or np.sum(p) <= 0:
        return float("nan")
    nll_pl = float(np.min(_power_law_nll(f, p)[0]))
    r = AR1_RHO_GRID[None, :]
    shape = 1.0 + r**2 - 2.0 * r * np.cos(2.0 * np.pi * f[:, None])  # S = c / shape
    c = np.mean(p[:, None] * shape, axis=0)
    nll_ar = float(np.min(f.size * np.log(c) - np.sum(np.log(shape), axis=0)))
    return nll_ar - nll_pl


def _synth(m: int, beta: float, draws: int, rng) -> np.ndarray:
    """(m, draws) Gaussian series of spectrum ``f**-beta`` (unit level), the first ``m``
    rows of a ``2 m``-row FFT synthesis (not circular), as :meth:`PowerLawNoise.sample`."""
    n2 = 2 * m
    f = np.fft.rfftfreq(n2)
    s = np.zeros_like(f)
    s[1:] = f[1:] ** (-beta)
    amp = np.sqrt(s * n2 / 2.0)[:, None]
    shape = (f.size, draws)
    spec = amp * (rng.standard_normal(shape) + 1j * rng.standard_normal(shape))
    spec[-1] = np.sqrt(s[-1] * n2) * rng.standard_normal(draws)
    return np.fft.irfft(spec, n2, axis=0)[:m]


def power_law_draws(seg: np.ndarray, beta: float, draws: int, rng) -> np.ndarray:
    """``draws`` series of power-law noise of exponent ``beta`` laid out as ``seg``.

    Each run of equal labels in ``seg`` (a trial, rows in time order) is its own
    series, synthesised as :class:`PowerLawNoise` does (unit level: the statistics they
    calibrate do not depend on it).

    Parameters
    ----------
    seg : (n,) int array
        Trial label of each row.
    beta : float
        Spectral exponent.
    draws : int
        Number of series.
    rng : numpy Generator

    Returns
    -------
    (n, draws) array
    """
    seg = np.asarray(seg)
    out = np.empty((seg.size, draws))
    bounds = np.flatnonzero(np.r_[True, seg[1:] != seg[:-1], True])
    for a, b in zip(bounds[:-1], bounds[1:], strict=True):
        out[a:b] = _synth(b - a, beta, draws, rng)
    return out


@dataclass(frozen=True)
class PowerLawNoise(NoiseModel):
    """An AR(1) noise model whose draws are power-law noise instead.

    Its likelihood, whitening and sd are those of the AR(1) model it was made from (the
    fits of a bootstrap keep using them); :meth:`sample` draws Gaussian noise of spectrum
    :math:`c f^{-\\beta}` per trial, times :meth:`sd`. ``thin`` > 1: the draw is made at
    ``thin`` times the rows and every ``thin``-th row kept (a thinned bootstrap,
    :func:`knotmech.diagnose.fitting.thinned_noise`), which keeps its spectrum exact.
    """

    beta: float = 0.0
    c: float = 1.0
    thin: int = 1

    @classmethod
    def from_noise(cls, noise: NoiseModel, fit: PowerLawFit) -> PowerLawNoise:
        return cls(noise.scale, noise.growth, noise.rho, noise.fref, noise.given_sigma,
                   beta=fit.beta, c=fit.c)  # fmt: skip

    def sample(self, mean: np.ndarray, starts: np.ndarray, rng: np.random.Generator):
        """One draw (same shape as ``mean``)."""
        z = np.empty(mean.size)
        k = int(self.thin)
        for a, b in _segments(np.asarray(starts, bool)):
            m = (b - a) * k
            n2 = 2 * m
            f = np.fft.rfftfreq(n2)
            s = np.zeros_like(f)
            s[1:] = self.c * f[1:] ** (-self.beta)
            amp = np.sqrt(s * n2 / 2.0)
            spec = amp * (rng.standard_normal(f.size) + 1j * rng.standard_normal(f.size))
            if n2 % 2 == 0:
                spec[-1] = np.sqrt(s[-1] * n2) * rng.standard_normal()
            z[a:b] = np.fft.irfft(spec, n2)[:m:k]
        return self.sd(mean) * z

    def thinned(self, k: int, given_sigma=None) -> PowerLawNoise:
        """On every ``k``-th row: the draws are made at ``k`` times the rows and cut (their
        spectrum stays exact); the AR(1) part as :meth:`NoiseModel.thinned`."""
        return replace(super().thinned(k, given_sigma), thin=self.thin * int(k))

    def describe(self) -> dict:
        return {**super().describe(), "spectrum": f"power law, beta {self.beta:.3g}"}
