"""Property tests on random chains and random parameters (theory: equations, spectrum, stability).

hypothesis draws chains (links, masses, lengths, radii, springs, dampers,
follower loads, gravity) and random mechanical matrices; the properties hold
for every draw:

- M symmetric positive definite, D and S symmetric, G and N skew (theory: equations);
- eigenpair residuals: eta recomputed from the vectors within bounds (theory: spectrum);
- modal flexibility equal to the directly inverted dynamic stiffness (theory: spectrum);
- verdicts consistent with the structural theorems and with the computed
  eigenvalues and their bounds (theory: stability).

Sizes and example counts are kept small (the whole file runs in well under a minute).
"""

from __future__ import annotations

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

import pinlin
from pinlin import FollowerWrench, JointDamper, JointSpring, LinearizedSystem
from stress_cases import eta

SETTINGS = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])

positive = st.floats(min_value=0.05, max_value=5.0, allow_nan=False, allow_infinity=False)
log_scale = st.floats(min_value=-3.0, max_value=3.0, allow_nan=False, allow_infinity=False)


@st.composite
def chains(draw):
    """A random hanging chain: 1..5 links, springs, optional dampers and follower load, gravity or not."""
    n = draw(st.integers(min_value=1, max_value=5))
    lengths = draw(st.lists(positive, min_size=n, max_size=n))
    masses = draw(st.lists(positive, min_size=n, max_size=n))
    radius = draw(st.sampled_from([0.0, 0.02]))
    ks = [10.0 ** draw(log_scale) for _ in range(n)]
    damped = draw(st.booleans())
    cs = [10.0 ** (draw(log_scale) - 2) for _ in range(n)] if damped else None
    P = draw(st.sampled_from([0.0, 0.0, 0.3, 2.0]))
    g = draw(st.sampled_from([0.0, 9.81]))
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n, lengths, masses, radius=radius))
    el = [JointSpring(f"joint{i + 1}", k) for i, k in enumerate(ks)]
    if cs is not None:
        el += [JointDamper(f"joint{i + 1}", c) for i, c in enumerate(cs)]
    if P:
        el.append(FollowerWrench("tip", force=(0.0, 0.0, P)))
    scene = pinlin.Scene(robot, el, gravity=(0.0, 0.0, -g))
    return pinlin.linearize(scene, robot.neutral())


@st.composite
def mechanical(draw):
    """Random M spd, D psd (or 0), G skew (or 0), S symmetric (any inertia), N skew (or 0); n = 1..6."""
    n = draw(st.integers(min_value=1, max_value=6))
    seed = draw(st.integers(min_value=0, max_value=2**32 - 1))
    rng = np.random.default_rng(seed)
    A = rng.standard_normal((n, n))
    M = A @ A.T + 0.1 * n * np.eye(n)
    parts = {}
    for name, on in (("D", draw(st.booleans())), ("G", draw(st.booleans())), ("N", draw(st.booleans()))):
        B = rng.standard_normal((n, n)) if on else np.zeros((n, n))
        parts[name] = B @ B.T if name == "D" else B - B.T
    shift = draw(st.sampled_from([2.0, 0.0, -0.5]))  # S positive definite, indefinite, or mostly negative
    B = rng.standard_normal((n, n))
    S = B @ B.T / n + shift * np.eye(n)
    return LinearizedSystem(M, parts["D"], parts["G"], S, parts["N"])


@SETTINGS
@given(chains())
def test_linearized_chain_matrices_have_their_symmetries(sys):
    assert_allclose(sys.M, sys.M.T, rtol=0, atol=0)
    np.linalg.cholesky(sys.M)  # positive definite
    assert np.min(np.linalg.eigvalsh(sys.M)) > 0
    assert_allclose(sys.D, sys.D.T, rtol=0, atol=0)
    assert_allclose(sys.S, sys.S.T, rtol=0, atol=0)
    assert_allclose(sys.G, -sys.G.T, rtol=0, atol=0)
    assert_allclose(sys.N, -sys.N.T, rtol=0, atol=0)
    # joint dampers only: D is diagonal and positive semidefinite; no gyroscopic terms at rest
    assert sys.is_zero("G")
    assert np.all(np.linalg.eigvalsh(sys.D) >= -1e-15 * max(np.linalg.norm(sys.D), 1e-300))


