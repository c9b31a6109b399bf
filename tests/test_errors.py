"""The error hierarchy: every error derives from PinlinError and a built-in, and crosses process boundaries."""

import inspect
import pickle

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
