r"""Hitches on a post: ideal-rope holding criteria and the hold verdict.

Theory of hitches in the framework of Bayman (Am. J. Phys. 45 (1977) 185) and
Maddocks & Keller (SIAM J. Appl. Math. 47 (1987) 1185): a hitch is a chain of

- *wraps*: the rope on the post (friction :math:`\mu`) or around its own standing
  part (rope-on-rope friction :math:`\mu_{rr}`) over an angle :math:`\theta`; at
  the onset of slip the tension grows by at most :math:`e^{\mu\theta}` (capstan);
- *nips* (the wrap-overs of J. Walker's, Sci. Am. 1983, and L. Kauffman's, Knots
  and Physics, expositions of Bayman, where the top strand squeezes the bottom one
  against the rod): a strand pinched between the support and a crossing *rider*;
  the rider of tension :math:`T_r` presses it with a normal force
  :math:`N = n\,T_r` and the pinched strand can carry a tension jump of up to
  :math:`(\mu_\mathrm{below} + \mu_\mathrm{above})N` (both faces grip).

Reading the chain from the free end (tension :math:`T_\mathrm{low}`) to the load
gives the largest load the hitch holds, :math:`T_\mathrm{high} \le K\,T_\mathrm{low}`,
or, when a nip feeds back on the rider that presses it strongly enough, *self
locking* (:math:`K = \infty`: any load holds, Bayman's "self-locking unit").

Two models are implemented (``derivations/hitches.py`` derives every ``K``):

``ideal-rope``
    Zero-thickness, perfectly flexible rope. A rider that crosses a strand of zero
    thickness is not deflected, so it exerts no point force: :math:`n = 0` and the
    hitch is a capstan of its total wrap,
    :math:`K = e^{\mu\Theta_\mathrm{post} + \mu_{rr}\Theta_\mathrm{rope}}`. The hold
    criterion is linear in :math:`T_\mathrm{low}`, which is the statement of
    Maddocks & Keller quoted by the clove-hitch paper (Sec. 8): at slip
    :math:`T_\mathrm{high}` is proportional to :math:`T_\mathrm{low}`, so **with a
    free end (:math:`T_\mathrm{low}=0`) the ideal-rope clove hitch slips at any load,
    whatever d and D** (:data:`FREE_END_STATEMENT`). This model decides the
    closed-form verdict; its validity is d/D <= 0.1 and no half hitches.
``thick-nip``
    Finite rod diameter d (derived here, not taken from the papers): a rider
    lifted over a strand of diameter d lying on a support of diameter
    :math:`D_s` is deflected by :math:`2\arccos\frac{D_s+d}{D_s+3d}`, so
    :math:`n = 2\sqrt{1-\bigl(\frac{D_s+d}{D_s+3d}\bigr)^2}` (perpendicular
    crossing), and wraps use :func:`~knotmech.analytic.capstan.mu_eff`. It shows
    Bayman-type self-locking above a critical friction. Informational only: the
    clove-hitch paper's experiments (Fig. 4) find holding below a critical load that
    depends on d/2R, which neither model captures.

Assumed wrap angles (a modelling choice, stated in every answer): clove hitch two
full turns on the post with both ends passing under the rider; two half hitches a
single turn (:math:`\pi`) on the post then two half hitches, each a full turn
(:math:`2\pi`) around the standing part with the end pinched under its own turn;
round turn :math:`2\pi` (ends leaving on the same side; opposite sides add
:math:`\pi`); cow hitch (girth hitch, lark's head) two full turns on the post in
opposite senses, the bight between them lying over both legs (a pair of half hitches
tied in opposite directions, where the clove hitch's are tied in the same direction).
Its load is on one leg and :math:`T_\mathrm{low}` on the other. Only the ideal-rope
model answers for the cow hitch: a zero-thickness rope is a capstan whatever the sense of
its turns, :math:`K = e^{4\pi\mu}` as for the clove hitch, so with one leg free it slips
at any load (the hitch is meant to be loaded on both legs); the thick-nip chain is not
derived for it (the bight presses the legs where it crosses them, a geometry not
checked here), so :func:`thick_hitch_ratio` refuses it.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np

from knotmech import _json, knots
from knotmech.analytic.capstan import mu_eff
from knotmech.errors import InputError, check_nonnegative, check_positive, vectorised

__all__ = [
    "KNOTS",
    "HitchGeometry",
    "FREE_END_STATEMENT",
    "nip_factor",
    "ideal_hitch_ratio",
    "thick_hitch_ratio",
    "thick_hitch_lock_parameter",
    "hitch_holds",
    "hitch_margin",
    "hitch_critical_mu",
    "ModelAnswer",
    "HoldVerdict",
    "hold_verdict",
]

TWO_PI = 2.0 * math.pi

FREE_END_STATEMENT = knots.get("clove-hitch").free_end_note


@dataclass(frozen=True)
class HitchGeometry:
    """Wrap angles of a hitch in the chain model.

    Attributes
    ----------
    name : str
    post_wrap_in : float
        Wrap on the post between the load-side nip (or the load) and the rider [rad].
    post_wrap_out : float
        Wrap on the post between the rider and the free-end nip [rad] (clove hitch).
    half_hitches : int
        Number of half hitches around the standing part.
    half_hitch_wrap : float
        Wrap of each half hitch around the standing part [rad].
    post_nips : bool
        Whether both ends pass under a rider on the post (clove hitch, cow hitch).
    description : str
    thick_nip : bool
        Whether the thick-nip model is derived for this hitch (not for the cow hitch).
    """

    name: str
    post_wrap_in: float
    post_wrap_out: float = 0.0
    half_hitches: int = 0
    half_hitch_wrap: float = TWO_PI
    post_nips: bool = False
    description: str = ""
    thick_nip: bool = True

    @property
    def post_wrap(self) -> float:
        """Total wrap on the post [rad]."""
        return self.post_wrap_in + self.post_wrap_out

    @property
    def rope_wrap(self) -> float:
        """Total wrap around the standing part [rad]."""
        return self.half_hitches * self.half_hitch_wrap


def _from_record(k) -> HitchGeometry:
    w = k.wraps
    return HitchGeometry(k.name, post_wrap_in=w.post_wrap_in, post_wrap_out=w.post_wrap_out,
                         half_hitches=w.half_hitches, post_nips=w.post_nips,
                         description=w.description, thick_nip=w.thick_nip)  # fmt: skip


#: the hitches this module knows: the registry's hitches with a closed-form geometry
#: (:mod:`knotmech.knots`; ``capstan`` is handled by :func:`hold_verdict`)
KNOTS: dict[str, HitchGeometry] = {
    k.name: _from_record(k) for k in knots.records(family="hitch") if k.wraps is not None
}


def _geometry(knot: str) -> HitchGeometry:
    key = str(knot).strip().lower().replace("_", "-").replace(" ", "-")
    if key not in KNOTS:
        raise InputError(f"knot must be one of {', '.join(KNOTS)}, got {knot!r}")
    return KNOTS[key]


def _thick_geometry(knot: str) -> HitchGeometry:
    g = _geometry(knot)
    if not g.thick_nip:
        raise InputError(
            f"knot: the thick-nip model is not derived for the {g.name} (it is for "
            f"{', '.join(k for k, v in KNOTS.items() if v.thick_nip)})"
        )
    return g


def _mu_rr(mu, mu_rr):
    return mu if mu_rr is None else check_nonnegative("mu_rr", mu_rr)


@vectorised
def nip_factor(rod_diameter, support_diameter):
    r"""Normal force at a nip per unit rider tension, :math:`n = N/T_r`.

    .. math:: n = 2\sqrt{1 - \Bigl(\frac{D_s + d}{D_s + 3d}\Bigr)^2}

    The rider (diameter d) lies on a support of diameter :math:`D_s` with its
    centreline at radius :math:`(D_s+d)/2` and is lifted to :math:`(D_s+3d)/2` where
    it crosses a strand of the same diameter; the two straight tangents meeting over
    the strand turn the rider by :math:`2\arccos\frac{D_s+d}{D_s+3d}`, and the
    concentrated force is :math:`2T_r\sin` of half that angle. Perpendicular
    crossing, rigid circular cross-sections, no indentation. :math:`n\approx
    4\sqrt{d/D_s}\to 0` for thin rods (the ideal-rope limit). Derived in
    ``derivations/hitches.py`` (this work).

    Parameters
    ----------
    rod_diameter : array_like
        d [m], > 0.
    support_diameter : array_like
        :math:`D_s` [m], > 0: the post, or the standing part (= d) for half hitches.

    Returns
    -------
    ndarray
        n [-].
    """
    d = check_positive("rod_diameter", rod_diameter)
    Ds = check_positive("support_diameter", support_diameter)
    c = (Ds + d) / (Ds + 3 * d)
    return 2 * np.sqrt(1 - c**2)


def _ideal_ratio(g: HitchGeometry, mu, mrr):
    """exp(mu Theta_post + mu_rr Theta_rope), ``inf`` where it overflows (the hold verdict
    and :func:`hitch_holds` read ``inf`` as locked; :func:`ideal_hitch_ratio` refuses it)."""
    with np.errstate(over="ignore"):
        return np.exp(mu * g.post_wrap + mrr * g.rope_wrap)


def _ratio_of(knot, mu, mu_rr):
    """:func:`_ideal_ratio` of ``knot`` with its arguments checked (``inf`` kept)."""
    mu = check_nonnegative("mu", mu)
    return _ideal_ratio(_geometry(knot), mu, _mu_rr(mu, mu_rr))


def _held(ratio, low_tension):
    """K T_low: the largest load held [N]; 0 with a free end even where K is ``inf``."""
    with np.errstate(invalid="ignore"):
        return np.where(np.asarray(low_tension) == 0, 0.0, ratio * low_tension)


@vectorised
def ideal_hitch_ratio(knot, mu, mu_rr=None):
    r"""Holding ratio :math:`K = T_\mathrm{high}/T_\mathrm{low}` of an ideal-rope hitch.

    .. math:: K = e^{\mu\Theta_\mathrm{post} + \mu_{rr}\Theta_\mathrm{rope}}

    Parameters
    ----------
    knot : str
        One of :data:`KNOTS`.
    mu : array_like
        Rope-post friction coefficient [-], >= 0.
    mu_rr : array_like, optional
        Rope-rope friction coefficient [-], >= 0 (default: ``mu``).

    Returns
    -------
    ndarray
        K [-], finite: an ideal-rope hitch never self-locks, so it slips with a
        free end (:data:`FREE_END_STATEMENT`).

    Notes
    -----
    Zero-thickness, flexible, inextensible rope, Amontons-Coulomb friction; a
    rider crossing a zero-thickness strand is not deflected and exerts no point
    force. References: Bayman (1977); Maddocks & Keller (1987) as summarised in
    the clove-hitch paper, Sec. 8; derivation ``derivations/hitches.py``.
    """
    g = _geometry(knot)
    mu = check_nonnegative("mu", mu)
    k = _ideal_ratio(g, mu, _mu_rr(mu, mu_rr))
    if not np.all(np.isfinite(k)):
        raise InputError(
            f"mu = {np.max(mu):.3g} overflows the {g.name}'s ideal ratio exp(mu Theta) (mu "
            f"above {np.log(np.finfo(float).max) / (g.post_wrap + g.rope_wrap):.3g}); a rope's "
            "friction coefficient is below about 1.5"
        )
    return k


def _thick_parts(g: HitchGeometry, mu, mrr, d, D):
    """Wrap coefficients, nip factors and grips of the thick-nip chain."""
    m_post = mu_eff(mu, D / d)
    m_rope = mu_eff(mrr, 1.0)
    n_post = nip_factor(d, D)
    n_rope = nip_factor(d, d)
    return m_post, m_rope, n_post, n_rope, mu + mrr, 2 * mrr


@vectorised
def thick_hitch_lock_parameter(knot, mu, mu_rr=None, *, rod_diameter, post_diameter):
    r"""Self-locking parameter :math:`\Lambda` of the thick-nip model (locks when >= 1).

    Clove hitch: :math:`\Lambda = (\mu+\mu_{rr})\,n(d,D)\,e^{\mu_\mathrm{eff}\theta_\mathrm{out}}`;
    half hitches: :math:`\Lambda = 2\mu_{rr}\,n(d,d)\,e^{\mu_\mathrm{eff}(\mu_{rr},1)\,\theta_h}`;
    round turn: 0 (no nip). See :func:`thick_hitch_ratio`.
    """
    g = _thick_geometry(knot)
    mu = check_nonnegative("mu", mu)
    mrr = _mu_rr(mu, mu_rr)
    d = check_positive("rod_diameter", rod_diameter)
    D = check_positive("post_diameter", post_diameter)
    m_post, m_rope, n_post, n_rope, g_post, g_rope = _thick_parts(g, mu, mrr, d, D)
    lock = np.zeros(np.broadcast(mu, mrr, d, D).shape)
    # a huge mu overflows the exponential: inf, read as locked (as _ideal_ratio does)
    with np.errstate(over="ignore"):
        if g.post_nips:
            lock = np.maximum(lock, g_post * n_post * np.exp(m_post * g.post_wrap_out))
        if g.half_hitches:
            lock = np.maximum(lock, g_rope * n_rope * np.exp(m_rope * g.half_hitch_wrap))
    return lock


@vectorised
def thick_hitch_ratio(knot, mu, mu_rr=None, *, rod_diameter, post_diameter):
    r"""Holding ratio :math:`K` of the thick-nip model (``inf`` when self-locking).

    Clove hitch (free end -> nip -> wrap :math:`\theta_o` -> rider -> wrap
    :math:`\theta_i` -> nip -> load), with :math:`E_x = e^{\mu_\mathrm{eff}\theta_x}`
    and :math:`G = (\mu+\mu_{rr})\,n(d,D)`:

    .. math:: K = \frac{(E_i + G)\,E_o}{1 - G E_o}

    Half hitch (free end -> nip under its own turn -> wrap :math:`\theta_h` around
    the standing part), :math:`h = E_h/(1 - G_r E_h)` with
    :math:`G_r = 2\mu_{rr} n(d,d)`; two half hitches :math:`K = E_\mathrm{post}h^2`.
    Whenever a denominator is :math:`\le 0` the hitch self-locks (:math:`K=\infty`).

    Parameters
    ----------
    knot : str
    mu, mu_rr : array_like
        Friction coefficients [-] (``mu_rr`` defaults to ``mu``).
    rod_diameter, post_diameter : array_like
        d, D [m], > 0.

    Returns
    -------
    ndarray
        K [-] (may be ``inf``); tends to :func:`ideal_hitch_ratio` as
        :math:`d/D \to 0` for hitches without half hitches.

    Notes
    -----
    Derived here (``derivations/hitches.py``) in Bayman's wrap-over framework; the
    rider's own rope-rope friction is neglected (as Bayman does), the rider
    crosses perpendicularly, and the nips are rigid. It predicts load-independent
    holding, unlike the experiments of the clove-hitch paper (Fig. 4).
    """
    g = _thick_geometry(knot)
    mu = check_nonnegative("mu", mu)
    mrr = _mu_rr(mu, mu_rr)
    d = check_positive("rod_diameter", rod_diameter)
    D = check_positive("post_diameter", post_diameter)
    m_post, m_rope, n_post, n_rope, g_post, g_rope = _thick_parts(g, mu, mrr, d, D)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        if g.post_nips:
            e_in = np.exp(m_post * g.post_wrap_in)
            e_out = np.exp(m_post * g.post_wrap_out)
            G = g_post * n_post
            den = 1 - G * e_out
            K = np.where(den > 0, (e_in + G) * e_out / np.where(den > 0, den, 1.0), np.inf)
        else:
            K = np.exp(m_post * g.post_wrap)
        if g.half_hitches:
            e_h = np.exp(m_rope * g.half_hitch_wrap)
            den = 1 - g_rope * n_rope * e_h
            h = np.where(den > 0, e_h / np.where(den > 0, den, 1.0), np.inf)
            K = K * h**g.half_hitches
    return np.asarray(K, dtype=float)


def _check_tensions(high_tension, low_tension):
    th = check_positive("high_tension", high_tension)
    tl = check_nonnegative("low_tension", low_tension)
    if np.any(tl > th):
        raise InputError("low_tension must be <= high_tension (the load is the larger tension)")
    return th, tl


@vectorised
def hitch_holds(knot, *, high_tension, low_tension, mu, mu_rr=None):
    r"""Whether an ideal-rope hitch holds: :math:`T_\mathrm{high} \le K\,T_\mathrm{low}`.

    Parameters
    ----------
    knot : str
    high_tension : array_like
        Load [N], > 0.
    low_tension : array_like
        Free-end tension [N], 0 <= low_tension <= high_tension.
    mu, mu_rr : array_like
        [-]; ``mu_rr`` defaults to ``mu``.

    Returns
    -------
    ndarray of bool
        False whenever ``low_tension == 0`` (:data:`FREE_END_STATEMENT`).
    """
    th, tl = _check_tensions(high_tension, low_tension)
    return th <= _held(_ratio_of(knot, mu, mu_rr), tl)


@vectorised
def hitch_margin(knot, *, high_tension, low_tension, mu, mu_rr=None):
    r"""Load margin of an ideal-rope hitch: :math:`K T_\mathrm{low}/T_\mathrm{high} - 1`.

    >= 0 means it holds; -1 with a free end.
    """
    th, tl = _check_tensions(high_tension, low_tension)
    return _held(_ratio_of(knot, mu, mu_rr), tl) / th - 1


@vectorised
def hitch_critical_mu(knot, *, high_tension, low_tension, mu_rr=None):
    r"""Smallest rope-post :math:`\mu` at which an ideal-rope hitch holds.

    .. math::

        \mu_c = \frac{\ln(T_\mathrm{high}/T_\mathrm{low})}
        {\Theta_\mathrm{post}+\Theta_\mathrm{rope}}\ (\mu_{rr}=\mu),\qquad
        \mu_c = \max\Bigl(0, \frac{\ln(T_\mathrm{high}/T_\mathrm{low})
        - \mu_{rr}\Theta_\mathrm{rope}}{\Theta_\mathrm{post}}\Bigr)\ (\mu_{rr}\ \text{given})

    ``inf`` for a free end (no friction suffices).
    """
    g = _geometry(knot)
    th, tl = _check_tensions(high_tension, low_tension)
    with np.errstate(divide="ignore"):
        log_ratio = np.log(th) - np.log(tl)  # inf when tl == 0
    if mu_rr is None:
        return log_ratio / (g.post_wrap + g.rope_wrap)
    mrr = check_nonnegative("mu_rr", mu_rr)
    return np.maximum(0.0, (log_ratio - mrr * g.rope_wrap) / g.post_wrap)


# --------------------------------------------------------------------------- verdict
@dataclass(frozen=True)
class ModelAnswer:
    """One model's answer to "does it hold?".

    Attributes
    ----------
    model : str
        Model name (``ideal-rope``, ``thick-nip``, ``thick-capstan``, ...).
    holds : bool
    margin : float
        Load margin ``capacity/load - 1`` (>= 0 holds; ``inf`` when self-locking).
    capacity : float
        Largest load the model says is held for the given free-end load [N].
    critical_mu : float
        Smallest rope-post friction coefficient for which it holds [-] (``inf``:
        none does).
    decides : bool
        Whether this answer is the verdict.
    inside_validity : bool
        Whether the inputs lie inside the model's validity range.
    assumptions, validity, notes : tuple of str
    reference : str
    """

    model: str
    holds: bool
    margin: float
    capacity: float
    critical_mu: float
    decides: bool
    inside_validity: bool
    assumptions: tuple[str, ...]
    validity: tuple[str, ...]
    reference: str
    notes: tuple[str, ...] = ()

    def to_dict(self) -> dict:
        """Strict JSON-ready dict (:mod:`knotmech._json`): a non-finite number is null, and
        ``margin_unbounded``, ``capacity_unbounded`` (+inf: self-locking) and
        ``critical_mu_none`` (inf: no friction coefficient suffices) say which."""
        return _json.jsonable(
            {
                **asdict(self),
                "margin_unbounded": bool(math.isinf(self.margin) and self.margin > 0),
                "capacity_unbounded": bool(math.isinf(self.capacity) and self.capacity > 0),
                "critical_mu_none": bool(math.isinf(self.critical_mu)),
            }
        )


@dataclass(frozen=True)
class HoldVerdict:
    """Verdict of :func:`hold_verdict`: the deciding answer plus every model's answer.

    ``answers`` is a list so that further models (e.g. a DER phase diagram) can be
    appended; exactly one has ``decides=True``.
    """

    knot: str
    inputs: dict
    answers: tuple[ModelAnswer, ...]
    notes: tuple[str, ...] = field(default_factory=tuple)

    @property
    def deciding(self) -> ModelAnswer:
        return next(a for a in self.answers if a.decides)

    @property
    def holds(self) -> bool:
        return self.deciding.holds

    @property
    def margin(self) -> float:
        return self.deciding.margin

    @property
    def decided_by(self) -> str:
        return self.deciding.model

    def with_answer(self, answer: ModelAnswer, *, decides: bool = False) -> HoldVerdict:
        """Return a copy with ``answer`` appended (and deciding, if ``decides``)."""
        from dataclasses import replace

        old = tuple(replace(a, decides=False) if decides else a for a in self.answers)
        return replace(self, answers=old + (replace(answer, decides=decides),))

    def to_dict(self) -> dict:
        """Strict JSON-ready dict (a non-finite number is null; ``margin_unbounded`` when
        the margin is +inf, self-locking)."""
        return _json.jsonable(
            {
                "knot": self.knot,
                "holds": bool(self.holds),
                "margin": self.margin,
                "margin_unbounded": bool(math.isinf(self.margin) and self.margin > 0),
                "decided_by": self.decided_by,
                "inputs": self.inputs,
                "answers": [a.to_dict() for a in self.answers],
                "notes": list(self.notes),
            }
        )


def _exp(x: float) -> float:
    """exp that saturates to inf instead of raising OverflowError."""
    return math.exp(x) if x < 700.0 else math.inf


def _capacity(ratio: float, free: float) -> float:
    """Largest load held: ratio * free end tension, 0 for a free end even if ratio is inf."""
    return 0.0 if free == 0 else ratio * free


def _margin(capacity: float, load: float) -> float:
    return math.inf if math.isinf(capacity) else capacity / load - 1.0


def _bisect_mu(holds_at, hi=20.0, iters=60) -> float:
    """Smallest mu in [0, hi] with holds_at(mu) True (monotone); inf if none."""
    if holds_at(0.0):
        return 0.0
    if not holds_at(hi):
        return math.inf
    lo = 0.0
    for _ in range(iters):
        mid = 0.5 * (lo + hi)
        if holds_at(mid):
            hi = mid
        else:
            lo = mid
    return hi


#: largest d/D for which the zero-thickness (ideal-rope) models are taken as valid
THIN_ROPE_LIMIT = 0.1
_THIN_ROPE_VALIDITY = (
    f"rope thin compared with the post (d/D <= {THIN_ROPE_LIMIT:g} taken as the limit)"
)

_COMMON_ASSUMPTIONS = (
    "rigid circular post, inextensible rope, Amontons-Coulomb friction",
    "static equilibrium at the onset of slip (no dynamics, no creep)",
)


def _capstan_answers(mu, theta, d, D, load, free):
    Dt = D / d
    me = float(mu_eff(mu, Dt))
    cap_thick = _capacity(_exp(me * theta), free)
    cap_ideal = _capacity(_exp(mu * theta), free)
    crit_thick = _bisect_mu(lambda m: load <= _capacity(_exp(float(mu_eff(m, Dt)) * theta), free))
    crit_ideal = math.log(load / free) / theta if free > 0 and theta > 0 else math.inf
    if free > 0 and load <= free:
        crit_ideal = 0.0
    thick = ModelAnswer(
        model="thick-capstan",
        holds=bool(load <= cap_thick),
        margin=_margin(cap_thick, load),
        capacity=cap_thick,
        critical_mu=crit_thick,
        decides=True,
        inside_validity=True,
        assumptions=_COMMON_ASSUMPTIONS
        + (
            f"finite-thickness capstan: T_high/T_low = exp(mu_eff theta), "
            f"mu_eff(mu={mu:g}, D/d={Dt:g}) = {me:.4f}",
            "friction at the contact radius, tension at the centreline radius R = (D+d)/2",
            "bending rigidity and lift-off regions neglected",
        ),
        validity=("any D/d > 0, mu >= 0; planar wrap without self-contact",),
        reference="clove-hitch paper (Extreme Mech. Lett. 2022) eq. (3); derivations/mu_eff.py",
        notes=(f"effective friction coefficient mu_eff = {me:.4f}",),
    )
    ideal = ModelAnswer(
        model="ideal-capstan",
        holds=bool(load <= cap_ideal),
        margin=_margin(cap_ideal, load),
        capacity=cap_ideal,
        critical_mu=crit_ideal,
        decides=False,
        inside_validity=bool(d / D <= THIN_ROPE_LIMIT),
        assumptions=_COMMON_ASSUMPTIONS
        + ("Euler-Eytelwein: zero-thickness rope, T_high/T_low = exp(mu theta)",),
        validity=(_THIN_ROPE_VALIDITY,),
        reference="Euler (1762), Eytelwein (1808); derivations/capstan_ode.py",
    )
    return thick, ideal


def _hitch_answers(g: HitchGeometry, mu, mrr, d, D, load, free):
    K = float(_ideal_ratio(g, mu, mrr))
    cap = _capacity(K, free)
    crit = float(
        hitch_critical_mu(g.name, high_tension=load, low_tension=free, mu_rr=None)
        if mrr == mu
        else hitch_critical_mu(g.name, high_tension=load, low_tension=free, mu_rr=mrr)
    )
    ideal = ModelAnswer(
        model="ideal-rope",
        holds=bool(load <= cap),
        margin=_margin(cap, load),
        capacity=cap,
        critical_mu=crit,
        decides=True,
        # half hitches wrap the standing part, of the rope's own diameter: never thin
        inside_validity=bool(d / D <= THIN_ROPE_LIMIT and g.half_hitches == 0),
        assumptions=_COMMON_ASSUMPTIONS
        + (
            "zero-thickness, perfectly flexible rope: crossings carry no point force",
            f"{g.description}: post wrap {g.post_wrap / math.pi:g} pi, "
            f"wrap on the standing part {g.rope_wrap / math.pi:g} pi",
            f"holds iff T_high <= K T_low with K = exp(mu*{g.post_wrap:.4g} + "
            f"mu_rr*{g.rope_wrap:.4g}) = {K:.4g}",
        ),
        validity=(_THIN_ROPE_VALIDITY,)
        + (
            ("not for half hitches: they wrap the standing part, whose diameter is the rope's",)
            if g.half_hitches
            else ()
        ),
        reference=(
            "Bayman, Am. J. Phys. 45 (1977) 185; Maddocks & Keller, SIAM J. Appl. Math. 47 "
            "(1987) 1185 (as summarised in the clove-hitch paper, Sec. 8); derivations/hitches.py"
        ),
        notes=_free_end_notes(g, free),
    )
    if not g.thick_nip:
        return (ideal,)
    Kt = float(thick_hitch_ratio(g.name, mu, mrr, rod_diameter=d, post_diameter=D))
    lock = float(thick_hitch_lock_parameter(g.name, mu, mrr, rod_diameter=d, post_diameter=D))
    cap_t = math.inf if math.isinf(Kt) else _capacity(Kt, free)
    tie = mrr == mu

    def holds_thick(m):
        k = float(thick_hitch_ratio(g.name, m, m if tie else mrr, rod_diameter=d, post_diameter=D))
        return math.isinf(k) or load <= k * free

    thick = ModelAnswer(
        model="thick-nip",
        holds=bool(load <= cap_t),
        margin=_margin(cap_t, load),
        capacity=cap_t,
        critical_mu=_bisect_mu(holds_thick),
        decides=False,
        inside_validity=True,
        assumptions=_COMMON_ASSUMPTIONS
        + (
            "rigid rod of diameter d; wraps use mu_eff(mu, D/d) (and mu_eff(mu_rr, 1) on the "
            "standing part)",
            "a rider lifted over a crossing strand presses it with N = n T_rider "
            "(perpendicular crossing); the pinched strand grips on both faces",
            f"self-locking parameter {lock:.3g} (locks at >= 1: any load holds)",
        ),
        validity=(
            "derived in this package (not from the papers); load-independent, whereas the "
            "clove-hitch paper's experiments (Fig. 4) show slip above a critical load "
            "depending on d/2R",
        ),
        reference="derivations/hitches.py (Bayman's wrap-over mechanism with finite thickness)",
    )
    return ideal, thick


def _free_end_notes(g: HitchGeometry, free) -> tuple:
    """What the ideal-rope theory says of this hitch's free-end case (its registry record)."""
    note = knots.get(g.name).free_end_note
    return (note,) if free == 0 and note else ()


