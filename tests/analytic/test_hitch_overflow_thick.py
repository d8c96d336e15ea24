"""The thick-nip lock parameter at a hostile mu: inf (locked), no overflow warning (found by
the API-promise campaign: clove hitch, mu = 224, post 102 m)."""

import math
import warnings

from knotmech.analytic.hitch import hold_verdict, thick_hitch_lock_parameter


def test_thick_lock_parameter_overflows_to_locked_without_a_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        lock = thick_hitch_lock_parameter("clove-hitch", 224.0, rod_diameter=4e-3,
                                          post_diameter=102.0)  # fmt: skip
        assert math.isinf(float(lock)) and float(lock) > 0
        hold_verdict("clove-hitch", rod_diameter=4e-3, post_diameter=102.0, mu=224.0, load=1.0)
    # an ordinary mu stays finite (the paper's rod and post, mu = 0.3)
    assert 0 < float(thick_hitch_lock_parameter("clove-hitch", 0.3, rod_diameter=4e-3,
                                                post_diameter=30e-3)) < 1e3  # fmt: skip
