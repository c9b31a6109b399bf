"""The lean modal analysis: what is deferred, and the vectorized pieces, tested against definitions.

- the stability margin is computed on first access (the verdict itself costs one
  pass through the rules), cached, the same from every thread and after pickling;
- condition numbers and modal constants are formed on first access from the
  products the analysis kept, and equal their definitions;
- the ordering of a spectrum whose conjugate pairs are not adjacent;
- eigh refined by Newton steps: backward errors at rounding level on a chain whose
  M has cond ~ 1e9 (eigh alone: 1e-11).
"""

from __future__ import annotations

import pickle
import threading

import numpy as np
from numpy.testing import assert_allclose

import pinlin
from pinlin.numerics import condition_number
from pinlin.spectral.ordering import order_spectrum
from pinlin.spectral.qep import RawSpectrum
from pinlin.spectral.refine import refined_eigh
from pinlin.spectral.stability.decide import _margin
from spectral_cases import chain, double_pendulum, eta_reference


def test_margin_is_computed_on_first_access_and_kept():
    modes = pinlin.modal_analysis(double_pendulum(P=4.0, c=0.05))
    v = modes.stability
    assert v.kind == "asymptotically_stable"
    assert v.__dict__["_margin"] is None  # not computed by the analysis
    question = v.__dict__["_margin_of"]
    expected = _margin(v.kind, question.kind_at, v.uncertainty)
    margin = v.margin
    assert margin == expected and v.__dict__["_margin"] == margin
    assert f"margin {margin:.1e}" in v.reason and v.error == np.finfo(float).eps / margin
    # the same number from a fresh analysis read in eight threads at once
    fresh = pinlin.modal_analysis(double_pendulum(P=4.0, c=0.05)).stability
    seen = []
    threads = [threading.Thread(target=lambda: seen.append(fresh.margin)) for _ in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert seen == [margin] * 8


def test_a_lazy_margin_survives_pickling_and_to_dict():
    modes = pinlin.modal_analysis(double_pendulum(P=4.0, c=0.05))
    # the verdict is itself formed on first access: formed here, pickled with its margin still lazy
    assert modes.stability.__dict__["_margin"] is None
    copy = pickle.loads(pickle.dumps(modes))
    assert copy.stability.__dict__["_margin"] is None
    assert copy.stability.margin == modes.stability.margin
    d = modes.stability.to_dict()
    assert d["margin"] == modes.stability.margin and d["reason"] == modes.stability.reason
    assert copy.stability == modes.stability


def test_condition_and_constants_formed_on_access_equal_their_definitions():
    sys = double_pendulum(P=12.0, c=0.05)
    modes = pinlin.modal_analysis(sys)
    assert "condition" not in modes.__dict__
    for k in range(len(modes)):
        x, y = modes.right[:, k], modes.left[:, k]
        expected = condition_number(sys.M, sys.C, sys.K, modes.eigenvalues[k], x, y)
        assert_allclose(modes.condition[k], expected, rtol=1e-12)
    assert not modes.condition.flags.writeable
    X = modes.right / np.sqrt(np.einsum("ij,ij->j", modes.right.conj(), sys.M @ modes.right).real)
    assert_allclose(modes.constants.k, np.einsum("ij,ij->j", X.conj(), sys.S @ X).real, rtol=1e-12, atol=1e-14)
    assert_allclose(modes.backward_error, eta_reference(sys.M, sys.C, sys.K, modes.eigenvalues, modes.right),
                    rtol=0.1, atol=4 * np.finfo(float).eps)


def test_ordering_with_pairs_out_of_place():
    """Pairs stored apart (not as LAPACK stores them): matched by exact conjugate value, vectors made conjugate."""
    lam = np.array([2j, -1.0, 1 + 1j, -2j, 1 - 1j, 0.5])
    n = 2
    rng = np.random.default_rng(0)
    X = rng.standard_normal((n, 6)) + 1j * rng.standard_normal((n, 6))
    P = np.stack([X, 2 * X, 3 * X, 4 * X])
    raw = order_spectrum(RawSpectrum(lam=lam, P=P, Y=None, block=np.arange(6), eta=np.arange(6.0)))
    assert_allclose(raw.lam, [0.5, -1.0, 1 + 1j, 1 - 1j, 2j, -2j], rtol=0)
    assert_allclose(raw.P[..., 3], np.conj(raw.P[..., 2]), rtol=0)
    assert_allclose(raw.P[..., 5], np.conj(raw.P[..., 4]), rtol=0)
    assert raw.eta[3] == raw.eta[2] and raw.block[5] == raw.block[4]


def test_newton_refinement_reaches_rounding_where_eigh_does_not():
    sys = chain(100, 10.0 ** np.linspace(-5, 5, 100))
    norm_S, norm_M = np.linalg.norm(sys.S), np.linalg.norm(sys.M)
    plain = refined_eigh(sys.S, sys.M, norm_S, norm_M, tol=1e-15, max_steps=0)
    refined = refined_eigh(sys.S, sys.M, norm_S, norm_M, tol=1e-15)
    assert plain.eta.max() > 1e-12 and refined.steps >= 1 and refined.eta.max() <= 1e-15
    # the eta reported is the definition's
    R = sys.S @ refined.X - (sys.M @ refined.X) * refined.w
    eta = np.linalg.norm(R, axis=0) / ((np.abs(refined.w) * norm_M + norm_S) * np.linalg.norm(refined.X, axis=0))
    assert_allclose(refined.eta, eta, rtol=1e-10, atol=1e-18)
    # and the analysis built on it agrees with QZ within both error bounds (first-order, times 10)
    sym, qz = pinlin.modal_analysis(sys), pinlin.modal_analysis(sys, method="general")
    assert sym.method == "symmetric" and "Newton" in sym.method.reason
    gap = np.abs(sym.eigenvalues - qz.eigenvalues)
    assert np.all(gap <= 10 * (sym.error_bound + qz.error_bound))
