# SPDX-License-Identifier: GPL-3.0-or-later
# Sphinx configuration of btob's documentation site.  Built by docs/tools/build.py (the CMake target `docs`), which
# stages this folder with the generated pages (command reference, performance, result schemas), the notebooks and
# CHANGELOG.md into <build>/docs/source and runs sphinx-build there, with the built Python package on sys.path.
import os

project = "btob"
author = "the btob developers"
copyright = "the btob developers; GPL-3.0-or-later"
version = release = os.environ.get("BTOB_VERSION", "")

extensions = [
    "myst_parser",          # pages in Markdown (MyST)
    "nbsphinx",             # the tutorials: analyses/notebooks, executed during the build
    "sphinx.ext.autodoc",   # the Python reference from the built module's docstrings
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",   # $...$ and $$...$$ rendered by MathJax, served from the site itself (below)
    "breathe",              # the C++ reference: Doxygen's XML of the installed headers (docs/tools/gen_cpp.py)
]
# Doxygen's XML, made by docs/tools/build.py before sphinx-build runs (BTOB_DOXYGEN_XML names its folder).
breathe_projects = {"btob": os.environ.get("BTOB_DOXYGEN_XML", "")}
breathe_default_project = "btob"
breathe_default_members = ("members",)
breathe_show_include = False  # each page states its header once, at the top

# Mathematics in the pages' LaTeX: $x$ inline, $$...$$ displayed (with (label) numbering), amsmath environments.
myst_enable_extensions = ["colon_fence", "deflist", "dollarmath", "amsmath"]
myst_dmath_double_inline = True
# MathJax offline: Debian's libjs-mathjax (2.7, setup.sh) is copied into the built site (_static/mathjax, the files
# the TeX-AMS_CHTML configuration loads: see offline_mathjax) and loaded from there, so no page fetches anything from
# the network (the browser test checks it).  A relative mathjax_path is relative to _static.
MATHJAX_DIR = "/usr/share/javascript/mathjax"
mathjax_path = "mathjax/MathJax.js?config=TeX-AMS_CHTML"
# MathJax 2 finds Sphinx's \(...\) and \[...\] in the math spans only (not a $ in a table of prices).
mathjax2_config = {
    "tex2jax": {"inlineMath": [["\\(", "\\)"]], "displayMath": [["\\[", "\\]"]], "processEscapes": True,
                "ignoreClass": "document", "processClass": "math|output_area"},
    "CommonHTML": {"linebreaks": {"automatic": True}},
    "showMathMenu": False,
    "messageStyle": "none",
}
nbsphinx_assume_equations = True  # the notebooks' Markdown may hold $...$: the same local MathJax
myst_heading_anchors = 3
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
# Included into other pages, never pages of their own:
exclude_patterns = ["_build", "examples/**", "**.ipynb_checkpoints", "results/**", "ARCHITECTURE.md", "README.md", "CHANGELOG.md",
                    "reference/outputs/**", "reference/csv/**", "reference/python_api.md", "performance_data.md", "paper_tables.md"]
suppress_warnings = ["myst.header"]

# Notebooks run during the build (a kernel per notebook, cells of seconds); an error in a cell fails the build.
nbsphinx_execute = "always"
nbsphinx_timeout = 300
nbsphinx_allow_errors = False
html_theme = "furo"
html_title = "btob"
html_static_path = ["_static"]
html_css_files = ["btob.css"]  # wrapped text blocks, scrolling tables and formulas
html_js_files = ["btob_search.js"]  # search results without page summaries when the site is opened from disk
html_show_sourcelink = False
autodoc_member_order = "bysource"
autodoc_typehints = "none"
# The notebooks need no widgets: no require.js from a CDN (the site must work offline).
nbsphinx_requirejs_path = ""


def offline_furo(app, exception):
    """Debian's furo ships its sources unbundled: furo.js is an ES module importing gumshoe-patched.js (a browser
    refuses module scripts from file:// pages), and furo.css imports normalize.css from the web server's
    /javascript/ (Debian's libjs path).  Bundle the two scripts into the classic script furo.js (gumshoe is UMD: it
    sets window.Gumshoe) and import the packaged normalize.css from beside furo.css, so the site works from disk."""
    if exception is not None or app.builder.format != "html":
        return
    import shutil
    scripts, styles = os.path.join(app.outdir, "_static", "scripts"), os.path.join(app.outdir, "_static", "styles")
    furo_js = os.path.join(scripts, "furo.js")
    text = open(furo_js).read() if os.path.exists(furo_js) else ""
    if text.startswith("import Gumshoe"):
        gumshoe = open(os.path.join(scripts, "gumshoe-patched.js")).read()
        with open(furo_js, "w") as f:
            f.write(gumshoe + "\n" + text.split("\n", 1)[1])
    furo_css = os.path.join(styles, "furo.css")
    css = open(furo_css).read() if os.path.exists(furo_css) else ""
    debian_normalize = "/usr/share/javascript/normalize.css/normalize.css"
    if "/javascript/normalize.css/normalize.css" in css and os.path.exists(debian_normalize):
        shutil.copy(debian_normalize, os.path.join(styles, "normalize.css"))
        with open(furo_css, "w") as f:
            f.write(css.replace("url(/javascript/normalize.css/normalize.css)", "url(normalize.css)"))


# What MathJax 2's TeX-AMS_CHTML configuration loads at run time, relative to its root: the loader, the combined
# configuration, the TeX input and MathML element jax, the CommonHTML output with its font data and the TeX web fonts
# (woff; CommonHTML needs no other format), and the extensions the configuration names (menu, zoom, a11y...).
MATHJAX_FILES = ["MathJax.js", "config/TeX-AMS_CHTML.js", "extensions", "jax/input/TeX", "jax/element",
                 "jax/output/CommonHTML", "fonts/HTML-CSS/TeX/woff"]


def offline_mathjax(app, exception):
    """Copies MATHJAX_FILES of Debian's libjs-mathjax into the site's _static/mathjax (following Debian's symbolic
    links to fonts-mathjax), so that the site is self-contained: it renders from disk or any web server, offline."""
    if exception is not None or app.builder.format != "html":
        return
    import shutil
    if not os.path.exists(os.path.join(MATHJAX_DIR, "MathJax.js")):
        raise RuntimeError(f"no MathJax at {MATHJAX_DIR}: apt-get install libjs-mathjax (setup.sh)")
    dest = os.path.join(app.outdir, "_static", "mathjax")
    for rel in MATHJAX_FILES:
        src, dst = os.path.join(MATHJAX_DIR, rel), os.path.join(dest, rel)
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        if os.path.isdir(src):
            shutil.copytree(src, dst, dirs_exist_ok=True)
        else:
            shutil.copy(src, dst)


def keyword_block(app, what, name, obj, options, lines):
    """The functions' docstrings are composed from each request's fields (python/bind.hpp): a summary, then
    "Keyword arguments (...):" and one indented line per field, written for help() in a terminal.  Show that list as
    a literal block, so a field's text (|C_N|, r^2n, ...) is not read as reStructuredText markup."""
    for i, line in enumerate(lines):
        if line.startswith("Keyword arguments") and line.rstrip().endswith(":"):
            lines[i] = line.rstrip() + ":"
            if i + 1 < len(lines) and lines[i + 1].strip():
                lines.insert(i + 1, "")
            return


def setup(app):
    app.connect("autodoc-process-docstring", keyword_block)
    app.connect("build-finished", offline_furo)
    app.connect("build-finished", offline_mathjax)
