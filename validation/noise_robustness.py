"""Power curve and null sizes of ``knotmech diagnose`` on recordings of its own (issue 14).

The generator here is written independently of :mod:`knotmech.diagnose.synth`: its
baselines are the closed forms of ``shared/spec/recordings.md`` section 2 written out
again (pinch ``F_t = 2 mu F_n``; tension profile ``T_high exp(-mu s / R)``; capstan pull
``min(T_low + k u, T_low exp(mu theta))``), its mismatches are shapes outside the
effect catalogue, and its noises are those of real sensors:

- mismatches (amplitude ``size`` noise sd at the largest point): ``ripple`` (a sine of
  1.5-3 periods over the range, random phase), ``tanh_step`` (a smooth step of width 2 %
  of the range at 25-75 % of it, up or down), ``stribeck`` (an excess decaying as
  ``exp(-x / (0.15 range))`` from the start: Stribeck-shaped friction that is high at
  low load or displacement), ``bump`` (a Gaussian bump of sd 4 % of the range at
  20-80 % of it, up or down: a local snag), ``kink`` (a change of slope at 30-70 % of
  the range, the excess growing linearly after it: a second regime);
- noises (sd ``sd`` of the kind): ``white``; ``ar1`` (rho 0.8); ``ar2`` (phi 1.2, -0.4);
  ``pink`` (1/f power spectrum, shaped by FFT); ``hetero`` (sd growing 4-fold with the
  signal); ``quantised`` (white, rounded to steps of 1.5 sd); ``outliers`` (white, 2 %
  of the rows displaced by 10 sd).

Outputs: the found-mismatch rate (verdict other than ``none``) against size, per kind
and shape, under white noise (the power curve), and for two shapes under AR(2) and
1/f noise (coloured power); the null verdicts per noise kind (false positives = an
effect or ``unexplained``; ``undetermined`` counted apart) with Wilson 95 % intervals;
the outliers planted in the ``outliers`` nulls and how many were reported; a sweep of
row counts (8 rows to 1e5) with a 30-sd ripple and white and AR(2) nulls; and
``concealed``: every mismatch above 10 sd that came out ``none`` (there must be none).

``python -m validation.noise_robustness [--full] [--out DIR]``. Quick: pinch only,
one seed, 40 rows (17 recordings); full: see :data:`SETTINGS` (three kinds, five shapes,
sizes 1-100 sd under white noise, ripple and bump under AR(2) and 1/f noise, nulls of
seven noises, 120 rows; the row sweep 8-1e5 rows).
"""

from __future__ import annotations

import json
import os
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from knotmech.diagnose import diagnose
from knotmech.diagnose.recording import recording_from_arrays
from knotmech.diagnose.stats import wilson_interval
from knotmech.materials import VPS32_YOUNGS_MODULUS

from ._common import finish, output_dir, save_figure, to_jsonable

SUMMARY = (
    "Verdicts of knotmech diagnose on recordings from a generator of its own (ripples, tanh "
    "steps and Stribeck decays; white, AR(1), AR(2), pink, heteroscedastic, quantised noise "
    "and outliers) against the truth: the found rate rises with the size, no mismatch above "
    "10 sd is called none, and nulls stay at the nominal size."
)


NAME = "noise_robustness"
KINDS = ("pinch", "tension_profile", "capstan_pull")
SHAPES = ("ripple", "tanh_step", "stribeck", "bump", "kink")
NOISES = ("white", "ar1", "ar2", "pink", "hetero", "quantised", "outliers")
SIZES = (1.0, 3.0, 10.0, 30.0, 100.0)
SETTINGS = {
    True: {
        "kinds": ("pinch",),
        "shapes": ("ripple", "tanh_step"),
        "seeds": 1,
        "null_seeds": 1,
        "n": 40,
    },
    False: {
        "kinds": KINDS,
        "shapes": SHAPES,
        "seeds": 3,
        "null_seeds": 20,
        "n": 120,
        # power under coloured noise: these shapes, these noises, these seeds
        "coloured_shapes": ("ripple", "bump"),
        "coloured_noises": ("ar2", "pink"),
        "coloured_seeds": 2,
        # row sweep: (rows, seeds) with a 30-sd ripple and white and AR(2) nulls
        "rows": ((8, 4), (20, 4), (1000, 2), (10_000, 1), (100_000, 1)),
        # a 30-sd ripple of 1e5 rows takes minutes of bootstrap on a shared core (the
        # large-recording speed is diagbig's): nulls only beyond this
        "ripple_rows_max": 10_000,
    },
}