def __getattr__(name: str):
    """``COW_FREE_LEG_STATEMENT``: the ideal-rope statement for a cow hitch with one leg free,
    and what practice says (its registry record's ``free_end_note``)."""
    if name == "COW_FREE_LEG_STATEMENT":
        return knots.get("cow-hitch").free_end_note
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def hold_verdict(
    knot,
    *,
    rod_diameter,
    post_diameter,
    mu,
    load,
    free_end_load=0.0,
    mu_rr=None,
    wrap_angle=None,
) -> HoldVerdict:
    """Does a rod tied to a post hold a load? Every model's answer and the verdict.

    Parameters
    ----------
    knot : str
        ``capstan`` or one of :data:`KNOTS` (``clove-hitch``, ``two-half-hitches``,
        ``round-turn``, ``round-turn-two-half-hitches``, ``cow-hitch``).
    rod_diameter, post_diameter : float
        d, D [m], > 0.
    mu : float
        Rod-post friction coefficient [-], >= 0.
    load : float
        Tension on the loaded end, :math:`T_\\mathrm{high}` [N], > 0.
    free_end_load : float
        Tension on the other end, :math:`T_\\mathrm{low}` [N], 0 <= free_end_load <= load.
    mu_rr : float, optional
        Rod-rod friction coefficient [-] (default: ``mu``).
    wrap_angle : float, optional
        Wrap angle [rad], > 0; required for ``capstan``, refused for hitches.

    Returns
    -------
    HoldVerdict
        ``holds``, ``margin``, ``decided_by`` and ``answers``. For ``capstan`` the
        finite-thickness capstan decides and the ideal capstan is reported; for
        hitches the ideal-rope theory (the reference theory of the papers) decides and
        the thick-nip model is reported (not for the cow hitch: not derived), each with
        ``inside_validity``.

    Notes
    -----
    Closed forms only, each model's answer. The verdict of knotmech, which lets no
    model outside its validity decide and adds the DER phase diagram, materials and
    warnings, is :func:`knotmech.hold` (``knotmech.hold_verdict`` is its deprecated
    alias).
    """
    key = str(knot).strip().lower().replace("_", "-").replace(" ", "-")
    d = check_positive("rod_diameter", rod_diameter, scalar=True)
    D = check_positive("post_diameter", post_diameter, scalar=True)
    mu = check_nonnegative("mu", mu, scalar=True)
    load = check_positive("load", load, scalar=True)
    free = check_nonnegative("free_end_load", free_end_load, scalar=True)
    if free > load:
        raise InputError(
            "free_end_load must be <= load (the load is the larger tension), "
            f"got {free:g} > {load:g}"
        )
    mrr = mu if mu_rr is None else check_nonnegative("mu_rr", mu_rr, scalar=True)
    inputs = {
        "rod_diameter": d,
        "post_diameter": D,
        "mu": mu,
        "mu_rr": mrr,
        "load": load,
        "free_end_load": free,
    }
    notes: list[str] = []
    if key == "capstan":
        if wrap_angle is None:
            raise InputError("wrap_angle is required for capstan (e.g. 360deg)")
        theta = check_positive("wrap_angle", wrap_angle, scalar=True)
        inputs["wrap_angle"] = theta
        answers = _capstan_answers(mu, theta, d, D, load, free)
        if free == 0:
            notes.append("a capstan with a free end (T_low = 0) holds no load")
    else:
        if wrap_angle is not None:
            raise InputError(f"wrap_angle applies to capstan only, not to {knot!r}")
        g = _geometry(key)
        answers = _hitch_answers(g, mu, mrr, d, D, load, free)
        if free == 0 and g.name == "clove-hitch":
            notes.append(
                "the clove-hitch paper (Sec. 8, Fig. 4) finds experimentally that a clove "
                "hitch with a free end holds below a critical load depending on d/2R, "
                "contradicting the ideal-rope prediction"
            )
    return HoldVerdict(knot=key, inputs=inputs, answers=tuple(answers), notes=tuple(notes))
