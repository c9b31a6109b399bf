"""pinlin.numerics.small_linalg gives numpy.linalg's numbers to the last bit and its errors (issue 27)."""

from __future__ import annotations

import numpy as np
import pytest

from pinlin.numerics.small_linalg import eigvalsh, singular_values, solve


def _matrices():
    rng = np.random.default_rng(27)
    for n in (1, 2, 7, 8, 17, 34):
        a = rng.standard_normal((n, n))
        yield a
        yield a + 1j * rng.standard_normal((n, n))
        yield (a @ a.T)[:, ::-1]  # not contiguous
        yield np.asfortranarray(a)


@pytest.mark.parametrize("k", range(24))
def test_the_same_numbers_as_numpy_linalg(k):
    a = list(_matrices())[k]
    h = a.conj().T @ a
    b = np.ascontiguousarray(a[:, ::-1].T) + 0.5
    for fast, ref in ((eigvalsh(h), np.linalg.eigvalsh(h)), (singular_values(a), np.linalg.svd(a, compute_uv=False)),
                      (solve(a, b), np.linalg.solve(a, b))):
        np.testing.assert_array_equal(fast, ref, strict=True)


def test_other_input_goes_through_numpy_linalg():
    a = np.eye(3, dtype=np.float32) * 2
    np.testing.assert_array_equal(eigvalsh(a), np.linalg.eigvalsh(a), strict=True)
    np.testing.assert_array_equal(solve(np.eye(2), np.ones(2)), np.ones(2), strict=True)  # 1-D right-hand side
    stack = np.stack([np.eye(2), 2 * np.eye(2)])
    np.testing.assert_array_equal(singular_values(stack), np.linalg.svd(stack, compute_uv=False), strict=True)


def test_failures_raise_linalg_error_silently():
    with pytest.raises(np.linalg.LinAlgError):
        solve(np.zeros((3, 3)), np.ones((3, 2)))
    with pytest.raises(np.linalg.LinAlgError):
        singular_values(np.full((3, 3), np.nan))
    with pytest.raises(np.linalg.LinAlgError):
        eigvalsh(np.full((3, 3), np.nan))
