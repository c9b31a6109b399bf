"""The frequency response's relative defect is its documented formula, by value (theory: error figures).

``FrequencyResponse.defects`` is documented as eta(s) = ||L(s) X - B||_F / (||L(s)||_F ||X||_F + ||B||_F)
(Rigal and Gaches 1967) of the X returned (B = I: all coordinates).  The residual of that very X is computed
exactly in mpmath.

- modal method on a nearly critically damped system (its eigenvectors are ill-conditioned, so the modal sum
  carries an error far above the rounding of forming its residual): each defect equals the exact one within
  10 % (measured within 6 %);
- direct method (backward stable: the residual is at the rounding level of forming it, so each figure is
  only within a factor 2 of exact): the median ratio over 40 frequencies of a seeded system lies within
  [0.8, 1.5] (measured 1.09, range 0.68-1.84).

A defect half its value fails both.
"""

import mpmath as mp
import numpy as np

import pinlin


def _exact_defects(sys, omega, X):
    n = sys.n
    out = []
    with mp.workdps(40):
        M, C, K = (mp.matrix(np.asarray(a, dtype=float).tolist()) for a in (sys.M, sys.C, sys.K))
        for k, w in enumerate(omega):
            s = mp.mpc(0, w)
            L = s**2 * M + s * C + K
            Xm = mp.matrix([[mp.mpc(complex(X[i, j, k])) for j in range(n)] for i in range(n)])
            R = L * Xm - mp.eye(n)
            out.append(float(mp.mnorm(R, "f") / (mp.mnorm(L, "f") * mp.mnorm(Xm, "f") + mp.sqrt(n))))
    return np.array(out)


def test_modal_defects_equal_the_formula():
    M = np.diag([1.0, 2.0])
    C = np.diag([2 * (1 - 1e-7), 3.0])  # the first oscillator nearly critically damped
    K = np.array([[1.0, 0.3], [0.3, 5.0]])
    sys = pinlin.LinearizedSystem.from_matrices(M, C, K)
    omega = np.linspace(0.1, 3.0, 7)
    fr = pinlin.frequency_response(sys, omega, method="modal")
    exact = _exact_defects(sys, omega, fr.response)
    assert np.all(exact > 1e-16)
    np.testing.assert_allclose(fr.defects, exact, rtol=0.1)
    assert fr.error == np.max(fr.defects)


def test_direct_defects_equal_the_formula_statistically():
    rng = np.random.default_rng(3)
    n = 4
    A = rng.standard_normal((n, n))
    Cm = rng.standard_normal((n, n))
    Km = rng.standard_normal((n, n))
    sys = pinlin.LinearizedSystem.from_matrices(A @ A.T + n * np.eye(n), 0.1 * (Cm + Cm.T) + 0.3 * np.eye(n),
                                                Km @ Km.T + np.eye(n))
    omega = np.linspace(0.1, 5.0, 40)
    fr = pinlin.frequency_response(sys, omega, method="direct")
    ratio = fr.defects / _exact_defects(sys, omega, fr.response)
    assert np.all((ratio > 0.4) & (ratio < 3.0)), ratio
    assert 0.8 <= np.median(ratio) <= 1.5, np.median(ratio)
