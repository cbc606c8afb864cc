"""Sphinx configuration of the reading site (``make docs``). The sources are generated into
``docs/_build/src`` by ``docs/build_pages.py``; this folder holds only the configuration, the
style sheet and the hand-written tutorial texts. MathJax is served from the build (the copy
shipped by the ``django-static-mathjax`` package on PyPI): the site needs no network."""

from __future__ import annotations

import re
import shutil
import sys
from importlib import resources
from pathlib import Path

DOCS = Path(__file__).resolve().parent
sys.path.insert(0, str(DOCS))

from sitegen.tex import MACROS  # noqa: E402

import chaplygin_nd  # noqa: E402

project = "chaplygin-nd"
author = "The chaplygin-nd contributors"
copyright = "2026, the chaplygin-nd contributors (code: BSD-3-Clause; the paper: its author's)"
version = release = chaplygin_nd.__version__

extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.mathjax"]
myst_enable_extensions = ["dollarmath", "amsmath"]
myst_heading_anchors = 2
autodoc_member_order = "bysource"
autodoc_typehints = "description"
html_theme = "alabaster"
html_title = f"chaplygin-nd {version}"
html_theme_options = {"description": "the paper's claims, decided", "fixed_sidebar": False,
                      "page_width": "1200px"}
html_last_updated_fmt = None
html_static_path = [str(DOCS / "_static")]
html_css_files = ["site.css"]
suppress_warnings = ["myst.header"]

# MathJax 3 (SVG output: no web fonts to load), copied next to the build; the paper's macros.
_MATHJAX = DOCS / "_build" / "mathjax"
_MATHJAX.mkdir(parents=True, exist_ok=True)
shutil.copy(Path(str(resources.files("mathjax") / "static" / "mathjax" / "es5" / "tex-svg-full.js")),
            _MATHJAX / "tex-svg-full.js")
html_static_path.append(str(_MATHJAX))
mathjax_path = "tex-svg-full.js"
mathjax3_config = {
    "tex": {"macros": MACROS, "inlineMath": [["\\(", "\\)"]], "displayMath": [["\\[", "\\]"]]},
    "options": {"ignoreHtmlClass": "tex2jax_ignore|mathjax_ignore|document",
                "processHtmlClass": "tex2jax_process|mathjax_process|math|output_area"},
}

_DOLLARS = re.compile(r"(?<![\\$`])\$(?!\$)([^$]+?)\$")


def dollars_to_math(app, what, name, obj, options, lines):
    """Docstrings write maths as ``$...$`` (readable in a terminal); reST needs ``:math:``."""
    text = _DOLLARS.sub(lambda m: ":math:`" + m.group(1).replace("`", "") + "`", "\n".join(lines))
    lines[:] = text.split("\n")  # a formula may span lines; the line count is unchanged


def setup(app):
    app.set_html_assets_policy("always")  # MathJax on every page (claim statements are raw HTML)
    app.connect("autodoc-process-docstring", dollars_to_math)