def _baseline(kind: str, n: int):
    """Control variable, noiseless baseline, noise sd and metadata of one kind."""
    if kind == "pinch":
        x = np.linspace(0.2, 10.0, n)
        meta = {
            "rod_diameter_m": 0.004,
            "pinch_diameter_m": 0.008,
            "youngs_modulus_Pa": VPS32_YOUNGS_MODULUS,
        }
        return x, 2.0 * 0.3 * x, 0.01, meta
    if kind == "tension_profile":
        meta = {"T_high_N": 10.0, "rod_diameter_m": 0.004, "post_diameter_m": 0.03}
        r = 0.5 * (0.03 + 0.004)
        x = np.linspace(0.0, 0.2, n)
        return x, 10.0 * np.exp(-0.25 * x / r), 0.02, meta
    if kind == "capstan_pull":
        meta = {
            "wrap_angle_rad": 2 * np.pi,
            "T_low_N": 1.0,
            "rod_diameter_m": 0.004,
            "post_diameter_m": 0.03,
            "youngs_modulus_Pa": VPS32_YOUNGS_MODULUS,
        }
        x = np.linspace(0.0, 0.05, n)
        plateau = np.exp(0.3 * 2 * np.pi)
        k = (plateau - 1.0) / 0.01
        return x, np.minimum(1.0 + k * x, plateau), 0.03, meta
    raise ValueError(kind)


def _shape(shape: str, t: np.ndarray, rng) -> np.ndarray:
    """A mismatch of unit largest magnitude over t in [0, 1]."""
    if shape == "ripple":
        g = np.sin(2 * np.pi * rng.uniform(1.5, 3.0) * t + rng.uniform(0, 2 * np.pi))
    elif shape == "tanh_step":
        g = 0.5 * (1 + np.tanh((t - rng.uniform(0.25, 0.75)) / 0.02)) * rng.choice([-1.0, 1.0])
    elif shape == "stribeck":
        g = np.exp(-t / 0.15)
    elif shape == "bump":
        g = np.exp(-0.5 * ((t - rng.uniform(0.2, 0.8)) / 0.04) ** 2) * rng.choice([-1.0, 1.0])
    elif shape == "kink":
        g = np.maximum(t - rng.uniform(0.3, 0.7), 0.0) * rng.choice([-1.0, 1.0])
    else:
        raise ValueError(shape)
    return g / np.max(np.abs(g))


def _noise(kind: str, n: int, sd: float, signal: np.ndarray, rng) -> np.ndarray:
    """One draw of a noise kind with marginal sd ``sd`` (before outliers/quantising)."""
    e = rng.standard_normal(n + 200)
    if kind in ("white", "quantised", "outliers"):
        z = e[:n]
    elif kind == "ar1":
        z = np.empty(n + 200)
        z[0] = e[0]
        for i in range(1, n + 200):
            z[i] = 0.8 * z[i - 1] + np.sqrt(1 - 0.64) * e[i]
        z = z[200:]
    elif kind == "ar2":
        z = np.zeros(n + 200)
        for i in range(2, n + 200):
            z[i] = 1.2 * z[i - 1] - 0.4 * z[i - 2] + e[i]
        z = z[200:]
        z = z / np.std(z)
    elif kind == "pink":
        f = np.fft.rfftfreq(n)
        amp = np.zeros_like(f)
        amp[1:] = 1.0 / np.sqrt(f[1:])
        spec = amp * (rng.standard_normal(f.size) + 1j * rng.standard_normal(f.size))
        z = np.fft.irfft(spec, n)
        z = (z - np.mean(z)) / np.std(z)
    elif kind == "hetero":
        level = np.abs(signal) / np.max(np.abs(signal))
        z = e[:n] * (0.4 + 1.6 * level) / 1.0
    else:
        raise ValueError(kind)
    out = sd * z
    if kind == "quantised":
        step = 1.5 * sd
        out = np.round((signal + out) / step) * step - signal
    if kind == "outliers":
        out[outlier_rows(n, rng)] += 10.0 * sd * rng.choice([-1.0, 1.0], max(1, round(0.02 * n)))
    return out


def outlier_rows(n: int, rng) -> np.ndarray:
    """The 2 % of ``n`` rows (at least one) the ``outliers`` noise displaces."""
    return rng.choice(n, size=max(1, int(round(0.02 * n))), replace=False)


def make(kind, shape, size, noise, seed, n):
    """One recording of this generator and its truth (``shape`` None: a null)."""
    rng = np.random.default_rng([seed, KINDS.index(kind), NOISES.index(noise)])
    x, f, sd, meta = _baseline(kind, n)
    t = (x - x[0]) / (x[-1] - x[0])
    mis = np.zeros(n) if shape is None else size * sd * _shape(shape, t, rng)
    state = rng.bit_generator.state
    e = _noise(noise, n, sd, f, rng)
    planted = []
    if noise == "outliers":
        # replay the draw up to the rows the noise displaced (same generator state)
        rng2 = np.random.default_rng()
        rng2.bit_generator.state = state
        rng2.standard_normal(n + 200)
        planted = sorted(int(i) for i in outlier_rows(n, rng2))
    y = f + mis + e
    rec = recording_from_arrays(kind, x, y, metadata=meta)
    return rec, {"sd": sd, "mismatch_sd": float(np.max(np.abs(mis)) / sd), "planted": planted}


