"""The mismatch engine judged on fresh recordings of two generators kept apart (issue 26).

Every recording is new (seeds no earlier run used) and comes from one of the two
generators of :mod:`validation.effect_recovery`, which share no code with
:mod:`knotmech.diagnose.synth` and differ from each other in method:

``tune`` (generator A: the one an engine change may be tried on)
    200 rows on a uniform grid, noise from PCG64, constant sd (0.5 % of the largest
    mean), the catalogue's own effect shapes.
``heldout`` (generator B: only run to judge; never tune on it)
    150-260 rows on a jittered grid, noise from SFC64 and ``scipy.signal.lfilter``,
    heteroscedastic sd (0.3 % x (0.6 + 0.4 |f|/max|f|)), other shapes of the same
    physics (linear static fall-off, softplus flattening onset, tanh-edged nips).

To their white and AR(1) (rho 0.9) noise this campaign adds, for the nulls, three
noises written here, again by a different code path per generator:

=========== ======================================= ========================================
noise        tune                                    heldout
=========== ======================================= ========================================
AR(2)        recursion, phi = (1.0, -0.5)            ``lfilter``, phi = (0.7, 0.15)
1/f          FFT-shaped spectrum, amplitude f^-1/2   sum of 8 AR(1) octaves, rho_j = 1 - 2^-j
outliers     white + 2 % of rows at +-10 sd          white + 3 % of rows at +-U(8, 15) sd
=========== ======================================= ========================================

Scores (``found``, ``flagged``, ``unexplained``), each with its Wilson 95 % interval
(:func:`knotmech.diagnose.stats.wilson_interval`):

- a catalogue effect of 3-10 sd is *found* when the verdict names it **and** the
  report's evidence for it shows a held-out improvement (:func:`heldout_shown`: the raw
  held-out RMS, the whitened one-step-ahead held-out RMS or the held-out prior's |z|
  falls); every accepted effect of every recording is also counted as a *claim*, and a
  claim without such evidence is a failure of its own;
- a null is *flagged* when the verdict is not ``none`` (named effect, ``unexplained``
  or ``undetermined``: all three count), per noise kind; target <= 5 %; the nulls are
  drawn twice, at the generator's own row count and at 50 rows (the same generators,
  shortened as the 50-row shapes are: ``n=50`` keeps the seed's other draws), and the
  50-row ones are reported apart (``flagged_50rows``), so a rule acting on short
  recordings shows its null cost where it acts;
- an out-of-catalogue shape of 6 or 10 sd is caught when the verdict is
  ``unexplained``, at the generator's own row count and at 50 rows; target >= 75 %.

Results are cached one line per recording (``<out>/diagnose_campaign_cache.jsonl``),
so a rerun only diagnoses recordings it has not seen (``--fresh`` starts over).

    python -m validation.diagnose_campaign [--full] [--out DIR] [--workers 2] [--fresh]
        [--figure docs/img/diagnose_campaign.png] [--cached-only]
        [--only effects|nulls|shapes] [--generator tune|heldout|both] [--seed0 N]
"""

from __future__ import annotations

import argparse
import json
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
from scipy.signal import lfilter
from scipy.stats import binomtest

from knotmech.diagnose.engine import diagnose
from knotmech.diagnose.stats import wilson_interval

from . import effect_recovery as gen
from ._common import finish, output_dir, save_figure, to_jsonable

NAME = "diagnose_campaign"
#: one sentence for the validation page: what this case checks, and against what
SUMMARY = (
    "knotmech diagnose's verdicts against the effects planted in fresh recordings of a "
    "tune and a held-out generator: effects found with a held-out improvement (target >= "
    "90 %), nulls flagged under five noises (<= 5 %), out-of-catalogue shapes unexplained "
    "(>= 75 %), each rate with its Wilson 95 % interval."
)

NULL_NOISES = ("white", "ar1", "ar2", "pink", "outliers")
#: targets of issue 26
TARGETS = {"found": 0.90, "flagged": 0.05, "unexplained": 0.75}
#: first seed of each generator in this campaign (effect_recovery used tune 0-5167 and
#: heldout 50000-55026 and 60000-70119)
SEED0 = {"tune": 7000, "heldout": 90_000}