@SETTINGS
@given(chains())
def test_chain_eigenpairs_have_small_residuals(sys):
    for method in ("auto", "general"):
        m = pinlin.modal_analysis(sys, method=method)
        e = eta(sys, m.eigenvalues, m.right)
        assert np.max(e) <= 100 * sys.n * np.finfo(float).eps
        assert_allclose(m.backward_error, e, rtol=1e-6, atol=4 * np.finfo(float).eps)  # pinlin reports what it achieved


@SETTINGS
@given(mechanical())
def test_random_eigenpairs_have_small_residuals(sys):
    m = pinlin.modal_analysis(sys)
    e = eta(sys, m.eigenvalues, m.right)
    assert np.max(e) <= 100 * sys.n * np.finfo(float).eps


@SETTINGS
@given(mechanical(), st.floats(min_value=0.1, max_value=10.0), st.floats(min_value=-1.0, max_value=1.0))
def test_modal_flexibility_equals_the_direct_inverse(sys, w, sigma):
    m = pinlin.modal_analysis(sys)
    s = complex(sigma, w)
    gap = np.min(np.abs(m.eigenvalues - s))
    if not m.is_simple or gap < 1e-3 * max(1.0, abs(s)):
        return  # defective (no modal form) or at an eigenvalue
    L = sys.dynamic_stiffness(s)
    direct = np.linalg.inv(L)
    modal = pinlin.flexibility(sys, s, method="modal", modes=m)
    # both are accurate to kappa(L) eps relative to ||H||, the modal sum also to the eigen-condition
    tol = 1e-9 * np.linalg.cond(L) * max(1.0, float(np.max(m.condition)))
    assert np.linalg.norm(modal - direct) <= tol * np.linalg.norm(direct)
    assert np.linalg.norm(L @ modal - np.eye(sys.n)) <= tol * 10


def _consistent(m, sys):
    """The verdict against the computed eigenvalues with their bounds and the theorems of theory: stability."""
    kind = m.stability.kind
    lam, r = m.eigenvalues, m.tolerances["safety"] * m.error_bound
    facts = m.structure
    if kind == "asymptotically_stable":
        assert np.all(lam.real < 0)
    elif kind == "marginally_stable":
        assert np.all(lam.real <= r)
    elif kind in ("divergence", "flutter"):
        assert np.any(lam.real > -r)  # something on or right of the axis
    # theorems (theory: stability), which must never be contradicted
    if not facts.circulatory:
        if facts.damping == "positive_definite" and facts.stiffness == "positive_definite":
            assert kind == "asymptotically_stable"
        if facts.stiffness == "positive_definite" and facts.damping in ("zero", "positive_semidefinite"):
            assert kind in ("asymptotically_stable", "marginally_stable", "undecided")
        if facts.damping == "positive_definite" and not facts.singular_stiffness and facts.negative_stiffness:
            assert kind in ("divergence", "flutter")
            assert np.sum(lam.real > 0) == facts.negative_stiffness  # Kelvin-Tait-Chetaev
        if facts.negative_stiffness % 2 == 1 and not facts.singular_stiffness:
            assert kind == "divergence"  # det K < 0: a real positive root
            assert np.any((np.abs(lam.imag) <= r) & (lam.real > 0))


@SETTINGS
@given(mechanical())
def test_verdicts_agree_with_the_structural_theorems(sys):
    m = pinlin.modal_analysis(sys)
    _consistent(m, sys)
    alone = pinlin.spectral.stability_from_structure(sys)
    if alone is not None:  # the theorem-only verdict is the same as the full one
        assert alone.kind == m.stability.kind


@SETTINGS
@given(chains())
def test_chain_verdicts_agree_with_the_structural_theorems(sys):
    _consistent(pinlin.modal_analysis(sys), sys)