def run_one(case) -> dict:
    kind, shape, size, noise, seed, n = case
    rec, truth = make(kind, shape, size, noise, seed, n)
    t0 = time.perf_counter()
    rep = diagnose(rec, seed=seed)
    out = rep.to_dict().get("outliers")
    found = set(out["rows"]) if out else set()
    return {
        "kind": kind,
        "shape": shape or "none",
        "size": size,
        "noise": noise,
        "seed": seed,
        "n": n,
        "verdict": rep.verdict,
        "final_rms_sd": float(rep.final["rms"] / truth["sd"]),
        "outliers": len(found),
        "outliers_planted": len(truth["planted"]),
        "outliers_planted_found": len(found & set(truth["planted"])),
        "leftover_warning": "leftover" in rep.details,
        "seconds": time.perf_counter() - t0,
    }


def cases(quick: bool):
    s = SETTINGS[bool(quick)]
    todo = []
    for kind in s["kinds"]:
        for shape in s["shapes"]:
            for size in SIZES:
                for seed in range(s["seeds"]):
                    todo.append((kind, shape, size, "white", seed, s["n"]))
        for noise in NOISES:
            for seed in range(s["null_seeds"]):
                todo.append((kind, None, 0.0, noise, 100 + seed, s["n"]))
        for shape in s.get("coloured_shapes", ()):
            for noise in s["coloured_noises"]:
                for size in SIZES:
                    for seed in range(s["coloured_seeds"]):
                        todo.append((kind, shape, size, noise, seed, s["n"]))
        for rows, seeds in s.get("rows", ()):
            for seed in range(seeds):
                if rows <= s["ripple_rows_max"]:
                    todo.append((kind, "ripple", 30.0, "white", 200 + seed, rows))
                todo.append((kind, None, 0.0, "white", 300 + seed, rows))
                todo.append((kind, None, 0.0, "ar2", 300 + seed, rows))
    # the long recordings first (the pool's tail is then short ones)
    todo.sort(key=lambda c: -c[5])
    return todo


def _rate(k: int, n: int) -> dict:
    lo, hi = wilson_interval(k, n) if n else (0.0, 1.0)
    return {"k": k, "n": n, "rate": k / n if n else None, "ci95": [lo, hi]}


def summarise(results, n_rows=None):
    """Power curves, null sizes, outlier counts, row sweep, concealed mismatches."""
    n_rows = n_rows or max(
        (r["n"] for r in results), key=lambda m: sum(r["n"] == m for r in results)
    )
    main = [r for r in results if r["n"] == n_rows]
    power, counts = {}, {}
    for r in main:
        if r["shape"] == "none":
            continue
        key = f"{r['kind']}/{r['shape']}" + ("" if r["noise"] == "white" else f"/{r['noise']}")
        counts.setdefault(key, {}).setdefault(str(r["size"]), []).append(r["verdict"] != "none")
    for k, d in counts.items():
        items = sorted(d.items(), key=lambda kv: float(kv[0]))
        power[k] = {s: float(np.mean(v)) for s, v in items}
        counts[k] = {s: _rate(int(np.sum(v)), len(v)) for s, v in items}
    nulls = {}
    for noise in NOISES:
        rs = [r for r in main if r["shape"] == "none" and r["noise"] == noise]
        fp = sum(r["verdict"] not in ("none", "undetermined") for r in rs)
        und = sum(r["verdict"] == "undetermined" for r in rs)
        nulls[noise] = {
            **_rate(fp, len(rs)),
            "false_positives": fp,
            "undetermined": und,
            "undetermined_ci95": list(wilson_interval(und, len(rs))) if rs else [0.0, 1.0],
            "verdicts": {
                v: sum(r["verdict"] == v for r in rs) for v in sorted({r["verdict"] for r in rs})
            },
        }
    out_rs = [r for r in main if r["noise"] == "outliers"]
    planted = sum(r["outliers_planted"] for r in out_rs)
    outliers = {
        "recordings": len(out_rs),
        "planted": planted,
        "reported": _rate(sum(r["outliers_planted_found"] for r in out_rs), planted),
        "all_reported_recordings": sum(
            r["outliers_planted_found"] == r["outliers_planted"] for r in out_rs
        ),
        "reported_not_planted": sum(r["outliers"] - r["outliers_planted_found"] for r in out_rs),
        "false_rows_other_nulls": sum(
            r["outliers"] for r in main if r["shape"] == "none" and r["noise"] != "outliers"
        ),
    }
    sweep = {}
    for r in results:
        if r["n"] == n_rows:
            continue
        what = "ripple 30 sd" if r["shape"] != "none" else f"null {r['noise']}"
        sweep.setdefault(str(r["n"]), {}).setdefault(what, []).append(
            {"kind": r["kind"], "verdict": r["verdict"], "seconds": round(r["seconds"], 1)}
        )
    concealed = [
        r for r in results if r["shape"] != "none" and r["size"] > 10 and r["verdict"] == "none"
    ]
    return {
        "rows": n_rows,
        "power": power,
        "power_counts": counts,
        "nulls": nulls,
        "outliers": outliers,
        "row_sweep": sweep,
        "concealed_over_10sd": concealed,
    }


