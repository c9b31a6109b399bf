"""Every public name has a numpydoc ``Examples`` section, and every docstring's examples run.

The public names are those of ``pinlin.__all__`` (less ``__version__`` and plain
constants such as ``EXAMPLES``), the public functions and classes of
``pinlin.plot``, ``pinlin.testing`` and ``pinlin.model`` (the names a user imports from
there, less those already checked under ``pinlin``), and the documented public methods of those classes (a method that
overrides a documented method of a public base class shares its contract and is
checked on the base).  For each: (a) its docstring has an ``Examples`` section with
at least one ``>>>`` line, (b) its doctests pass.  The doctests of every module
under ``src/pinlin`` (module docstrings included) run too, once each: a module's
docstrings see its globals as well, as under ``doctest.testmod``, while the examples
of a public name see only ``np`` and ``pinlin``, as a user who copies them does.

The runner is the standard library's: :class:`doctest.DocTestFinder` and
:class:`doctest.DocTestRunner`, globals ``{"np": numpy, "pinlin": pinlin}``,
option flags ``ELLIPSIS | NORMALIZE_WHITESPACE``, matplotlib on the Agg backend.
A failure names the function: the tests are parametrized by its dotted name.
"""

from __future__ import annotations

import doctest
import importlib
import inspect
import io
import pkgutil
import re

import numpy as np
import pytest

import pinlin

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:  # pragma: no cover - the plot examples then fail with MissingDependencyError
    plt = None

OPTIONFLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
#: A numpydoc section heading "Examples" underlined by dashes, then a doctest line.
_EXAMPLES = re.compile(r"^Examples\n-{3,}\n(?:(?!^\S.*\n-{3,}\n)[\s\S])*?^\s*>>> ", re.MULTILINE)


def _is_constant(obj) -> bool:
    return not (inspect.isclass(obj) or callable(obj))


def _own_methods(cls) -> dict[str, object]:
    """Documented public methods defined on ``cls`` itself, less overrides of a documented base method."""
    out = {}
    for name, attr in vars(cls).items():
        if name.startswith("_"):
            continue
        func = attr.__func__ if isinstance(attr, (classmethod, staticmethod)) else attr
        if not inspect.isfunction(func) or not func.__doc__:
            continue
        inherited = any(name in vars(base) and getattr(vars(base)[name], "__doc__", None)
                        for base in cls.__mro__[1:] if base.__module__.startswith("pinlin"))
        if not inherited:
            out[name] = func
    return out


def public_objects() -> dict[str, object]:
    """Dotted name -> object, for every public function, class and documented method checked here."""
    out: dict[str, object] = {}
    sources = [(m.__name__, m, m.__all__) for m in (pinlin, pinlin.plot, pinlin.testing, pinlin.model)]
    for prefix, module, names in sources:
        for name in names:
            obj = getattr(module, name)
            if name.startswith("__") or _is_constant(obj) or any(obj is seen for seen in out.values()):
                continue
            out[f"{prefix}.{name}"] = obj
            if inspect.isclass(obj) and not issubclass(obj, BaseException):
                for method, func in _own_methods(obj).items():
                    out[f"{prefix}.{name}.{method}"] = func
    return out


PUBLIC = public_objects()


def examples_problem(obj) -> str | None:
    """Why ``obj``'s docstring fails the Examples rule, or None when it has a section with a doctest."""
    doc = inspect.getdoc(obj) if not inspect.isclass(obj) else inspect.cleandoc(obj.__doc__ or "")
    if not doc:
        return "no docstring"
    if not _EXAMPLES.search(doc + "\n"):
        return "no numpydoc Examples section with a '>>>' line"
    return None


#: Optional extras an example needs (pyproject's extras): its doctests are skipped, not failed, without them.
OPTIONAL = {"pinlin.plot.": "matplotlib", "pinlin.testing.mp_": "mpmath", "pinlin.expand_xacro": "xacro",
            ".to_control": "control", ".to_pandas": "pandas"}


def _needs(name: str) -> list[str]:
    return [module for key, module in OPTIONAL.items() if name.startswith(key) or name.endswith(key)]


