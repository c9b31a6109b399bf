"""The Modes result object: order, normalizations, derived fields, table."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin import LinearizedSystem
from pinlin.spectral import MODE_KINDS, Method
from spectral_cases import chain, double_pendulum, ring


@pytest.fixture(scope="module")
def modes():
    return pinlin.modal_analysis(chain(5, [0.5, 1.0, 2.0, 4.0, 8.0], dampers=[0.1, 0.0, 0.3, 0.0, 0.2]))


def test_order_by_frequency_with_conjugate_pairs_adjacent(modes):
    lam = modes.eigenvalues
    assert lam.shape == (10,)
    assert np.all(np.diff(np.abs(lam)) >= -1e-12 * np.abs(lam[1:]))
    i = 0
    while i < lam.size:
        if lam[i].imag != 0:
            assert lam[i].imag > 0 and lam[i + 1] == np.conj(lam[i])
            assert_allclose(modes.right[:, i + 1], np.conj(modes.right[:, i]), rtol=0, atol=0)
            assert_allclose(modes.left[:, i + 1], np.conj(modes.left[:, i]), rtol=0, atol=0)
            i += 2
        else:
            i += 1


def test_derived_fields(modes):
    lam = modes.eigenvalues
    assert_allclose(modes.natural_frequency, np.abs(lam), rtol=1e-15, atol=0)
    assert_allclose(modes.damping_ratio, -lam.real / np.abs(lam), rtol=1e-15, atol=0)
    assert_allclose(modes.frequency_hz, np.abs(lam) / (2 * np.pi), rtol=1e-15, atol=0)
    assert set(modes.kind) <= set(MODE_KINDS)
    assert modes.n == 5 and len(modes) == 10
    assert modes.elapsed > 0
    assert modes.system is not None and modes.matrices[0] is modes.system.M
    assert modes.is_simple and np.all(modes.multiplicity == 1) and np.all(modes.is_semisimple)
    assert modes.tolerances["cluster_tol"] == pinlin.spectral.CLUSTER_TOL


def test_arrays_are_read_only(modes):
    with pytest.raises(ValueError, match="read-only"):
        modes.eigenvalues[0] = 0
    with pytest.raises(AttributeError):
        modes.eigenvalues = None


def test_left_vectors_give_the_partial_fraction_form():
    """H(s) = L(s)^-1 = sum_k x_k y_k^T / (s - lam_k) for a simple L (Lancaster), checked at one s."""
    sys = double_pendulum(P=4.0, c=0.1)
    m = pinlin.modal_analysis(sys)
    s = 0.3 + 2.0j
    H = np.linalg.inv(sys.dynamic_stiffness(s))
    modal = (m.right / (s - m.eigenvalues)) @ m.left.T
    assert_allclose(modal, H, rtol=1e-12, atol=1e-14)


def test_rigid_body_damping_ratio_is_nan_and_kind_says_why():
    m = pinlin.modal_analysis(LinearizedSystem.from_matrices(np.eye(2), None, np.diag([0.0, 4.0])))
    zero = m.eigenvalues == 0
    assert zero.sum() == 2
    assert np.all(np.isnan(m.damping_ratio[zero]))
    assert [m.kind[i] for i in np.flatnonzero(zero)] == ["rigid_body", "rigid_body"]
    assert not np.any(np.isnan(m.damping_ratio[~zero]))


def test_unstable_kind():
    m = pinlin.modal_analysis(ring(k=4.0, c=0.2, Omega=3.0))
    assert m.kind.count("unstable") == 2


def test_table_contains_the_numbers_and_the_verdict(modes):
    text = modes.table()
    lines = text.splitlines()
    assert "method proportional" in lines[0] or "method general" in lines[0]
    assert "eta" in lines[1] and "kappa" in lines[1] and "zeta" in lines[1]
    first = modes.eigenvalues[0]
    assert f"{first.real:.6g}" in lines[3] and f"{modes.natural_frequency[0]:.6g}" in lines[3]
    assert lines[-1].startswith("stability: asymptotically stable")
    assert modes.summary() == text
    assert "more (higher frequencies)" in modes.table(max_rows=3)
    assert "Modes(n=5" in repr(modes)


def test_method_is_a_string_with_its_reason(modes):
    meth = modes.method
    assert isinstance(meth, Method) and isinstance(meth, str)
    assert meth in ("general", "proportional")
    assert meth.name == str(meth)
    assert meth.describe().startswith(f"{meth.name}: ")
    assert len(meth.reason) > 10