def _monotone(curve: dict, slack: float) -> bool:
    vals = list(curve.values())
    return all(b >= a - slack for a, b in zip(vals[:-1], vals[1:], strict=False))


def plot(summary):
    from matplotlib.figure import Figure

    kinds = sorted({k.split("/")[0] for k in summary["power"]})
    fig = Figure(figsize=(4.0 * max(len(kinds), 1), 3.8))
    for i, kind in enumerate(kinds):
        ax = fig.add_subplot(1, len(kinds), i + 1)
        for key, curve in summary["power"].items():
            if key.split("/")[0] != kind:
                continue
            label = "/".join(key.split("/")[1:])
            style = "o-" if label.count("/") == 0 else "s--"
            ax.plot([float(s) for s in curve], list(curve.values()), style, label=label, ms=4)
        ax.set_xscale("log")
        ax.set_xlabel("mismatch size [noise sd at its largest point]")
        if i == 0:
            ax.set_ylabel("found-mismatch rate (verdict not 'none')")
        ax.set_ylim(-0.05, 1.05)
        ax.legend(fontsize=6)
        ax.set_title(f"{kind} ({summary['rows']} rows)", fontsize=9)
    fig.suptitle("diagnose: power on out-of-catalogue shapes (solid: white noise)", fontsize=10)
    fig.tight_layout()
    return fig


def run(quick=True, out_dir=".", workers=None) -> dict:
    """Run the case; write ``noise_robustness.json`` and the power-curve figure."""
    todo = cases(bool(quick))
    workers = workers or (1 if quick else min(os.cpu_count() or 1, 2))
    t0 = time.perf_counter()
    if workers > 1:
        with ProcessPoolExecutor(workers) as pool:
            results = list(pool.map(run_one, todo, chunksize=2))
    else:
        results = [run_one(c) for c in todo]
    wall = time.perf_counter() - t0
    (output_dir(out_dir) / f"{NAME}_results.json").write_text(json.dumps(to_jsonable(results)))
    summary = summarise(results, SETTINGS[bool(quick)]["n"])
    png = save_figure(plot(summary), out_dir, "noise_robustness_power")
    n_seeds = SETTINGS[bool(quick)]["seeds"]
    slack = 1.0 / n_seeds if n_seeds > 1 else 0.0
    white_curves = {k: c for k, c in summary["power"].items() if k.count("/") == 1}
    checks = {
        "no mismatch above 10 sd is none": not summary["concealed_over_10sd"],
        "found-mismatch rate non-decreasing in size (per kind and shape, white noise)": all(
            _monotone(c, slack) for c in white_curves.values()
        ),
        # at or under the nominal 5 %: no noise kind's rate significantly above it (the
        # lower end of its Wilson 95 % interval at most 5 %)
        "false positives on nulls of every noise kind not above 5 %": all(
            v["rate"] is not None and v["ci95"][0] <= 0.05 for v in summary["nulls"].values()
        ),
        "outliers of the outlier nulls reported": summary["outliers"]["planted"] == 0
        or summary["outliers"]["reported"]["rate"] >= 0.9,
    }
    numbers = {
        "n_recordings": len(results),
        "power": summary["power"],
        "null_false_positive_rate": {k: v["rate"] for k, v in summary["nulls"].items()},
        "null_undetermined": {k: v["undetermined"] for k, v in summary["nulls"].items()},
        "outliers_reported": summary["outliers"]["reported"],
        "wall_seconds": wall,
    }
    notes = [
        "Found = verdict other than 'none'. Null false positive = an effect or 'unexplained'; "
        "'undetermined' is counted apart (the recording says it cannot tell).",
        f"Monotone check allows a drop of one seed in {n_seeds} between sizes.",
    ]
    return finish(
        NAME,
        out_dir=out_dir,
        checks=checks,
        numbers=numbers,
        figures=[png],
        notes=notes,
        quick=bool(quick),
        extra={"table": summary},
    )


if __name__ == "__main__":
    import sys

    from ._common import main

    sys.exit(main(run))
