"""Margins that say what they cover, and dissipation-induced instability (theory: stability).

Sources:

- Ziegler's column: H. Ziegler, "Die Stabilitaetskriterien der Elastomechanik", Ing.-Arch. 20 (1952) 49-56, and
  "Linear elastic stability", ZAMP 4 (1953); O. N. Kirillov, *Nonconservative Stability Problems of Modern
  Physics* (de Gruyter, 2013), sec. 1.2: two rigid links of length l, point masses 2m (middle joint) and m (tip),
  joint springs k, a follower load P at the tip, no gravity.  In the joint angles (phi1 of the lower link,
  phi2 the relative angle; tip displacement l (2 phi1 + phi2), middle joint l phi1):
  M = m l^2 [[6, 2], [2, 1]], K = [[k, P l], [0, k]] - [[0, 0], [0, 0]]... exactly
  K = [[2k - P l, P l - k], [-k, k]] in absolute angles, which is [[k, P l], [0, k]] in joint angles
  (with T = [[1, 0], [1, 1]] mapping joint to absolute angles: T^T K_abs T).  Undamped flutter at
  P = (7/2 - sqrt 2) k / l; with equal joint dampers, in the limit of vanishing damping, P = 41/28 k / l.
- Characteristic polynomial of a 2-DOF system with D = eps D1: det(lam^2 M + eps lam D1 + K) =
  a4 lam^4 + eps b3 lam^3 + a2 lam^2 + eps b1 lam + a0 + O(eps^2) with a4 = det M, b3 = <M, D1>,
  a2 = <M, K>, b1 = <D1, K>, a0 = det K (<A, B> = A11 B22 + A22 B11 - A12 B21 - A21 B12).  At a root
  lam = i omega of the undamped polynomial the first-order rate is (implicit function theorem)
  d lam / d eps = -(b3 lam^3 + b1 lam) / (4 a4 lam^3 + 2 a2 lam) = -(b1 - b3 omega^2) / (2 a2 - 4 a4 omega^2),
  real; the Hurwitz determinant H3 / eps^2 = b3 a2 b1 - a4 b1^2 - b3^2 a0 changes sign where it does
  (theory: stability).
- Gyroscopic stabilization (Thomson and Tait 1879; Chetaev): M = I, S = diag(k1, k2) with k1, k2 < 0,
  G = g [[0, -1], [1, 0]]: det = lam^4 + (k1 + k2 + g^2) lam^2 + k1 k2, stable iff g^2 > (sqrt(-k1) +
  sqrt(-k2))^2; any full damping destabilizes (Kelvin-Tait-Chetaev); with D = eps I the rate is
  -(k1 + k2 - 2 omega^2) / (2 (k1 + k2 + g^2) - 4 omega^2).
"""

from __future__ import annotations

import json

import mpmath as mp
import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin

mp.mp.dps = 40

_T = np.array([[1.0, 0.0], [1.0, 1.0]])  # joint angles -> absolute angles


def ziegler_matrices(P):
    """(M, K) of Ziegler's column in joint angles (k = l = m = 1), derived in the module doc."""
    M_abs = np.array([[3.0, 1.0], [1.0, 1.0]])
    K_abs = np.array([[2.0 - P, P - 1.0], [-1.0, 1.0]])
    return _T.T @ M_abs @ _T, _T.T @ K_abs @ _T


def ziegler_system(P, D=None):
    M, K = ziegler_matrices(P)
    return pinlin.LinearizedSystem.from_matrices(M, D, K)


def _mp_ziegler(P):
    P = mp.mpf(P)
    return mp.matrix([[6, 2], [2, 1]]), mp.matrix([[1, P], [0, 1]])


def _det(A):
    return A[0, 0] * A[1, 1] - A[0, 1] * A[1, 0]


def _bracket(A, B):
    return A[0, 0] * B[1, 1] + A[1, 1] * B[0, 0] - A[0, 1] * B[1, 0] - A[1, 0] * B[0, 1]


def _coefficients(M, K, D1):
    return _det(M), _bracket(M, D1), _bracket(M, K), _bracket(D1, K), _det(K)


