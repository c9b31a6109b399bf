"""Sphinx configuration of pinlin's documentation (build: see index.md, "Building these pages").

Sphinx with autodoc and numpydoc, MyST for the Markdown pages, MyST-NB for the
notebooks: the stored notebooks (``notebooks/*.ipynb``) are rendered from their
outputs, never executed here; the user-guide pages are MyST text notebooks whose
``{code-cell}`` examples run during the build and show their output (an example
that raises fails the build). The package documented, and imported by those
examples, is the one of this source tree (``../src``), whatever is installed.
Math is rendered by MathJax served from the built pages themselves
(``sphinx-mathjax-offline``), never from a CDN. Strict:
``sphinx-build -W`` turns every warning into an error, and numpydoc's
validation warns when a docstring's Parameters drift from the signature
(PR01: a parameter not documented; PR02: a documented parameter that does not exist).
Nitpicky: every cross-reference must resolve.  References to pinlin's names link to the
one place each object is described (:func:`resolve_pinlin_names`); Python's and numpy's
names link to their sites through intersphinx inventories bundled in ``_inventories/``
(written offline by ``_inventories/make_inventories.py`` with Sphinx's own inventory
writer, holding only the names these pages reference, each at its real address).
No network: no inventory is fetched, no remote images, no CDN scripts.
"""

from __future__ import annotations

import contextlib
import importlib
import inspect
import io
import logging as std_logging
import os
import pkgutil
import re
import sys
from pathlib import Path

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import make_refnode

#: This tree's sources: documented by autodoc and imported by the executed examples (their kernels
#: inherit PYTHONPATH), ahead of any installed pinlin (an editable install may point at another tree).
SRC = Path(__file__).resolve().parents[1] / "src"
sys.path.insert(0, str(SRC))
os.environ["PYTHONPATH"] = os.pathsep.join([str(SRC), *filter(None, [os.environ.get("PYTHONPATH")])])

import pinlin  # noqa: E402

if Path(pinlin.__file__).resolve().parents[1] != SRC:
    raise ImportError(f"the docs would document {pinlin.__file__}, not this tree's {SRC}")

#: The executed pages' kernels show their figures inline (their output); this process, which runs the
#: remaining ```python blocks, needs no display (its figures are drawn and closed).
os.environ["MPLBACKEND"] = "module://matplotlib_inline.backend_inline"
std_logging.getLogger("matplotlib.animation").setLevel(std_logging.WARNING)  # its INFO line per saved animation

project = "pinlin"
author = "pinlin developers"
copyright = "pinlin developers"
release = version = pinlin.__version__

#: ``sphinx-mathjax-offline`` sets ``mathjax_path`` to its bundled MathJax 3 and copies it into ``_static``.
extensions = ["sphinx.ext.autodoc", "sphinx.ext.intersphinx", "sphinx.ext.mathjax", "sphinx-mathjax-offline", "numpydoc", "myst_nb"]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
root_doc = "index"
#: Every cross-reference must resolve: a name that is not a link is an error under -W.
nitpicky = True
#: External names that have no inventory to link to: Pinocchio's classes (its documentation is Doxygen's,
#: with no intersphinx inventory), and the pieces Sphinx makes of a subscripted annotation such as
#: ``tuple[str, ...]`` (``tuple[str``).  No pinlin name may be listed here.
nitpick_ignore_regex = [(r"py:class", r"pinocchio\..*"), (r"py:class", r"[\w.]+\[.*")]
#: The bundled inventories (see the module docstring); the build never downloads one.
intersphinx_mapping = {
    "python": ("https://docs.python.org/3", "_inventories/python.inv"),
    "numpy": ("https://numpy.org/doc/stable", "_inventories/numpy.inv"),
}
exclude_patterns = ["_build", "_inventories", "notebooks/README.md", "README.md", "**/.ipynb_checkpoints"]
html_theme = "furo"
html_title = f"pinlin {release}"
html_static_path: list[str] = []

# --- autodoc: signatures from the code, descriptions from the docstrings
autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_preserve_defaults = True

