"""Validation cases: theory and simulation side by side (not part of the wheel).

Each module ``validation/<name>.py`` (names starting with ``_`` are helpers) is
one case of issue 6. It exposes

``run(quick=True, out_dir=".", **options) -> dict``

which computes, writes its figures (PNG) and ``<out_dir>/<name>.json``, and
returns a summary with at least

- ``name``: the module name,
- ``verdict``: ``"pass"`` or ``"fail"`` (every entry of ``checks`` true),
- ``figures``: list of PNG paths,
- ``numbers``: the numbers its test asserts (plain floats, lists, strings),

and, by convention, ``checks`` (check name -> bool), ``notes`` (sentences a reader
needs: assumptions, what is missing) and ``quick``. Optional keyword options a
case may accept: ``scheduler`` (Dask address for its sweeps) and ``progress``.

Run them all with ``knotmech validate --quick --out DIR`` (index page in
``DIR/index.html``), or one with ``python -m validation.<name> --out DIR`` from
the repository root. Helpers are in :mod:`validation._common`.
"""
