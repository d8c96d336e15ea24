"""validation.compare_hold_tables: two small synthetic hold tables with known changes, the
one-line refusals (exit 2), and the committed clove-hitch pair (5 of 100 verdicts change,
48 -> 47 hold). Nothing here simulates."""

import json

import pytest

from knotmech.verdict.tables import HOLD_COLUMNS, HOLD_TABLE_FORMAT
from validation import compare_hold_tables as c

X, Y, M = (0.05, 0.2), (0.001, 0.01), (0.3,)


def _table(path, points, *, knot="clove-hitch", cpu=12.5, limit=1e-3):
    data = {
        "format": HOLD_TABLE_FORMAT, "version": 1, "knot": knot, "law": "anchor",
        "criterion": {"name": "creep-speed", "limit_d_per_s": limit, "window_s": 1.0},
        "axes": {"d_over_2R": sorted({p[0] for p in points}),
                 "t_over_EA": sorted({p[1] for p in points}), "mu": sorted({p[2] for p in points})},
        "columns": list(HOLD_COLUMNS), "points": points, "meta": {"cpu_s_total": cpu},
    }  # fmt: skip
    path.write_text(json.dumps(data))
    return path


def _grid(creep, ran=None, solved=None):
    """The 2 x 2 x 1 grid's rows: creep speed [d/s] per point, all ran to the end and
    kept their topology unless ``ran``/``solved`` say otherwise (index -> 0)."""
    rows, k = [], 0
    for x in X:
        for y in Y:
            rows.append([x, y, M[0], creep[k], 0 if ran == k else 1, 1,
                         0 if solved == k else 1])  # fmt: skip
            k += 1
    return rows


@pytest.fixture
def pair(tmp_path):
    # old: all four hold (|creep| < 1e-3 d/s). new: (0.05, 0.01) creeps 2e-3 d/s (slips:
    # 2e-3 >= 1e-3), (0.2, 0.01) ran off (slips); the other two still hold, one crept the
    # other way (-5e-4 d/s: |creep| counts)
    old = _table(tmp_path / "old.json", _grid([1e-5, 2e-4, 3e-6, 9e-4]), cpu=100.0)
    new = _table(tmp_path / "new.json", _grid([-5e-4, 2e-3, 3e-6, None], ran=3), cpu=40.5)
    return old, new


def test_known_changes_are_found_with_the_librarys_verdict(pair, capsys):
    assert c.main([str(p) for p in pair]) == 0
    out = capsys.readouterr().out
    assert "holds: 4 -> 2 of 4" in out and "verdicts changed: 2 of 4" in out
    rows = [s.split() for s in out.splitlines() if s.startswith("  ") and "->" in s]
    assert rows[1:] == [
        ["0.05", "0.01", "0.3", "0.0002", "0.002", "holds", "->", "slips"],
        ["0.2", "0.01", "0.3", "0.0009", "ran", "off", "holds", "->", "slips"],
    ]
    assert "cpu_s_total: old 100, new 40.5" in out
    assert "grid: d/2R [0.05, 0.2] x T/EA [0.001, 0.01] x mu [0.3] (4 points)" in out


def test_json_output_and_a_solver_failure_is_no_verdict(tmp_path, capsys):
    old = _table(tmp_path / "old.json", _grid([1e-5, 2e-4, 3e-6, 9e-4], solved=0))
    new = _table(tmp_path / "new.json", _grid([1e-5, 2e-4, 3e-6, 9e-4]))
    assert c.main([str(old), str(new), "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["holds"] == [3, 4] and r["points"] == 4
    (ch,) = r["changed"]
    assert (ch["d_over_2R"], ch["t_over_EA"], ch["old"], ch["new"]) == (0.05, 0.001, None, True)
    assert ch["old_run"] == "failed" and ch["new_creep"] == 1e-5


def test_each_table_is_read_at_its_own_criterion_limit(tmp_path):
    old = _table(tmp_path / "old.json", _grid([1e-5, 2e-4, 3e-6, 9e-4]))
    new = _table(tmp_path / "new.json", _grid([1e-5, 2e-4, 3e-6, 9e-4]), limit=1e-4)
    r = c.compare_files(old, new)
    # at 1e-4 d/s, 2e-4 and 9e-4 no longer hold
    assert r["limits"] == [1e-3, 1e-4] and r["holds"] == [4, 2] and len(r["changed"]) == 2


@pytest.mark.parametrize(
    ("make", "words"),
    [
        (lambda t: _table(t / "b.json", _grid([0, 0, 0, 0]), knot="cow-hitch"),
         "different knots: clove-hitch and cow-hitch"),
        (lambda t: _table(t / "b.json", [[x, y, 0.5, 0, 1, 1, 1] for x in X for y in Y]),
         "grids differ in mu: [0.3] and [0.5]"),
        (lambda t: t / "missing.json", "cannot read hold table"),
        (lambda t: (t / "b.json").write_text("{") and t / "b.json", "is not JSON"),
        (lambda t: (t / "b.json").write_text('{"format": "x"}') and t / "b.json",
         "not a knotmech hold table"),
    ],
)  # fmt: skip
def test_refusals_are_one_line_exit_2(make, words, tmp_path, capsys):
    old = _table(tmp_path / "a.json", _grid([0, 0, 0, 0]))
    assert c.main([str(old), str(make(tmp_path))]) == 2
    cap = capsys.readouterr()
    assert cap.out == "" and len(cap.err.strip().splitlines()) == 1 and words in cap.err


def test_committed_clove_hitch_pair_and_the_case(tmp_path):
    r = c.compare_files(c.FLOOR0, c.SHIPPED)
    assert r["holds"] == [48, 47] and len(r["changed"]) == 5 and r["points"] == 100
    assert r["cpu_s_total"] == [1855.3, 593.3]
    got = {(p["d_over_2R"], p["t_over_EA"], p["mu"]): (p["old"], p["new"]) for p in r["changed"]}
    assert got[(0.2308, 0.001, 0.3)] == (True, False)
    assert got[(0.04762, 0.1, 0.8)] == (None, True)
    res = c.run(out_dir=tmp_path)
    assert res["verdict"] == "pass" and res["numbers"]["changed"] == 5
    assert (tmp_path / "compare_hold_tables.json").is_file()