# --- numpydoc: the docstring format and its check against the signature
numpydoc_show_class_members = False
numpydoc_xref_param_type = False
numpydoc_validation_checks = {"PR01", "PR02"}
#: Objects left out of the signature check, each with its reason (regular expressions on the full name).
numpydoc_validation_exclude = {
    r"\.__init__$",  # constructors are documented in their class docstring's Parameters
    # Docstrings to fix in their own files (then remove the line):
    r"^pinlin\.linearization\.Evaluation$",  # model/evaluation.py: parameter ``at_rest`` not documented
}
#: Checks skipped for docstrings matching a pattern (``re.search`` on the raw docstring):
#: - a class documenting ``Attributes`` (the result dataclasses, built by pinlin and read by users) has its
#:   fields as constructor parameters by construction: skip PR01 and PR02;
#: - a docstring without a Parameters section (a one-line accessor, a private helper made public) has nothing
#:   to drift: skip PR01.  Once a docstring lists parameters, it must list all of them, and only them.
_ATTRIBUTES = r"Attributes\n\s*-{5,}"
_NO_PARAMETERS = r"\A(?![\s\S]*Parameters\n\s*-{5,})"
numpydoc_validation_overrides = {"PR01": [_ATTRIBUTES, _NO_PARAMETERS], "PR02": [_ATTRIBUTES]}

# --- MyST and MyST-NB: $...$ and $$...$$ math (amsmath environments too), labelled equations;
# the text notebooks of the guide are executed, the stored notebooks rendered as they are
myst_enable_extensions = ["dollarmath", "amsmath"]
myst_dmath_double_inline = True
nb_execution_mode = "force"
nb_execution_excludepatterns = ["notebooks/*"]  # stored with their outputs; the test suite executes them
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_execution_timeout = 300
nb_merge_streams = True
suppress_warnings: list[str] = []

#: The packages of the API reference, in reading order.  An object is described once, on the page of
#: the package that defines it (the longest of these names that prefixes its ``__module__``); the
#: other packages that export it link there.
API_PACKAGES = [
    "pinlin.model", "pinlin.model.elements", "pinlin.model.constraints", "pinlin.linearization",
    "pinlin.spectral", "pinlin.adjoint", "pinlin.frf", "pinlin.response", "pinlin.nonlinear",
    "pinlin.periodic", "pinlin.studies", "pinlin.boundaries", "pinlin.interop", "pinlin.plot", "pinlin.results",
    "pinlin.errors", "pinlin.numerics", "pinlin.report", "pinlin.report.sweep", "pinlin.testing", "pinlin.cli",
]

logger = logging.getLogger(__name__)

#: Inline spans where a bar is meant literally: ``literal``, :role:`text` (math included) and `interpreted`.
_INLINE_KEEP = re.compile(r"(``.+?``|:[a-z:]+:`[^`]*`|`[^`]*`)")


def escape_bars(app, what, name, obj, options, lines) -> None:
    """Escape ``|`` in docstring prose: in pinlin's docstrings |lam| is an absolute value and ||A|| a norm,
    never a reStructuredText substitution.  Math blocks, literal blocks and inline literals keep theirs."""
    block_indent = None  # indentation of the directive or literal block being skipped
    for i, line in enumerate(lines):
        indent = len(line) - len(line.lstrip())
        if block_indent is not None:
            if not line.strip() or indent > block_indent:
                continue
            block_indent = None
        stripped = line.strip()
        if stripped.startswith(".. ") or stripped.endswith("::"):
            block_indent = indent
            if stripped.startswith(".. math::") and stripped != ".. math::":
                continue  # one-line math: the formula follows the directive
            if stripped.startswith(".. "):
                continue
        parts = _INLINE_KEEP.split(line)
        lines[i] = "".join(p if k % 2 else p.replace("|", "\\|") for k, p in enumerate(parts))


def _home(obj, exporters: list[str]) -> str:
    """The package whose page describes ``obj``: the longest exporter prefixing its module, else the first."""
    module = getattr(obj, "__module__", None) or ""
    owners = [p for p in exporters if module == p or module.startswith(p + ".")]
    return max(owners, key=len) if owners else exporters[0]


_HOMES: dict[str, str] = {}


def canonical_homes() -> dict[str, str]:
    """``package.name`` -> the package documenting it, for every name in an API package's ``__all__``."""
    if _HOMES:
        return _HOMES
    exporters: dict[tuple, list[str]] = {}
    names: dict[str, tuple] = {}
    for package in API_PACKAGES:
        module = importlib.import_module(package)
        for name in module.__all__:
            obj = getattr(module, name)
            # a constant is one object only under one name: equal numbers share an identity
            key = (id(obj),) if _linkable(obj) else (id(obj), name)
            names[f"{package}.{name}"] = (obj, key)
            exporters.setdefault(key, []).append(package)
    _HOMES.update({full: _home(obj, exporters[key]) for full, (obj, key) in names.items()})
    return _HOMES


