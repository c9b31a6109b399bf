"""A time-invariant system given as constant matrices and any period: multipliers exp(lam T), exponents'
real parts, and frequencies equal to the eigenvalues' imaginary parts (the 2 pi / T ambiguity resolved by the
harmonic content)."""

from __future__ import annotations

import numpy as np
import scipy.linalg
from numpy.testing import assert_allclose

from pinlin.periodic import floquet_analysis_matrices


def _system(seed=3):
    rng = np.random.default_rng(seed)
    n = 3
    Q = np.linalg.qr(rng.standard_normal((n, n)))[0]
    M = np.eye(n) + 0.1 * (lambda X: X @ X.T)(rng.standard_normal((n, n)))
    K = Q @ np.diag([1.7, 22.0, 85.0]) @ Q.T          # frequencies about 1.2, 4.5, 8.8 rad/s
    C = 0.02 * K + 0.3 * (lambda X: X - X.T)(rng.standard_normal((n, n)))
    return M, C, K


def test_frequencies_equal_imaginary_parts_of_the_eigenvalues():
    M, C, K = _system()
    n = M.shape[0]
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
    lam = np.linalg.eigvals(A)
    T = 2.0                                            # 2 pi / T = 3.14 rad/s: most frequencies alias
    res = floquet_analysis_matrices(M, C, K, T)
    order = [int(np.argmin(np.abs(np.exp(lam * T) - mu))) for mu in res.multipliers]
    assert_allclose(res.multipliers, np.exp(lam[order] * T), rtol=1e-12)
    assert_allclose(res.exponents.real, lam[order].real, rtol=0, atol=1e-12)
    assert_allclose(res.frequencies, lam[order].imag, rtol=0, atol=1e-10)
    assert np.any(np.abs(res.dominant_harmonic) >= 2)  # the ambiguity mattered
    # a constant system's periodic parts are single harmonics
    J = (res.harmonic_content.shape[1] - 1) // 2
    assert_allclose(res.harmonic_content[np.arange(2 * n), res.dominant_harmonic + J], 1.0, atol=1e-10)
    assert_allclose(res.monodromy, scipy.linalg.expm(A * T), rtol=0, atol=1e-12 * np.linalg.norm(res.monodromy))


def test_table_and_repr_and_to_dict():
    import json

    res = floquet_analysis_matrices(*_system(), 2.0)
    text = res.table()
    assert len(text.splitlines()) == 2 + 6 + 1 and "stability:" in text
    assert repr(res).startswith("FloquetAnalysis(m=6") and len(repr(res)) < 300
    data = json.loads(json.dumps(res.to_dict()))
    assert data["type"] == "FloquetAnalysis" and data["stability"]["kind"] == "asymptotically_stable"
    assert len(data["multipliers"]["re"]) == 6 and data["error"] == res.error
    assert res.elapsed > 0 and "Gauss-Legendre" in res.method
