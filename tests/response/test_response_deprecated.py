"""The 0.3 spellings of the responses: the old argument order and ``tol`` still work for 0.4, with a warning."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin

SYS = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), np.diag([1.0, 4.0]))
T = np.linspace(0.0, 2.0, 9)
X0, V0 = np.array([0.1, -0.2]), np.array([0.0, 0.3])
OLD_FREE = r"free_response\(sys, x0, v0, t\) is deprecated .* use free_response\(sys, t, x0, v0\)"
OLD_FORCED = r"forced_response\(sys, f, t, x0, v0\) is deprecated .* use forced_response\(sys, t, f, x0, v0\)"


def _exact(t):
    """x(t) of the two decoupled damped oscillators x'' + 0.1 x' + w^2 x = 0 (hand-derived)."""
    out = []
    for w2, x0, v0 in zip([1.0, 4.0], X0, V0):
        wd = np.sqrt(w2 - 0.0025)
        out.append(np.exp(-0.05 * t) * (x0 * np.cos(wd * t) + (v0 + 0.05 * x0) / wd * np.sin(wd * t)))
    return np.column_stack(out)


def test_free_response_new_order_is_the_exact_motion():
    assert_allclose(pinlin.free_response(SYS, T, X0, V0), _exact(T), rtol=0, atol=1e-13)


@pytest.mark.parametrize(
    ("args", "kwargs"),
    [((X0, V0, T), {}), ((X0, V0), {"t": T}), ((X0,), {"v0": V0, "t": T}), ((None, X0, T), {})],
    ids=["positional", "t by keyword", "v0 and t by keyword", "x0 None"],
)
def test_free_response_old_order_warns_and_gives_the_same_motion(args, kwargs):
    with pytest.warns(DeprecationWarning, match=OLD_FREE):
        x = pinlin.free_response(SYS, *args, **kwargs)
    x0, v0 = (X0, V0) if args[0] is not None else (np.zeros(2), X0)
    expected = pinlin.free_response(SYS, T, x0, v0)
    assert_allclose(x, expected, rtol=0, atol=0)


def test_free_response_old_order_with_as_many_times_as_coordinates():
    """n = len(t) = 2: the old call is told apart by its times, the third argument, being the increasing one."""
    t = np.array([0.0, 1.5])
    with pytest.warns(DeprecationWarning, match=OLD_FREE):
        x = pinlin.free_response(SYS, [0.1, 0.0], [0.0, 0.3], t)
    assert_allclose(x, pinlin.free_response(SYS, t, [0.1, 0.0], [0.0, 0.3]), rtol=0, atol=0)


def test_free_response_tol_is_rtol_with_a_warning():
    with pytest.warns(DeprecationWarning, match=r"free_response\(tol=...\) is deprecated .* use rtol=..."):
        x = pinlin.free_response(SYS, T, X0, V0, tol=1e-6)
    assert_allclose(x, _exact(T), rtol=0, atol=1e-13)
    with pytest.raises(pinlin.ParameterError, match="tol: is the deprecated name of rtol; pass only rtol"):
        pinlin.free_response(SYS, T, X0, V0, tol=1e-6, rtol=1e-6)


@pytest.mark.parametrize(
    ("f", "kwargs"),
    [(None, {}), (lambda tt: np.array([np.sin(tt), 0.0]), {"substeps": 4, "interpolation": "cubic"}), (np.ones((len(T), 2)), {})],
    ids=["free", "callable", "samples"],
)
def test_forced_response_old_order_warns_and_gives_the_same_response(f, kwargs):
    with pytest.warns(DeprecationWarning, match=OLD_FORCED):
        old = pinlin.forced_response(SYS, f, T, X0, V0, **kwargs)
    new = pinlin.forced_response(SYS, T, f, X0, V0, **kwargs)
    assert_allclose(old.x, new.x, rtol=0, atol=0)
    assert_allclose(old.xdot, new.xdot, rtol=0, atol=0)


def test_forced_response_old_order_with_t_by_keyword():
    with pytest.warns(DeprecationWarning, match=OLD_FORCED):
        old = pinlin.forced_response(SYS, None, t=T, x0=X0, v0=V0)
    assert_allclose(old.x, _exact(T), rtol=0, atol=1e-13)


def test_forced_response_new_order_does_not_warn():
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error", DeprecationWarning)
        resp = pinlin.forced_response(SYS, T, None, X0, V0)
        free = pinlin.free_response(SYS, T, X0)
    assert_allclose(resp.x, _exact(T), rtol=0, atol=1e-13)
    assert free.shape == (len(T), 2)


def test_the_old_order_with_both_a_position_and_a_keyword_for_t_is_refused():
    with pytest.raises(TypeError, match="multiple values for argument 't'"), pytest.warns(DeprecationWarning):
        pinlin.forced_response(SYS, None, T, t=T)
