"""The look-ahead for repeatable effects (:func:`knotmech.diagnose.engine._repeated_lookahead`).

Held-out recordings 105049 and 105050 of the issue-26 campaign (tension profiles, white
noise, two and three nips of 6 and 10 noise sd) were ``undetermined`` before it: the
one-nip fit's remainder still held the other steps, so its noise looked like AR(1) noise
of rho 0.75 and 0.925 and like 1/f noise (exponents 0.675 and 0.75), whose draws gave
one-nip likelihood ratios as large as the observed 44.6 and 27.6 (power-law p 0.01 and
0.08). Section 18 of docs/notes/diagnose-noise-and-statistics/issue26-campaign.md.
"""

from __future__ import annotations

import numpy as np
import pytest

from knotmech.diagnose import diagnose
from knotmech.diagnose.engine import LOOKAHEAD_LEVEL_SHARE, LOOKAHEAD_MAX


def _nips(seed, size):
    from validation.diagnose_campaign import make

    rec, truth = make("heldout", "tension_profile", "self_contact_nip", size, "white", seed)
    return rec, truth, diagnose(rec, seed=seed % 100_000)


@pytest.mark.parametrize(
    ("seed", "size", "lr1", "lr2", "beta1"),
    [(105049, 6.0, 44.56, 589.1, 0.675), (105050, 10.0, 27.62, 95.01, 0.75)],
)
def test_several_nips_in_white_noise_are_added_at_once(seed, size, lr1, lr2, beta1):
    """The one-nip candidate is rejected by the power-law draws of its remainder (as
    before the look-ahead); two nips at once are accepted (likelihood ratio 589.1 and
    95.0 on 4 new degrees of freedom); the verdict names the nips and every true nip is
    found within 1 mm (the generator's tanh edges are 0.2 % of the span wide)."""
    rec, truth, rep = _nips(seed, size)
    assert rep.verdict == "self_contact_nip"
    one, two = rep.details["candidates"][:2]
    assert "instances" not in one and not one["accepted"]
    assert one["likelihood_ratio"] == pytest.approx(lr1, abs=0.01)
    assert one["power_law"]["beta"] == pytest.approx(beta1)
    assert one["power_law"]["p_value"] >= 0.01  # alpha_each: nip the only effect tested
    assert two["instances"] == 2 and two["accepted"]
    assert two["likelihood_ratio"] == pytest.approx(lr2, abs=0.01)
    assert two["delta_bic"] == pytest.approx(lr2 - 4 * np.log(rec.n), rel=1e-3)
    assert two["p_value"] < 0.01 * LOOKAHEAD_LEVEL_SHARE / (LOOKAHEAD_MAX - 1)
    (eff,) = rep.effects
    found = np.asarray(eff["parameters"]["positions_m"])
    for s in truth["positions_m"]:
        assert np.min(np.abs(found - s)) < 1e-3
    assert "x 2 at once" in rep.summary


def test_lookahead_level_is_half_the_effect_level():
    """Two look-ahead tests (2 and 3 instances) share half the per-effect level."""
    assert LOOKAHEAD_MAX == 3
    assert 0.01 * LOOKAHEAD_LEVEL_SHARE / (LOOKAHEAD_MAX - 1) == pytest.approx(0.0025)