def rates_closed_form(M, K, D1):
    """(omega, d lam / d eps) for each undamped frequency of a 2-DOF system (module doc), mpmath."""
    a4, b3, a2, b1, a0 = _coefficients(M, K, D1)
    disc = mp.sqrt(a2**2 - 4 * a4 * a0)
    out = []
    for w2 in ((a2 - disc) / (2 * a4), (a2 + disc) / (2 * a4)):  # a4 w^4 - a2 w^2 + a0 = 0
        out.append((mp.sqrt(w2), -(b1 - b3 * w2) / (2 * a2 - 4 * a4 * w2)))
    return out


def hurwitz_limit(M, K, D1):
    a4, b3, a2, b1, a0 = _coefficients(M, K, D1)
    return b3 * a2 * b1 - a4 * b1**2 - b3**2 * a0


def _row(stability, prefix):
    return next(r for r in stability.dissipation if r.shape.startswith(prefix))


# ----------------------------------------------------------------------------- Ziegler's column


def test_ziegler_at_1_8_is_marginal_but_damping_destabilizes():
    modes = pinlin.modal_analysis(ziegler_system(1.8))
    st = modes.stability
    assert st.kind == "marginally_stable"
    # the structured margin says what it kept; the unstructured one is 0 and says what breaks it
    assert "perturbations that keep D = 0 and G = 0 exactly" in st.reason
    assert "every system within that relative perturbation of the data" not in st.reason
    assert st.unstructured_margin == 0.0
    assert "equal dampers" in st.unstructured_reason and "into Re lam > 0" in st.unstructured_reason
    assert "dissipation-induced instability" in st.reason
    equal = _row(st, "equal dampers")
    assert equal.destabilizes is True and equal.theorem is None
    assert_allclose(equal.D1, np.eye(2), rtol=0, atol=0)
    M, K = _mp_ziegler("1.8")
    closed = rates_closed_form(M, K, mp.eye(2))
    rate = max(float(r) for _, r in closed)
    omega = float(max(closed, key=lambda c: c[1])[0])
    assert abs(equal.rate - rate) <= 1e-10, (equal.rate, rate)
    assert abs(equal.rate - rate) <= max(equal.rate_error, 1e-15) * 10
    assert 0 < equal.rate_error < 1e-11
    assert_allclose(equal.eigenvalue.imag, omega, rtol=1e-14)
    assert hurwitz_limit(M, K, mp.eye(2)) < 0  # the Hurwitz condition of the limit fails: unstable
    # and a real small damping shows it: Re lam = rate eps + O(eps^2)
    eps = 1e-8
    lam = pinlin.modal_analysis(ziegler_system(1.8, eps * np.eye(2))).eigenvalues
    assert_allclose(lam.real.max() / eps, rate, rtol=1e-6)
    # Bottema: N != 0, x and y not parallel, so some D1 >= 0 destabilizes
    worst = st.dissipation[0]
    assert worst.destabilizes is True and worst.theorem == "Bottema"
    w = np.linalg.eigvalsh(worst.D1)
    assert_allclose(w, [0.0, 1.0], atol=1e-15)  # rank one, unit norm


def test_ziegler_below_the_damped_limit_equal_dampers_stabilize():
    modes = pinlin.modal_analysis(ziegler_system(1.2))
    st = modes.stability
    assert st.kind == "marginally_stable" and st.unstructured_margin == 0.0
    equal = _row(st, "equal dampers")
    M, K = _mp_ziegler("1.2")
    rate = max(float(r) for _, r in rates_closed_form(M, K, mp.eye(2)))
    assert rate < 0 and hurwitz_limit(M, K, mp.eye(2)) > 0
    assert equal.destabilizes is False
    assert abs(equal.rate - rate) <= 1e-10
    assert "unstructured margin 0: damping D = eps D1 of shape" in st.reason
    # still, some positive semidefinite damping destabilizes (Bottema)
    assert st.dissipation[0].destabilizes is True


def test_ziegler_through_the_urdf_gives_the_same_table():
    from boundaries.boundary_cases import ziegler

    sys = ziegler()(1.8)
    M, K = ziegler_matrices(1.8)
    assert_allclose(sys.M, M, atol=1e-14)
    assert_allclose(sys.S + sys.N, K, atol=1e-14)
    equal = _row(pinlin.modal_analysis(sys).stability, "equal dampers")
    expected = _row(pinlin.modal_analysis(ziegler_system(1.8)).stability, "equal dampers")
    assert equal.destabilizes is True
    assert_allclose(equal.rate, expected.rate, rtol=1e-12)


# ----------------------------------------------------------------------------- theorems


