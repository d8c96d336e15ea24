"""Validation case 2 (clove hitch tension profile, free end): numbers of its JSON summary.

Reference: the clove-hitch paper (Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788),
sec. 7 and Fig. 3b: (d, D, L) = (4, 30, 374) mm, mu_rr = 0.3, T_high = 1.47 N; T(s)
decays at mu_eff (eq. 3) on the post, with non-exponential nip regions at the entry, the
middle and the exit of the knot, and falls to zero past the knot.
"""

import json
from pathlib import Path

import numpy as np
import pytest

from knotmech.analytic.capstan import mu_eff
from knotmech.cli.validate import load_case

case = load_case("clove_tension_profile")


def test_analyse_profile_on_a_synthetic_hitch():
    """Two exponential wraps at rate 0.26 separated by a drop, a rise and an exit drop:
    the rates are recovered exactly and the three non-exponential regions are found."""
    rate = 0.26
    x = np.linspace(0.0, 20.0, 401)
    lt = np.zeros_like(x)
    lt[x > 2] = -rate * (x[x > 2] - 2)  # first wrap from s/R = 2
    lt[x > 3] -= 0.3  # entry nip drop over one step
    lt[(x > 9) & (x < 11)] = lt[np.searchsorted(x, 9)]  # flat middle (off the post)
    lt[x >= 11] = lt[np.searchsorted(x, 9)] + 0.1 - rate * (x[x >= 11] - 11)  # rise, 2nd wrap
    lt[x > 17] -= 4.0  # exit: T drops to ~0
    t = 1.47 * np.exp(lt)
    an = case.analyse_profile(x, t, rate=rate, t_high=1.47)
    assert len(an["rates"]) >= 3
    assert np.allclose(an["rates"], rate, rtol=1e-9)
    starts = [a for a, _ in an["regions"]]
    assert len(an["regions"]) >= 3
    for where in (3.0, 9.0, 17.0):  # a region at each feature
        assert any(a - 0.1 <= where <= b + 0.1 for a, b in an["regions"]), (where, an["regions"])
    assert starts == sorted(starts)


@pytest.fixture(scope="module")
def der(tmp_path_factory):
    pytest.importorskip("knotmech.scenes.clove_hitch")
    # mu_rc = 0.3 only, in this process (one DER run, about 25 s)
    return case.run(
        quick=True, out_dir=tmp_path_factory.mktemp("ctp"), processes=1, mu_values=(0.3,)
    )


def test_der_profile_decays_at_mu_eff_with_nips(der):
    assert der["verdict"] == "pass", der["checks"]
    n = der["numbers"]["mu_rc=0.3"]
    me = float(mu_eff(0.3, 30 / 4))  # 0.2623
    assert n["mu_eff"] == pytest.approx(me, rel=1e-12)
    assert len(n["fitted_rates"]) >= 2
    # measured: 0.276 and 0.262 (first and second wrap)
    assert np.allclose(n["fitted_rates"], me, rtol=0.15)
    assert n["n_nip_regions"] >= 2
    assert n["nip_regions_with_rod_contact"] >= 2  # located from T(s) alone, confirmed here
    assert n["T_free_end_over_T_high"] < 0.02
    assert n["verdict"] == "hold"
    png = Path(der["figures"][0])
    assert png.read_bytes()[:4] == b"\x89PNG"
    on_disk = json.loads((png.parent / "clove_tension_profile.json").read_text())
    assert on_disk["numbers"] == der["numbers"]


@pytest.mark.slow
def test_three_friction_coefficients(tmp_path):
    """The paper's three mu_rc: every profile passes and faster decay with larger mu_rc."""
    res = case.run(quick=True, out_dir=tmp_path)
    assert res["verdict"] == "pass", res["checks"]
    rates = [np.mean(res["numbers"][f"mu_rc={m:g}"]["fitted_rates"]) for m in (0.2, 0.3, 0.4)]
    assert rates[0] < rates[1] < rates[2]


GOLDEN = Path(__file__).parents[1] / "golden" / "docs_clove_tension_profile.json"


def _comparable(numbers: dict) -> dict:
    """The case's numbers without the run's wall time, through JSON (tuples as lists)."""
    out = json.loads(json.dumps(numbers))
    for value in out.values():
        if isinstance(value, dict):
            value.pop("wall_s", None)
    return out


def test_numbers_unchanged(der):
    """The quick mu_rc = 0.3 run's numbers and checks equal, bit for bit, those written
    before ``run`` was split into short functions (issue 22; the DER run is deterministic,
    its wall time is left out)."""
    golden = json.loads(GOLDEN.read_text(encoding="utf-8"))
    assert _comparable(der["numbers"]) == golden["numbers"]
    assert der["checks"] == golden["checks"]


if __name__ == "__main__":  # regenerate (only on the commit whose output is the reference)
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        res = case.run(quick=True, out_dir=tmp, processes=1, mu_values=(0.3,))
    GOLDEN.write_text(
        json.dumps({"numbers": _comparable(res["numbers"]), "checks": res["checks"]}, indent=1)
        + "\n",
        encoding="utf-8",
    )
