"""``knotmech diagnose --baseline der``: the DER capstan (kinetic friction only) as baseline.

Synthetic recordings are made BY the DER capstan (:class:`DERCurves`, same settings as the
baseline) with a known shift and Gaussian noise (1 % of T_low, fixed seed). With mu_s = 0.5 >
mu_k = 0.35 the kinetic-only baseline misses the onset peak and ``static_friction`` (a re-run
with mu_s > mu_k) must be named; with mu_s = mu_k it must not. Each diagnosis runs ~17 DER
simulations of 40 elements (~0.4 s each, plus the numba compilation once).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from knotmech.analytic.capstan import mu_eff
from knotmech.cli.main import main
from knotmech.diagnose import diagnose
from knotmech.diagnose.der import DERCurves, refine_grid, step_span
from knotmech.diagnose.recording import recording_from_arrays
from knotmech.errors import InputError

D_ROD, E = 4e-3, 1.26e6
EA = E * np.pi * D_ROD**2 / 4
META = {
    "wrap_angle_rad": np.pi,
    "T_low_N": 0.01 * EA,
    "rod_diameter_m": D_ROD,
    "post_diameter_m": 4 * D_ROD,
    "youngs_modulus_Pa": E,
}
X = np.linspace(0.0, 8e-3, 200)
SHIFT = 5e-4


def _der_recording(mu_s, mu_k, seed):
    # the curves need only the metadata and x; y is a placeholder (not constant: the reader
    # refuses a constant reading)
    dummy = recording_from_arrays("capstan_pull", X, 1.0 + X, metadata=META)
    curves = DERCurves(dummy)
    y = curves.at(X - SHIFT, mu_s, mu_k)
    y = y + 0.01 * META["T_low_N"] * np.random.default_rng(seed).standard_normal(X.size)
    return recording_from_arrays("capstan_pull", X, y, metadata=META), curves


@pytest.fixture(scope="module")
def static_case():
    rec, curves = _der_recording(0.5, 0.35, seed=1)
    return rec, curves, diagnose(rec, baseline="der")


def test_der_plateau_matches_capstan_law(static_case):
    # kinetic plateau of the DER curve vs T_low exp(mu_eff theta), mu_eff from the clove-hitch
    # paper eq. 3 (surface friction on a post D/d = 4): within 2 %
    _, curves, _ = static_case
    u, t = curves.curve(0.35, 0.35)
    plateau = np.mean(t[u > 0.5 * u[-1]]) / META["T_low_N"]
    assert plateau == pytest.approx(np.exp(mu_eff(0.35, 4.0) * np.pi), rel=0.02)


def test_der_names_static_friction(static_case):
    _, _, rep = static_case
    assert rep.verdict == "static_friction"
    p = rep.effects[0]["parameters"]
    # truth mu_s = 0.5, mu_k = 0.35 (seeds 1-5: mu_s 0.492-0.516, mu_k 0.3499-0.3502)
    assert p["mu_static"] == pytest.approx(0.5, abs=0.04)
    assert p["mu_kinetic"] == pytest.approx(0.35, abs=0.01)
    assert rep.final["parameters"]["delta0_m"] == pytest.approx(SHIFT, abs=1e-4)
    assert rep.final["parameters"]["u_scale"] == pytest.approx(1.0, abs=0.03)
    assert rep.heldout_rms_after < 0.8 * rep.heldout_rms_before
    assert "no parametric bootstrap" in rep.effects[0]["evidence"]["p_value_method"]
    assert rep.details["baseline_model"] == "der"
    assert rep.details["der"]["n_elements"] == 40


def test_der_kinetic_only_gives_none():
    rec, _ = _der_recording(0.35, 0.35, seed=2)
    rep = diagnose(rec, baseline="der")
    assert rep.verdict == "none"
    assert rep.final["parameters"]["mu"] == pytest.approx(0.35, abs=0.01)
    assert rep.heldout_rms_after == rep.heldout_rms_before


def test_der_refuses_other_experiments():
    fn = np.linspace(0.5, 9.0, 60)
    meta = {"rod_diameter_m": 0.004, "pinch_diameter_m": 0.008, "youngs_modulus_Pa": 1.26e6}
    rec = recording_from_arrays("pinch", fn, 0.6 * fn, metadata=meta)
    with pytest.raises(InputError, match="capstan_pull and knot_pull only"):
        diagnose(rec, baseline="der")


def test_cli_baseline_der(static_case, tmp_path, capsys):
    rec, _, _ = static_case
    path = tmp_path / "pull.csv"
    lines = ["# knotmech-recording: 1", "# experiment: capstan_pull"]
    lines += [f"# {k}: {float(v)!r}" for k, v in META.items()]
    lines.append("displacement_m,T_high_N")
    lines += [f"{float(a)!r},{float(b)!r}" for a, b in zip(rec.x, rec.y, strict=True)]
    path.write_text("\n".join(lines) + "\n")
    out = tmp_path / "out.json"
    rc = main(["diagnose", str(path), "--json", str(out), "--baseline", "der"])
    text = capsys.readouterr().out
    assert rc == 0
    assert text.startswith("static friction at the onset of sliding: mu_s = ")
    assert "(asymptotic LR, no bootstrap)" in text
    d = json.loads(out.read_text())
    assert d["verdict"] == "static_friction"


def test_step_span_is_the_recorded_stretch():
    # 60 steps over what the recording samples: from 0 (or below) the largest x, from a
    # zero offset the stretch above it, at least a quarter of the largest x
    assert step_span(np.array([0.0, 8e-3]), 8e-3) == pytest.approx(8e-3)
    assert step_span(np.array([-1e-3, 8e-3]), 8e-3) == pytest.approx(8e-3)
    assert step_span(np.array([2e-3, 10e-3]), 10e-3) == pytest.approx(8e-3)
    assert step_span(np.array([2.04e-3, 10e-3]), 10e-3) == 8e-3  # first row dropped
    assert step_span(np.array([9.9e-3, 10e-3]), 10e-3) == pytest.approx(2.5e-3)


def test_refine_grid_adds_runs_inside_the_grid():
    grid = np.linspace(0.2, 0.6, 5)
    np.testing.assert_allclose(
        refine_grid(grid, 0.33), [0.2, 0.3, 0.325, 0.33, 0.335, 0.4, 0.5, 0.6]
    )
    np.testing.assert_allclose(refine_grid(grid, 0.598), [0.2, 0.3, 0.4, 0.5, 0.593, 0.598, 0.6])
    assert refine_grid(grid, 0.3).size == 7  # the run at 0.3 exists already
