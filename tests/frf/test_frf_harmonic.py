"""Harmonic forcing (theory: responses): X = H(i omega) F.

Reference: a direct solve of L(i omega) X = F with ``numpy.linalg.solve`` in the
test (acceptance: 1e-10 relative).  The resonance test shows the growth
|i omega - lam|^-m at a root with a Jordan chain of length m.
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from response_cases import double_pendulum, rotating_ring, turntable


def _systems():
    dp = double_pendulum(P=4.0, damping=0.02)
    tt, q = turntable()
    ring = rotating_ring()
    return {
        "double pendulum, damped + N": pinlin.linearize(dp, dp.neutral()),
        "turntable (G)": pinlin.linearize(tt, q),
        "rotating ring (D + G)": pinlin.linearize(ring, ring.neutral()),
        "Jordan stiffness (defective)": pinlin.LinearizedSystem.from_matrices(
            np.eye(2), 0.2 * np.eye(2), [[2.0, 1.0], [0.0, 2.0]]
        ),
        "two free masses (rigid body)": pinlin.LinearizedSystem.from_matrices(
            np.diag([1.0, 3.0]), 0.1 * np.eye(2), [[2.0, -2.0], [-2.0, 2.0]]
        ),
    }


SYSTEMS = _systems()


def _direct(sys, F, omega):
    return np.array([np.linalg.solve(-(w**2) * sys.M + 1j * w * sys.C + sys.K, F) for w in omega])


@pytest.mark.parametrize("name", sorted(SYSTEMS))
def test_modal_amplitude_matches_direct_solve(name):
    sys = SYSTEMS[name]
    rng = np.random.default_rng(5)
    F = rng.standard_normal(sys.n) + 1j * rng.standard_normal(sys.n)
    lam = pinlin.modal_analysis(sys).eigenvalues
    # a sweep, plus frequencies 1e-3 away from each resonance
    omega = np.concatenate([np.linspace(0.05, 1.5 * np.abs(lam.imag).max() + 1, 97), np.abs(lam.imag[lam.imag > 0]) + 1e-3])
    X = pinlin.harmonic_response(sys, F, omega, method="modal")
    ref = _direct(sys, F, omega)
    assert X.shape == (omega.size, sys.n) and X.dtype == complex
    err = np.linalg.norm(X - ref, axis=1) / np.linalg.norm(ref, axis=1)
    assert np.max(err) < 1e-10, np.max(err)
    # the exact relative defect at every frequency, from its definition
    L = [-(w**2) * sys.M + 1j * w * sys.C + sys.K for w in omega]
    exact = np.array([np.linalg.norm(Lk @ x - F) / (np.linalg.norm(Lk) * np.linalg.norm(x) + np.linalg.norm(F))
                      for Lk, x in zip(L, np.asarray(X))])
    assert np.max(exact) < 1e-12
    # the modal method's check: exact at CHECK_SAMPLES points, an upper bound at the others,
    # which stays within a few hundred rounding units of the exact defect here
    assert np.all(X.defects >= exact * (1 - 1e-6) - 4 * np.finfo(float).eps)
    assert np.max(X.defects) < 1e-11 and X.error == np.max(X.defects)
    assert X.method == ("modal" if pinlin.modal_analysis(sys).is_simple else "modal + Jordan chains")
    assert_allclose(X.distance, np.min(np.abs(1j * omega[:, None] - lam), axis=1), rtol=1e-14, atol=0)
    # the default, direct, against the same reference
    D = pinlin.harmonic_response(sys, F, omega)
    assert D.method == "direct" and D.distance is None and D.projection_residual is None
    # (two backward-stable solves differ by up to cond(L) eps: 1e-3 from an undamped resonance, ~1e-13)
    assert np.max(np.linalg.norm(D - ref, axis=1) / np.linalg.norm(ref, axis=1)) < 1e-10
    assert D.error < 1e-15


def test_direct_method_and_scalar_frequency():
    sys = SYSTEMS["turntable (G)"]
    F = np.array([1.0, -0.5])
    X = pinlin.harmonic_response(sys, F, 1.3, method="direct")
    assert X.shape == (2,) and isinstance(X.omega, float) and X.method == "direct"
    assert_allclose(X, _direct(sys, F, [1.3])[0], rtol=1e-13, atol=0)
    modal = pinlin.harmonic_response(sys, F, 1.3, method="modal")
    assert_allclose(modal, X, rtol=1e-12, atol=0)
    assert isinstance(modal.defects, float) and isinstance(modal.distance, float)


def test_steady_state_solves_the_equation_in_time():
    # x(t) = Re(X e^{i w t}) from a complex force with a phase lag, checked by finite differences in t.
    sys = SYSTEMS["double pendulum, damped + N"]
    F = np.array([0.3, 1.0j])
    w = 2.5
    X = pinlin.harmonic_response(sys, F, w)
    t = np.linspace(0.0, 3.0, 7)
    h = 1e-4

    def x(tt):
        return np.real(np.exp(1j * w * tt)[:, None] * X)

    xd = (x(t + h) - x(t - h)) / (2 * h)
    xdd = (x(t + h) - 2 * x(t) + x(t - h)) / h**2
    lhs = xdd @ sys.M.T + xd @ sys.C.T + x(t) @ sys.K.T
    assert_allclose(lhs, np.real(np.exp(1j * w * t)[:, None] * F), rtol=0, atol=1e-5)


def test_resonance_grows_with_the_chain_length():
    # M = I, C = c I, lam^2 + c lam + 2 = 0.  K = [[2, 1], [0, 2]]: the roots carry a chain of length 2,
    # and at omega = sqrt(2) (|i omega - lam| ~ c/2) the amplitude grows like c^-2; for the semisimple
    # K = 2 I it grows like c^-1.
    F = np.array([0.0, 1.0])
    c = np.array([1e-1, 1e-2, 1e-3])
    defective, semisimple, distance = [], [], []
    for ci in c:
        jordan = pinlin.LinearizedSystem.from_matrices(np.eye(2), ci * np.eye(2), [[2.0, 1.0], [0.0, 2.0]])
        plain = pinlin.LinearizedSystem.from_matrices(np.eye(2), ci * np.eye(2), 2 * np.eye(2))
        d = pinlin.harmonic_response(jordan, F, np.sqrt(2), method="modal")
        s = pinlin.harmonic_response(plain, F, np.sqrt(2), method="modal")
        assert_allclose(d, np.linalg.solve(-2 * np.eye(2) + 1j * np.sqrt(2) * ci * np.eye(2) + [[2.0, 1.0], [0.0, 2.0]], F), rtol=1e-10, atol=0)
        defective.append(np.linalg.norm(d))
        semisimple.append(np.linalg.norm(s))
        distance.append(d.distance)
    slope_d = np.polyfit(np.log(distance), np.log(defective), 1)[0]
    slope_s = np.polyfit(np.log(distance), np.log(semisimple), 1)[0]
    assert_allclose(slope_d, -2.0, rtol=0, atol=0.02)
    assert_allclose(slope_s, -1.0, rtol=0, atol=0.02)


@pytest.mark.parametrize("method", ["direct", "modal"])
def test_undamped_resonance_raises_the_same_error_everywhere(method):
    """At a pole every function of the engine raises the same ParameterError naming the point."""
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(1), None, [[4.0]])  # lam = +-2i
    pattern = r"omega\[1\] = 2 is at an eigenvalue of the system, where H has a pole .*undamped resonance"
    with pytest.raises(pinlin.ParameterError, match=pattern):
        pinlin.harmonic_response(sys, [1.0], [1.0, 2.0], method=method)
    with pytest.raises(pinlin.ParameterError, match=pattern):
        pinlin.frequency_response(sys, [1.0, 2.0], method=method)
    with pytest.raises(pinlin.ParameterError, match=r"s\[1\] = .*2j.* is at an eigenvalue"):
        pinlin.flexibility(sys, [1.0j, 2.0j], method=method)


def test_computed_natural_frequency_is_a_pole_for_both_methods():
    """At the computed natural frequency of the undamped double pendulum L(i omega) is
    singular to working precision; the direct method used to return |H| ~ 1e15 silently."""
    sys = pinlin.linearize(double_pendulum(P=4.0), np.zeros(2))
    modes = pinlin.modal_analysis(sys)
    w = float(modes.eigenvalues[0].imag)
    for method in ("direct", "modal"):
        with pytest.raises(pinlin.ParameterError, match="is at an eigenvalue"):
            pinlin.harmonic_response(sys, [0.0, 1.0], w, method=method, modes=modes)
    # a relative step of 1e-6 away it is a (large, accurate) response again
    X = pinlin.harmonic_response(sys, [0.0, 1.0], w * (1 + 1e-6))
    assert X.error < 1e-15 and np.linalg.norm(X) > 1e4


@pytest.mark.parametrize(
    ("F", "omega", "kwargs", "match"),
    [
        ([1.0], 1.0, {}, r"F: expected shape \(2,\)"),
        ([1.0, np.nan], 1.0, {}, "F: must be finite"),
        (None, 1.0, {}, "F"),
        ([1.0, 0.0], np.inf, {}, "finite"),
        ([1.0, 0.0], [[1.0, 2.0]], {}, "1-D"),
        ([1.0, 0.0], [], {}, "non-empty"),
        ([1.0, 0.0], "fast", {}, "omega"),
        ([1.0, 0.0], 1.0, {"method": "fft"}, "method"),
        ([1.0, 0.0], 1.0, {"error_tol": 0.0}, "tol"),
    ],
)
def test_bad_inputs_raise(F, omega, kwargs, match):
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), np.eye(2))
    with pytest.raises(pinlin.ParameterError, match=match):
        pinlin.harmonic_response(sys, F, omega, **kwargs)


def test_defect_above_tol_warns():
    sys = SYSTEMS["turntable (G)"]
    with pytest.warns(pinlin.AccuracyWarning, match="defect"):
        X = pinlin.harmonic_response(sys, [1.0, 0.0], [0.5, 1.0], error_tol=1e-300)
    assert np.max(X.defects) > 1e-300 and X.error == np.max(X.defects)
    with pytest.warns(DeprecationWarning, match="defects"):
        assert np.array_equal(X.defect, X.defects)  # the 0.1 name, for one release