SETTINGS = {
    True: {  # quick: the held-out generator only, a few recordings (< 30 s)
        "generators": ("heldout",),
        "effect_sizes": (6.0,),
        "effect_noises": ("white",),
        "effects": (
            ("capstan_pull", "static_friction"),
            ("pinch", "adhesion"),
            ("tension_profile", "self_contact_nip"),
        ),
        "reps": 1,
        "null_reps": 1,
        "null_rows": (50,),
        "ooc_sizes": (10.0,),
        "ooc_rows": (50,),
        "ooc_reps": 1,
    },
    False: {
        "generators": ("heldout", "tune"),
        "effect_sizes": (3.0, 6.0, 10.0),
        "effect_noises": ("white", "ar1"),
        "effects": tuple((k, e) for k, effs in gen.EFFECTS.items() for e in effs),
        "reps": 1,
        "null_reps": 4,
        "null_rows": (50,),
        "ooc_sizes": (6.0, 10.0),
        "ooc_rows": (None, 50),
        "ooc_reps": 2,
    },
}


# --------------------------------------------------------------------------- noise
def _ar2_unit(phi, w):
    """Stationary AR(2) ``e_t = phi1 e_(t-1) + phi2 e_(t-2) + w_t``, unit marginal sd
    (Box & Jenkins: var = (1 - phi2) / ((1 + phi2)((1 - phi2)^2 - phi1^2)))."""
    p1, p2 = phi
    var = (1.0 - p2) / ((1.0 + p2) * ((1.0 - p2) ** 2 - p1**2))
    return lfilter([1.0], [1.0, -p1, -p2], w) / np.sqrt(var)


def _unit_noise(generator: str, noise: str, n: int, seed: int) -> np.ndarray:
    """Unit-sd noise of one kind, drawn by ``generator``'s own code (module table)."""
    if noise in ("white", "ar1", "outliers"):
        return gen._Noise(generator, seed).unit(n, gen.RHO if noise == "ar1" else 0.0)
    burn = 300
    if generator == "tune":
        rng = np.random.default_rng(seed)
        if noise == "ar2":
            e = np.zeros(n + burn)
            w = rng.standard_normal(n + burn)
            for i in range(2, n + burn):
                e[i] = 1.0 * e[i - 1] - 0.5 * e[i - 2] + w[i]
            return e[burn:] / np.sqrt(1.5 / (0.5 * (2.25 - 1.0)))
        f = np.fft.rfftfreq(n)
        amp = np.zeros_like(f)
        amp[1:] = f[1:] ** -0.5
        z = np.fft.irfft(amp * (rng.standard_normal(f.size) + 1j * rng.standard_normal(f.size)), n)
        return (z - z.mean()) / z.std()
    rng = np.random.Generator(np.random.SFC64(seed))
    if noise == "ar2":
        return _ar2_unit((0.7, 0.15), rng.normal(0.0, 1.0, n + burn))[burn:]
    out = np.zeros(n)
    for j in range(1, 9):  # octaves of AR(1): a 1/f spectrum between their corners
        rho = 1.0 - 2.0**-j
        w = rng.normal(0.0, 1.0, n)
        w[0] /= np.sqrt(1.0 - rho**2)  # a stationary start
        out += lfilter([1.0], [1.0, -rho], w) * np.sqrt(1.0 - rho**2)
    return out / np.sqrt(8.0)


#: the tune generator's outliers: share of the rows, smallest and largest size [noise sd]
TUNE_OUTLIERS = (0.02, 10.0, 10.0)


