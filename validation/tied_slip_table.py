"""The tied bends' and loops' slip loads over the friction coefficient mu (issue 25).

Each tied bend (:func:`knotmech.scenes.bends.bend`) and loop round a pin
(:func:`knotmech.scenes.loops.loop`) is pulled at its record's defaults (d = 4 mm,
E = 1 MPa, B/d^2 = 0.785 N; set to 0.1 B/d^2, pulled 20 d at 40 mm/s; protocol in
docs/notes/knots-and-curves/tied-knots-pulled.md and tied-loops-pulled.md) at a list of
mu, and one JSON per knot is written to ``docs/notes/knots-and-curves/slip-over-mu/``::

    {"knot": NAME, "loading": "...", "bending_scale": 1.0, "rows": {"0.1": row, ...}}

(``bending_scale`` absent means 1; a file with kappa != 1 is ``<knot>-kappa<k>.json``). A
run adds its rows to the knot's file. Rendering reads every ``*.json`` of the folder,
whoever wrote it, and writes the table (knot x mu: slip load, or "holds (to F)" with the
largest force, a lower bound of the slip load; CPU seconds of each run) between the
markers of docs/notes/knots-and-curves/tied-slip-over-mu.md, and the figures
docs/img/tied/slip_over_mu.png (load against mu) and docs/img/tied/slip_over_kappa.png (load
against the bending scale kappa at mu = 0.3, :data:`KAPPA_MU`, for each knot run at two or
more kappa)::

    OPENBLAS_NUM_THREADS=1 python -m validation.tied_slip_table --run \
        --knots sheet-bend,bowline --mu 0.1,0.3,0.6,1.0 [--bending-scale 0.01] \
        [--loading end-to-end]
    python -m validation.tied_slip_table            # --render (the default)

A pull stops when a pulled end reaches 0.1 EA (:data:`knotmech.scenes.bends.STRAIN_LIMIT`,
the rod model's strain limit); a knot that has not slipped by then *held to at least* that
load (the row's ``held_to_strain_limit``; the table's "strain limit").

As a validation case (``knotmech validate``) :func:`run` renders the committed JSON into
``out_dir`` without simulating anything.
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

from knotmech import knots
from knotmech.errors import InputError

from ._common import finish, save_figure

NAME = "tied_slip_table"
#: one sentence for the validation page: what this case checks, and against what
SUMMARY = (
    "The tied bends' and loops' DER slip loads over mu (committed runs), each knot's slip "
    "load or held lower bound against mu, set beside the published security orderings in "
    "docs/notes/knots-and-curves/tied-slip-over-mu.md."
)
ROOT = Path(__file__).resolve().parent.parent
FOLDER = ROOT / "docs" / "notes" / "knots-and-curves" / "slip-over-mu"
NOTE = ROOT / "docs" / "notes" / "knots-and-curves" / "tied-slip-over-mu.md"
FIGURE = ROOT / "docs" / "img" / "tied" / "slip_over_mu.png"
FIGURE_KAPPA = ROOT / "docs" / "img" / "tied" / "slip_over_kappa.png"
#: the friction coefficient of the bending-scale figure
KAPPA_MU = 0.3
START, END = "<!-- slip-table:start -->", "<!-- slip-table:end -->"
D = 4e-3  #: the scenes' default rope diameter [m]
#: the scenes' default axial stiffness EA [N] (E = 1 MPa): a force above
#: :data:`knotmech.verdict.inputs.STRAIN_LIMIT` EA stretches the rod beyond the model
EA = 1e6 * math.pi * D * D / 4


def _family(knot: str) -> str:
    """``"bend"`` or ``"loop"`` for a tied bend or loop; a one-line InputError otherwise."""
    from knotmech.scenes.loops import LOOPS

    tied = [k.name for k in knots.records(family="bend") if "scenes.tied." in k.curve]
    key = knots.key(knot) if isinstance(knot, str) else ""
    if key in tied:
        return "bend"
    if key in LOOPS:
        return "loop"
    raise InputError(f"knot must be a tied bend or loop ({', '.join(tied + list(LOOPS))}), "
                     f"got {knot!r}")  # fmt: skip


def _check(mu: float, bending_scale: float, pin_diameter: float) -> None:
    """One-line InputError for mu <= 0 or not finite, kappa outside (0, 1], pin <= 0."""
    for name, x, hi in (("mu", mu, math.inf), ("bending scale", bending_scale, 1.0),
                        ("pin diameter", pin_diameter, math.inf)):  # fmt: skip
        if not isinstance(x, int | float) or not math.isfinite(x) or not 0 < x <= hi:
            raise InputError(f"{name} must be a finite number in (0, {hi:g}], got {x!r}")


def slip_row(knot: str, mu: float, *, bending_scale: float = 1.0,
             pin_diameter: float = 0.02, loading: str = "loop") -> dict:  # fmt: skip
    """Pull one tied bend or loop at its defaults and return its row (plain JSON).

    Parameters
    ----------
    knot : str
        A tied bend (``sheet-bend`` ...) or loop (``bowline`` ...), or an alias.
    mu : float
        Rope-rope friction coefficient (static = kinetic; the pin's too for a loop).
    bending_scale : float
        kappa in (0, 1]: bending stiffness times the solid rod's (a rope ~ 0.01).
    pin_diameter : float [m]
        The loops' pin (default 20 mm = 5 d); not used by a bend.
    loading : str
        A loop's loading (``"loop"``, or ``"end-to-end"`` for the alpine butterfly); not
        used by a bend.

    Returns
    -------
    dict
        ``cpu_s`` (process CPU of the run [s]), ``steps``, ``newton_iterations``,
        ``rejected_steps``, ``nodes``, ``status``, ``message``, ``verdict``, ``slip_load_N``
        (None unless it slips), ``max_force_N``, ``frames_checked`` and the family's
        draw-in numbers (bends: ``tail_drawn``, ``came_undone``, ``roll_d``; loops:
        ``slipped_by``, ``tail_draw_in_d``, ``eye_growth_d``, ``pull_travel_d``,
        ``topology_preserved``).

    Raises
    ------
    InputError
        An unknown knot, a mu, kappa or pin diameter out of range (before any run).
    """
    family = _family(knot)
    _check(mu, bending_scale, pin_diameter)
    return (bend_row if family == "bend" else loop_row)(
        knot, mu, bending_scale=bending_scale, pin_diameter=pin_diameter,
        loading=loading)  # fmt: skip


def bend_row(knot: str, mu: float, *, bending_scale: float = 1.0, **_) -> dict:
    """The row of one bend pull (:func:`slip_row`; no input check here)."""
    from knotmech.scenes.bends import bend

    t = time.process_time()
    r = bend(knot, mu_rod_rod=mu, bending_scale=bending_scale)
    return {"cpu_s": time.process_time() - t, **r.summary(rod_diameter=D)}


def loop_row(knot: str, mu: float, *, bending_scale: float = 1.0,
             pin_diameter: float = 0.02, loading: str = "loop", **_) -> dict:  # fmt: skip
    """The row of one loop pull round a pin, or end to end (:func:`slip_row`; no input
    check here)."""
    from knotmech.scenes.loops import loop

    t = time.process_time()
    pin = None if loading == "end-to-end" else pin_diameter
    r = loop(knot, pin_diameter=pin, mu_rod_rod=mu, bending_scale=bending_scale,
             loading=loading)  # fmt: skip
    return {"cpu_s": time.process_time() - t, **r.summary(rod_diameter=D)}


def warm_up(family: str) -> None:
    """Compile the kernels by a tiny untimed pull, so the first row's CPU is the run's."""
    if family == "bend":
        from knotmech.scenes.bends import bend

        bend("sheet-bend", settle_time=0.01, set_travel=1e-4, pull_distance=1e-4, n_frames=10)
    else:
        from knotmech.scenes.loops import loop

        loop("bowline", pin_diameter=0.02, settle_time=0.01, set_travel=1e-3,
             pull_distance=1e-3, n_frames=10)  # fmt: skip


def file_for(knot: str, bending_scale: float = 1.0, folder=FOLDER, loading: str = "loop") -> Path:
    """``<folder>/<knot>.json``, or ``<knot>-kappa<k>.json`` for kappa != 1 (end to end:
    ``<knot>-end-to-end.json``)."""
    tail = "" if bending_scale == 1.0 else f"-kappa{bending_scale:g}"
    tail = ("-end-to-end" if loading == "end-to-end" else "") + tail
    return Path(folder) / f"{knots.key(knot)}{tail}.json"


def add_rows(knot: str, mus, *, bending_scale: float = 1.0, folder=FOLDER, log=print,
             loading: str = "loop") -> Path:  # fmt: skip
    """Run :func:`slip_row` at each mu and add the rows to the knot's file (written after
    each run, so a stopped batch keeps what it made)."""
    family = _family(knot)
    for mu in mus:
        _check(mu, bending_scale, 0.02)
    path = file_for(knot, bending_scale, folder, loading)
    data = json.loads(path.read_text()) if path.is_file() else {}
    # keys as this function writes them ("1", not "1.0"), so that a re-run replaces its row
    rows = {f"{float(m):g}": r for m, r in data.get("rows", {}).items()}
    named = loading if loading in _NAMED_LOADINGS else knots.get(knot).loading
    data = {"knot": knots.key(knot), "loading": named,
            "bending_scale": bending_scale, "rows": rows}  # fmt: skip
    for mu in mus:
        row = slip_row(knot, mu, bending_scale=bending_scale, loading=loading)
        data["rows"][f"{mu:g}"] = row
        data["rows"] = dict(sorted(data["rows"].items(), key=lambda kv: float(kv[0])))
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(data, indent=1) + "\n")
        log(f"{knot} ({family}) mu {mu:g} kappa {bending_scale:g}: {_cell(row)}")
    return path


def read_folder(folder=FOLDER) -> list[dict]:
    """Every ``*.json`` of the folder with ``knot`` and ``rows``, sorted by knot, then
    bending scale from 1 down."""
    out = []
    for p in sorted(Path(folder).glob("*.json")):
        data = json.loads(p.read_text())
        if not isinstance(data, dict) or "knot" not in data or "rows" not in data:
            raise InputError(f"{p.name}: not a slip-over-mu file (needs 'knot' and 'rows')")
        out.append(data)
    return sorted(out, key=lambda d: (d["knot"], -(d.get("bending_scale") or 1.0)))


#: loadings named in a row's label (a loop's default, round the pin, is not)
_NAMED_LOADINGS = ("end-to-end",)


def _label(data: dict) -> str:
    kappa = data.get("bending_scale", 1.0)
    loading = data.get("loading", "")
    return (
        data["knot"]
        + (f" ({loading.replace('-', ' ')})" if loading in _NAMED_LOADINGS else "")
        + ("" if kappa in (None, 1, 1.0) else f" (kappa {kappa:g})")
    )


def _fmt(x) -> str:
    return "?" if x is None else f"{x:.3g}"


def _cell(row: dict) -> str:
    """``0.0347 (8.9 s)``, ``holds (to 0.505) (11 s)``, ``failed (12 s)`` or ``came apart in
    the set (2.7 s)`` (a knot fallen apart before the pull: no slip load)."""
    cpu = row.get("cpu_s")
    cost = "" if cpu is None else f" ({cpu:.0f} s)" if cpu >= 10 else f" ({cpu:.1f} s)"
    if row.get("status") not in (None, "success"):
        apart = str(row.get("message", "")).startswith("came apart before the pull")
        return f"{'came apart in the set' if apart else 'failed'}{cost}"
    if row.get("verdict") == "slips" and row.get("slip_load_N") is not None:
        undone = " undone" if row.get("came_undone") else ""
        return f"{_fmt(row['slip_load_N'])}{undone}{cost}"
    if row.get("verdict") == "holds" and row.get("held_to_strain_limit"):
        return f"holds (to {_fmt(row.get('max_force_N'))}, strain limit){cost}"
    if row.get("verdict") == "holds":
        return f"holds (to {_fmt(row.get('max_force_N'))}{_stretched(row)}){cost}"
    return f"{row.get('verdict') or '?'}{cost}"


def _stretched(row: dict) -> str:
    """`` *`` when the row's largest force strains the rod of its bending scale's run beyond
    :data:`knotmech.verdict.inputs.STRAIN_LIMIT` (E = 1 MPa, d = 4 mm), else ""."""
    from knotmech.verdict.inputs import STRAIN_LIMIT

    f = row.get("max_force_N")
    return " *" if f is not None and f > STRAIN_LIMIT * EA else ""


def table(files: list[dict]) -> str:
    """The markdown table: one line per file (knot, kappa), one column per mu."""
    mus = sorted({float(m) for f in files for m in f["rows"]})
    head = "| knot | " + " | ".join(f"mu = {m:g}" for m in mus) + " |"
    lines = [head, "|---" * (len(mus) + 1) + "|"]
    for f in files:
        rows = {float(m): r for m, r in f["rows"].items()}
        cells = [_cell(rows[m]) if m in rows else "-" for m in mus]
        lines.append(f"| {_label(f)} | " + " | ".join(cells) + " |")
    if any(r.get("held_to_strain_limit") for f in files for r in f["rows"].values()):
        lines.append("")
        lines.append(
            "strain limit: the pull stopped when a pulled end reached 0.1 EA (1.26 N at "
            "E = 1 MPa, d = 4 mm; 10 % strain, the rod model's limit) before the knot "
            "slipped: it held to at least the load shown (the pull force there), a lower "
            "bound of its slip load."
        )
    if any(_stretched(r) and not r.get("held_to_strain_limit")
           for f in files for r in f["rows"].values()):  # fmt: skip
        lines.append("")
        lines.append(
            "\\* the pull ended above 10 % strain (force > 0.1 EA = 1.26 N at E = 1 MPa, "
            "d = 4 mm): the knot locked and the rod was stretched beyond the rod model's "
            'validity; read it as "held to at least 1.26 N", not as the load shown.'
        )
    return "\n".join(lines)


def write_table(files: list[dict], note=NOTE) -> Path:
    """Put :func:`table` between the markers of ``note`` (created with them if absent)."""
    note = Path(note)
    text = note.read_text() if note.is_file() else f"{START}\n{END}\n"
    if START not in text or END not in text:
        raise InputError(f"{note}: the markers {START} and {END} are missing")
    head, rest = text.split(START, 1)
    tail = rest.split(END, 1)[1]
    note.write_text(f"{head}{START}\n{table(files)}\n{END}{tail}")
    return note


def points(data: dict) -> tuple[list, list, list]:
    """(mu, force [N], held?) of a file's successful runs: the slip load, or the largest
    force of a run that held (a lower bound)."""
    out = []
    for m, r in data["rows"].items():
        if r.get("status") not in (None, "success"):
            continue
        if r.get("verdict") == "slips" and r.get("slip_load_N") is not None:
            out.append((float(m), r["slip_load_N"], False))
        elif r.get("verdict") == "holds" and r.get("max_force_N") is not None:
            out.append((float(m), r["max_force_N"], True))
    out.sort()
    return [p[0] for p in out], [p[1] for p in out], [p[2] for p in out]


def figure(files: list[dict]):
    """Slip load against mu, one line per file (a colour per knot, dashed for a bending scale
    other than 1); held runs as open triangles (lower bounds), failed runs as crosses at
    their largest force (not joined)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.4, 4.6))
    ax = fig.add_subplot()
    names = sorted({f["knot"] for f in files})  # one colour per knot, dashed for kappa != 1
    for f in files:
        mu, force, held = points(f)
        colour = f"C{names.index(f['knot']) % 10}"
        ls = "-" if f.get("bending_scale", 1.0) in (None, 1, 1.0) else "--"
        ax.plot(mu, force, ls, color=colour, label=_label(f))
        for x, y, h in zip(mu, force, held, strict=True):
            ax.plot([x], [y], "^" if h else "o", color=colour, mfc="none" if h else colour)
        for m, r in f["rows"].items():
            if r.get("status") not in (None, "success") and r.get("max_force_N"):
                ax.plot([float(m)], [r["max_force_N"]], "x", color=colour)
    ax.set_yscale("log")
    ax.set_xlabel("rope-rope friction coefficient mu")
    ax.set_ylabel("slip load [N]\n(open triangle: held to; x: run failed, largest force)")
    ax.set_title("Tied bends and loops, d = 4 mm, E = 1 MPa (B/d$^2$ = 0.785 N)", fontsize=9)
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    return fig


