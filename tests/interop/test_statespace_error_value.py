"""The state-space error figure is its documented formula, by value (theory: error figures).

``StateSpaceModel.error`` and ``LinearizedSystem.first_order``'s third value are documented as
||M X - Y||_F / (||M||_F ||X||_F + ||Y||_F) for X = M^-1 Y, Y = [K, C, F] (the backward error of the
Cholesky solves).  X is recovered exactly from A and B (its blocks are -A21, -A22 and B2: negation is exact),
and the residual of that very X is computed exactly in mpmath.  The figure itself is formed in double
precision, where the rounding of M X - Y is of the size of the residual: per system the ratio lies within
[0.75, 2], and its median over 30 seeded systems within [0.85, 1.3] (measured 0.89-1.35, median 1.04); a
figure half its value (median 0.5) or twice it fails.
"""

import mpmath as mp
import numpy as np

import pinlin


def _exact(M, A, B, C, K, F):
    n = M.shape[0]
    X = np.hstack([-A[n:, :n], -A[n:, n:], B[n:]])
    Y = np.hstack([K, C, F])
    with mp.workdps(40):
        Mm, Xm, Ym = (mp.matrix(a.tolist()) for a in (M, X, Y))
        R = Mm * Xm - Ym
        return float(mp.mnorm(R, "f") / (mp.mnorm(Mm, "f") * mp.mnorm(Xm, "f") + mp.mnorm(Ym, "f")))


def _systems(count=30, n=5):
    rng = np.random.default_rng(11)
    for _ in range(count):
        G, D, H = (rng.standard_normal((n, n)) for _ in range(3))
        yield pinlin.LinearizedSystem.from_matrices(G @ G.T + 0.5 * np.eye(n), D + D.T, H + H.T + 3 * np.eye(n))


def test_first_order_error_is_the_relative_residual_of_its_solves():
    ratios = []
    for sys in _systems():
        F = np.eye(sys.n)
        A, B, err = sys.first_order(F)
        exact = _exact(sys.M, A, B, sys.C, sys.K, F)
        assert exact > 0
        ratios.append(err / exact)
        # the state-space model carries the same figure for the same inputs (all coordinates)
        model = pinlin.state_space(sys)
        assert model.error == err
    ratios = np.array(ratios)
    assert np.all((ratios >= 0.75) & (ratios <= 2.0)), ratios
    assert 0.85 <= np.median(ratios) <= 1.3, np.median(ratios)
