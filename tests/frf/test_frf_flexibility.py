"""Dynamic flexibility H = L^-1, its modal form and frequency responses (paper Sec. 10, 12).

References: the direct LU inverse against the modal sum built on the spectral
module (two independent methods), and 50-digit mpmath inverses.
"""

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from adjoint_reference import adj_mp, chain, double_pendulum, inv_mp, random_system
from pinlin.frf import FlexibilityArray, flexibility, modal_adjugate

JORDAN = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, [[3.0, 1.0], [-1.0, 1.0]])


def _away_from_spectrum(points, eigenvalues, fraction):
    """Points whose distance to every eigenvalue exceeds ``fraction * max(|lam_k|, 1)``."""
    d = np.abs(points[:, None] - eigenvalues[None, :]) / np.maximum(np.abs(eigenvalues), 1.0)[None, :]
    return points[d.min(axis=1) > fraction]


def _relative(a, b):
    return np.linalg.norm(a - b, axis=(-2, -1)) / np.linalg.norm(b, axis=(-2, -1))


@pytest.fixture(scope="module")
def chain20():
    sys = chain(20)
    return sys, pinlin.modal_analysis(sys)


def test_direct_matches_50_digit_inverse():
    sys = double_pendulum()
    pts = np.array([0.5 + 2.0j, 7.0j, -1.0 + 0.1j])
    H = pinlin.flexibility(sys, pts)
    for k, s in enumerate(pts):
        assert_allclose(H[k], inv_mp(sys, s), rtol=0, atol=1e-14 * np.linalg.norm(H[k]))
    assert np.all(H.defects < 1e-15) and H.error == np.max(H.defects) and H.method == "direct"


def test_modal_equals_direct_double_pendulum():
    sys = double_pendulum()
    modes = pinlin.modal_analysis(sys)
    rng = np.random.default_rng(4)
    pts = np.concatenate([1j * np.linspace(0.05, 30.0, 300), rng.standard_normal(50) * 5 + 5j * rng.standard_normal(50)])
    pts = _away_from_spectrum(pts, modes.eigenvalues, 1e-3)
    Hd = flexibility(sys, pts)
    Hm = flexibility(sys, pts, method="modal", modes=modes)
    assert np.max(_relative(Hm, Hd)) < 1e-10
    assert Hm.error < 1e-13 and Hm.method == "modal"


def test_modal_equals_direct_20_link_chain(chain20):
    sys, modes = chain20
    pts = _away_from_spectrum(1j * np.logspace(-2, 4, 400), modes.eigenvalues, 1e-3)
    assert len(pts) > 300
    Hd = flexibility(sys, pts)
    Hm = flexibility(sys, pts, method="modal", modes=modes)
    assert np.max(_relative(Hm, Hd)) < 1e-10
    assert Hd.error < 1e-13 and Hm.error < 1e-10


def test_shapes_and_metadata():
    sys = double_pendulum()
    H = flexibility(sys, 2.0j)
    # per-point figures follow the points: scalars for a scalar s, 1-D over the points otherwise
    assert isinstance(H, FlexibilityArray) and H.shape == (2, 2) and isinstance(H.defects, float)
    assert H.s == 2.0j and H.distance is None  # no modal analysis, no distance
    H3 = flexibility(sys, [1.0j, 2.0j, 3.0j])
    assert H3.shape == (3, 2, 2) and H3.defects.shape == (3,) and H3.elapsed > 0
    assert_allclose(H3[1], np.asarray(H), rtol=1e-15)
    assert type(H3[1]) is np.ndarray  # a slice carries no error figure
    with pytest.raises(AttributeError):
        _ = H3[1].defects
    with pytest.warns(DeprecationWarning, match="defects"):
        assert np.array_equal(H3.residual, H3.defects)  # the 0.1 name, for one release


def test_spectral_representation_of_the_adjugate():
    """adj L = det M sum_k x_k y_k^T prod_{j != k}(lam - lam_j) against 50-digit cofactors."""
    for sys in (double_pendulum(), random_system(np.random.default_rng(8), 4)):
        modes = pinlin.modal_analysis(sys)
        for lam in (0.3 + 1.1j, -0.7 + 0.2j):
            A = modal_adjugate(sys, lam, modes)
            ref = adj_mp(sys, lam)
            assert_allclose(np.asarray(A), ref, rtol=0, atol=1e-12 * np.linalg.norm(ref))
            assert A.residual < 1e-13
        # at an eigenvalue it is p'(lam_k) x_k y_k^T, equal to the SVD form
        lam = modes.eigenvalues[0]
        A = modal_adjugate(sys, lam, modes)
        assert_allclose(np.asarray(A), np.asarray(pinlin.adjugate(sys, lam)), rtol=0, atol=1e-11 * np.linalg.norm(A))


# ---------------------------------------------------------------------------- frequency response


def test_frequency_response_convention_and_values():
    sys = double_pendulum()
    w = np.linspace(0.1, 20.0, 101)
    resp = pinlin.frequency_response(sys, w, inputs="joint2", outputs=["joint1", "joint2"])
    assert resp.response.shape == (2, 1, 101)  # (outputs, inputs, frequencies), python-control
    assert resp.input_names == ("joint2",) and resp.output_names == ("joint1", "joint2")
    assert_allclose(resp.omega, w, rtol=0)
    assert_allclose(resp.frequency, w / (2 * np.pi), rtol=1e-15)
    mag, phase, omega = resp
    assert_allclose(mag * np.exp(1j * phase), resp.response, rtol=1e-14)
    for k in (0, 50, 100):
        H = inv_mp(sys, 1j * w[k])
        assert_allclose(resp.response[:, 0, k], H[:, 1], rtol=1e-13)
    assert resp.error < 1e-14 and resp.method == "direct" and resp.elapsed > 0