def test_gyroscopic_stabilization_is_destroyed_by_any_full_damping():
    k1, k2, g = -1.0, -2.0, 3.0  # g^2 = 9 > (1 + sqrt 2)^2 = 5.83
    J = np.array([[0.0, -1.0], [1.0, 0.0]])
    sys = pinlin.LinearizedSystem(np.eye(2), np.zeros((2, 2)), g * J, np.diag([k1, k2]), np.zeros((2, 2)))
    st = pinlin.modal_analysis(sys).stability
    assert st.kind == "marginally_stable" and st.unstructured_margin == 0.0
    assert "perturbations that keep D = 0 and N = 0 exactly" in st.reason
    worst, equal = st.dissipation[0], _row(st, "equal dampers")
    assert worst.destabilizes is True and worst.theorem == "Kelvin-Tait-Chetaev"
    assert equal.destabilizes is True and equal.theorem == "Kelvin-Tait-Chetaev"
    mass = _row(st, "Rayleigh, mass")
    assert mass.destabilizes is True and mass.theorem == "Kelvin-Tait-Chetaev"
    # closed form of the rate for D1 = I
    s, gg = mp.mpf(k1 + k2), mp.mpf(g) ** 2
    disc = mp.sqrt((s + gg) ** 2 - 4 * k1 * k2)
    rates = [-(s - 2 * w2) / (2 * (s + gg) - 4 * w2) for w2 in (((s + gg) - disc) / 2, ((s + gg) + disc) / 2)]
    assert abs(equal.rate - float(max(rates))) <= 1e-10
    assert float(max(rates)) > 0


def test_conservative_system_with_positive_stiffness_is_never_destabilized():
    sys = pinlin.LinearizedSystem.from_matrices(np.diag([1.0, 2.0]), None, [[3.0, 1.0], [1.0, 2.0]])
    st = pinlin.modal_analysis(sys).stability
    assert st.kind == "marginally_stable" and st.unstructured_margin == 0.0
    assert "conservative" in st.reason or "D = 0 and G = 0" in st.reason
    for row in st.dissipation:
        assert row.destabilizes is False and row.theorem == "Lagrange-Dirichlet (Kelvin)", row
    # x = y real: the rate is -x^T D1 x / (2 x^T M x) < 0 (theory: stability); D1 = M gives exactly -1/2
    assert_allclose(_row(st, "Rayleigh, mass").rate, -0.5, rtol=1e-14)
    assert "dissipation-induced" not in st.reason


# ----------------------------------------------------------------------------- the unstructured margin


def test_unstructured_margin_of_an_asymptotic_verdict_is_its_formula():
    """delta_u = min_k |Re lam_k| / (f s_k) - eta_k with s_k from x, y and the weights (module doc of unstructured)."""
    sys = ziegler_system(1.2, 0.1 * np.eye(2))
    modes = pinlin.modal_analysis(sys)
    st = modes.stability
    assert st.kind == "asymptotically_stable"
    M, C, K = sys.M, sys.D + sys.G, sys.S + sys.N
    nM, nC, nK = (np.linalg.norm(A) for A in (M, C, K))
    cC = max(nC, np.sqrt(nM * nK))
    expected = np.inf
    for k, lam in enumerate(modes.eigenvalues):
        x = modes.right[:, k]
        L = lam**2 * M + lam * C + K
        # the left vector from the definition: the null vector of L^T, by SVD
        y = np.linalg.svd(L.T)[2][-1].conj()
        s = (abs(lam) ** 2 * nM + abs(lam) * cC + nK) * np.linalg.norm(x) * np.linalg.norm(y) / abs(
            y @ (2 * lam * M + C) @ x)
        eta = np.linalg.norm(L @ x) / ((abs(lam) ** 2 * nM + abs(lam) * nC + nK) * np.linalg.norm(x))
        expected = min(expected, abs(lam.real) / (10.0 * s) - max(eta, np.finfo(float).eps))
    assert_allclose(st.unstructured_margin, expected, rtol=1e-6)
    assert st.unstructured_margin < st.margin  # the larger class of perturbations: the smaller margin
    assert "first-order" in st.unstructured_reason and "all of M, D, G, S, N" in st.unstructured_reason
    assert st.dissipation == ()


