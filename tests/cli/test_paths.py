"""Output-path checks made before any work starts (knotmech.cli._paths)."""

from __future__ import annotations

import pytest

from knotmech.cli._paths import check_output_path, plot_formats, writing
from knotmech.errors import InputError


def test_ordinary_paths_pass(tmp_path):
    assert check_output_path(None) is None
    assert check_output_path(tmp_path / "r.json") == tmp_path / "r.json"
    existing = tmp_path / "old.json"
    existing.write_text("{}")
    assert check_output_path(str(existing)) == existing
    assert check_output_path(tmp_path / "f.PNG", formats=plot_formats(), option="--plot")


@pytest.mark.parametrize(
    ("name", "formats", "words"),
    [
        ("/nonexistent/dir/r.json", None, "does not exist"),
        ("/dev/full", None, "not a regular file"),
        ("", None, "empty file name"),
        ("{tmp}", None, "is a directory"),
        ("{tmp}/sub/", None, "is a directory"),
        ("{tmp}/fit.xyz", ("png", "pdf"), "unsupported format '.xyz'"),
        ("{tmp}/fit", ("png", "pdf"), "no file extension"),
        ("{tmp}/file.txt/r.json", None, "is not a folder"),
    ],
)
def test_bad_paths_one_line(tmp_path, name, formats, words):
    (tmp_path / "file.txt").write_text("x")
    name = name.replace("{tmp}", str(tmp_path))
    with pytest.raises(InputError) as info:
        check_output_path(name, formats=formats, option="--out")
    msg = str(info.value)
    assert words in msg and msg.startswith("--out") and "\n" not in msg


def test_plot_formats_are_matplotlibs():
    fmts = plot_formats()
    assert {"png", "pdf", "svg"} <= set(fmts) and "xyz" not in fmts


def test_writing_turns_oserror_into_input_error():
    with pytest.raises(InputError, match=r"--json /dev/full: could not write"):
        with writing("/dev/full", option="--json"):
            with open("/dev/full", "w") as fh:
                fh.write("x" * 10000)
                fh.flush()


def test_two_outputs_to_one_file_are_refused(tmp_path):
    from knotmech.cli._paths import check_distinct

    a = tmp_path / "out.json"
    check_distinct([("--json", a), ("--plot", tmp_path / "out.png"), ("--csv", None), ("--x", "-")])
    with pytest.raises(InputError, match="--json and --npz name the same file"):
        check_distinct([("--json", a), ("--npz", tmp_path / "." / "out.json")])
