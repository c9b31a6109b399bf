"""The parts of Modes formed on first access, and the lean pieces, tested against definitions.

- the structural facts, the verdict and the notes are formed on first access: equal
  to what the eager functions give for the same inputs, the same whichever part is
  read first, the same after pickling (before or after reading them), in to_dict
  and repr; errors are still raised by modal_analysis itself;
- the symmetric path predicts from cond(M) when eigh cannot reach eigh_tol (QZ, no
  eigh run) and otherwise refines eigh's pairs above eigh_tol to rounding, keeping
  the others exactly as eigh gave them;
- the quick "no cluster" test never hides a cluster the full search finds;
- the real residual and the cached options give what the general code gives.
"""

from __future__ import annotations

import json
import pickle
import threading

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

import pinlin
from pinlin.numerics.accuracy import backward_errors, residual_figures
from pinlin.numerics.clustering import _far_apart, find_clusters
from pinlin.spectral import analysis, qep
from pinlin.spectral.deferred import mass_notes
from pinlin.spectral.problem import as_problem
from pinlin.spectral.qualitative import structural_facts
from pinlin.spectral.refine import pencil_backward_errors, refined_eigh
from pinlin.spectral.stability import decide_stability
from spectral_cases import chain, double_pendulum

EPS = np.finfo(float).eps

LAZY = ("structure", "stability", "notes", "condition", "constants", "participation")


def _verdict_key(v) -> tuple:
    """Everything a verdict says except the time it took to form."""
    return (v.kind, v.reason, v.theorem, v.eigenvalue, v.error_bound, v.bounded, v.safety, v.margin, v.uncertainty)


def _facts_key(f) -> str:
    return json.dumps(pinlin.results.to_jsonable(f), sort_keys=True)


def _same_arrays(a, b) -> bool:
    return a is b or (a is not None and b is not None and np.array_equal(np.asarray(a), np.asarray(b), equal_nan=True))


def _timeless(data):
    """JSON data of a result without its ``elapsed`` entries (a verdict formed on access has its own time)."""
    if isinstance(data, dict):
        return {k: _timeless(v) for k, v in data.items() if k != "elapsed"}
    if isinstance(data, list):
        return [_timeless(v) for v in data]
    return json.loads(json.dumps(data, allow_nan=False))


def _read(modes, order):
    return {name: getattr(modes, name) for name in order}


def _check_same(x: dict, y: dict) -> None:
    assert _facts_key(x["structure"]) == _facts_key(y["structure"])
    assert _verdict_key(x["stability"]) == _verdict_key(y["stability"])
    assert x["notes"] == y["notes"]
    assert _same_arrays(x["condition"], y["condition"]) and _same_arrays(x["participation"], y["participation"])
    cx, cy = x["constants"], y["constants"]
    assert (cx is None) == (cy is None)
    if cx is not None:
        for name in ("m", "d", "g", "k", "n", "residual"):
            assert _same_arrays(getattr(cx, name), getattr(cy, name))


SYSTEMS = {
    "double pendulum, follower force (general)": lambda: double_pendulum(P=4.0, c=0.05),
    "hanging chain (symmetric)": lambda: chain(6, [10.0 ** k for k in range(-2, 4)]),
    "damped chain (proportional or general)": lambda: chain(4, [1.0] * 4, dampers=[0.1] * 4),
    "tuple (general)": lambda: (np.array([[1, 2, 2], [3, 1, 1], [3, 2, 1.0]]),
                                np.array([[3, 2, 1], [2, 1, 3], [1, 3, 2.0]]),
                                np.array([[1, 1, 2], [2, 3, 1], [3, 1, 2.0]])),
}


@pytest.mark.parametrize("make", list(SYSTEMS.values()), ids=list(SYSTEMS))
def test_lazy_parts_do_not_depend_on_the_order_they_are_read(make):
    sys = make()
    forward = _read(pinlin.modal_analysis(sys), LAZY)
    backward = _read(pinlin.modal_analysis(sys), LAZY[::-1])
    _check_same(forward, backward)
    # and the eager arrays of two analyses are bitwise the same
    a, b = pinlin.modal_analysis(sys), pinlin.modal_analysis(sys)
    for name in ("eigenvalues", "right", "left", "backward_error", "error_bound", "multiplicity"):
        assert np.array_equal(getattr(a, name), getattr(b, name))
    assert a.kind == b.kind