def _outliers(generator: str, n: int, seed: int, tune=TUNE_OUTLIERS) -> np.ndarray:
    """Displacements of the ``outliers`` noise in noise sd (zero on most rows).

    ``tune``: (share of rows, smallest, largest size [sd]) of the tune generator's
    outliers, sizes uniform between the two (default 2 % at 10 sd; (0.03, 8, 15) gives
    the held-out generator's share and sizes by the tune generator's own code).
    """
    out = np.zeros(n)
    if generator == "tune":
        share, lo, hi = tune
        rng = np.random.default_rng([seed, 3])
        k = max(1, round(share * n))
        # the signs are drawn before the rows (the order of the original one-line draw)
        sign = rng.choice([-1.0, 1.0], k)
        rows = rng.choice(n, k, replace=False)
        size = lo if hi == lo else rng.uniform(lo, hi, k)
        out[rows] = size * sign
    else:
        rng = np.random.Generator(np.random.SFC64([seed, 3]))
        k = max(1, round(0.03 * n))
        out[rng.choice(n, k, replace=False)] = rng.uniform(8.0, 15.0, k) * rng.choice(
            [-1.0, 1.0], k
        )
    return out


def make(generator, kind, effect, size, noise, seed, n=None, tune_outliers=TUNE_OUTLIERS):
    """One recording of the campaign and its truth.

    White and AR(1) noise are :func:`validation.effect_recovery.make`'s own (the same
    recording for the same seed); AR(2), 1/f and outliers are drawn here
    (``tune_outliers``: see :func:`_outliers`).
    """
    if noise in ("white", "ar1"):
        return gen.make(generator, kind, effect, size, noise, seed, n)
    meta, x, mean, trial, speed, truth, sd = gen.make_mean(generator, kind, effect, size, seed, n)
    z = _unit_noise(generator, noise, x.size, seed + 1)
    if noise == "outliers":
        z = z + _outliers(generator, x.size, seed + 1, tune_outliers)
    rec = gen.as_recording(kind, meta, x, mean + sd * z, trial, speed)
    truth.update(effect=effect or "none", size=size, noise=noise, n=int(x.size))
    truth["sd_median"] = float(np.median(sd))
    return rec, truth


# --------------------------------------------------------------------------- cases
def _effect_cases(g, s, seed):
    out = []
    for kind, eff in s["effects"]:
        for noise in s["effect_noises"]:
            for size in s["effect_sizes"]:
                out += [(g, kind, eff, size, noise, None, seed + i) for i in range(s["reps"])]
                seed += s["reps"]
    return out


def _null_cases(g, s, seed, quick, rows=None):
    """Nulls of every noise kind (``rows`` None: the generator's own row count)."""
    out = []
    kinds = tuple(gen.EFFECTS)
    for i, noise in enumerate(NULL_NOISES):
        for kind in (kinds[i % len(kinds)],) if quick else kinds:  # quick: kinds in turn
            out += [(g, kind, None, 0.0, noise, rows, seed + j) for j in range(s["null_reps"])]
            seed += s["null_reps"]
    return out


def _short_null_cases(g, s, seed, quick):
    """The nulls again at each of ``null_rows`` (50): the cell where the out-of-catalogue
    shapes' 50-row rules act."""
    out = []
    for rows in s["null_rows"]:
        out += _null_cases(g, s, seed + len(out), quick, rows)
    return out


def _ooc_cases(g, s, seed):
    out = []
    for kind in gen.EFFECTS:
        for rows in s["ooc_rows"]:
            for size in s["ooc_sizes"]:
                out += [
                    (g, kind, "out_of_catalogue", size, "white", rows, seed + i)
                    for i in range(s["ooc_reps"])
                ]
                seed += s["ooc_reps"]
    return out


#: the parts of a run ``--only`` may restrict it to
PARTS = ("effects", "nulls", "shapes")


def cases(quick: bool, generators=None, only=None, seed0=None) -> list:
    """(generator, kind, effect, size, noise, rows, seed) of every recording of the run
    (``rows`` None: the generator's own count); seeds consecutive per generator, in the
    order effects, nulls, shapes, 50-row nulls (added last: the earlier parts keep
    their seeds).

    ``only``: one of :data:`PARTS` (the other parts' seeds are still counted, so a
    part's recordings are the same with and without it). ``seed0``: first seed of
    every generator instead of :data:`SEED0` (a fresh held-out set; the quick offset
    900 is not added).
    """
    s = SETTINGS[bool(quick)]
    out = []
    for g in generators or s["generators"]:
        seed = (SEED0[g] + (900 if quick else 0)) if seed0 is None else int(seed0)
        eff = _effect_cases(g, s, seed)
        nul = _null_cases(g, s, seed + len(eff), bool(quick))
        ooc = _ooc_cases(g, s, seed + len(eff) + len(nul))
        short = _short_null_cases(g, s, seed + len(eff) + len(nul) + len(ooc), bool(quick))
        parts = {"effects": eff, "nulls": nul + short, "shapes": ooc}
        out += [c for k in PARTS if only in (None, k) for c in parts[k]]
    return out