def kappa_points(files: list[dict], mu: float = KAPPA_MU) -> dict:
    """``{(knot, loading): [(kappa, force [N], held?), ...]}`` at ``mu``, sorted by kappa,
    for each knot and named loading (end to end; "" for a knot's own) with successful runs
    at two or more bending scales (the slip load, or the largest force of a run that held:
    a lower bound)."""
    out = {}
    for f in files:
        row = f["rows"].get(f"{mu:g}")
        if row is None or row.get("status") not in (None, "success"):
            continue
        if row.get("verdict") == "slips" and row.get("slip_load_N") is not None:
            point = (row["slip_load_N"], False)
        elif row.get("verdict") == "holds" and row.get("max_force_N") is not None:
            point = (row["max_force_N"], True)
        else:
            continue
        loading = f.get("loading", "")
        key = (f["knot"], loading if loading in _NAMED_LOADINGS else "")
        out.setdefault(key, []).append((float(f.get("bending_scale") or 1.0), *point))
    return {k: sorted(v) for k, v in out.items() if len(v) >= 2}


def kappa_figure(files: list[dict], mu: float = KAPPA_MU):
    """Slip load against the bending scale kappa at ``mu`` (log x), one line per knot: in
    units of :math:`B/d^2` (B = kappa E pi d^4/64, the run's own bending stiffness; left)
    and of EA (right, the strain the load puts on the rod; 0.1 is the rod model's strain
    limit). Held runs are open markers with an up arrow (lower bounds); a knot run at two
    bending scales only is joined by a dotted line."""
    from matplotlib.figure import Figure

    b1 = 1e6 * math.pi * D**4 / 64 / D**2  # B/d^2 [N] of the solid rod (kappa = 1)
    fig = Figure(figsize=(9.0, 4.2))
    axes = fig.subplots(1, 2)
    for i, ((knot, _), pts) in enumerate(sorted(kappa_points(files, mu).items())):
        kappa = [p[0] for p in pts]
        for ax, scale in zip(axes, ([b1 * k for k in kappa], [EA] * len(kappa)), strict=True):
            y = [p[1] / s for p, s in zip(pts, scale, strict=True)]
            # two points only (kappa 1 and 0.01): dotted, nothing measured between them
            ax.plot(kappa, y, "-" if len(pts) > 2 else ":", color=f"C{i}", label=knot)
            for x, v, (_, _, held) in zip(kappa, y, pts, strict=True):
                ax.plot([x], [v], "o", color=f"C{i}", mfc="none" if held else f"C{i}")
                if held:
                    ax.annotate("", xy=(x, v * 1.7), xytext=(x, v),
                                arrowprops={"arrowstyle": "->", "color": f"C{i}"})  # fmt: skip
    axes[1].axhline(0.1, color="0.5", ls=":", label="0.1 EA (strain limit)")
    for ax, unit in zip(axes, ("kappa B/d$^2$", "EA"), strict=True):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("bending scale kappa (B = kappa E pi d$^4$/64)")
        ax.set_ylabel(f"slip load / {unit}\n(open, arrow: held to at least)")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7, loc="best")
    fig.suptitle(f"Slip load against the bending scale, mu = {mu:g}, d = 4 mm, E = 1 MPa "
                 "(EA = 12.6 N)", fontsize=9)  # fmt: skip
    fig.tight_layout()
    return fig


