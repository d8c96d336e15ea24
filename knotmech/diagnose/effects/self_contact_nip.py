r"""``self_contact_nip``: rod-rod pinch regions on the post (tension_profile).

Each nip is a discrete tension drop, :math:`T \to T\prod_j (1 - f_j H(s - s_j))`.
The position :math:`s_j` is searched (a scan of sample gaps scored by GLS, then a
local refinement with the exact mean) and held fixed; the drop fraction
:math:`f_j \in [0, 0.95]` is free. Repeatable, one nip per addition; the searched
position counts as one degree of freedom. Clove-hitch paper, sec. 7 and Fig. 3(b).
"""

from __future__ import annotations

import numpy as np

from knotmech.diagnose.effects._common import CLOVE
from knotmech.diagnose.effects.base import Effect
from knotmech.diagnose.fitting import (
    FIT_ROWS,
    Fit,
    fit_model,
    refit_all_rows,
    thinned_null,
    whiten_columns,
)
from knotmech.diagnose.model import build_model, param_vector
from knotmech.diagnose.stats import estimate_noise

__all__ = ["SelfContactNip"]


def _count(params) -> int:
    j = 0
    while f"nip_position_{j}" in params:
        j += 1
    return j


class SelfContactNip(Effect):
    name = "self_contact_nip"
    experiments = ("tension_profile",)
    parameters = {
        "positions_m": ([], "arc lengths of the tension drops [m]"),
        "drop_fractions": ([], "fraction of the tension lost at each drop"),
    }
    signature = "discrete tension drops at certain arc lengths (steps)"
    reference = CLOVE + ", sec. 7 and Fig. 3(b): nip regions"
    repeatable = True
    extra_dof = 1
    report_keys = ("positions_m", "drop_fractions")
    key_parameter = ("positions_m", "positions_m", "abs")

    def add_parameters(self, rec, names, lower, upper, fixed):
        for j in range(_count(fixed)):
            names += [f"nip_drop_{j}"]
            lower += [0.0]
            upper += [0.95]

    def is_internal(self, key):
        return key.startswith("nip_")

    def output(self, rec, p, value):
        k = _count(p)
        if k == 0:
            return value
        s = rec.x
        out = np.array(value, dtype=float)  # a copy, multiplied in place nip by nip
        # arc lengths in order (one trial): the rows above a nip are a tail of the array
        ordered = bool(np.all(s[1:] >= s[:-1]))
        for j in range(k):
            pos, keep = p[f"nip_position_{j}"], 1.0 - p[f"nip_drop_{j}"]
            if ordered:
                out[int(np.searchsorted(s, pos, side="right")) :] *= keep
            else:
                out[s > pos] *= keep
        return out

    def fit(self, current, data, starts, *, given_sigma=None, known=None):
        """Score every sample gap for one more drop (GLS on [d/dmu, step], all gaps at
        once in O(n log n), :func:`_step_sums`); fit the best candidate and the best one
        away from it, refine the better fit locally (:meth:`_refine`).

        On a recording longer than :data:`~knotmech.diagnose.fitting.FIT_ROWS` the
        candidates are fitted on its thinned rows and the refinement scores the gaps
        with the thinned fit's values (:meth:`_fit_long`); ``known``, a fit of this
        effect from the same current model (the first pass, for the second pass of
        :func:`~knotmech.diagnose.fitting.fit_with_effect`), is returned when the
        refined positions are its own, instead of refitting that model on every row.
        """
        rec = current.model.rec
        s = rec.x
        fixed = dict(current.model.fixed)
        j = _count(fixed)
        effects = current.model.effect_objects_added + (self,)
        order = np.unique(s)
        mids = 0.5 * (order[1:] + order[:-1])
        if mids.size > 4:
            mids = mids[1:-1]
        taken = [fixed[f"nip_position_{i}"] for i in range(j)]
        if taken:
            gap = max(1.5 * float(np.median(np.diff(order))), 0.01 * float(np.ptp(s)))
            keep = np.min(np.abs(mids[:, None] - np.array(taken)[None, :]), axis=1) > gap
            mids = mids[keep]
        f = current.mean
        r = 0.5 * (rec.meta("post_diameter_m") + rec.meta("rod_diameter_m"))
        sd = current.noise.sd(f)
        ew = current.noise.whiten(data.y - f, sd, starts)
        jmu = whiten_columns(current.noise, sd, starts, (-f * s / r)[:, None])[:, 0]
        # the whitened step column of gap m is W(-f H(s > m) / sd); its products with
        # the whitened d/dmu column and residuals (a12, b2) and with itself (a22)
        (a12, b2), a22 = _step_sums(s, -f / sd, [jmu, ew], current.noise.rho, starts, mids)
        # score = reduction of whitened SS when regressing on [d/dmu, step_j], per candidate
        a11 = jmu @ jmu
        b1 = jmu @ ew
        det = a11 * a22 - a12**2
        det = np.where(det > 1e-300 * max(a11, 1e-300), det, np.inf)
        c2 = (a11 * b2 - a12 * b1) / det
        score = (b1**2 * a22 - 2 * a12 * b1 * b2 + b2**2 * a11) / det
        score = np.where(c2 > 0, score, -np.inf)
        cands = []
        for idx in _two_best(score, mids, 0.01 * float(np.ptp(s))):
            fx = dict(fixed)
            fx[f"nip_position_{j}"] = float(mids[idx])
            v = dict(current.params)
            v[f"nip_drop_{j}"] = float(np.clip(c2[idx], 0.01, 0.9))
            v.update(fx)
            cands.append((fx, v))
        if cands and rec.n > FIT_ROWS:
            return self._fit_long(cands, j, current, data, starts, given_sigma, known)
        best = _fit_best(rec, effects, cands, current, data, starts, given_sigma)
        if best is None:  # no drop-shaped candidate: a null step at the middle
            fx = dict(fixed)
            fx[f"nip_position_{j}"] = float(np.median(s))
            model = build_model(rec, effects, fx)
            v = dict(current.params)
            v[f"nip_drop_{j}"] = 0.0
            return fit_model(
                model,
                data,
                [param_vector(model, v)],
                current.noise,
                starts,
                given_sigma=given_sigma,
            )
        return self._refine(best, j, data, starts, given_sigma=given_sigma)

    def _refine(self, fit, j, data, starts, *, given_sigma=None):
        """Move nip ``j`` to the best sample gap near it (:meth:`_refined_position`); the
        model is refitted when the position moves."""
        pos = self._refined_position(fit, j, data, starts)
        if pos == fit.params[f"nip_position_{j}"]:
            return fit
        fx = dict(fit.model.fixed)
        fx[f"nip_position_{j}"] = pos
        model = build_model(fit.model.rec, fit.model.effect_objects_added, fx)
        v = dict(fit.params)
        v.update(fx)
        return fit_model(
            model, data, [param_vector(model, v)], fit.noise, starts, given_sigma=given_sigma
        )

    def _fit_long(self, cands, j, current, data, starts, given_sigma, known):
        """:meth:`fit` on a recording longer than ``FIT_ROWS``: the candidates ``cands``
        ((fixed, values) pairs) fitted and compared on the thinned rows
        (:func:`~knotmech.diagnose.fitting.thinned_null`: the same positions, the
        noise's correlation ``rho**k``); the best one's position refined on every row
        with its thinned values (mean and noise sd computed on every row); ``known`` when
        its fixed positions are the refined ones, else that model refitted on every row
        (:func:`~knotmech.diagnose.fitting.refit_all_rows`)."""
        rec = current.model.rec
        effects = current.model.effect_objects_added + (self,)
        sub, sdata, sstarts, sgs = thinned_null(current, data, starts, given_sigma, FIT_ROWS)
        thin = None
        for fx, v in cands:
            model = build_model(sub.model.rec, effects, fx)
            fit = fit_model(
                model, sdata, [param_vector(model, v)], sub.noise, sstarts, given_sigma=sgs
            )
            if thin is None or fit.loglik > thin[0].loglik:
                thin = (fit, fx)
        fx = dict(thin[1])
        model = build_model(rec, effects, fx)
        mean = model.mean(thin[0].p)
        noise = estimate_noise(data.y - mean, mean, starts, given_sigma=given_sigma)
        at_thin = Fit(model, thin[0].p, mean, noise, float("nan"))
        fx[f"nip_position_{j}"] = self._refined_position(at_thin, j, data, starts)
        if known is not None and known.model.effects == model.effects:
            if known.model.fixed == fx:
                return known
        model = build_model(rec, effects, fx)
        v = dict(thin[0].params)
        v.update(fx)
        return refit_all_rows(model, data, param_vector(model, v), starts, given_sigma=given_sigma)

    def _refined_position(self, fit, j, data, starts, window=60):
        """The best sample gap for nip ``j`` near its position (exact model, the fit's
        other values fixed).

        Every gap between consecutive arc lengths within ``window`` gaps of the current
        position (and not beyond a neighbouring nip) is scored with the exact mean,
        whitened (in O(n log n), :func:`_step_sums`). Returns the current position when
        the drop is 0 or there is no other gap.
        """
        rec = fit.model.rec
        s = rec.x
        p = fit.params
        pos = p[f"nip_position_{j}"]
        drop = p[f"nip_drop_{j}"]
        if drop <= 0:
            return pos
        order = np.unique(s)
        mids = 0.5 * (order[1:] + order[:-1])
        others = [
            p[f"nip_position_{i}"] for i in range(j + 10) if f"nip_position_{i}" in p and i != j
        ]
        lo = max([o for o in others if o < pos], default=-np.inf)
        hi = min([o for o in others if o > pos], default=np.inf)
        k = int(np.searchsorted(mids, pos))
        cand = mids[max(0, k - window) : k + window + 1]
        cand = cand[(cand > lo) & (cand < hi)]
        if cand.size < 2:
            return pos
        # mean with nip j at m: without * (1 - drop H(s > m)); residual
        # (y - without) + drop * without * H, whitened: ew0 + drop * W(without H / sd)
        without = fit.mean / np.where(s > pos, 1.0 - drop, 1.0)
        sd = fit.noise.sd(fit.mean)
        ew0 = fit.noise.whiten(data.y - without, sd, starts)
        (lin,), quad = _step_sums(s, without / sd, [ew0], fit.noise.rho, starts, cand)
        return float(cand[int(np.argmin(2.0 * drop * lin + drop**2 * quad))])

    def public(self, params, rec, out):
        n = _count(params)
        pos = [params[f"nip_position_{j}"] for j in range(n)]
        drops = [params[f"nip_drop_{j}"] for j in range(n)]
        order = np.argsort(pos)
        out["positions_m"] = [float(pos[i]) for i in order]
        out["drop_fractions"] = [float(drops[i]) for i in order]

    def sentence(self, p, rec):
        pos = ", ".join(f"{v:.3g}" for v in p["positions_m"])
        drops = ", ".join(f"{100 * f:.0f} %" for f in p["drop_fractions"])
        return f"self-contact nips: tension drops of {drops} at s = {pos} m"

    def plant(self, kind, s):
        rng, x = s.rng, s.x
        n_nips = int(rng.integers(1, 3))
        span = x[-1] - x[0]
        pos = np.sort(rng.uniform(0.2, 0.8, n_nips)) * span + x[0]
        if n_nips == 2 and pos[1] - pos[0] < 0.15 * span:
            pos[1] = min(pos[0] + 0.15 * span, x[0] + 0.9 * span)
        cur = dict(s.p)
        for j, s_j in enumerate(pos):
            level = s.experiment.mean(s.rec, cur, (self,))
            i = int(np.searchsorted(x, s_j, side="right"))
            drop = float(min(s.size * s.sd[i] / level[i], 0.9))
            cur[f"nip_position_{j}"] = float(s_j)
            cur[f"nip_drop_{j}"] = drop
        return cur, {"positions_m": [float(v) for v in pos]}


