"""Sphinx configuration of the knotmech documentation site.

Build it from the checkout's root (``tests/test_docs.py`` does, with warnings as errors)::

    python -m pip install -e ".[docs]"
    python -m sphinx -W --keep-going -b html docs docs/_build/html

Pages are Markdown (MyST); the API reference is generated from the numpydoc docstrings
(``docs/api/``, one page per public module: adding a subpackage is one four-line file
there). The classroom notebooks, kept as jupytext percent scripts in ``notebooks/``, are
converted to ``docs/_notebooks/*.ipynb`` at build time and rendered without executing.
"""

from __future__ import annotations

import sys
from pathlib import Path

import jupytext

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(ROOT))  # the checkout's knotmech, also when not installed

project = "knotmech"
author = "the knotmech developers"
copyright = "2026, the knotmech developers"  # noqa: A001 (Sphinx's name)

extensions = [
    "myst_nb",  # Markdown pages (MyST) and notebooks
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
]

# --- sources -------------------------------------------------------------------------
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
exclude_patterns = ["_build", "figures/*.py", "**/.ipynb_checkpoints"]
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence"]
myst_heading_anchors = 3
# notebooks: rendered as they are stored (no outputs); executing them takes minutes
nb_execution_mode = "off"

# --- API reference ---------------------------------------------------------------------
autodoc_default_options = {"members": True, "member-order": "bysource"}
autodoc_typehints = "none"  # the numpydoc sections give types and units
numpydoc_show_class_members = False
numpydoc_validation_checks: set[str] = set()
autosummary_generate = False

# --- output ----------------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = "knotmech"
html_theme_options = {
    "navigation_depth": 2,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
}
html_static_path: list[str] = []


def _notebooks() -> None:
    """Convert ``notebooks/*.py`` (jupytext percent format) to ``docs/_notebooks/*.ipynb``."""
    out = DOCS / "_notebooks"
    out.mkdir(exist_ok=True)
    for script in sorted((ROOT / "notebooks").glob("*.py")):
        target = out / f"{script.stem}.ipynb"
        text = jupytext.writes(jupytext.read(script), fmt="ipynb")
        if not target.exists() or target.read_text(encoding="utf-8") != text:
            target.write_text(text, encoding="utf-8")


_notebooks()