def heldout_shown(evidence: dict) -> bool:
    """True when an accepted effect's evidence shows the fit improve on held-out data.

    Any of: the raw held-out RMS falls (``heldout_rms_before`` -> ``heldout_rms``), the
    whitened one-step-ahead held-out RMS falls (``heldout_innovation_rms`` [before,
    after]), the held-out prior's |z| falls (``heldout_prior_z`` [before, after]).
    Evidence without any of these shows nothing (False).
    """
    falls = []
    before, after = evidence.get("heldout_rms_before"), evidence.get("heldout_rms")
    if before is not None and after is not None:
        falls.append(after < before)
    inn = evidence.get("heldout_innovation_rms")
    if inn:
        falls.append(inn[1] < inn[0])
    z = evidence.get("heldout_prior_z")
    if z:
        falls.append(abs(z[1]) < abs(z[0]))
    return any(falls)


def run_one(case) -> dict:
    """Diagnose one recording of the campaign; its truth, verdict and claims."""
    g, kind, eff, size, noise, rows, seed = case
    rec, truth = make(g, kind, eff, size, noise, seed, rows)
    t0 = time.process_time()
    rep = diagnose(rec, seed=seed % 100_000)
    claims = [
        {"name": e["name"], "heldout_shown": heldout_shown(e["evidence"])} for e in rep.effects
    ]
    shown = any(c["heldout_shown"] for c in claims if c["name"] == truth["effect"])
    return {
        "case": list(case),
        "generator": g,
        "kind": kind,
        "effect": truth["effect"],
        "size": size,
        "noise": noise,
        "rows": int(rec.n),
        "seed": seed,
        "verdict": rep.verdict,
        "claims": claims,
        "found": bool(rep.verdict == truth["effect"] and shown),
        "cpu_seconds": round(time.process_time() - t0, 2),
    }


# --------------------------------------------------------------------------- cache
def _load_cache(path: Path) -> dict:
    if not path.exists():
        return {}
    out = {}
    for line in path.read_text().splitlines():
        if line.strip():
            r = json.loads(line)
            out[tuple(r["case"])] = r
    return out


def run_cases(
    todo: list, cache_path: Path, workers: int = 1, fresh: bool = False, cached_only=False
) -> list:
    """Results of ``todo``, from the cache where there, diagnosed (and cached) otherwise
    (``cached_only``: only those in the cache, none diagnosed)."""
    if fresh and cache_path.exists():
        cache_path.unlink()
    done = _load_cache(cache_path)
    key = [tuple(json.loads(json.dumps(list(c)))) for c in todo]
    if cached_only:
        return [done[k] for k in key if k in done]
    new = [c for c, k in zip(todo, key, strict=True) if k not in done]
    with cache_path.open("a") as fh:

        def keep(r):
            done[tuple(r["case"])] = r
            fh.write(json.dumps(to_jsonable(r)) + "\n")
            fh.flush()

        if workers > 1 and len(new) > 1:
            with ProcessPoolExecutor(workers) as pool:
                for r in pool.map(run_one, new, chunksize=1):
                    keep(r)
        else:
            for c in new:
                keep(run_one(c))
    return [done[k] for k in key]


# --------------------------------------------------------------------------- summary
def _rate(k: int, n: int) -> dict:
    lo, hi = wilson_interval(k, n) if n else (0.0, 1.0)
    return {"k": int(k), "n": int(n), "rate": (k / n) if n else None, "wilson95": [lo, hi]}


def _group(rs, key, hit) -> dict:
    out = {}
    for r in rs:
        out.setdefault(key(r), []).append(r)
    return {k: _rate(sum(hit(r) for r in v), len(v)) for k, v in sorted(out.items())}