@pytest.mark.parametrize("make", list(SYSTEMS.values()), ids=list(SYSTEMS))
def test_lazy_parts_equal_the_eager_functions(make):
    """What the analysis defers is exactly what structural_facts and decide_stability give for its inputs."""
    sys = make()
    modes = pinlin.modal_analysis(sys)
    problem = as_problem(sys)
    facts = structural_facts(problem, 0.0)
    assert _facts_key(modes.structure) == _facts_key(facts)
    model = modes.verdict.model
    assert np.array_equal(model.bound(0.0), modes.error_bound)
    K, C = problem.K, problem.C
    verdict = decide_stability(
        facts, modes.eigenvalues, model, modes.clusters, K_is_zero=not np.any(K),
        exact_drift=bool(np.any(~np.any(K, axis=0) & ~np.any(C, axis=0))), safety=10.0, uncertainty=0.0,
        problem=problem, vectors=(modes.right, modes.left, modes.left_normalized),
    )
    assert _verdict_key(modes.stability) == _verdict_key(verdict)
    expected_notes = list(modes.verdict.notes) + mass_notes(facts, modes.eigenvalues, modes.error_bound)
    assert list(modes.notes) == expected_notes


def test_nothing_deferred_is_formed_by_the_analysis():
    modes = pinlin.modal_analysis(double_pendulum(P=4.0, c=0.05))
    assert not set(LAZY) & set(modes.__dict__)
    assert modes.error == float(np.max(modes.backward_error))  # the headline figure is eager
    repr(modes)  # repr reads the verdict's kind: formed then, and kept
    assert "stability" in modes.__dict__ and "condition" not in modes.__dict__


@pytest.mark.parametrize("read_first", [(), ("stability",), ("structure", "notes", "condition"), LAZY])
def test_pickle_round_trip_before_and_after_reading_lazy_parts(read_first):
    sys = double_pendulum(P=12.0, c=0.05)  # flutter: a verdict from the eigenvalues, with a lazy margin
    reference = _read(pinlin.modal_analysis(sys), LAZY)
    modes = pinlin.modal_analysis(sys)
    _read(modes, read_first)
    copy = pickle.loads(pickle.dumps(modes))
    assert set(read_first) <= set(copy.__dict__)
    assert np.array_equal(copy.eigenvalues, modes.eigenvalues) and copy.method.reason == modes.method.reason
    _check_same(_read(copy, LAZY), reference)
    assert _timeless(copy.to_dict()) == _timeless(modes.to_dict())


def test_to_dict_keeps_the_fields_of_pinlin_0_2_in_their_order():
    d = pinlin.modal_analysis(double_pendulum(P=4.0, c=0.05)).to_dict()
    keys = list(d)
    for name in ("structure", "stability", "notes", "condition", "constants", "participation", "method_reason"):
        assert name in d
    assert keys.index("is_simple") < keys.index("structure") < keys.index("stability") < keys.index("scaling")
    assert keys.index("elapsed") < keys.index("notes")
    assert "verdict" not in d and "deferred" not in d and "system" not in d and "matrices" not in d


def test_lazy_verdict_from_eight_threads():
    modes = pinlin.modal_analysis(double_pendulum(P=12.0, c=0.05))
    reference = _verdict_key(pinlin.modal_analysis(double_pendulum(P=12.0, c=0.05)).stability)
    seen = []
    barrier = threading.Barrier(8)

    def read():
        barrier.wait()
        seen.append(_verdict_key(modes.stability))

    threads = [threading.Thread(target=read) for _ in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert seen == [reference] * 8


@pytest.mark.filterwarnings("ignore:overflow encountered:RuntimeWarning", "ignore:invalid value:RuntimeWarning")
def test_errors_are_raised_by_modal_analysis_itself(monkeypatch):
    """An eigenvalue out of range is a ComputationError of the call, not of a later attribute access."""
    real = qep.dggev

    def huge(A, B, left=True):
        alphar, alphai, beta, vl, vr = real(A, B, left)
        beta = beta.copy()
        beta[0] = 1e-320  # lam_0 = alphar / beta overflows
        return alphar, alphai, beta, vl, vr

    monkeypatch.setattr(qep, "dggev", huge)
    with pytest.raises(pinlin.ComputationError, match="infinite eigenvalue|beyond double range"):
        pinlin.modal_analysis(double_pendulum(P=4.0, c=0.05))


def test_symmetric_path_prediction_skips_eigh_when_cond_M_forbids_it(monkeypatch):
    """eps cond(M) beyond the limit: QZ of size n directly, said in method.reason; eigh is never called."""
    masses = np.ones(6)
    masses[-1] = 1e-12
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(6, length=1.0, mass=masses))
    sys = pinlin.linearize(pinlin.Scene(robot, [pinlin.JointSpring(f"joint{i + 1}", 1.0) for i in range(6)]),
                           robot.neutral())

    def forbidden(*args, **kwargs):
        raise AssertionError("eigh was run although cond(M) predicted it fails")

    monkeypatch.setattr("pinlin.spectral.structured.refined_eigh", forbidden)
    m = pinlin.modal_analysis(sys)
    assert m.method == "symmetric" and "too ill-conditioned for eigh" in m.method.reason
    assert "right vectors only" in m.method.reason
    assert m.error <= 1e-14  # QZ is backward stable whatever cond(M)


