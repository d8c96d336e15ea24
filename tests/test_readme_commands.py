"""Every command the README tells a user to run, run as a user would (issues 11 and 22).

The commands are read from README.md at run time (nothing is hard-coded here): every line
of its ```bash blocks, and inline code spans that run a script of ``examples/`` or
``benchmarks/`` (``python examples/cantilever.py``). Each one runs in a fresh temporary
directory with ``knotmech ...`` replaced by ``sys.executable -m knotmech ...`` and
``python`` by ``sys.executable`` (the package is imported from this checkout; scripts run
from a copy of their folder there, and a file of the checkout named by a relative path,
such as ``knotmech/data/recordings/capstan_yarn_rig.csv``, is read where it is, so
nothing in the checkout is written), and must exit 0 within its timeout; ``> FILE`` sends
its output to FILE, and the files it names with ``--json``, ``--csv``, ``--plot`` and
``--out`` must exist afterwards.

Set-up steps are left to CI, which runs them itself: of ``python -m pip install -e . &&
knotmech tour`` only ``knotmech tour`` runs; ``python -m pytest`` (the suite itself) is
skipped, and so is ``python -m sphinx ...`` (the docs site, built by
``tests/test_docs.py``). A command that reads a file another README command writes
(``knotmech diagnose my_pinch.csv`` after ``knotmech diagnose --template pinch >
my_pinch.csv``) runs that command first, in the same folder; a ``knotmech diagnose FILE``
whose FILE no command writes gets a synthetic recording
(:func:`knotmech.diagnose.synth.make_recording`, a pinch test with adhesion of 6 noise sd,
seed 0) in the recording format of ``docs/recordings.md``.

Commands that simulate a knot or a hitch, ``knotmech validate`` and the benchmarks are
marked slow (run with ``-m slow``); the others run by default.
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"

# seconds; a README command that needs longer has stalled (or the README must say so)
QUICK_TIMEOUT = 240
SLOW_TIMEOUT = 1800  # knotmech validate --quick: 23 min of wall on the busy shared machine
# a command containing one of these runs for minutes: marked slow
SLOW_MARKERS = (
    "knotmech simulate clove-hitch",
    "knotmech simulate overhand",
    "knotmech simulate bend",
    "knotmech simulate sheet-bend",
    "knotmech simulate double-sheet-bend",
    "knotmech simulate flat-overhand-bend",
    "knotmech simulate figure-eight-bend",
    "knotmech simulate double-fishermans",
    "knotmech simulate two-half-hitches",
    "knotmech simulate bowline",
    "knotmech simulate prusik",
    "knotmech validate",
    "benchmarks/",
)
# options naming a file or folder the command writes
OUTPUT_OPTIONS = ("--json", "--csv", "--plot", "--out")
_INLINE = re.compile(r"`((?:[A-Z_]+=\S+\s+)*python\s+(?:examples|benchmarks)/[^`]+\.py[^`]*)`")


def _setup_free(line: str) -> str | None:
    """The part of a README line a test should run: install steps (``pip install``) and
    the test suite itself (``python -m pytest``) dropped; None if nothing is left."""
    keep = []
    for part in line.split("&&"):
        words = part.split()
        if not words:
            continue
        if "pip" in words[:3] and "install" in words:
            continue
        if words[:3] == ["python", "-m", "pytest"] or words[:1] == ["pytest"]:
            continue
        if words[:3] == ["python", "-m", "sphinx"]:  # the docs site: tests/test_docs.py
            continue
        keep.append(part.strip())
    return " && ".join(keep) if keep else None


def readme_commands() -> list[str]:
    """The commands of README.md, in order, without duplicates."""
    text = README.read_text(encoding="utf-8")
    found = []
    for block in re.findall(r"```bash\n(.*?)```", text, flags=re.S):
        for raw in block.splitlines():
            line = " ".join(shlex.split(raw, comments=True))  # drops "# ..." comments
            if line:
                found.append(line)
    found += [m.group(1).strip() for m in _INLINE.finditer(text)]
    out = []
    for line in found:
        cmd = _setup_free(line)
        if cmd and cmd not in out:
            out.append(cmd)
    return out


def _argv(cmd: str, workdir: Path | None = None) -> tuple[dict, list[str], str | None]:
    """(extra environment, argv, stdout file or None) of one command: leading VAR=value
    assignments, then ``knotmech`` -> ``sys.executable -m knotmech`` and ``python`` ->
    ``sys.executable``; a trailing ``> FILE`` becomes the stdout file. A script of
    examples/ or benchmarks/ runs from a copy of its folder in ``workdir`` (some write
    next to themselves, e.g. the cantilever example's docs/img figure, and the checkout
    must stay clean); a relative path naming a file of the checkout is made absolute."""
    words = shlex.split(cmd)
    stdout = None
    if len(words) >= 2 and words[-2] == ">":
        stdout = words[-1]
        words = words[:-2]
    env = {}
    while words and re.fullmatch(r"[A-Z_][A-Z0-9_]*=.*", words[0]):
        key, value = words.pop(0).split("=", 1)
        env[key] = value
    if words[0] == "knotmech":
        words = [sys.executable, "-m", "knotmech", *[_checkout_file(w) for w in words[1:]]]
    elif words[0] in ("python", "python3"):
        words = [sys.executable, *words[1:]]
        if len(words) > 1 and re.match(r"(examples|benchmarks)/", words[1]):
            base = workdir if workdir is not None else ROOT
            folder = words[1].split("/", 1)[0]
            if workdir is not None and not (workdir / folder).exists():
                shutil.copytree(ROOT / folder, workdir / folder)
            words[1] = str(base / words[1])
    return env, words, stdout


def _checkout_file(word: str) -> str:
    """``word``, or its absolute path when it is a relative path to a file of the checkout
    (a README command run from the checkout's root reads it there)."""
    if "/" in word and not word.startswith(("/", "-")) and (ROOT / word).is_file():
        return str(ROOT / word)
    return word


def _outputs(argv: list[str]) -> list[str]:
    return [argv[k + 1] for k, a in enumerate(argv[:-1]) if a in OUTPUT_OPTIONS]


def _write_recording(path: Path) -> None:
    """A synthetic pinch recording (adhesion, 6 noise sd, seed 0) in the version-1 file
    format: '# key: value' metadata lines, then the two required columns."""
    from knotmech.diagnose.synth import make_recording

    rec, _truth = make_recording("pinch", "adhesion", size=6.0, seed=0)
    lines = ["# knotmech-recording: 1"]
    lines += [f"# {k}: {v}" for k, v in rec.metadata.items()]
    lines.append(",".join(rec.columns))
    lines += [f"{x!r},{y!r}" for x, y in zip(rec.x.tolist(), rec.y.tolist(), strict=True)]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


def _writer_of(name: str) -> str | None:
    """The README command that writes ``name`` with ``> name``, if any."""
    for cmd in readme_commands():
        words = shlex.split(cmd)
        if len(words) >= 2 and words[-2:] == [">", name]:
            return cmd
    return None


def _run(cmd: str, workdir: Path, timeout: float) -> subprocess.CompletedProcess:
    """Run one README command in ``workdir`` as a user would (see the module docstring)."""
    env_extra, argv, stdout = _argv(cmd, workdir)
    env = dict(os.environ)
    env.update(env_extra)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    env.setdefault("MPLBACKEND", "Agg")
    env.setdefault("OPENBLAS_NUM_THREADS", "1")
    kwargs = dict(cwd=workdir, env=env, text=True, timeout=timeout, stdin=subprocess.DEVNULL)
    try:
        if stdout is None:
            return subprocess.run(argv, capture_output=True, **kwargs)
        with open(workdir / stdout, "w", encoding="utf-8") as out:
            return subprocess.run(argv, stdout=out, stderr=subprocess.PIPE, **kwargs)
    except subprocess.TimeoutExpired:
        pytest.fail(f"README command did not finish in {timeout} s: {cmd}")


def _prepare_input(argv: list[str], workdir: Path, timeout: float) -> None:
    """The recording a ``knotmech diagnose FILE`` command reads: written by the README
    command that writes FILE, else a synthetic one."""
    if not (argv[1:3] == ["-m", "knotmech"] and len(argv) > 4 and argv[3] == "diagnose"):
        return
    rec = workdir / argv[4]
    if argv[4].startswith("-") or rec.exists():
        return
    writer = _writer_of(argv[4])
    if writer is None:
        _write_recording(rec)
        return
    proc = _run(writer, workdir, timeout)
    assert proc.returncode == 0, f"{writer}\nexit {proc.returncode}\n{proc.stderr[-1500:]}"


def _params():
    out = []
    for cmd in readme_commands():
        slow = any(m in cmd for m in SLOW_MARKERS)
        marks = [pytest.mark.slow] if slow else []
        out.append(pytest.param(cmd, SLOW_TIMEOUT if slow else QUICK_TIMEOUT, marks=marks,
                                id=cmd[:60]))  # fmt: skip
    return out


def test_the_readme_has_commands():
    """The parser finds the README's command lines (a README without them, or a parser
    that lost them, would make the test below vacuous)."""
    cmds = readme_commands()
    assert any(c.startswith("knotmech tour") for c in cmds)
    assert sum(c.startswith("knotmech ") for c in cmds) >= 5
    assert not any("pip install" in c or "pytest" in c or "sphinx" in c for c in cmds)


def test_the_readme_is_short():
    """The README gets a newcomer running; results and notes live on the docs site."""
    assert len(README.read_text(encoding="utf-8").splitlines()) < 300


@pytest.mark.parametrize(("cmd", "timeout"), _params())
def test_readme_command_runs(cmd, timeout, tmp_path):
    _env, argv, stdout = _argv(cmd, tmp_path)
    _prepare_input(argv, tmp_path, timeout)
    proc = _run(cmd, tmp_path, timeout)
    tail = ((proc.stdout or "")[-1500:] + "\n" + proc.stderr[-1500:]).strip()
    assert proc.returncode == 0, f"{cmd}\nexit {proc.returncode}\n{tail}"
    for name in _outputs(argv) + ([stdout] if stdout else []):
        assert (tmp_path / name).exists(), f"{cmd}: {name} was not written\n{tail}"
    if stdout:
        assert (tmp_path / stdout).stat().st_size > 0, f"{cmd}: {stdout} is empty"
    if "examples/cantilever.py" in cmd:  # its figure, in the scratch folder it writes by default
        assert (tmp_path / "knotmech-examples" / "cantilever.png").exists()