def _effects_summary(eff: list) -> dict:
    return {
        "found": _rate(sum(r["found"] for r in eff), len(eff)),
        "found_by_size": dict(
            sorted(
                _group(eff, lambda r: f"{r['size']:g} sd", lambda r: r["found"]).items(),
                key=lambda kv: float(kv[0].split()[0]),
            )
        ),
        "found_by_noise": _group(eff, lambda r: r["noise"], lambda r: r["found"]),
        "found_by_effect": _group(
            eff, lambda r: f"{r['kind']}/{r['effect']}", lambda r: r["found"]
        ),
        "misses": [
            f"{r['kind']}/{r['effect']} {r['size']:g} sd {r['noise']} seed {r['seed']}: "
            f"{r['verdict']}"
            for r in eff
            if not r["found"]
        ],
    }


def _is_short_null(r: dict) -> bool:
    """A null of the 50-row cell (its case asks for 50 rows)."""
    return r["effect"] == "none" and r["case"][5] == 50


def _nulls_summary(nul: list, tag: str = "") -> dict:
    """Flagged nulls, all and per noise; ``tag`` ends every key ("_50rows")."""
    flagged = [r for r in nul if r["verdict"] != "none"]
    return {
        f"flagged{tag}": _rate(len(flagged), len(nul)),
        # the flagged ones that claim structure (a named effect or unexplained), not
        # undetermined: 50 rows of AR(1) noise at rho 0.9 leave ~2.6 independent
        # stretches, too few to tell it from a smooth mismatch, so undetermined is due
        f"claimed{tag}": _rate(
            sum(r["verdict"] not in ("none", "undetermined") for r in nul), len(nul)
        ),
        f"flagged_by_noise{tag}": _group(
            nul, lambda r: r["noise"], lambda r: r["verdict"] != "none"
        ),
        f"null_verdicts{tag}": [
            f"{r['kind']} {r['noise']} {r['rows']} rows seed {r['seed']}: {r['verdict']}"
            for r in flagged
        ],
    }


def _ooc_summary(ooc: list) -> dict:
    def hit(r):
        return r["verdict"] == "unexplained"

    return {
        "unexplained": _rate(sum(hit(r) for r in ooc), len(ooc)),
        "unexplained_by_rows": _group(
            ooc, lambda r: "50 rows" if r["rows"] == 50 else "own rows", hit
        ),
        "unexplained_by_kind": _group(ooc, lambda r: r["kind"], hit),
        "ooc_verdicts": [
            f"{r['kind']} {r['size']:g} sd {r['rows']} rows seed {r['seed']}: {r['verdict']}"
            for r in ooc
            if not hit(r)
        ],
    }


def summarise_generator(rs: list) -> dict:
    """Rates of one generator's results (found, claims, flagged nulls, unexplained)."""
    claims = [(r, c) for r in rs for c in r["claims"]]
    return {
        **_effects_summary([r for r in rs if r["effect"] not in ("none", "out_of_catalogue")]),
        "claims": len(claims),
        "claims_without_heldout": [
            f"{r['kind']}/{r['effect']} seed {r['seed']}: {c['name']}"
            for r, c in claims
            if not c["heldout_shown"]
        ],
        **_nulls_summary([r for r in rs if r["effect"] == "none" and not _is_short_null(r)]),
        **_nulls_summary([r for r in rs if _is_short_null(r)], "_50rows"),
        **_ooc_summary([r for r in rs if r["effect"] == "out_of_catalogue"]),
        "cpu_seconds_median": float(np.median([r["cpu_seconds"] for r in rs])),
        "cpu_seconds_total": round(float(np.sum([r["cpu_seconds"] for r in rs])), 1),
    }


def _pct(v: dict) -> str:
    if not v["n"]:
        return "-"
    lo, hi = v["wilson95"]
    return f"{v['k']}/{v['n']} = {100 * v['rate']:.0f} % ({100 * lo:.0f}-{100 * hi:.0f} %)"


