"""The engine on synthetic recordings with known truth, the report contract, the CLI.

Recordings come from knotmech.diagnose.synth with fixed seeds; effect sizes are
in noise standard deviations at the effect's strongest point.
"""

import json

import numpy as np
import pytest

from knotmech.cli.main import main
from knotmech.diagnose import diagnose, make_recording, recording_from_arrays
from knotmech.errors import InputError

SPEC_KEYS = {
    "knotmech_report",
    "experiment",
    "verdict",
    "effects",
    "regions",
    "baseline",
    "final",
    "heldout_rms_before",
    "heldout_rms_after",
}
#: parameter names the spec (section 4) requires per effect
SPEC_PARAMS = {
    "static_friction": {"mu_static", "mu_kinetic"},
    "adhesion": {"adhesion_force_N"},
    "contact_flattening": {"onset_load_parameter"},
    "self_contact_nip": {"positions_m"},
    "displacement_offset": {"offset_m"},
    "finite_thickness": {"mu", "mu_eff"},
    "rate_dependent_friction": {"dmu_dlnv"},
}


@pytest.mark.parametrize(
    ("experiment", "effect", "seed"),
    [
        ("capstan_pull", "static_friction", 11),
        ("capstan_pull", "displacement_offset", 12),
        ("capstan_pull", "rate_dependent_friction", 13),
        ("capstan_pull", "finite_thickness", 14),
        ("pinch", "adhesion", 15),
        ("pinch", "contact_flattening", 16),
        ("pinch", "rate_dependent_friction", 17),
        ("tension_profile", "self_contact_nip", 18),
        ("tension_profile", "finite_thickness", 19),
    ],
)
def test_each_effect_is_named_with_its_parameters(experiment, effect, seed):
    rec, truth = make_recording(experiment, effect, size=8.0, seed=seed, n=200)
    rep = diagnose(rec, seed=seed)
    assert rep.verdict == effect
    d = rep.to_dict()
    assert SPEC_KEYS <= set(d) and d["knotmech_report"] == 1
    eff = {e["name"]: e for e in d["effects"]}[effect]
    assert SPEC_PARAMS[effect] <= set(eff["parameters"])
    assert eff["evidence"]["p_value"] < 0.01 and eff["evidence"]["delta_bic"] > 0
    assert d["heldout_rms_after"] < d["heldout_rms_before"]
    assert d["regions"] and all(r["start"] <= r["end"] for r in d["regions"])
    par = eff["parameters"]
    if effect == "static_friction":
        assert par["mu_static"] == pytest.approx(truth["mu_static"], abs=2e-3)
        assert par["mu_static"] > par["mu_kinetic"]
    if effect == "adhesion":
        assert par["adhesion_force_N"] == pytest.approx(truth["adhesion_force_N"], rel=0.25)
    if effect == "displacement_offset":
        assert par["offset_m"] == pytest.approx(truth["offset_m"], rel=0.25)
    if effect == "contact_flattening":
        assert par["onset_load_parameter"] == pytest.approx(truth["onset_load_parameter"], abs=0.04)
    if effect == "self_contact_nip":
        span = float(np.ptp(rec.x))
        for s_true in truth["positions_m"]:
            assert min(abs(s - s_true) for s in par["positions_m"]) < 0.02 * span
    if effect == "finite_thickness":
        assert par["mu_eff"] == pytest.approx(truth["mu_eff"], abs=0.01)
    if effect == "rate_dependent_friction":
        assert par["dmu_dlnv"] == pytest.approx(truth["dmu_dlnv"], rel=0.3)


@pytest.mark.parametrize(
    ("experiment", "noise"),
    [("capstan_pull", "ar1"), ("pinch", "white"), ("tension_profile", "ar1")],
)
def test_null_recordings_give_none(experiment, noise):
    rec, _ = make_recording(experiment, None, noise=noise, seed=7, n=200)
    rep = diagnose(rec, seed=1)
    assert rep.verdict == "none"
    assert rep.regions == [] and rep.effects == []


def test_out_of_catalogue_is_unexplained_not_a_wrong_name():
    rec, _ = make_recording("pinch", "out_of_catalogue", size=10.0, seed=3, n=200)
    rep = diagnose(rec, seed=3)
    assert rep.verdict == "unexplained"
    assert rep.regions  # located: the upward bend sits in the upper part of the load range
    assert rep.regions[-1][1] > 0.6 * rec.x.max()


def test_finite_thickness_needs_mu_nominal():
    rec, _ = make_recording("tension_profile", "finite_thickness", size=8.0, seed=4, n=200)
    rec.metadata.pop("mu_nominal")
    rec.metadata.pop("mu_nominal_sigma")
    rep = diagnose(rec, seed=4)
    assert rep.verdict == "none"  # without an independent mu it is just a smaller mu
    assert "finite_thickness" in rep.details["skipped_effects"]


def test_arrays_api_and_bad_options():
    rng = np.random.default_rng(0)
    fn = np.linspace(0.5, 9.0, 60)
    ft = 0.6 * fn + 0.15 + 0.02 * rng.standard_normal(fn.size)
    meta = {"rod_diameter_m": 0.004, "pinch_diameter_m": 0.008, "youngs_modulus_Pa": 1.26e6}
    rep = diagnose(experiment="pinch", x=fn, y=ft, metadata=meta)
    assert rep.verdict == "adhesion"
    assert rep.effects[0]["parameters"]["adhesion_force_N"] == pytest.approx(0.15, abs=0.03)
    with pytest.raises(InputError, match="baseline 'der' is not available"):
        diagnose(recording_from_arrays("pinch", fn, ft, metadata=meta), baseline="der")
    with pytest.raises(InputError, match="needs a recording"):
        diagnose(experiment="pinch", x=fn)


def test_cli_writes_report_and_plot(tmp_path, capsys):
    rec, _ = make_recording("capstan_pull", "static_friction", size=8.0, seed=21, n=200)
    path = tmp_path / "pull.csv"
    lines = ["# knotmech-recording: 1", "# experiment: capstan_pull"]
    lines += [f"# {k}: {float(v)!r}" for k, v in rec.metadata.items() if k != "experiment"]
    lines.append("displacement_m,T_high_N")
    lines += [f"{float(a)!r},{float(b)!r}" for a, b in zip(rec.x, rec.y, strict=True)]
    path.write_text("\n".join(lines) + "\n")
    out, png = tmp_path / "out.json", tmp_path / "fit.png"
    rc = main(["diagnose", str(path), "--json", str(out), "--plot", str(png)])
    text = capsys.readouterr().out
    assert rc == 0
    assert text.startswith("static friction at the onset of sliding: mu_s = ")
    assert "held-out RMS -" in text.splitlines()[0]
    d = json.loads(out.read_text())
    assert SPEC_KEYS <= set(d) and d["verdict"] == "static_friction"
    assert png.stat().st_size > 10_000