def _fit_best(rec, effects, cands, current, data, starts, given_sigma):
    """The best-likelihood fit of the candidate nips ``cands`` ((fixed, values) pairs),
    each fitted from its values under ``current``'s noise; None without a candidate."""
    best = None
    for fx, v in cands:
        model = build_model(rec, effects, fx)
        fit = fit_model(
            model, data, [param_vector(model, v)], current.noise, starts, given_sigma=given_sigma
        )
        if best is None or fit.loglik > best.loglik:
            best = fit
    return best


def _two_best(score, mids, apart):
    """Indices of the best finite score and of the best one at least ``apart`` from it."""
    out = []
    if score.size == 0:
        return out
    i = int(np.argmax(score))
    if not np.isfinite(score[i]):
        return out
    out.append(i)
    far = np.where(np.abs(mids - mids[i]) >= apart, score, -np.inf)
    k = int(np.argmax(far))
    if np.isfinite(far[k]):
        out.append(k)
    return out


def _sums_above(keys, weights, cuts):
    """``sum(weights[keys > c])`` for every ``c`` in ``cuts`` (sorted or not)."""
    o = np.argsort(keys, kind="stable")
    ks = keys[o]
    tail = np.concatenate([np.cumsum(weights[o][::-1])[::-1], [0.0]])
    return tail[np.searchsorted(ks, cuts, side="right")]


