"""The slip-over-mu table: renderer on small fake files, and the row-maker's bad input.

Nothing here simulates (the rows are made by ``python -m validation.tied_slip_table --run``).
"""

import json
import math

import pytest

from knotmech.errors import InputError
from validation import tied_slip_table as t


def _row(verdict, slip=None, top=0.1, cpu=12.3, status="success"):
    return {"status": status, "verdict": verdict, "slip_load_N": slip, "max_force_N": top,
            "cpu_s": cpu}  # fmt: skip


@pytest.fixture
def folder(tmp_path):
    f = tmp_path / "slip"
    f.mkdir()
    a = {"knot": "sheet-bend", "loading": "ends", "rows": {
        "0.3": _row("slips", 0.0347, 0.0347, 8.94), "1": _row("slips", 0.228, 0.228, 6.2),
        "0.1": _row("slips", 0.0182, 0.0182, 9.3)}}  # fmt: skip
    b = {"knot": "bowline", "loading": "pin", "rows": {
        "0.3": _row("slips", 0.0646, 0.0646), "1": _row("holds", None, 0.505, 10.8),
        "0.6": _row("", None, 0.28, 9.8, status="failed")}}  # fmt: skip
    c = {"knot": "sheet-bend", "bending_scale": 0.01, "rows": {"0.3": _row("slips", 0.5, 0.5)}}
    for name, d in (("sheet-bend", a), ("bowline", b), ("sheet-bend-kappa0.01", c)):
        (f / f"{name}.json").write_text(json.dumps(d))
    return f


def test_table_has_a_line_per_file_and_a_column_per_mu(folder):
    text = t.table(t.read_folder(folder))
    lines = text.splitlines()
    assert lines[0] == "| knot | mu = 0.1 | mu = 0.3 | mu = 0.6 | mu = 1 |"
    assert lines[2] == "| bowline | - | 0.0646 (12 s) | failed (9.8 s) | holds (to 0.505) (11 s) |"
    assert lines[3] == "| sheet-bend | 0.0182 (9.3 s) | 0.0347 (8.9 s) | - | 0.228 (6.2 s) |"
    assert lines[4] == "| sheet-bend (kappa 0.01) | - | 0.5 (12 s) | - | - |"
    assert len(lines) == 5


def test_points_sorted_by_mu_with_held_runs_as_lower_bounds(folder):
    files = {t._label(f): f for f in t.read_folder(folder)}
    assert t.points(files["bowline"]) == ([0.3, 1.0], [0.0646, 0.505], [False, True])
    mu, force, held = t.points(files["sheet-bend"])
    assert mu == [0.1, 0.3, 1.0] and force == [0.0182, 0.0347, 0.228] and not any(held)


def test_render_writes_between_the_markers_only_and_the_figure(folder, tmp_path):
    note = tmp_path / "note.md"
    note.write_text(f"# head\n\nbefore\n{t.START}\nold table\n{t.END}\nafter\n")
    image = tmp_path / "img" / "slip.png"
    out = t.render(folder, note, image)
    text = note.read_text()
    assert out["files"] == 3
    assert text.startswith("# head\n\nbefore\n" + t.START + "\n| knot |")
    assert text.endswith(t.END + "\nafter\n") and "old table" not in text
    assert image.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    t.render(folder, note, image)  # idempotent
    assert note.read_text() == text


def test_a_note_without_markers_or_a_foreign_file_is_one_line_error(folder, tmp_path):
    note = tmp_path / "note.md"
    note.write_text("no markers\n")
    with pytest.raises(InputError, match="markers"):
        t.write_table(t.read_folder(folder), note)
    (folder / "other.json").write_text(json.dumps({"rows": {}}))
    with pytest.raises(InputError, match="other.json: not a slip-over-mu file"):
        t.read_folder(folder)


@pytest.mark.parametrize(
    ("args", "match"),
    [
        (("zeppelin-bend", 0.3), "knot must be a tied bend or loop"),
        (("reef", 0.3), "knot must be a tied bend or loop"),
        ((None, 0.3), "knot must be a tied bend or loop"),
        (("sheet-bend", 0.0), "mu must be"),
        (("sheet-bend", -0.3), "mu must be"),
        (("bowline", math.nan), "mu must be"),
        (("bowline", "0.3"), "mu must be"),
    ],
)
def test_row_maker_refuses_bad_input_before_any_run(args, match):
    with pytest.raises(InputError, match=match):
        t.slip_row(*args)


