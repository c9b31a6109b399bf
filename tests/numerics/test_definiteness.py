"""pinlin.numerics.definiteness: decisions against the rounding bound of the data (theory: stability).

References are hand values (diagonal matrices, whose computed eigenvalues are
exact) and mpmath's symmetric eigensolver at 40 digits on the stored matrices.
Every figure is checked from both sides: the certified bounds never exceed the
true values, and stay within a stated factor of them.
"""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from pinlin import numerics as nm
from pinlin.errors import ParameterError

EPS = np.finfo(float).eps


def mp_eigenvalues(A, dps=40) -> np.ndarray:
    """Eigenvalues of the stored (binary, exact) matrix A, ascending, from mpmath at ``dps`` digits."""
    with mp.workdps(dps):
        w = mp.eigsy(mp.matrix(np.asarray(A, dtype=float).tolist()), eigvals_only=True)
        return np.sort(np.array([float(x) for x in w]))


def spring_chain_stiffness(n, big, ground=1.0):
    """Stiffness of n unit masses in a line: ground spring ``ground``, then springs big, 1, big, 1, ..."""
    k = [ground] + [big if i % 2 else 1.0 for i in range(1, n)]
    S = np.zeros((n, n))
    for i, ki in enumerate(k):
        S[i, i] += ki
        if i:
            S[i - 1, i - 1] += ki
            S[i - 1, i] -= ki
            S[i, i - 1] -= ki
    return S


def test_rounding_bound_and_constant():
    assert nm.EIGENVALUE_ROUNDING == 1.0
    assert nm.rounding_bound(10, 2e10) == 10 * EPS * 2e10
    d = nm.definiteness(np.diag([1.0, 4.0, 2.0]))
    assert (d.rounding, d.norm, d.uncertainty) == (3 * EPS, 4.0, 0.0)
    assert d.tol == d.rounding + d.uncertainty and d.threshold == d.tol * d.norm


@pytest.mark.parametrize(
    "diag, kind, inertia, certificate",
    [
        ([1.0, 1e-15], "positive_definite", (0, 0, 2), "eigenvalues"),  # 1e-15 > 2 eps: certain
        # below 2 eps ||A||, but a diagonal matrix is positive definite relative to its diagonal
        ([1.0, 1e-16], "positive_definite", (0, 0, 2), "Cholesky"),
        ([1.0, -1e-16], "positive_semidefinite", (0, 1, 1), "eigenvalues"),  # sign undecided
        ([1.0, -1e-15], "indefinite", (1, 0, 1), "eigenvalues"),
        ([-1.0, -1e-15], "negative_definite", (2, 0, 0), "eigenvalues"),
        ([-1.0, 1e-16], "negative_semidefinite", (1, 1, 0), "eigenvalues"),
    ],
)
def test_decisions_at_the_rounding_bound(diag, kind, inertia, certificate):
    d = nm.definiteness(np.diag(diag))  # eigvalsh of a diagonal matrix is exact: hand values
    assert d.kind == kind and (d.negative, d.zero, d.positive) == inertia and d.certificate == certificate
    assert d.threshold == 2 * EPS * 1.0


def test_margin_of_a_diagonal_matrix_by_hand():
    d = nm.definiteness(np.diag([1.0, 1e-6]))
    assert d.kind == "positive_definite" and d.certificate == "eigenvalues"
    assert d.margin == pytest.approx(1e-6 - 2 * EPS, rel=1e-15)
    # the margin decides: an uncertainty below it keeps the kind, above it does not
    assert nm.definiteness(np.diag([1.0, 1e-6]), 0.9e-6).kind == "positive_definite"
    above = nm.definiteness(np.diag([1.0, 1e-6]), 1.1e-6)
    assert above.kind == "positive_semidefinite" and above.margin == 0.0 and above.zero == 1
    assert above.threshold == pytest.approx(2 * EPS + 1.1e-6, rel=1e-15)
    ind = nm.definiteness(np.diag([3.0, -0.5, 1e-3]))
    assert ind.kind == "indefinite" and ind.margin == pytest.approx((1e-3 - 3 * EPS * 3.0) / 3.0, rel=1e-14)


def test_at_is_the_decision_at_another_uncertainty():
    rng = np.random.default_rng(1)
    Q, _ = np.linalg.qr(rng.standard_normal((5, 5)))
    A = Q @ np.diag([1e-9, 1e-6, 1.0, -1e-4, 2.0]) @ Q.T
    A = (A + A.T) / 2
    base = nm.definiteness(A)
    for u in (0.0, 1e-10, 1e-7, 1e-5, 0.1):
        assert base.at(u).to_dict() == nm.definiteness(A, u).to_dict()