def markdown(summary: dict) -> str:
    """The campaign's table (rates with Wilson 95 % intervals), one column per generator."""
    gens = list(summary)
    rows = [("catalogue effects found, 3-10 sd (>= 90 %)", lambda s: s["found"])]
    first = summary[gens[0]]
    for k in first["found_by_size"]:
        rows.append((f"  found at {k}", lambda s, k=k: s["found_by_size"].get(k)))
    for k in first["found_by_noise"]:
        rows.append((f"  found, {k} noise", lambda s, k=k: s["found_by_noise"].get(k)))
    rows.append(("nulls flagged, all (<= 5 %)", lambda s: s["flagged"]))
    for k in first["flagged_by_noise"]:
        rows.append((f"  nulls flagged, {k}", lambda s, k=k: s["flagged_by_noise"].get(k)))
    rows.append(("nulls, 50 rows, flagged (<= 5 %)", lambda s: s["flagged_50rows"]))
    rows.append(
        ("  nulls, 50 rows, unexplained or named (not undetermined)", lambda s: s["claimed_50rows"])
    )
    for k in first["flagged_by_noise_50rows"]:
        rows.append((f"  nulls, 50 rows, {k}", lambda s, k=k: s["flagged_by_noise_50rows"].get(k)))
    rows.append(("out-of-catalogue unexplained, 6-10 sd (>= 75 %)", lambda s: s["unexplained"]))
    for k in first["unexplained_by_rows"]:
        rows.append((f"  unexplained, {k}", lambda s, k=k: s["unexplained_by_rows"].get(k)))
    lines = ["| rate (Wilson 95 %) | " + " | ".join(gens) + " |", "|---" * (len(gens) + 1) + "|"]
    for label, get in rows:
        cells = [_pct(get(summary[g])) if get(summary[g]) else "-" for g in gens]
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    claims = [f"{len(summary[g]['claims_without_heldout'])}/{summary[g]['claims']}" for g in gens]
    lines.append("| claims without a held-out improvement | " + " | ".join(claims) + " |")
    return "\n".join(lines) + "\n"