def test_row_maker_refuses_bad_kappa_and_pin():
    with pytest.raises(InputError, match="bending scale must be a finite number in \\(0, 1\\]"):
        t.slip_row("sheet-bend", 0.3, bending_scale=1.5)
    with pytest.raises(InputError, match="pin diameter"):
        t.slip_row("bowline", 0.3, pin_diameter=0.0)


def test_aliases_name_the_same_file(tmp_path):
    assert t.file_for("EDK", folder=tmp_path).name == "flat-overhand-bend.json"
    assert t.file_for("bowline", 0.01, tmp_path).name == "bowline-kappa0.01.json"
    end = t.file_for("butterfly", folder=tmp_path, loading="end-to-end")
    assert end.name == "alpine-butterfly-end-to-end.json"


def test_a_knot_fallen_apart_before_the_pull_is_its_own_cell():
    """A loop run that failed because its knot came apart in the settle or the set (the
    alpine butterfly) reads so; any other failure stays "failed"."""
    apart = {"cpu_s": 2.5, "status": "failed",
             "message": "came apart before the pull (settle and set): average crossing "
                        "number 2.0 < 4 (a twisted eye, not the knot); no slip load"}  # fmt: skip
    assert t._cell(apart) == "came apart in the set (2.5 s)"
    assert t._cell({**apart, "message": "knot type changed"}) == "failed (2.5 s)"


def test_cli_bad_input_exits_2_in_one_line(capsys):
    assert t.main(["--run"]) == 2
    assert t.main(["--run", "--knots", "sheet-bend", "--mu", "0.3,x"]) == 2
    assert t.main(["--run", "--knots", "sheet-bend,zeppelin", "--mu", "0.3"]) == 2
    out = capsys.readouterr().out.strip().splitlines()
    assert len(out) == 3 and all(line.startswith("error: ") for line in out)


def test_the_validation_case_renders_the_committed_runs(tmp_path):
    """``knotmech validate`` runs the case on the committed rows: nothing is simulated."""
    out = t.run(out_dir=tmp_path)
    assert out["name"] == "tied_slip_table" and out["figures"]
    assert out["numbers"]["sheet-bend"]["0.3"].startswith("0.0347 (")
    assert out["checks"]["sheet-bend: holds more at mu 1 than at 0.1"] is True
    assert out["checks"]["double-fishermans: holds more at mu 1 than at 0.1"] is True
    assert out["verdict"] == "pass"
    # the double fisherman's comes undone at 0.165 N at mu = 0.3 and slips at 0.124 N at 0.6
    assert "double-fishermans: 0.165 N at mu 0.3, 0.124 N at mu 0.6" in out["notes"][1]
    assert (tmp_path / "tied_slip_table.md").read_text().startswith("| knot | mu = 0.1 |")


def test_a_hold_beyond_ten_percent_strain_is_marked(folder):
    # E = 1 MPa, d = 4 mm: EA = 12.57 N, so 0.1 EA = 1.257 N; 7.22 N is 57 % strain
    assert t.EA == pytest.approx(12.566, rel=1e-4)
    data = {"knot": "figure-eight-bend", "loading": "end-to-end", "rows": {
        "1": _row("holds", None, 7.22, 70.5), "0.6": _row("holds", None, 1.2, 57.0)}}  # fmt: skip
    (folder / "figure-eight-bend.json").write_text(json.dumps(data))
    lines = t.table(t.read_folder(folder)).splitlines()
    row = next(line for line in lines if line.startswith("| figure-eight-bend"))
    assert "holds (to 1.2) (57 s)" in row and "holds (to 7.22 *) (70 s)" in row
    assert row.startswith("| figure-eight-bend (end to end) |")
    assert lines[-1].startswith("\\* the pull ended above 10 % strain")


