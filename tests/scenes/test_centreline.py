"""A user's centreline file: bad input is one InputError line; a good file is read in SI."""

import numpy as np
import pytest

from knotmech.errors import InputError
from knotmech.scenes.centreline import centreline, read_centreline

KW = dict(rod_diameter=4e-3, youngs_modulus=1e6, density=1100.0, mu_rod_rod=0.3)


def _line(n=20, dx=5.0):
    return "\n".join(f"{k * dx:g}, 0, 0" for k in range(n))


def test_a_file_in_mm_is_read_in_metres(tmp_path):
    f = tmp_path / "knot.csv"
    f.write_text("x, y, z\n" + _line())
    (x,) = read_centreline(f, unit="mm")
    assert x.shape == (20, 3)
    assert x[-1, 0] == pytest.approx(0.095)


def test_two_rods_are_split_by_the_rod_column():
    text = "\n".join(f"{r}, {k}, {r}, 0" for r in (0, 1) for k in range(12))
    a, b = read_centreline(text, unit="cm")
    assert a.shape == b.shape == (12, 3)
    assert b[0, 1] == pytest.approx(0.01)


@pytest.mark.parametrize(
    "text, match",
    [
        (_line(5), "at least 10 are needed"),
        (_line() + "\nnan, 0, 0", "not finite"),
        (_line() + "\n1, 2", "has 2 columns"),
        (_line() + "\na, b, c", "not numbers"),
        ("1, 2\n3, 4\n", "expected 3 columns"),
        ("\n".join(f"3, {k}, 0, 0" for k in range(12)), "rod must be 0 or 1"),
    ],
)
def test_bad_centreline_text_is_one_line_error(text, match):
    with pytest.raises(InputError, match=match) as exc:
        read_centreline(text + "\n")
    assert "\n" not in str(exc.value)


def test_missing_file_and_bad_unit():
    with pytest.raises(InputError, match="cannot read"):
        read_centreline("/nonexistent/knot.csv")
    with pytest.raises(InputError, match="unit must be"):
        read_centreline(_line() + "\n", unit="inch")


def test_self_intersecting_centreline_is_refused():
    # a figure "8" in the plane: the two lobes cross at the origin
    s = np.linspace(0, 2 * np.pi, 80)
    x = np.column_stack([0.02 * np.sin(s), 0.01 * np.sin(2 * s), 0 * s])
    x = np.vstack([[-0.05, 0.0, 0.0], x[1:-1], [0.05, 0.0, 0.0]])
    with pytest.raises(InputError, match="intersects itself"):
        centreline(x, ends=[("pull", "pull")], **KW)


def test_ends_must_name_pull_fixed_or_free():
    x = np.column_stack([np.linspace(0, 0.1, 20), np.zeros(20), np.zeros(20)])
    with pytest.raises(InputError, match="'pull', 'fixed' or 'free'"):
        centreline(x, ends=[("pull", "loose")], **KW)
    with pytest.raises(InputError, match="at least one end must be 'pull'"):
        centreline(x, ends=[("fixed", "free")], **KW)
    with pytest.raises(InputError, match="for each of the 1 rod"):
        centreline(x, ends=[("pull", "free"), ("pull", "free")], **KW)


def test_rod_through_the_post_is_refused():
    x = np.column_stack([np.linspace(-0.1, 0.1, 40), np.zeros(40), np.zeros(40)])
    with pytest.raises(InputError, match="cuts the post"):
        centreline(x, ends=[("pull", "fixed")], post_diameter=0.02, **KW)


def test_straight_rod_pulled_against_a_fixed_end_gives_ea_strain():
    """Verification: a straight rod (no knot) pulled by delta reads F = EA delta / L_free
    (L_free between the inner gripped nodes, two edges shorter than the rod) plus the drag
    of the moving rod, c v L / 2 = 0.005 B/d^2 (the scene's drag is 1 % of B/d^2 at v)."""
    L, d, E = 0.1, 4e-3, 1e6
    x = np.column_stack([np.linspace(0, L, 21), np.zeros(21), np.zeros(21)])
    res = centreline(
        x, ends=[("fixed", "pull")], settle_time=0.02, pull_distance=1e-3, pull_speed=0.02,
        n_nodes=21, n_frames=10, **KW,
    )  # fmt: skip
    assert res.status == "success", res.message
    assert res.verdict == "holds"
    ea = E * np.pi * d**2 / 4
    drag = 0.005 * E * np.pi * d**4 / 64 / d**2
    assert res.pull_force[-1] == pytest.approx(ea * 1e-3 / (L - 2 * L / 20) + drag, rel=0.01)
    assert res.knots_start == res.knots_checked == ("(1,)",)
