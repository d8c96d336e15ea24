"""`knotmech validate --out DIR`: the folder is checked (and made) before any case runs."""

from knotmech.cli.main import main


def test_out_that_is_a_file_is_one_line(tmp_path, capsys):
    target = tmp_path / "afile"
    target.write_text("")
    assert main(["validate", "--out", str(target), "--only", "coating"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.endswith("exists and is not a folder") and "\n" not in err


def test_out_that_cannot_be_made_is_one_line(tmp_path, capsys):
    blocker = tmp_path / "f"
    blocker.write_text("")
    assert main(["validate", "--out", str(blocker / "sub"), "--only", "coating"]) == 2
    err = capsys.readouterr().err.strip()
    assert "cannot create the folder" in err and "\n" not in err