def _step_sums(s, g, vectors, rho, starts, cuts):
    r"""Products of whitened step columns with vectors and with themselves, all cuts at once.

    The column of cut :math:`m` is :math:`e(m) = W(g\,H(s > m))`, ``W`` the AR(1)
    whitening of :meth:`knotmech.diagnose.stats.NoiseModel.whiten` (unit sd: ``g``
    already divided by the noise sd),
    :math:`e_i = (u_i - \rho u_{i-1})/\sqrt{1-\rho^2}`, :math:`e_i = u_i` at a trial
    start. Both :math:`e(m)\cdot w = \sum_{s_i > m} q_i` and
    :math:`e(m)\cdot e(m) = \sum_{s_i > m} v_i + \sum_{\min(s_i, s_{i-1}) > m} p_i`
    are sums over the rows above the cut, so a sort and cumulative sums give every cut
    in O((n + M) log n) time and O(n + M) memory, instead of an (n, M) matrix of columns.

    Parameters
    ----------
    s, g : (n,) arrays
        Control variable (rows in recording order) and the column's scale per row.
    vectors : list of (n,) arrays
        Whitened vectors ``w``.
    rho : float
        Lag-one correlation.
    starts : (n,) bool array
        Trial starts.
    cuts : (M,) array
        Cut positions.

    Returns
    -------
    lin : list of (M,) arrays
        :math:`e(m)\cdot w` for each vector.
    quad : (M,) array
        :math:`e(m)\cdot e(m)`.
    """
    n = s.size
    c = np.sqrt(1.0 - rho**2)
    inv = np.where(starts, 1.0, 1.0 / c)
    nxt = np.zeros(n, dtype=bool)  # row i + 1 exists and continues row i's trial
    nxt[:-1] = ~starts[1:]
    lin = []
    for w in vectors:
        q = g * w * inv
        q[:-1] -= np.where(nxt[:-1], rho * g[:-1] * w[1:] / c, 0.0)
        lin.append(_sums_above(s, q, cuts))
    v = g * g * inv * inv + np.where(nxt, (rho / c) ** 2 * g * g, 0.0)
    quad = _sums_above(s, v, cuts)
    if n > 1 and rho != 0.0:
        pair = ~starts[1:]
        key = np.minimum(s[1:], s[:-1])[pair]
        pw = (-2.0 * rho / c**2) * (g[1:] * g[:-1])[pair]
        quad = quad + _sums_above(key, pw, cuts)
    return lin, quad