def test_frequency_response_modal_matches_direct_on_the_chain(chain20):
    sys, modes = chain20
    w = np.logspace(-1, 3, 500)
    w = np.abs(_away_from_spectrum(1j * w, modes.eigenvalues, 1e-3))
    direct = pinlin.frequency_response(sys, w, inputs=[19])
    modal = pinlin.frequency_response(sys, w, inputs=[19], method="modal", modes=modes)
    # relative to the column norm: the far entry H[0, 19] is 1e-11 of it at low frequency, and
    # both methods are accurate normwise only (backward stable), not entry by entry
    rel = np.linalg.norm(modal.response - direct.response, axis=0) / np.linalg.norm(direct.response, axis=0)
    assert np.max(rel) < 1e-10
    tip = np.abs(modal.response[19, 0] - direct.response[19, 0]) / np.abs(direct.response[19, 0])
    assert np.max(tip) < 1e-10  # the driving-point entry is not small
    assert modal.error < 1e-10
    unchecked = pinlin.frequency_response(sys, w, inputs=19, outputs=19, method="modal", modes=modes, check=False)
    assert unchecked.defects is None and unchecked.error is None  # not measured
    assert_allclose(unchecked.response[0, 0], modal.response[19, 0], rtol=1e-13)


def test_modal_method_handles_a_defective_system():
    """M = I, K = [[3, 1], [-1, 1]]: p = (s^2 + 2)^2 with one Jordan chain of length 2 at each root.

    adj L = [[s^2 + 1, -1], [1, s^2 + 3]], so H = adj L / (s^2 + 2)^2 in closed form; the modal
    method evaluates it through the Jordan blocks of the expansion.
    """
    s = np.array([0.5j, 1.3j, 0.4 + 2.0j, -0.3 + 0.1j])
    H = flexibility(JORDAN, s, method="modal")
    q = (s * s + 2.0) ** 2
    exact = np.stack([[s * s + 1, -np.ones_like(s)], [np.ones_like(s), s * s + 3]]).transpose(2, 0, 1) / q[:, None, None]
    assert_allclose(np.asarray(H), exact, rtol=1e-12, atol=0)
    assert H.method == "modal + Jordan chains" and H.error < 1e-13
    # the harmonic and frequency responses use the same engine: the same numbers
    resp = pinlin.frequency_response(JORDAN, [1.3], method="modal")
    assert_allclose(resp.response[:, :, 0], exact[1], rtol=1e-12, atol=0)
    with pytest.raises(pinlin.NotSimpleError, match="simple dynamic stiffness"):
        modal_adjugate(JORDAN, 0.5j)  # Corollary 10.2 needs simple roots


def test_bad_input():
    sys = double_pendulum()
    with pytest.raises(pinlin.ParameterError, match="finite"):
        flexibility(sys, [1.0j, np.inf])
    with pytest.raises(pinlin.ParameterError, match="1-D"):
        flexibility(sys, np.ones((2, 2)))
    with pytest.raises(pinlin.ParameterError, match="at least one"):
        flexibility(sys, [])
    with pytest.raises(pinlin.ParameterError, match="complex numbers"):
        flexibility(sys, "1j")
    with pytest.raises(pinlin.ParameterError, match="method"):
        flexibility(sys, 1.0j, method="adjugate")
    with pytest.raises(pinlin.ParameterError, match="LinearizedSystem"):
        flexibility(sys.M, 1.0j)
    osc = pinlin.LinearizedSystem.from_matrices([[1.0]], None, [[4.0]])
    with pytest.raises(pinlin.ParameterError, match="eigenvalue"):
        flexibility(osc, 2.0j)  # L(2i) = 0 exactly
    with pytest.raises(pinlin.ParameterError, match="eigenvalue"):
        flexibility(osc, 2.0j, method="modal")
    with pytest.raises(pinlin.ParameterError, match="real angular"):
        pinlin.frequency_response(sys, [1.0 + 1.0j])
    with pytest.raises(pinlin.ParameterError, match="1-D"):
        pinlin.frequency_response(sys, np.ones((3, 2)))
    with pytest.raises(pinlin.ParameterError, match="finite"):
        pinlin.frequency_response(sys, [1.0, np.nan])
    with pytest.raises(pinlin.ParameterError, match="unknown coordinate 'joint9'"):
        pinlin.frequency_response(sys, [1.0], inputs="joint9")
    with pytest.raises(pinlin.ParameterError, match="out of range"):
        pinlin.frequency_response(sys, [1.0], outputs=[0, 2])
    with pytest.raises(pinlin.ParameterError, match="indices or names"):
        pinlin.frequency_response(sys, [1.0], inputs=[1.5])
    with pytest.raises(pinlin.ParameterError, match="real angular"):
        pinlin.frequency_response(sys, "fast")
    with pytest.raises(pinlin.ParameterError, match="non-empty"):
        pinlin.frequency_response(sys, [1.0], outputs=[])
    with pytest.raises(pinlin.ParameterError, match="method"):
        pinlin.frequency_response(sys, [1.0], method="fast")
    other = pinlin.modal_analysis(random_system(np.random.default_rng(0), 2))
    with pytest.raises(pinlin.ParameterError, match="another system"):
        flexibility(sys, 1.0j, method="modal", modes=other)
    with pytest.raises(pinlin.ParameterError, match="modal_analysis"):
        flexibility(sys, 1.0j, method="modal", modes="modes")
    with pytest.raises(pinlin.ParameterError, match="shape"):
        flexibility(sys, 1.0j, method="modal", modes=pinlin.modal_analysis(random_system(np.random.default_rng(0), 3)))