def render(folder=FOLDER, note=NOTE, image=FIGURE, image_kappa=None) -> dict:
    """Read every file of ``folder``, write the table into ``note`` and the two figures
    (``image_kappa`` by default :data:`FIGURE_KAPPA` with the default ``image``, else
    ``slip_over_kappa.png`` beside ``image``)."""
    if image_kappa is None:
        same = Path(image) == FIGURE
        image_kappa = FIGURE_KAPPA if same else Path(image).with_name(FIGURE_KAPPA.name)
    files = read_folder(folder)
    write_table(files, note)
    Path(image).parent.mkdir(parents=True, exist_ok=True)
    figure(files).savefig(image, dpi=110)
    kappa_figure(files).savefig(image_kappa, dpi=110)
    return {"files": len(files), "note": str(note), "figure": str(image),
            "figure_kappa": str(image_kappa)}  # fmt: skip


def run(quick: bool = True, out_dir=".") -> dict:
    """Validation case: render the committed runs into ``out_dir`` (no simulation).

    Checks: every knot holds at least as much at its largest mu as at its smallest (a held
    run counting as its lower bound): friction holds a knot harder. Where the load falls by
    more than 10 % from one mu to the next larger, a note says so (the double fisherman's
    comes undone at 0.165 N at mu = 0.3 and slips at 0.124 N at 0.6: one run a point).
    """
    files = read_folder()
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    (out / f"{NAME}.md").write_text(table(files) + "\n")
    fig = save_figure(figure(files), out, NAME)
    checks, falls = {}, []
    for f in files:
        mu, force, _ = points(f)
        if len(force) < 2:
            continue
        checks[f"{_label(f)}: holds more at mu {mu[-1]:g} than at {mu[0]:g}"] = (
            force[-1] >= force[0]
        )
        steps = zip(mu, mu[1:], force, force[1:], strict=False)
        falls += [f"{_label(f)}: {a:.3g} N at mu {m0:g}, {b:.3g} N at mu {m1:g}"
                  for m0, m1, a, b in steps if b < 0.9 * a]  # fmt: skip
    numbers = {_label(f): {m: _cell(r) for m, r in f["rows"].items()} for f in files}
    notes = ["renders the committed runs; python -m validation.tied_slip_table --run makes them"]
    if falls:
        notes.append("falls with mu by more than 10 % (one run a point): " + "; ".join(falls))
    return finish(NAME, out_dir=out, checks=checks, numbers=numbers, figures=[fig],
                  quick=quick, notes=notes)  # fmt: skip


def _floats(text: str) -> list[float]:
    try:
        return [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise InputError(f"--mu must be comma-separated numbers, got {text!r}") from None


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--run", action="store_true", help="pull --knots at each --mu, then render")
    p.add_argument("--render", action="store_true", help="render the folder (the default)")
    p.add_argument("--knots", default="", help="comma-separated tied bends and loops")
    p.add_argument("--mu", default="0.1,0.3,0.6,1.0")
    p.add_argument("--bending-scale", type=float, default=1.0)
    p.add_argument(
        "--loading",
        default="loop",
        help="the loops' loading: loop (default) or end-to-end (alpine butterfly)",
    )
    a = p.parse_args(argv)
    try:
        if a.run:
            names = [k for k in a.knots.split(",") if k]
            if not names:
                raise InputError("--run needs --knots K1,K2,...")
            mus = _floats(a.mu)
            fams = [_family(k) for k in names]
            for fam in dict.fromkeys(fams):
                warm_up(fam)
            for k in names:
                add_rows(k, mus, bending_scale=a.bending_scale, loading=a.loading)
        print(json.dumps(render()))
    except InputError as e:
        print(f"error: {e}")
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
