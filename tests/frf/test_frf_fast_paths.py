"""The fast paths of the H(s) engine: the Schur form for many points, the sampled modal check.

References are independent: numpy's dense solve of L(s) X = B at every point, and
the exact relative defect ||L X - B|| / (||L|| ||X|| + ||B||) recomputed here.
The bound of the modal check is tested from both sides: never below the exact
defect, and within a stated factor of it.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.frf.engine import residuals, stiffness_norms
from pinlin.frf.modal import CHECK_SAMPLES
from pinlin.frf.schur import schur_pays, schur_pencil, schur_solve
from spectral_cases import chain

EPS = np.finfo(float).eps


def _L(sys, s):
    return s * s * np.asarray(sys.M) + s * np.asarray(sys.C) + np.asarray(sys.K)


def _exact_defects(sys, s, X, B):
    out = []
    for k, sk in enumerate(s):
        L = _L(sys, sk)
        out.append(np.linalg.norm(L @ X[k] - B) / (np.linalg.norm(L) * np.linalg.norm(X[k]) + np.linalg.norm(B)))
    return np.array(out)


@pytest.fixture(scope="module")
def damped_chain():
    """12 links, springs, light dampers and a follower force: M, D, S, N all nonzero, L not symmetric."""
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(12, length=1.0, mass=1.0))
    el = [pinlin.JointSpring(f"joint{i + 1}", 5.0) for i in range(12)]
    el += [pinlin.JointDamper(f"joint{i + 1}", 0.02) for i in range(12)]
    el.append(pinlin.FollowerWrench("tip", force=(0, 0, 0.5)))
    return pinlin.linearize(pinlin.Scene(robot, el), robot.neutral())


def test_schur_solve_matches_dense_solves(damped_chain):
    sys = damped_chain
    s = np.concatenate([1j * np.linspace(0.05, 40.0, 60), [0.3 + 2.0j, -1.0 + 0.5j]])
    B = np.eye(sys.n)[:, [0, 5]]
    X = schur_solve(schur_pencil(sys), s, B)
    ref = np.array([np.linalg.solve(_L(sys, sk), B) for sk in s])
    assert_allclose(X, ref, rtol=1e-11 * np.max(np.abs(ref)), atol=1e-11 * np.max(np.abs(ref)))
    # backward stable: relative defects at a few hundred rounding units (n = 12)
    assert np.max(_exact_defects(sys, s, X, B)) < 300 * EPS


def test_schur_pencil_blocks_cover_the_pencil(damped_chain):
    p = schur_pencil(damped_chain)
    N = 2 * damped_chain.n
    assert sum(p.sizes) == N and p.starts[0] == 0 and set(p.sizes) <= {1, 2}
    # S is quasi-triangular: nothing below the 2 x 2 blocks
    below = np.tril(p.S, -2)
    assert np.all(below == 0)
    assert np.all(np.tril(p.T, -1) == 0)


def test_direct_method_takes_the_schur_path_for_many_points_and_agrees(damped_chain):
    sys = damped_chain
    w = np.linspace(0.05, 40.0, 2000)
    assert schur_pays(sys.n, w.size, 1) and not schur_pays(sys.n, 3, 1) and not schur_pays(sys.n, w.size, sys.n)
    resp = pinlin.frequency_response(sys, w, inputs=[2], outputs=[11])
    ref = np.array([np.linalg.solve(_L(sys, 1j * x), np.eye(sys.n)[:, [2]])[11, 0] for x in w])
    # forward errors follow cond(L(i w)): compared relative to the largest entry
    assert_allclose(resp.response[0, 0], ref, rtol=1e-10, atol=1e-10 * np.max(np.abs(ref)))
    assert resp.method == "direct" and resp.error < 1e-13


def test_schur_solve_at_an_eigenvalue_is_a_pole_error():
    n = 20
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(n), None, np.diag(np.arange(1.0, n + 1) ** 2))
    w = np.linspace(0.55, 19.95, 2000)
    w[1000] = 7.0  # sqrt(49): an undamped resonance
    assert schur_pays(n, w.size, 1)
    with pytest.raises(pinlin.ParameterError, match=r"omega\[1000\] = 7 is at an eigenvalue"):
        pinlin.frequency_response(sys, w, inputs=[6])


@pytest.mark.parametrize("outputs", [None, [11]])
def test_modal_check_is_sampled_and_bounds_the_defect_everywhere(damped_chain, outputs):
    sys = damped_chain
    modes = pinlin.modal_analysis(sys)
    w = np.linspace(0.05, 40.0, 500)
    resp = pinlin.frequency_response(sys, w, inputs=[0], outputs=outputs, method="modal", modes=modes)
    H = pinlin.frequency_response(sys, w, inputs=[0], method="modal", modes=modes, check=False).response[:, 0, :].T
    exact = _exact_defects(sys, 1j * w, H[:, :, None], np.eye(sys.n)[:, [0]])
    # from above: the figure is never below the truth (rounding of the recomputation aside) ...
    assert np.all(resp.defects >= exact * (1 - 1e-6) - 4 * EPS)
    # ... exact at the sampled frequencies (and the notes say how many) ...
    sampled = np.isclose(resp.defects, exact, rtol=1e-6, atol=4 * EPS)
    assert sampled.sum() >= CHECK_SAMPLES
    assert f"exact relative defect at {CHECK_SAMPLES}" in resp.notes[-1] or "exact relative defect at" in resp.notes[-1]
    # ... and from below: within a factor of the truth plus the rounding of the modal sum
    assert np.max(resp.defects) < 1e4 * np.max(exact) + 1e4 * sys.n * EPS
    assert resp.error == np.max(resp.defects)


def test_modal_check_with_few_points_is_exact_everywhere(damped_chain):
    sys = damped_chain
    w = np.linspace(0.05, 40.0, CHECK_SAMPLES)
    resp = pinlin.frequency_response(sys, w, inputs=[0], method="modal")
    H = resp.response[:, 0, :].T
    exact = _exact_defects(sys, 1j * w, H[:, :, None], np.eye(sys.n)[:, [0]])
    assert_allclose(resp.defects, exact, rtol=1e-6, atol=4 * EPS)
    assert not any("upper bound" in note for note in resp.notes)


def test_inaccurate_modal_bound_says_it_is_a_bound():
    """A warning from the bound names it as one, with the sampled exact figure beside it."""
    sys = chain(30, 10.0 ** np.linspace(-3, 3, 30))
    modes = pinlin.modal_analysis(sys)
    w = np.linspace(0.01, 0.9 * np.abs(modes.eigenvalues).max(), 3000)
    w = w[np.min(np.abs(1j * w[:, None] - modes.eigenvalues[None, :]), axis=1) > 1e-3]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        resp = pinlin.frequency_response(sys, w, inputs=[0], outputs=[29], method="modal", modes=modes, error_tol=1e-300)
    text = str(caught[-1].message)
    assert issubclass(caught[-1].category, pinlin.AccuracyWarning)
    k = int(np.argmax(resp.defects))
    if "upper bound" in text:
        assert "at most" in text and "sampled points" in text
    nL = stiffness_norms(sys, 1j * w[[k]])
    X = pinlin.frequency_response(sys, w[[k]], inputs=[0], method="modal", modes=modes).response[:, 0, :].T[:, :, None]
    res = residuals(sys, 1j * w[[k]], X, np.eye(sys.n)[:, [0]])
    assert resp.defects[k] >= res[0] / (nL[0] * np.linalg.norm(X) + 1.0) * (1 - 1e-6)