def test_pull_summary_is_the_row_the_table_and_benchmark_print():
    from types import SimpleNamespace

    import numpy as np

    from knotmech.scenes.bends import pull_summary

    r = SimpleNamespace(stats={"steps": 5, "newton_iterations": 9}, positions=np.zeros((3, 7, 3)),
                        status="success", message="", verdict="holds", slip_load=math.nan,
                        max_force=0.5, frames_checked=3)  # fmt: skip
    row = pull_summary(r)
    assert row == {"steps": 5, "newton_iterations": 9, "rejected_steps": 0, "nodes": 7,
                   "status": "success", "message": "", "verdict": "holds", "slip_load_N": None,
                   "max_force_N": 0.5, "frames_checked": 3,
                   "held_to_strain_limit": False}  # fmt: skip
    r.verdict, r.slip_load = "slips", 0.25
    assert pull_summary(r)["slip_load_N"] == 0.25
    # the table reads the row back: a slip is its load, a hold its largest force
    assert t._cell({"cpu_s": 12.0, **pull_summary(r)}) == "0.25 (12 s)"


def test_a_hold_to_the_strain_limit_is_told_as_such(folder):
    """A pull stopped at 0.1 EA before the knot slipped (the row's
    ``held_to_strain_limit``): "strain limit" in its cell and a footnote saying it is a
    lower bound; no "*" (it did not stretch the rod beyond the limit)."""
    data = {"knot": "figure-eight-bend", "rows": {
        "1": {**_row("holds", None, 1.14, 14.8), "held_to_strain_limit": True}}}  # fmt: skip
    (folder / "figure-eight-bend.json").write_text(json.dumps(data))
    lines = t.table(t.read_folder(folder)).splitlines()
    row = next(line for line in lines if line.startswith("| figure-eight-bend"))
    assert "holds (to 1.14, strain limit) (15 s)" in row and "*" not in row
    assert any(line.startswith("strain limit: the pull stopped") for line in lines)
    # a stop a step past the limit (1.2583 N > 0.1 EA = 1.2566 N) is no "*" hold
    data["rows"]["1"]["max_force_N"] = 1.2583
    (folder / "figure-eight-bend.json").write_text(json.dumps(data))
    lines = t.table(t.read_folder(folder)).splitlines()
    assert not any(line.startswith("\\*") for line in lines)


def test_kappa_points_need_two_bending_scales_at_mu(folder, tmp_path):
    """The bending-scale figure's points at mu = 0.3: the sheet bend has kappa 1 (slips at
    0.0347 N) and 0.01 (0.5 N); the bowline only kappa 1 (left out). A held run is a lower
    bound."""
    files = t.read_folder(folder)
    pts = t.kappa_points(files)
    assert list(pts) == [("sheet-bend", "")]
    assert [p[:2] for p in next(iter(pts.values()))] == [(0.01, 0.5), (1.0, 0.0347)]
    held = {"knot": "bowline", "bending_scale": 0.1, "rows": {"0.3": _row("holds", None, 0.4)}}
    (folder / "bowline-kappa0.1.json").write_text(json.dumps(held))
    pts = t.kappa_points(t.read_folder(folder))
    assert pts[("bowline", "")] == [(0.1, 0.4, True), (1.0, 0.0646, False)]
    out = t.render(folder=folder, note=tmp_path / "n.md", image=tmp_path / "a.png",
                   image_kappa=tmp_path / "k.png")  # fmt: skip
    assert (tmp_path / "k.png").stat().st_size > 1000 and out["figure_kappa"].endswith("k.png")
    # given only the mu figure's path, the kappa figure goes beside it (not into docs/)
    out = t.render(folder=folder, note=tmp_path / "n.md", image=tmp_path / "b" / "a.png")
    assert out["figure_kappa"] == str(tmp_path / "b" / "slip_over_kappa.png")


def test_a_rerun_replaces_a_row_written_as_1_0(tmp_path, monkeypatch):
    """A file with the row "1.0" (written by hand or an older run) gets its row replaced by
    a run at mu 1, not a second row "1" beside it (the table would show one of the two)."""
    path = tmp_path / "sheet-bend.json"
    path.write_text(json.dumps({"knot": "sheet-bend", "rows": {"1.0": _row("holds", None, 7.2)}}))
    monkeypatch.setattr(t, "slip_row", lambda knot, mu, **kw: _row("slips", 0.2, 0.2))
    t.add_rows("sheet-bend", [1.0], folder=tmp_path, log=lambda s: None)
    rows = json.loads(path.read_text())["rows"]
    assert list(rows) == ["1"] and rows["1"]["slip_load_N"] == 0.2