def test_symmetric_path_prediction_keeps_eigh_when_cond_M_allows_it():
    sys = chain(20, 10.0 ** np.linspace(-5, 5, 20))
    w = np.linalg.eigvalsh(sys.M)
    assert EPS * w[-1] / w[0] < 1e-2
    m = pinlin.modal_analysis(sys)
    assert m.method == "symmetric" and "eigh" in m.method.reason and "QZ" not in m.method.reason
    assert m.error <= 1e-15
    # the reported figures are the definition's, with L(lam) = lam^2 M + S
    X = m.right
    R = (sys.M @ X) * m.eigenvalues**2 + sys.S @ X
    weight = np.abs(m.eigenvalues) ** 2 * np.linalg.norm(sys.M) + np.linalg.norm(sys.S)
    assert_allclose(m.backward_error, np.linalg.norm(R, axis=0) / weight, rtol=1e-6, atol=2 * EPS)


@pytest.mark.parametrize("n", [50, 200])
def test_backward_errors_at_rounding_on_a_stiff_chain(n):
    """Joint stiffnesses over ten decades, cond(M) up to 6e9: eigh alone leaves 1e-11 ... 1e-9."""
    rng = np.random.default_rng(0)
    sys = chain(n, 10.0 ** rng.uniform(-5, 5, n))
    plain = refined_eigh(sys.S, sys.M, np.linalg.norm(sys.S), np.linalg.norm(sys.M), tol=1e-15, max_steps=0)
    assert plain.eta.max() > 1e-12
    m = pinlin.modal_analysis(sys)
    assert m.method == "symmetric" and "Newton" in m.method.reason
    assert m.error <= 1e-15


def test_partial_newton_steps_keep_the_pairs_already_at_tolerance():
    sys = chain(40, 10.0 ** np.linspace(-5, 5, 40))
    nS, nM = np.linalg.norm(sys.S), np.linalg.norm(sys.M)
    start = refined_eigh(sys.S, sys.M, nS, nM, tol=1e-15, max_steps=0)
    done = refined_eigh(sys.S, sys.M, nS, nM, tol=1e-15)
    kept = start.eta <= 1e-15
    assert 0 < kept.sum() < kept.size and done.steps >= 1
    assert np.array_equal(done.X[:, kept], start.X[:, kept]) and np.array_equal(done.w[kept], start.w[kept])
    assert done.eta.max() <= 1e-15
    # every reported figure is the definition's for the returned vectors
    assert_allclose(done.MX, sys.M @ done.X, rtol=1e-13, atol=1e-13 * nM)
    eta = pencil_backward_errors(done.w, done.X, sys.M @ done.X, sys.S @ done.X, nS, nM)
    assert_allclose(done.eta, eta, rtol=1e-6, atol=2 * EPS)
    # a refined pair's eigenvalue is the Rayleigh quotient of its returned vector and products (a kept one is
    # eigh's, within its backward error); x^T M x cancels here (cond(M) ~ 1e8), so the products are the returned ones
    X = done.X[:, ~kept]
    quotient = np.einsum("ij,ij->j", X, done.AX[:, ~kept]) / np.einsum("ij,ij->j", X, done.MX[:, ~kept])
    assert_allclose(done.w[~kept], quotient, rtol=4 * EPS, atol=0)
    assert_allclose(done.AX, sys.S @ done.X, rtol=0, atol=1e-15 * np.abs(sys.S).max() * np.abs(done.X).max() * 40)


