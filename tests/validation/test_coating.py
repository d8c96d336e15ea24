"""Validation case 7 (coating): LLD film on the 1.59 mm rod and mu(phi_p), numbers of its JSON."""

import json
from pathlib import Path

import numpy as np
import pytest

from knotmech.cli.validate import load_case

case = load_case("coating")


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    return case.run(quick=True, out_dir=tmp_path_factory.mktemp("coating"))


def test_verdict_outputs_and_honest_disagreement(result):
    assert result["verdict"] == "pass", result["checks"]
    assert [Path(f).name for f in result["figures"]] == ["coating_film.png", "coating_mu.png"]
    on_disk = json.loads((Path(result["figures"][0]).parent / "coating.json").read_text())
    assert on_disk["numbers"] == result["numbers"]
    # the measured layer is NOT explained by LLD with the estimated viscosity, and says so
    assert result["agreement_with_measurement"] is False
    assert any("does NOT explain" in note for note in result["notes"])


def test_viscosity_estimate_by_hand(result):
    n = result["numbers"]
    # Mark-Houwink-Sakurada, PMMA in THF (Chen et al. 1993): 7.56e-5 * 15000**0.731 dL/g
    # ln 15000 = 9.61581, * 0.731 = 7.02916, exp = 1129.1 -> 0.08536 dL/g
    assert n["intrinsic_viscosity_dL_per_g"] == pytest.approx(0.08536, rel=1e-3)
    # c = 0.05 * 1.19 g/cm^3 = 5.95 g/dL; c[eta] = 0.5079; Huggins with k_H = 0.35:
    # 0.5886 mPa s * (1 + 0.5079 + 0.35 * 0.5079**2) = 0.9407 mPa s
    assert n["c_times_intrinsic_viscosity"] == pytest.approx(0.5079, rel=1e-3)
    assert n["viscosity_assumed_Pa_s"] == pytest.approx(0.9407e-3, rel=1e-3)


def test_lld_film_by_hand(result):
    n = result["numbers"]
    # Ca = 0.9407e-3 * 5e-3 / 34.3e-3 = 1.3713e-4
    assert n["capillary_number"] == pytest.approx(1.3713e-4, rel=1e-3)
    # l_c = sqrt(0.0343 / (1066.5 * 9.80665)) = 1.8110 mm; r / l_c = 0.795 / 1.811 = 0.439
    assert n["capillary_length_m"] == pytest.approx(1.8110e-3, rel=1e-3)
    assert n["r_over_capillary_length"] == pytest.approx(0.439, abs=1e-3)
    # Goucher-Ward: 1.3375 * 0.795 mm * Ca^(2/3) (= 2.6593e-3) = 2.8277 um;
    # White-Tallmadge divides by (1 - 0.0035568): 2.8376 um
    assert n["wet_film_fibre_law_m"] == pytest.approx(2.8376e-6, rel=2e-3)
    # lower bound: 3.5568e-3 / (1/0.795e-3 + sqrt(2)/1.8110e-3 [1/m]) = 1.7446 um
    assert n["wet_film_lower_bound_m"] == pytest.approx(1.7446e-6, rel=2e-3)
    # dried layer: 5 % binder -> 0.0872 to 0.1419 um, against 5.85 um measured (41x)
    np.testing.assert_allclose(n["dry_layer_predicted_m"], [0.0872e-6, 0.1419e-6], rtol=2e-3)
    assert n["measured_over_predicted_dry_upper"] == pytest.approx(41.2, abs=0.1)
    # viscosity that would make the dried layer 5.85 um: wet h = 117 um, h/r = 0.14717,
    # x = 0.14717 / 1.14717 = 0.12829, Ca = (x / 1.3375)**1.5 = 0.029706 -> 0.2038 Pa s
    assert n["viscosity_needed_dry_Pa_s"] == pytest.approx(0.2038, rel=2e-3)
    assert n["viscosity_needed_wet_Pa_s"] == pytest.approx(2.77e-3, rel=5e-3)


def test_mu_versus_particle_fraction(result):
    n = result["numbers"]
    # coated-rod paper Fig. 12: mu = 0.2, 0.5, 0.6, 0.7, 0.9 at 0, 1, 4, 7, 13 %
    np.testing.assert_allclose(n["mu_at_data"], [0.2, 0.5, 0.6, 0.7, 0.9], atol=1e-12)
    assert 0.5 < n["mu_at_2.5_percent"] < 0.6
    assert 0.7 < n["mu_at_10_percent"] < 0.9
    inverse = n["volume_fraction_for_mu"]
    assert 0.0 < inverse["0.3"] < 0.01 and 0.07 < inverse["0.8"] < 0.13
    assert inverse["0.4"] > inverse["0.3"]
