# Sphinx configuration of btob's documentation site.  Built by docs/tools/build.py (the CMake target `docs`), which
# stages this folder with the generated pages (command reference, performance, result schemas), the notebooks and
# CHANGELOG.md into <build>/docs/source and runs sphinx-build there, with the built Python package on sys.path.
import os

project = "btob"
author = "the btob authors"
copyright = "the btob authors"
version = release = os.environ.get("BTOB_VERSION", "")

extensions = [
    "myst_parser",          # pages in Markdown (MyST)
    "nbsphinx",             # the tutorials: analyses/notebooks, executed during the build
    "sphinx.ext.autodoc",   # the Python reference from the built module's docstrings
    "sphinx.ext.napoleon",
]
myst_enable_extensions = ["colon_fence", "deflist"]
# No TeX maths on the site: MathJax would load from a CDN, and the site must render offline (the browser test).
nbsphinx_assume_equations = False
myst_heading_anchors = 3
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
exclude_patterns = ["_build", "**.ipynb_checkpoints", "results/**", "ARCHITECTURE.md", "README.md"]
suppress_warnings = ["myst.header"]

# Notebooks run during the build (a kernel per notebook, cells of seconds); an error in a cell fails the build.
nbsphinx_execute = "always"
nbsphinx_timeout = 300
nbsphinx_allow_errors = False
html_theme = "furo"
html_title = "btob"
html_static_path = []
html_show_sourcelink = False
autodoc_member_order = "bysource"
autodoc_typehints = "none"