def test_margin_against_mpmath_from_both_sides():
    """The margin is a certified lower bound of the true relative distance to a change of inertia,
    within the rounding bound of it: (min|lambda| - rho)/||A|| <= margin + ... and margin <= min|lambda|/||A||."""
    rng = np.random.default_rng(2)
    for n in (2, 5, 12):
        Q, _ = np.linalg.qr(rng.standard_normal((n, n)))
        w = 10.0 ** rng.uniform(-9, 0, n) * rng.choice([-1.0, 1.0], n)
        A = Q @ np.diag(w) @ Q.T
        A = (A + A.T) / 2
        d = nm.definiteness(A)
        exact = mp_eigenvalues(A)
        norm = np.max(np.abs(exact))
        true = np.min(np.abs(exact)) / norm
        assert 0 < d.margin <= true  # a bound, positive where the truth is
        assert d.margin >= true - 2 * d.rounding  # within twice the rounding bound of it
        assert (d.negative, d.positive) == (int(np.sum(exact < 0)), int(np.sum(exact > 0)))


def test_issue_16_chain_stiffness_is_positive_definite_beyond_doubt():
    """10 unit masses, springs alternating 1 and 1e10: lambda_min(S) = 0.0405 against n eps ||S|| = 4.4e-5."""
    S = spring_chain_stiffness(10, 1e10)
    d = nm.definiteness(S)
    exact = mp_eigenvalues(S)
    assert_allclose(exact[0], 0.04051, rtol=1e-3)
    assert_allclose(d.threshold, 10 * EPS * exact[-1], rtol=1e-12)
    assert d.kind == "positive_definite" and d.certificate == "eigenvalues"
    assert d.margin <= exact[0] / exact[-1] <= d.margin + 2 * d.rounding
    # the ratio lambda_min / lambda_max is 2e-12: pinlin 0.2's fixed ratio 1e-10 called it singular
    assert exact[0] / exact[-1] < 1e-10


def test_cholesky_certifies_the_30_link_chain_that_the_eigenvalue_bound_cannot():
    """30 links, 1e12: lambda_min(S) = 0.0052 < n eps ||S|| = 0.013, but S is tridiagonal, so Cholesky's
    inner products have two terms and its backward error is about 3 u ||S||."""
    S = spring_chain_stiffness(30, 1e12)
    exact = mp_eigenvalues(S)
    d = nm.definiteness(S)
    assert exact[0] < d.threshold  # the eigenvalue test alone would leave it open
    assert d.kind == "positive_definite" and d.certificate == "Cholesky" and d.positive == 30
    lower = nm.cholesky_lower_bound(S)
    assert 0 < lower <= exact[0] <= 2 * lower  # certified, and within a factor 2 of the truth
    assert d.margin == lower / d.norm
    # a dense matrix with the same eigenvalues gets no such help: k = n
    Q, _ = np.linalg.qr(np.random.default_rng(3).standard_normal((30, 30)))
    dense = Q @ np.diag(exact) @ Q.T
    assert nm.definiteness((dense + dense.T) / 2).kind == "positive_semidefinite"


def test_cholesky_certificate_on_the_diagonal_scale():
    """A near-massless link: M = diag-dominant with a 1e-17 entry, positive definite relative to its diagonal."""
    M = np.array([[2.0, 1.0, 0.0], [1.0, 2.0, 1e-17], [0.0, 1e-17, 3e-17]])
    exact = mp_eigenvalues(M)
    d = nm.definiteness(M)
    assert exact[0] < d.threshold and d.kind == "positive_definite" and d.certificate == "Cholesky"
    # lambda_min(A) >= lambda_min(H) min a_ii: a bound within a factor 4 here
    assert 0 < d.margin * d.norm <= exact[0] <= 4 * d.margin * d.norm
    # cancellation is another matter: [[1, 1], [1, 1 + 4e-16]] is positive definite only within rounding
    assert nm.definiteness(np.array([[1.0, 1.0], [1.0, 1.0 + 4 * EPS]])).kind == "positive_semidefinite"
    assert nm.cholesky_lower_bound(np.array([[1.0, 2.0], [2.0, 1.0]])) is None  # indefinite: no factor


def test_certainly_psd_needs_exact_zeros():
    beam_damper = np.zeros((4, 4))
    beam_damper[2, 2] = 5.0
    d = nm.definiteness(beam_damper)
    assert d.kind == "positive_semidefinite" and d.certainly_psd  # zero rows and columns are exact
    Q, _ = np.linalg.qr(np.random.default_rng(4).standard_normal((4, 4)))
    rotated = Q @ beam_damper @ Q.T
    r = nm.definiteness((rotated + rotated.T) / 2)
    assert r.kind == "positive_semidefinite" and not r.certainly_psd  # its zeros are rounding: unproven
    assert nm.definiteness(np.zeros((3, 3))).certainly_psd and nm.definiteness(np.eye(2)).certainly_psd
    assert not nm.definiteness(np.diag([1.0, 0.0, -1e-20])).certainly_psd  # -1e-20 is a real entry
    assert nm.definiteness(np.diag([1.0, 0.0, -1e-20])).at(0.0).certainly_psd is False