def _globs() -> dict:
    return {"np": np, "pinlin": pinlin}


def run_doctests(tests) -> tuple[int, str]:
    """Run doctests with the house's flags; the number failed and the runner's report."""
    out = io.StringIO()
    runner = doctest.DocTestRunner(optionflags=OPTIONFLAGS)
    try:
        for test in tests:
            runner.run(test, out=out.write)
    finally:
        if plt is not None:
            plt.close("all")
    return runner.failures, out.getvalue()


def _doctests_of(obj, name: str) -> list[doctest.DocTest]:
    finder = doctest.DocTestFinder(recurse=False)
    return finder.find(obj, name, module=inspect.getmodule(obj) or False, globs=_globs())


@pytest.mark.parametrize("name", sorted(PUBLIC))
def test_has_examples(name):
    problem = examples_problem(PUBLIC[name])
    assert problem is None, f"{name}: {problem}"


@pytest.mark.parametrize("name", sorted(PUBLIC))
def test_examples_run(name):
    for module in _needs(name):
        pytest.importorskip(module)
    failed, report = run_doctests(_doctests_of(PUBLIC[name], name))
    assert failed == 0, f"{name}: {failed} example(s) failed\n{report}"


_COVERED: set[tuple[str, int]] = set()


def _covered() -> set[tuple[str, int]]:
    """(file, line) of the docstrings run by :func:`test_examples_run`: the module tests skip them."""
    if not _COVERED:
        _COVERED.update((t.filename, t.lineno) for name, obj in PUBLIC.items() for t in _doctests_of(obj, name))
    return _COVERED


def _modules() -> list[str]:
    names = ["pinlin"]
    for info in pkgutil.walk_packages(pinlin.__path__, prefix="pinlin."):
        names.append(info.name)
    return sorted(names)


@pytest.mark.parametrize("module_name", _modules())
def test_module_doctests(module_name):
    module = importlib.import_module(module_name)
    covered = _covered()
    globs = {**vars(module), **_globs()}  # as doctest.testmod(module, extraglobs=...) runs them
    tests = [t for t in doctest.DocTestFinder().find(module, module_name, globs=globs)
             if t.examples and (t.filename, t.lineno) not in covered]
    failed, report = run_doctests(tests)
    assert failed == 0, f"{module_name}: {failed} example(s) failed\n{report}"


# --- the checks themselves, on fakes


def _no_examples():
    """Return nothing.

    Returns
    -------
    None
    """


def _good_examples():
    """Return 2.

    Examples
    --------
    >>> print(np.round(2.0, 6))
    2.0
    """
    return 2


def _wrong_output():
    """Return 2.

    Examples
    --------
    >>> 1 + 1
    3
    """


def _examples_word_only():
    """Return 2, see the Examples of another function.

    Notes
    -----
    The Examples section of :func:`pinlin.linearize` shows the call.
    """


def test_examples_rule_catches_a_function_without_examples():
    assert examples_problem(_no_examples) == "no numpydoc Examples section with a '>>>' line"
    assert examples_problem(_examples_word_only) == "no numpydoc Examples section with a '>>>' line"
    assert examples_problem(lambda: None) == "no docstring"
    assert examples_problem(_good_examples) is None


def test_runner_reports_a_wrong_example_and_passes_a_right_one():
    failed, report = run_doctests(_doctests_of(_wrong_output, "fake._wrong_output"))
    assert failed == 1
    assert "fake._wrong_output" in report and "Expected:\n    3\nGot:\n    2" in report
    assert run_doctests(_doctests_of(_good_examples, "fake._good_examples")) == (0, "")


def test_every_public_function_and_class_is_checked():
    assert {"pinlin.linearize", "pinlin.Robot", "pinlin.Robot.joint", "pinlin.plot.eigenvalue_map",
            "pinlin.testing.check_element"} <= set(PUBLIC)
    assert "pinlin.EXAMPLES" not in PUBLIC and "pinlin.__version__" not in PUBLIC
    assert "pinlin.plot.VERDICT_COLORS" not in PUBLIC