@settings(max_examples=300, deadline=None)
@given(
    st.lists(st.tuples(st.floats(-3, 3), st.floats(0, 3)), min_size=1, max_size=6),
    st.sampled_from([1e-5, 1e-3, 0.1]),
    st.sampled_from([0.0, 0.5, 2.0]),
)
def test_quick_no_cluster_test_never_hides_a_cluster(points, tol, scale):
    """Spectra of exact conjugate pairs (Im > 0 first) and reals, close points included by construction."""
    lam = []
    for re, im in points:
        re, im = round(re, 2), round(im, 2)  # coarse grid: near and equal points are common
        lam += [complex(re, im), complex(re, -im)] if im else [complex(re, 0)]
    lam = np.array(lam)
    if _far_apart(lam, tol, scale):
        # the full search (with every pair as a candidate) links nothing
        d = np.abs(lam[:, None] - lam[None, :])
        a = np.abs(lam)
        limit = tol * np.maximum(np.maximum(a[:, None], a[None, :]), scale)
        off = ~np.eye(lam.size, dtype=bool)
        assert not np.any((d <= limit) & off)
    else:
        assert find_clusters(lam, tol, scale) is not None  # (the full search decides; nothing claimed here)


def test_real_residual_equals_the_complex_one():
    """Real vectors with lam^2 real: L(lam) x formed in real arithmetic gives the same eta, ||x|| and w(lam)."""
    rng = np.random.default_rng(3)
    n, k = 5, 7
    X = rng.standard_normal((n, k))
    M, K = rng.standard_normal((n, n)), rng.standard_normal((n, n))
    lam = np.where(np.arange(k) % 2 == 0, 1j, 1.0) * rng.uniform(0.1, 3, k)
    products = (X, M @ X, np.zeros((n, k)), K @ X)
    norms = (np.linalg.norm(M), 0.0, np.linalg.norm(K))
    eta, nx, w = residual_figures(lam, *products, norms)
    eta_c, nx_c, w_c = residual_figures(lam, *(p.astype(complex) for p in products), norms)
    assert np.array_equal(nx, nx_c) and np.array_equal(w, w_c)
    assert_allclose(eta, eta_c, rtol=4 * EPS, atol=0)
    assert_allclose(eta, backward_errors(lam, *products, norms), rtol=0, atol=0)
    # and the definition
    R = M @ X * lam**2 + K @ X
    assert_allclose(eta, np.linalg.norm(R, axis=0) / ((np.abs(lam) ** 2 * norms[0] + norms[2]) * nx), rtol=1e-12)


def test_options_are_validated_once_and_returned_fresh():
    a = analysis._check_options("auto", True, cluster_tol=1e-5, rank_tol=1e-8, structure_tol=1e-10,
                                uncertainty=0.0, safety=10.0, eigh_tol=1e-15)
    a["safety"] = -1.0  # a caller's dict is its own
    b = analysis._check_options("auto", True, cluster_tol=1e-5, rank_tol=1e-8, structure_tol=1e-10,
                                uncertainty=0.0, safety=10.0, eigh_tol=1e-15)
    assert b["safety"] == 10.0 and a is not b
    with pytest.raises(pinlin.ParameterError, match="safety"):
        analysis._check_options("auto", True, cluster_tol=1e-5, rank_tol=1e-8, structure_tol=1e-10,
                                uncertainty=0.0, safety=0.5, eigh_tol=1e-15)
    with pytest.raises(pinlin.ParameterError, match="cluster_tol"):  # numpy scalars: validated too
        analysis._check_options("auto", True, cluster_tol=np.float64(2.0), rank_tol=1e-8, structure_tol=1e-10,
                                uncertainty=0.0, safety=10.0, eigh_tol=1e-15)


@pytest.mark.parametrize("make", [lambda: double_pendulum(P=12.0, c=0.05), lambda: SYSTEMS["tuple (general)"]()],
                         ids=["double pendulum", "tuple"])
def test_the_general_solver_stores_its_spectrum_in_the_canonical_order(make):
    """QZ's pairs are ordered by the solver itself: ordering them again changes nothing (pairs exact conjugates)."""
    from dataclasses import replace

    from pinlin.spectral.ordering import order_spectrum

    problem = as_problem(make())
    raw = qep.solve_general(problem)
    assert raw.ordered
    again = order_spectrum(replace(raw, ordered=False))
    for name in ("lam", "P", "Y", "block", "eta", "norm_x", "weight"):
        assert np.array_equal(getattr(again, name), getattr(raw, name)), name
    a = np.abs(raw.lam)
    assert np.all(np.diff(a) >= 0)
    pos = (raw.lam.imag > 0).nonzero()[0]
    assert np.array_equal(raw.lam[pos + 1], raw.lam[pos].conj())
