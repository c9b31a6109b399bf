"""The error hierarchy: every error derives from PinlinError and a built-in, and crosses process boundaries."""

import ast
import importlib
import inspect
import pickle
from pathlib import Path

import pytest

import pinlin
import pinlin.errors as errors

ERROR_TYPES = [obj for _, obj in inspect.getmembers(errors, inspect.isclass) if issubclass(obj, pinlin.PinlinError)]


def test_every_error_has_a_builtin_base():
    for cls in ERROR_TYPES:
        if cls is pinlin.PinlinError:
            continue
        assert issubclass(cls, (ValueError, RuntimeError, MemoryError, ImportError)), cls


@pytest.mark.parametrize(
    "error",
    [
        pinlin.ParameterError("tol", "must be positive"),
        pinlin.TimePeriodicError("depends on the angle", joint="table", variation=0.25),
        pinlin.SceneFileError("unknown key", "scene.toml", "spring[1].k"),
        pinlin.NotAnEigenvalueError("not an eigenvalue", lam=1j, distance=0.5),
        pinlin.JointNotFoundError("joint9", ["joint1", "joint2"], context="scene"),
        pinlin.ConvergenceError("no convergence", [1.0, 0.5]),
    ],
    ids=lambda e: type(e).__name__,
)
def test_errors_survive_pickling_with_their_data(error):
    """Subclasses take their data as constructor arguments; Exception's default pickling would call
    cls(*args) and fail, so errors raised in a process pool could not reach the caller."""
    copy = pickle.loads(pickle.dumps(error))
    assert type(copy) is type(error)
    assert str(copy) == str(error)
    assert copy.__dict__ == error.__dict__


#: Signals a search raises and catches itself (``pinlin.boundaries.critical``); no caller ever sees them.
INTERNAL_SIGNALS = {"BracketChanged", "PlanMismatch"}


def _raised_pinlin_classes():
    """(module, class name, class) of every ``raise X(...)`` / ``raise X`` in src whose X is a PinlinError."""
    root = Path(pinlin.__file__).parent
    found = set()
    for path in sorted(root.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        names = set()
        for node in ast.walk(tree):
            if isinstance(node, ast.Raise) and node.exc is not None:
                target = node.exc.func if isinstance(node.exc, ast.Call) else node.exc
                if isinstance(target, ast.Name):
                    names.add(target.id)
        if not names:
            continue
        parts = path.relative_to(root.parent).with_suffix("").parts
        module_name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        module = importlib.import_module(module_name)
        for name in names:
            obj = getattr(module, name, None)
            if isinstance(obj, type) and issubclass(obj, pinlin.PinlinError):
                found.add((module_name, name, obj))
    return found


def test_every_class_src_raises_is_exported_from_pinlin():
    raised = _raised_pinlin_classes()
    assert len(raised) > 30  # the walk sees the raise sites (ParameterError alone has hundreds)
    missing = sorted(f"{module}: {name}" for module, name, cls in raised
                     if name not in INTERNAL_SIGNALS and not (name in pinlin.__all__ and getattr(pinlin, name) is cls))
    assert missing == []


@pytest.mark.parametrize(("old", "parent"), [("NoPeriodError", "InputError"), ("AssemblyError", "LoopClosureError")])
@pytest.mark.parametrize("module", [pinlin, errors], ids=["pinlin", "pinlin.errors"])
def test_a_merged_class_is_its_parent_with_a_deprecation_warning(module, old, parent):
    with pytest.warns(DeprecationWarning, match=rf"{module.__name__}\.{old} is deprecated .* use pinlin\.{parent}"):
        cls = getattr(module, old)
    assert cls is getattr(pinlin, parent)
    assert old not in pinlin.__all__ and old not in errors.__all__


def test_an_unknown_name_is_still_an_attribute_error():
    with pytest.raises(AttributeError, match="module 'pinlin' has no attribute 'NoSuchError'"):
        pinlin.NoSuchError  # noqa: B018


def test_a_merged_class_still_catches_what_its_old_name_caught():
    """A scene that moves nothing has no period: the old name catches the error the parent now is."""
    with pytest.warns(DeprecationWarning):
        old = pinlin.NoPeriodError
    robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    with pytest.raises(old, match="the scene is autonomous"):
        pinlin.periodic_orbit(pinlin.Scene(robot), [0.1, 0.0])
