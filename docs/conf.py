"""Sphinx configuration of the contactlab documentation.

Build (warnings are errors; the gallery scripts run during the build)::

    sphinx-build -W -b html docs docs/_build/html
"""
from __future__ import annotations

import os
import sys
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
os.environ.setdefault("MPLBACKEND", "Agg")

import contactlab  # noqa: E402

project = "contactlab"
author = "the contactlab developers"
copyright = "contactlab developers"
version = release = contactlab.__version__

extensions = [
    "myst_parser",
    "numpydoc",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.intersphinx",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "auto_examples/*.ipynb",
                    "auto_examples/*.py", "auto_examples/*.zip", "**.codeobj.json"]
templates_path = ["_templates"]

# --- MyST: the Markdown pages (docs/*.md, theory/, start/, about/)
myst_enable_extensions = ["dollarmath", "amsmath", "deflist", "colon_fence"]
myst_heading_anchors = 3
suppress_warnings = ["myst.header"]   # pages written for GitHub may start at a level-2 heading

# --- API reference from docstrings
autosummary_generate = True
autosummary_imported_members = True
autosummary_ignore_module_all = False
autodoc_default_options = {"members": True, "show-inheritance": False}
autodoc_typehints = "none"            # numpydoc shows the documented types and units
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()

intersphinx_mapping: dict = {}         # the build must not need the network

# --- gallery: every examples/gallery/plot_*.py runs during the build and renders its plots
sphinx_gallery_conf = {
    "examples_dirs": [str(ROOT / "examples" / "gallery")],
    "gallery_dirs": ["auto_examples"],
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "image_scrapers": ("matplotlib",),
    "matplotlib_animations": False,
    "reset_modules": ("matplotlib",),
    "show_memory": False,
    "plot_gallery": "True",
}

# --- the API reference page is generated from contactlab.__all__ and the Contact methods, so
# every public name (also those added later) is listed; tests/unit/test_docstrings.py checks it.
_SECTIONS = [
    ("The contact", "Compose a profile and two bodies; every effect is one method.",
     ["Contact"], []),
    ("Profiles and materials", "", ["Elastic", "Rigid", "effective_moduli"],
     ["contactlab.profiles", "contactlab.materials", "contactlab.materials.viscoelastic"]),
    ("Load paths", "", ["LoadPath"], ["contactlab.loadpath"]),
    ("Results", "Immutable result objects; each records its sources in ``.citations``.",
     ["NormalState", "AdhesiveNormalState", "AdhesionCycle", "TangentialState", "ShiftHistory",
      "TorsionState", "TwistHistory", "ViscoelasticHistory", "PathResult"], ["contactlab.effects"]),
    ("Plots", "One style for every ``plot()``; ``units=\"engineering\"`` for µm, mN·m, MPa.", [],
     ["contactlab.plotting"]),
    ("Citations", "", ["cite"], ["contactlab.citations"]),
    ("Scenes, studies and the command line", "", ["sweep"],
     ["contactlab.scene", "contactlab.sweeps", "contactlab.cli"]),
    ("Formulas", "", [], ["contactlab.symbolic"]),
    ("Plugins and conformance checks", "", ["register_profile", "register_material"],
     ["contactlab.registry", "contactlab.testing", "contactlab.params"]),
    ("The MDR foundation", "", [], ["contactlab.foundation"]),
    ("Errors and warnings", "", [], ["contactlab.errors"]),
    ("Numerics", "", [], ["contactlab.numeric"]),
]
_MODULE_NAMES = {"profiles", "materials", "errors", "foundation", "loadpath", "registry",
                 "citations"}


def _contact_members() -> list[str]:
    import inspect
    return [n for n, _ in inspect.getmembers(contactlab.Contact) if not n.startswith("_")]


def _write_api_index() -> None:
    placed = {n for _, _, names, _ in _SECTIONS for n in names}
    rest = [n for n in contactlab.__all__ if n not in placed and not n.startswith("__")
            and n not in _MODULE_NAMES]
    out = ["API reference", "=============", "",
           "Every public name of ``contactlab`` (``contactlab.__all__``) and every method of",
           ":class:`~contactlab.Contact`, from their numpydoc docstrings. Quantities are SI: m, N,",
           "Pa, rad, N*m, J, s. ``contactlab.__version__`` is the version string "
           f"(``{contactlab.__version__}``).", "", ".. currentmodule:: contactlab", ""]
    sections = list(_SECTIONS)
    if rest:
        sections.append(("More public names", "", rest, []))
    for title, text, names, modules in sections:
        out += [title, "-" * len(title), ""]
        if text:
            out += [text, ""]
        if title == "The contact":      # the class page without members: one page per method
            out += [".. autosummary::", "   :toctree: generated",
                    "   :template: class_nomembers", "   :nosignatures:", "", "   Contact", ""]
            names = [f"Contact.{m}" for m in _contact_members()]
        if names:
            out += [".. currentmodule:: contactlab", "", ".. autosummary::",
                    "   :toctree: generated", "   :nosignatures:", ""]
            out += [f"   {n}" for n in names] + [""]
        if modules:
            out += [".. autosummary::", "   :toctree: generated",
                    "   :template: module", "   :nosignatures:", ""]
            out += [f"   {m.removeprefix('contactlab.')}" for m in modules] + [""]
    text = "\n".join(out)
    path = Path(__file__).parent / "api" / "index.rst"
    path.parent.mkdir(exist_ok=True)          # docs/api/ is generated (not in a fresh checkout)
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


_write_api_index()
# module pages leave out what the top level already documents (one page per object)
autosummary_context = {"toplevel": [n for n in contactlab.__all__
                                    if not n.startswith("__") and n not in _MODULE_NAMES]}

# --- HTML
html_theme = "furo"
html_title = f"contactlab {release}"
html_static_path: list[str] = []
html_show_sourcelink = False

warnings.filterwarnings("ignore", category=UserWarning,
                        message="Matplotlib is currently using agg")