def test_zero_matrix_and_report_fields():
    z = nm.definiteness(np.zeros((3, 3)))
    assert (z.kind, z.zero, z.threshold, z.margin, z.certificate) == ("zero", 3, 0.0, 0.0, "exactly zero")
    fields = nm.definiteness(np.eye(2)).to_dict()
    # the keys the report schema requires, and no private ones
    assert {"kind", "negative", "zero", "positive", "min_eigenvalue", "max_eigenvalue", "tol", "threshold"} <= set(fields)
    assert not any(k.startswith("_") for k in fields) and fields["margin"] == pytest.approx(1 - 2 * EPS)


def test_nonsingularity_and_det_sign():
    assert nm.det_sign(np.array([[0.0, 1.0], [1.0, 0.0]])) == -1
    assert nm.det_sign(np.diag([2.0, 3.0])) == 1
    assert nm.det_sign(np.array([[1.0, 2.0], [2.0, 4.0]])) == 0  # exactly singular
    ns = nm.nonsingularity(np.diag([4.0, -1e-3]))
    assert ns.sign == -1 and ns.margin == pytest.approx((1e-3 - 2 * EPS * 4.0) / 4.0, rel=1e-14)
    assert ns.at(1e-3).sign == 0 and ns.at(1e-4).sign == -1
    assert nm.det_sign(np.diag([4.0, -1e-3]), 1e-3) == 0
    assert nm.det_sign(np.diag([1.0, 1e-16])) == 0  # within the rounding bound of singular
    # non-symmetric: sign from the SVD's orthogonal factors, against the exact determinant
    A = np.array([[1.0, 2.0, 0.0], [3.0, 1.0, 1.0], [0.0, 1.0, 5.0]])
    with mp.workdps(30):
        exact = mp.det(mp.matrix(A.tolist()))
    assert nm.det_sign(A) == int(mp.sign(exact)) == -1


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: nm.definiteness(np.eye(2) * 1j), "A: expected a real matrix, got complex entries"),
        (lambda: nm.definiteness(np.ones((2, 3))), r"A: expected a square matrix, got shape \(2, 3\)"),
        (lambda: nm.definiteness(np.array([[np.nan]])), "A: has non-finite entries"),
        (lambda: nm.definiteness(np.eye(2), -1e-3), r"uncertainty: expected a relative uncertainty in \[0, 1\)"),
        (lambda: nm.definiteness(np.eye(2), 1.0), r"uncertainty: expected a relative uncertainty in \[0, 1\)"),
        (lambda: nm.definiteness(np.eye(2)).at(float("inf")), r"uncertainty: expected a relative uncertainty"),
        (lambda: nm.nonsingularity(np.zeros((0, 0))), r"A: expected a square matrix, got shape \(0, 0\)"),
        (lambda: nm.check_uncertainty(True), r"uncertainty: expected a relative uncertainty in \[0, 1\), got True"),
    ],
)
def test_bad_input_is_refused_by_name(call, match):
    with pytest.raises(ParameterError, match=match):
        call()


@st.composite
def spectra(draw):
    """A symmetric matrix Q diag(w) Q^T with eigenvalues over up to 16 decades, random signs."""
    n = draw(st.integers(1, 7))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    w = 10.0 ** rng.uniform(-draw(st.floats(0, 16)), 0, n) * np.where(rng.random(n) < 0.3, -1.0, 1.0)
    Q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    A = Q @ np.diag(w) @ Q.T
    return (A + A.T) / 2, draw(st.sampled_from([0.0, 0.0, 1e-12, 1e-6]))


@settings(max_examples=40, deadline=None)
@given(spectra())
def test_property_never_wrong_and_decided_where_the_data_decide(case):
    """Against mpmath on the stored matrix: every certain sign is right; and an eigenvalue 10 times
    beyond the bound (rounding c n eps ||A|| plus the uncertainty) is never left undecided."""
    A, u = case
    d = nm.definiteness(A, u)
    exact = mp_eigenvalues(A)
    norm = np.max(np.abs(exact))
    bound = d.rounding * norm + u * norm
    assert d.negative <= np.sum(exact < -u * norm) and d.positive <= np.sum(exact > u * norm)  # never wrong
    assert d.negative >= np.sum(exact < -10 * bound) and d.positive >= np.sum(exact > 10 * bound)
    if d.kind == "positive_definite":
        assert exact[0] > u * norm
    if d.kind in ("positive_definite", "negative_definite", "indefinite"):
        assert d.margin <= np.min(np.abs(exact)) / norm