def test_to_dict_carries_both_margins_and_the_table():
    st = pinlin.modal_analysis(ziegler_system(1.8)).stability
    data = json.loads(json.dumps(st.to_dict(), allow_nan=False))
    assert data["margin"] == st.margin and data["unstructured_margin"] == 0.0
    assert data["kept"].startswith("perturbations that keep D = 0 and G = 0")
    shapes = [r["shape"] for r in data["dissipation"]]
    assert any(s.startswith("equal dampers") for s in shapes)
    assert data["dissipation"][1]["destabilizes"] is True


# ----------------------------------------------------------------------------- one number for one bound


def test_default_scene_quotes_one_bound_and_has_no_negative_zero(tmp_path):
    from pinlin.cli import main

    out_json = tmp_path / "r.json"
    assert main(["analyze", "--json", str(out_json)]) == 0
    report = json.loads(out_json.read_text())
    modes = report["modes"]
    assert "underdamped" not in modes["kind"] and set(modes["kind"]) == {"undamped"}
    # the table's bound column is modes.error_bound, and the verdict names the factor it applied to it
    bounds = [float(b) for b in modes["error_bound"]]
    column = [line.split()[8] for line in modes["table"].splitlines()[3:7]]  # after |lam| in rad/s and Hz
    assert column == [f"{b:.1e}" for b in bounds]
    reason = report["stability"]["reason"]
    i = int(np.argmax(bounds))
    assert f"bound {10 * bounds[i]:.1e} (the safety factor 10 times the error bound {bounds[i]:.1e})" in reason
    text = json.dumps(report)
    assert "-0.0," not in text and "-0.0]" not in text and "-0," not in text
    assert all(not (float(z) == 0 and np.signbit(float(z))) for z in modes["damping_ratio"])


def test_state_space_export_has_no_negative_zero():
    from pinlin.model.scene_file import default_scene_path, load_scene
    from pinlin.report.document import analyze

    _, sys, _ = analyze(load_scene(default_scene_path()))
    ss = pinlin.state_space(sys)
    for name in ("A", "B", "C", "D"):
        a = getattr(ss, name)
        assert not np.any((a == 0) & np.signbit(a)), name
    A, B, _ = sys.first_order(np.eye(2))
    assert not np.any((A == 0) & np.signbit(A)) and not np.any((B == 0) & np.signbit(B))


# ----------------------------------------------------------------------------- the vanishing-damping limit


def _limit_closed_form(d1, d2):
    """Root of b3 a2 b1 - a4 b1^2 - b3^2 a0 = 0 for Ziegler's column with D1 = diag(d1, d2) in joint angles.

    With M = [[6, 2], [2, 1]], K = [[1, P], [0, 1]]: a4 = 2, b3 = d1 + 6 d2, a2 = 7 - 2P, b1 = d1 + d2,
    a0 = 1, so P = (7 - (2 b1^2 + b3^2) / (b3 b1)) / 2 (41/28 for d1 = d2).
    """
    d1, d2 = mp.mpf(d1), mp.mpf(d2)
    b3, b1 = d1 + 6 * d2, d1 + d2
    closed = (7 - (2 * b1**2 + b3**2) / (b3 * b1)) / 2
    # the same from the general 2-DOF condition, solved numerically in mpmath
    root = mp.findroot(lambda P: hurwitz_limit(*_mp_ziegler(P), mp.diag([d1, d2])), closed + mp.mpf("0.01"))
    assert abs(root - closed) < mp.mpf(10) ** -30
    return float(closed)


def test_vanishing_damping_limit_of_equal_dampers_is_41_28():
    r = pinlin.critical_parameter(ziegler_system, (0.5, 3.0), damping=np.eye(2))
    assert r.mechanism == "vanishing damping" and r.kind == "flutter"
    assert abs(r.value - 41 / 28) <= 1e-10, r.value - 41 / 28
    assert abs(r.value - 41 / 28) <= r.error_bound < 1e-10
    assert _limit_closed_form(1, 1) == pytest.approx(41 / 28, rel=1e-15)
    # the limit lies below the undamped flutter load 7/2 - sqrt 2 (Ziegler's paradox)
    assert r.value < 3.5 - np.sqrt(2.0)
    # and the limit is the limit: the damped flutter load at a small eps is close (Routh-Hurwitz)
    from boundaries.boundary_cases import damped_flutter_load, ziegler_theta

    assert abs(float(damped_flutter_load(ziegler_theta, mp.mpf("1e-6"), 10.0)) - r.value) < 1e-6


