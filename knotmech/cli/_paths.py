"""Checks of the files a command will write, made before any work starts.

A command that runs for a minute and then fails to write its report (a missing
folder, a directory given as a file name, ``/dev/full``, an image format
matplotlib cannot draw) has wasted the minute and usually shows a traceback.
Every subcommand therefore calls :func:`check_output_path` on each output option
first, and wraps the writing itself in :func:`writing`, so that a failure that
could not be foreseen (a full disk) is still one line and exit status 2.

Example::

    from knotmech.cli._paths import check_output_path, plot_formats, writing

    json_path = check_output_path(args.json, option="--json")
    plot_path = check_output_path(args.plot, formats=plot_formats(), option="--plot")
    ...
    with writing(json_path, option="--json"):
        report.write_json(json_path)
"""

from __future__ import annotations

import contextlib
import os
import stat
from collections.abc import Iterable
from pathlib import Path

from knotmech.errors import InputError

__all__ = ["check_output_path", "plot_formats", "writing"]


def plot_formats() -> tuple[str, ...]:
    """File extensions matplotlib can save a figure as, lower case, without the dot.

    Returns
    -------
    tuple of str
        For example ``("eps", "jpeg", "jpg", "pdf", "png", ...)``; taken from the
        installed matplotlib (imported here, lazily: about 0.2 s).

    Raises
    ------
    InputError
        matplotlib is not installed.
    """
    try:
        from matplotlib.backend_bases import FigureCanvasBase
    except ImportError:  # pragma: no cover - matplotlib is a dependency
        raise InputError("drawing a plot needs matplotlib (pip install matplotlib)") from None
    return tuple(sorted(FigureCanvasBase.get_supported_filetypes()))


def check_output_path(path, *, formats: Iterable[str] | None = None, option: str = "--json"):
    """Check that a command will be able to write ``path``; return it as a Path.

    Called on every output option before a command starts its work. Nothing is
    created or written.

    Parameters
    ----------
    path : str or os.PathLike or None
        The file name the user gave. ``None`` (option not given) is returned as is.
    formats : iterable of str, optional
        Accepted file extensions (case-insensitive, with or without the dot), for
        example :func:`plot_formats`. ``None``: any extension, or none.
    option : str
        The option's name as the user typed it, used in the message (``"--json"``,
        ``"--plot"``, ``"--csv"``...).

    Returns
    -------
    pathlib.Path or None

    Raises
    ------
    InputError
        One line naming the option and the path, when: the name is empty or ``-``
        (standard output, which only ``hold --json`` writes to); it is an
        existing directory (or ends in a path separator); its folder does not exist,
        is not a folder or is not writable; it exists but is not a regular file
        (``/dev/full``, a FIFO) or is not writable; or, with ``formats``, its
        extension is missing or not among them.
    """
    if path is None:
        return None
    text = os.fspath(path)
    if not isinstance(text, str) or not text.strip():
        raise InputError(f"{option}: empty file name")
    if text == "-":  # read by check_distinct and hold --json as standard output
        raise InputError(
            f"{option} -: this output is a file, not standard output; give a file name"
        )
    p = Path(text)
    where = f"{option} {text}"
    if text.endswith(("/", os.sep)) or p.is_dir():
        raise InputError(f"{where}: is a directory; give a file name")
    if formats is not None:
        _check_format(p, formats, where)
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.exists():
        raise InputError(f"{where}: folder {parent} does not exist")
    if not parent.is_dir():
        raise InputError(f"{where}: {parent} is not a folder")
    if p.exists() or p.is_symlink():
        _check_existing(p, where)
    elif not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(f"{where}: folder {parent} is not writable")
    return p


def _check_format(p: Path, formats: Iterable[str], where: str) -> None:
    """The extension of ``p`` is one of ``formats`` (case-insensitive, dot or not)."""
    allowed = sorted({f.lower().lstrip(".") for f in formats})
    ext = p.suffix.lower().lstrip(".")
    if not ext:
        raise InputError(f"{where}: no file extension; use one of {', '.join(allowed)}")
    if ext not in allowed:
        raise InputError(f"{where}: unsupported format '.{ext}'; use one of {', '.join(allowed)}")


def _check_existing(p: Path, where: str) -> None:
    """An existing ``p`` is a writable regular file."""
    try:
        mode = p.stat().st_mode
    except OSError as exc:  # dangling symlink, permission
        raise InputError(f"{where}: cannot be written ({exc.strerror or exc})") from None
    if not stat.S_ISREG(mode):
        raise InputError(f"{where}: exists and is not a regular file")
    if not os.access(p, os.W_OK):
        raise InputError(f"{where}: file is not writable")


def check_distinct(outputs) -> None:
    """Refuse two outputs to one file (the second would overwrite the first).

    Parameters
    ----------
    outputs : iterable of (str, path or None)
        (option as the user typed it, the path it names); None (not given) and ``-``
        (standard output) are skipped.

    Raises
    ------
    InputError
        One line naming both options and the file.
    """
    seen = {}
    for option, path in outputs:
        if path is None or os.fspath(path) == "-":
            continue
        key = os.path.realpath(os.fspath(path))
        if key in seen:
            raise InputError(
                f"{seen[key]} and {option} name the same file {os.fspath(path)}: give each "
                "output its own file"
            )
        seen[key] = option


@contextlib.contextmanager
def writing(path, *, option: str = "--json"):
    """Context manager turning an OSError while writing ``path`` into one InputError line.

    For what :func:`check_output_path` cannot foresee: a disk that fills up, a
    folder removed while the command ran.

    Parameters
    ----------
    path : str or os.PathLike
        The file being written (for the message).
    option : str
        The option's name, for the message.
    """
    try:
        yield
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        raise InputError(f"{option} {os.fspath(path)}: could not write ({reason})") from None