class PackageDirective(SphinxDirective):
    """``.. pinlin-package:: pinlin.spectral``: the package's docstring and the members it is the home of.

    Names it re-exports from another package are listed with a link to where they are described.
    """

    required_arguments = 1

    def run(self):
        package = self.arguments[0]
        module = importlib.import_module(package)
        homes = canonical_homes()
        own = [n for n in module.__all__ if homes[f"{package}.{n}"] == package]
        others = [n for n in module.__all__ if homes[f"{package}.{n}"] != package]
        lines = [f".. automodule:: {package}", f"   :members: {', '.join(own)}" if own else "   :no-members:", ""]
        if others:
            links = ", ".join(f":py:obj:`{n} <{homes[f'{package}.{n}']}.{n}>`" for n in others)
            lines += [f"Also exported here: {links}.", ""]
        body = nodes.container()
        self.state.nested_parse(StringList(lines, source=package), self.content_offset, body)
        return body.children


class TopLevelDirective(SphinxDirective):
    """``.. pinlin-top-level::``: every name of ``pinlin.__all__`` with a link to its description."""

    def run(self):
        homes = canonical_homes()
        by_object: dict[int, str] = {}
        for full, home in homes.items():
            package, name = full.rsplit(".", 1)
            if package == home:
                by_object.setdefault(id(getattr(importlib.import_module(package), name)), f"{home}.{name}")
        rows = []
        for name in pinlin.__all__:
            if name.startswith("__"):
                continue
            target = by_object.get(id(getattr(pinlin, name)))
            if target is None:
                logger.warning(f"pinlin.{name} is described on no API page: export it from a package of API_PACKAGES",
                               location=self.get_location())
                continue
            rows.append(f"* :py:obj:`pinlin.{name} <{target}>` -- ``{target}``")
        body = nodes.container()
        self.state.nested_parse(StringList(rows, source="pinlin"), self.content_offset, body)
        return body.children


def _import(dotted: str):
    """The object a dotted pinlin name denotes (a module, or attributes down from the longest importable one)."""
    parts = dotted.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        try:
            for attr in parts[cut:]:
                obj = getattr(obj, attr)
        except AttributeError:
            return None
        return obj
    return None


def _linkable(obj) -> bool:
    """Objects with an identity of their own (a constant's value is shared by unrelated names)."""
    return inspect.ismodule(obj) or inspect.isclass(obj) or callable(obj) or isinstance(obj, property)


_DOCUMENTED: dict[int, str] = {}


def _documented_by_identity(env) -> dict[int, str]:
    """id(object) -> the full name under which the API pages describe it."""
    if not _DOCUMENTED:
        for name in env.get_domain("py").objects:
            obj = _import(name) if name.startswith("pinlin") else None
            if obj is not None and _linkable(obj):
                _DOCUMENTED.setdefault(id(obj), name)
    return _DOCUMENTED


def _target(env, name: str):
    """(docname, anchor) of the description of pinlin name ``name``, else of its nearest described parent:
    a module's package page, a constant's module, an attribute's class."""
    py = env.get_domain("py")
    while name.startswith("pinlin"):
        if name in py.objects:
            entry = py.objects[name]
            return entry.docname, entry.node_id
        if name in py.modules:
            entry = py.modules[name]
            return entry.docname, entry.node_id
        obj = _import(name)
        parent = name.rpartition(".")[0]
        if obj is None:  # an instance attribute (a dataclass field without default): its class
            if not inspect.isclass(_import(parent)):
                return None
            name = parent
            continue
        home = _documented_by_identity(env).get(id(obj)) if _linkable(obj) else None
        if home is not None:
            entry = py.objects[home]
            return entry.docname, entry.node_id
        name = parent
    return None


def resolve_pinlin_names(app, env, node, contnode):
    """Link a reference to a pinlin name that is not described under that name.

    The API pages describe each object once, under the package that defines it
    (``pinlin.linearization.linearize``); docstrings name it as users import it
    (``pinlin.linearize``), by its module path (``pinlin.linearization.linearize.linearize``)
    or relative to their own module (``:mod:`.energy```).  Such a reference links to the
    description of the same object; one to an undocumented module, constant or attribute
    links to the page that describes its package, module or class.  Anything else stays
    unresolved (an error under ``nitpicky``).
    """
    if node.get("refdomain") != "py":
        return None
    target = node["reftarget"].lstrip(".~")
    module, cls = node.get("py:module") or "", node.get("py:class") or ""
    candidates = [target] if target.startswith("pinlin") else []
    if module.startswith("pinlin") and not target.startswith("pinlin"):
        if cls:
            candidates.append(f"{module}.{cls}.{target}")
        parts = module.split(".")
        candidates += [".".join(parts[:k] + [target]) for k in range(len(parts), 0, -1)]
    if module.startswith("pinlin") and not target.startswith("pinlin"):
        # a docstring of a module that its package's page shows names its own module's names
        candidates += [f"{sub}.{target}" for sub in _submodules(module)]
    elif target.startswith("pinlin.") and _import(target) is None:
        # a package's name for what one of its modules defines and the package does not export
        package, _, last = target.rpartition(".")
        candidates += [f"{sub}.{last}" for sub in _submodules(package)]
    last = target.rpartition(".")[2]
    for name in [*candidates, *_defined_once(last)]:
        found = _target(env, name)
        if found is not None:
            return make_refnode(app.builder, node["refdoc"], found[0], found[1], contnode)
    return None


