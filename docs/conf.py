"""Sphinx configuration of the rollspring documentation site (``make docs``).

Why Sphinx: it is what the scientific-Python packages rollspring's users already read are built
with (NumPy, SciPy, SymPy and MuJoCo's documentation are Sphinx sites), and it gives, from one
tool: MyST Markdown pages (``docs/*.md``, which GitHub renders too), the API reference from the
docstrings (``sphinx.ext.autodoc`` with ``napoleon``), the command-line reference generated from
the commands themselves (``docs/_ext/rollspring_docs.py``) and a gallery of examples executed at
build time with their figures (``sphinx-gallery``). ``make docs`` builds it with warnings as errors.

Math is rendered in the reader's browser by MathJax 3, served from the site itself: the Makefile
installs the pinned npm package (``docs/package.json``, ``docs/package-lock.json``) and this file
copies its single self-contained bundle (``tex-svg-full.js``: every TeX extension and the SVG
glyphs in one file, no font files to fetch) into ``_static``. So the built site makes no
request to any other host and works offline. (The alternative, ``sphinx.ext.imgmath``, needs
``dvipng``/``dvisvgm`` on every machine that builds, and renders formulas as images that do not
scale or copy as text.)
"""

from __future__ import annotations

import os
import shutil
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(DOCS / "_ext"))

# Quiet, deterministic example runs: no progress bars, a fixed Matplotlib backend.
os.environ.setdefault("MPLBACKEND", "Agg")

from importlib.metadata import version as _version  # noqa: E402

project = "rollspring"
author = "the rollspring authors"
copyright = "the rollspring authors; MIT licence"  # noqa: A001
release = _version("rollspring")
version = release

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
    "rollspring_docs",  # docs/_ext: the generated pages (API, CLI, paper check)
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = [
    "README.md",  # how to build the site, for people reading the repository
    "_generated/cli.md",  # included by cli.md
    "node_modules",
    "_build",
    "gallery/*.ipynb",
    "tutorial/*.ipynb",
    "gallery/sg_execution_times.rst",
    "tutorial/sg_execution_times.rst",
]
templates_path: list[str] = []

# -- MyST ----------------------------------------------------------------------------------------
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_dmath_double_inline = True
myst_heading_anchors = 3

# -- math: MathJax from the pinned npm package, served from _static ------------------------------
MATHJAX_BUNDLE = DOCS / "node_modules" / "mathjax" / "es5" / "tex-svg-full.js"
_STATIC_BUILD = ROOT / "build" / "docs" / "static"
if MATHJAX_BUNDLE.is_file():
    (_STATIC_BUILD / "mathjax").mkdir(parents=True, exist_ok=True)
    shutil.copyfile(MATHJAX_BUNDLE, _STATIC_BUILD / "mathjax" / "tex-svg-full.js")
else:  # a clear message instead of a site with raw TeX
    raise RuntimeError(f"{MATHJAX_BUNDLE} is missing: run `make docs` (it runs npm ci in docs/)")
mathjax_path = "mathjax/tex-svg-full.js"
mathjax3_config = {
    "tex": {"tags": "ams"},
    # the accessibility menu would load further components on demand: keep the page self-contained
    "options": {"enableMenu": False},
}

# -- HTML ----------------------------------------------------------------------------------------
html_theme = "furo"
html_title = f"rollspring {release}"
html_static_path = [str(_STATIC_BUILD)]
html_show_sourcelink = False
html_last_updated_fmt = None

# -- autodoc -------------------------------------------------------------------------------------
autodoc_default_options = {
    "members": True,
    # pydantic's machinery, not rollspring's API
    "exclude-members": "model_config, model_fields, model_computed_fields, model_post_init",
}
autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_typehints_format = "short"
autodoc_preserve_defaults = True
napoleon_google_docstring = True
napoleon_numpy_docstring = True

# -- sphinx-gallery: every example runs at build time and its figures are kept ------------------
sphinx_gallery_conf = {
    "examples_dirs": [str(ROOT / "examples" / "tutorial"), str(ROOT / "examples" / "gallery")],
    "gallery_dirs": ["tutorial", "gallery"],
    "filename_pattern": r"/plot_",
    "ignore_pattern": r"__init__\.py",
    "download_all_examples": False,
    "remove_config_comments": True,
    "image_scrapers": ("matplotlib",),
    "reset_modules": ("matplotlib",),
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "show_memory": False,
    "show_signature": False,
    "min_reported_time": 3600,
    "write_computation_times": False,
    "plot_gallery": "True",
    "within_subsection_order": "FileNameSortKey",
    "matplotlib_animations": False,
    "capture_repr": ("_repr_html_", "__repr__"),
}