def test_vanishing_damping_limit_of_dampers_c_and_3c():
    expected = _limit_closed_form(1, 3)
    assert_allclose(expected, 139 / 152, rtol=1e-15)
    r = pinlin.critical_parameter(ziegler_system, (0.5, 3.0), damping=np.diag([1.0, 3.0]))
    assert abs(r.value - expected) <= 1e-10
    assert abs(r.value - expected) <= r.error_bound
    # a callable shape p -> D1 (scaled: the limit depends on the shape, not its size)
    r2 = pinlin.critical_parameter(ziegler_system, (0.5, 3.0), damping=lambda P: 5.0 * np.diag([1.0, 3.0]))
    assert abs(r2.value - expected) <= 1e-10


def test_vanishing_damping_limit_through_the_urdf():
    from boundaries.boundary_cases import ziegler

    r = pinlin.critical_parameter(ziegler(), (0.5, 3.0), damping=np.eye(2))
    assert abs(r.value - 41 / 28) <= 1e-10


def test_mass_proportional_damping_keeps_the_undamped_flutter_load():
    """D1 = M: d lam / d eps = -1/2 for every mode (D = G = 0), so the limit is the coalescence 7/2 - sqrt 2."""
    r = pinlin.critical_parameter(ziegler_system, (0.5, 3.0), damping=ziegler_matrices(0.0)[0])
    assert r.mechanism == "coalescence"
    assert abs(r.value - (3.5 - np.sqrt(2.0))) <= max(r.error_bound, 1e-12)
    assert any("limit is it" in n for n in r.notes)


def test_vanishing_damping_refuses_bad_input():
    with pytest.raises(pinlin.ParameterError, match="damping"):
        pinlin.critical_parameter(ziegler_system, (0.5, 3.0), damping=np.eye(3))
    with pytest.raises(pinlin.ParameterError, match="symmetric"):
        pinlin.critical_parameter(ziegler_system, (0.5, 3.0), damping=[[1.0, 1.0], [0.0, 1.0]])
    with pytest.raises(pinlin.BracketError, match="stabilize"):
        pinlin.critical_parameter(ziegler_system, (1.8, 3.0), damping=np.eye(2))


def test_sleeping_top_is_the_gyroscopic_twin():
    """The sleeping top (theory: boundaries): M = A I, G = C Omega J, S = -m g l I; stable iff C^2 Omega^2 > 4 A m g l.

    With D = eps I, p(lam) = (A lam^2 + eps lam - mgl)^2 + (C Omega lam)^2, so at lam = i omega
    (A omega^2 - C Omega omega + mgl = 0) the rate is (A omega^2 + mgl) / (C^2 Omega^2 - 2 A (A omega^2 + mgl)).
    """
    A, C, mgl, Omega = 1.0, 0.5, 1.0, 5.0  # C^2 Omega^2 = 6.25 > 4
    J = np.array([[0.0, -1.0], [1.0, 0.0]])
    sys = pinlin.LinearizedSystem(A * np.eye(2), np.zeros((2, 2)), C * Omega * J, -mgl * np.eye(2), np.zeros((2, 2)))
    st = pinlin.modal_analysis(sys).stability
    assert st.kind == "marginally_stable" and st.unstructured_margin == 0.0
    assert "D = 0 and N = 0" in st.kept
    equal = _row(st, "equal dampers")
    assert equal.destabilizes is True and equal.theorem == "Kelvin-Tait-Chetaev"
    disc = mp.sqrt(mp.mpf(C * Omega) ** 2 - 4 * A * mgl)
    rates = []
    for omega in ((C * Omega - disc) / (2 * A), (C * Omega + disc) / (2 * A)):
        e = A * omega**2 + mgl
        rates.append(e / ((C * Omega) ** 2 - 2 * A * e))
    assert abs(equal.rate - float(max(rates))) <= 1e-10


def test_exported_numbers_have_no_negative_zero():
    """to_dict turns an exact -0.0 into 0 (every JSON export goes through it), e.g. an equilibrium's q."""
    from pinlin.results import to_jsonable

    assert json.dumps(to_jsonable(np.array([-0.0, 0.0, -1.5]))) == "[0.0, 0.0, -1.5]"
    assert json.dumps(to_jsonable(complex(-0.0, -0.0))) == '{"re": 0.0, "im": 0.0}'