_DEFINITIONS: dict[str, set[str]] = {}


def _defined_once(name: str) -> list[str]:
    """The module path of the one pinlin function or class called ``name``, if exactly one is (a docstring
    naming a function of another module by its bare name)."""
    if not _DEFINITIONS:
        for module_name in ["pinlin", *_submodules("pinlin")]:
            for attr, obj in vars(importlib.import_module(module_name)).items():
                if (inspect.isfunction(obj) or inspect.isclass(obj)) and obj.__module__ == module_name:
                    _DEFINITIONS.setdefault(attr, set()).add(f"{module_name}.{attr}")
    found = _DEFINITIONS.get(name, set())
    return sorted(found) if len(found) == 1 else []


def _submodules(package: str) -> list[str]:
    """Every module under ``package`` (none when it is not an importable package)."""
    try:
        module = importlib.import_module(package)
    except ImportError:
        return []
    if not hasattr(module, "__path__"):
        return []
    return [info.name for info in pkgutil.walk_packages(module.__path__, prefix=package + ".")]


#: Pages whose ```python blocks run during the build, in order, in one namespace per page.
EXAMPLE_PAGES = "guide/"


def run_examples(app, doctree) -> None:
    """Run the python code blocks of a user-guide page; an exception is a warning (an error under -W)."""
    docname = app.env.docname
    if not docname.startswith(EXAMPLE_PAGES):
        return
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    namespace: dict = {"__name__": f"pinlin_docs_{docname.replace('/', '_')}"}
    try:
        for block in doctree.findall(nodes.literal_block):
            if block.get("language") != "python":
                continue
            try:
                with contextlib.redirect_stdout(io.StringIO()):  # the examples print for their readers
                    exec(compile(block.astext(), f"{docname}.md", "exec"), namespace)
            except Exception as exc:  # any failure of an example is reported, with where it is
                logger.warning(f"example in {docname} failed: {type(exc).__name__}: {exc}", location=block)
                return
    finally:
        plt.close("all")


#: The project's planning document is not shipped: a page that names it sends readers nowhere.
#: The theory part (``theory/``) is where the mathematics lives; link its sections (``theory-*`` labels).
_INTERNAL_REFERENCE = re.compile(r"\b" + "S" + "PEC" + r"\b")  # spelt in two parts: this file names no document
#: Also check the docstrings (autodoc) -- True once the code's own references point at the theory.
CHECK_DOCSTRINGS = True


def no_internal_references(app, docname, source) -> None:
    """Warn (an error under -W) when a documentation page refers to the unshipped planning document."""
    for number, line in enumerate(source[0].splitlines(), 1):
        if _INTERNAL_REFERENCE.search(line):
            logger.warning(f"{docname} refers to the planning document, which is not shipped: link a theory section",
                           location=(docname, number))


def no_internal_references_in_docstrings(app, what, name, obj, options, lines) -> None:
    """The same check on a docstring."""
    if CHECK_DOCSTRINGS and any(_INTERNAL_REFERENCE.search(line) for line in lines):
        logger.warning(f"the docstring of {name} refers to the planning document, which is not shipped: link a theory "
                       "section")


def setup(app):
    app.connect("source-read", no_internal_references)
    app.connect("autodoc-process-docstring", no_internal_references_in_docstrings)
    app.connect("doctree-read", run_examples)
    app.connect("missing-reference", resolve_pinlin_names)
    app.connect("autodoc-process-docstring", escape_bars, priority=600)  # after numpydoc's rewrite (500)
    app.add_directive("pinlin-package", PackageDirective)
    app.add_directive("pinlin-top-level", TopLevelDirective)
    return {"parallel_read_safe": True}