def plot(summary: dict):
    """Four panels: found by size, nulls flagged by noise (own rows, 50 rows),
    unexplained by rows."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(13.0, 3.4))
    panels = (
        ("found_by_size", "catalogue effects found", TARGETS["found"]),
        ("flagged_by_noise", "nulls flagged (not none)", TARGETS["flagged"]),
        ("flagged_by_noise_50rows", "nulls of 50 rows flagged", TARGETS["flagged"]),
        ("unexplained_by_rows", "out of catalogue: unexplained", TARGETS["unexplained"]),
    )
    for i, (key, title, target) in enumerate(panels):
        ax = fig.add_subplot(1, len(panels), i + 1)
        for j, (g, s) in enumerate(summary.items()):
            labels = list(s[key])
            rate = np.array([s[key][k]["rate"] for k in labels])
            ci = np.array([s[key][k]["wilson95"] for k in labels]).reshape(-1, 2)
            xs = np.arange(len(labels)) + (j - 0.5 * (len(summary) - 1)) * 0.25
            ax.errorbar(
                xs, rate, yerr=[rate - ci[:, 0], ci[:, 1] - rate], fmt="o", capsize=3, label=g
            )
            ax.set_xticks(np.arange(len(labels)), labels, fontsize=7)
        ax.axhline(target, color="k", ls="--", lw=0.8)
        ax.set_ylim(-0.03, 1.03)
        ax.set_title(title, fontsize=9)
        if i == 0:
            ax.set_ylabel("rate, Wilson 95 % interval")
            ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


def _checks(summary: dict, quick: bool) -> dict:
    """Full run: the targets on the point rates (the 50-row nulls per noise too). Quick
    run (a few recordings): not significantly off target (found and unexplained: Wilson
    upper bound at or above it; the own-row nulls: exact one-sided binomial test against
    5 % at the 5 % level; its five 50-row nulls are reported, not gated)."""
    checks = {}
    for g, s in summary.items():
        checks[f"{g}: every claimed effect shows a held-out improvement"] = not s[
            "claims_without_heldout"
        ]
        if quick:
            checks[f"{g}: found not below 90 %"] = s["found"]["wilson95"][1] >= TARGETS["found"]
            # the 50-row nulls are reported, not gated, in the quick run: one per noise,
            # and 50 rows of AR(1) or 1/f noise are often undetermined or unexplained
            # (issue26-campaign.md section 17); the full run gates them per noise
            f = s["flagged"]
            checks[f"{g}: nulls flagged not above 5 %"] = (
                binomtest(f["k"], f["n"], TARGETS["flagged"], alternative="greater").pvalue >= 0.05
            )
            u = s["unexplained"]
            checks[f"{g}: unexplained not below 75 %"] = u["wilson95"][1] >= TARGETS["unexplained"]
            continue
        checks[f"{g}: found >= 90 %"] = (s["found"]["rate"] or 0.0) >= TARGETS["found"]
        for noise, v in s["flagged_by_noise"].items():
            checks[f"{g}: {noise} nulls flagged <= 5 %"] = v["rate"] <= TARGETS["flagged"]
        for noise, v in s["flagged_by_noise_50rows"].items():
            checks[f"{g}: {noise} nulls, 50 rows, flagged <= 5 %"] = v["rate"] <= TARGETS["flagged"]
        checks[f"{g}: unexplained >= 75 %"] = (s["unexplained"]["rate"] or 0.0) >= TARGETS[
            "unexplained"
        ]
    return checks


def run(
    quick=True,
    out_dir=".",
    workers=1,
    fresh=False,
    generators=None,
    figure=None,
    cached_only=False,
    only=None,
    seed0=None,
) -> dict:
    """Run the campaign; write its JSON, markdown table and figure (also to ``figure``).
    ``cached_only``: summarise the recordings already in the cache, diagnose none (a
    partial run says how many of the run's recordings it holds: ``numbers.recordings``
    of ``numbers.planned``); ``only``, ``seed0``: see :func:`cases`."""
    todo = cases(bool(quick), generators, only, seed0)
    out = output_dir(out_dir)
    t0 = time.perf_counter()
    results = run_cases(todo, out / f"{NAME}_cache.jsonl", workers, fresh, cached_only)
    wall = time.perf_counter() - t0
    gens = dict.fromkeys(r["generator"] for r in results)
    summary = {g: summarise_generator([r for r in results if r["generator"] == g]) for g in gens}
    table = markdown(summary)
    (out / f"{NAME}.md").write_text(table)
    fig = plot(summary)
    png = save_figure(fig, out_dir, NAME)
    if figure:
        Path(figure).parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(figure, dpi=120)
    numbers = {
        "recordings": len(results),
        "planned": len(todo),
        "wall_seconds": round(wall, 1),
        **summary,
    }
    checks = _checks(summary, bool(quick))
    checks["every planned recording diagnosed"] = len(results) == len(todo)
    return finish(
        NAME,
        out_dir=out_dir,
        checks=checks,
        numbers=numbers,
        figures=[png],
        quick=bool(quick),
        notes=[
            "generators of validation/effect_recovery.py (not synth.py) plus AR(2), 1/f and "
            "outlier noises written here; 'tune' may be tried changes on, 'heldout' only judges",
            "found = verdict names the planted effect and its evidence shows a held-out "
            "improvement; flagged = verdict not none",
        ],
        extra={"table_markdown": table},
    )


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--full", action="store_true")
    p.add_argument("--out", default="validation-out")
    p.add_argument("--generator", choices=("tune", "heldout", "both"), default=None)
    p.add_argument("--workers", type=int, default=1)
    p.add_argument("--fresh", action="store_true", help="ignore the cached results")
    p.add_argument("--figure", default=None, help="also save the figure here")
    p.add_argument("--cached-only", action="store_true", help="summarise the cache only")
    p.add_argument("--only", choices=PARTS, default=None, help="one part of the run")
    p.add_argument("--seed0", type=int, default=None, help="first seed (a fresh set)")
    a = p.parse_args(argv)
    gens = None if a.generator in (None, "both") else (a.generator,)
    res = run(not a.full, a.out, a.workers, a.fresh, gens, a.figure, a.cached_only, a.only, a.seed0)
    print(res["table_markdown"])
    print(json.dumps(res["checks"], indent=1))
    print(f"{NAME}: {res['verdict']}")
    return 0 if res["verdict"] == "pass" else 1


if __name__ == "__main__":
    raise SystemExit(main())
