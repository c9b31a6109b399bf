"""Each rule of the stability verdict, directly (theory: stability).

The rules of :data:`pinlin.spectral.stability.rules.RULES` are called one by
one on hand-made evidence: structural facts of small hand systems, and
eigenvalues with first-order bounds chosen so that the safety factor decides.
Each test reads from the verdict what it *used* (``error_bound`` is the bound
times the safety factor, ``safety`` the factor) instead of rebuilding it: a
rule that ignored the safety factor, or reported a bound it did not use, fails.
"""

from __future__ import annotations

import numpy as np
import pytest

from pinlin import LinearizedSystem
from pinlin.spectral import Cluster
from pinlin.spectral.accuracy import DefectiveBound, ErrorModel
from pinlin.spectral.problem import as_problem
from pinlin.spectral.qualitative import structural_facts
from pinlin.spectral.stability import decide_stability, rules

I2, Z2 = np.eye(2), np.zeros((2, 2))
SKEW = np.array([[0.0, 1.0], [-1.0, 0.0]])
EPS = np.finfo(float).eps


def facts(M=I2, D=Z2, G=Z2, S=I2, N=Z2, uncertainty=0.0):
    return structural_facts(as_problem(LinearizedSystem(M, D, G, S, N)), uncertainty)


def evidence(f, lam, bound, *, safety=10.0, clusters=(), K_is_zero=False, exact_drift=False):
    return rules.Evidence.of(
        f, np.asarray(lam, dtype=complex), np.asarray(bound, dtype=float), clusters,
        K_is_zero=K_is_zero, exact_drift=exact_drift, safety=safety,
    )


def test_the_rules_and_their_order():
    assert [r.__name__ for r in rules.RULES] == [
        "structure_theorems", "kelvin_tait_chetaev", "lagrange_dirichlet", "certainly_unstable",
        "certainly_asymptotic", "defective_on_axis", "reflection_symmetry", "semisimple_zero", "undecided",
    ]


def test_evidence_applies_the_safety_factor_once():
    ev = evidence(facts(D=I2), [-1 + 1j, -1 - 1j], [0.01, 0.02], safety=7.0)
    assert ev.r.tolist() == [0.07, 0.14] and ev.safety == 7.0


# ------------------------------------------------------------------ theorems


def test_structure_theorems_thomson_tait_chetaev_attaches_the_bound_it_reports():
    ev = evidence(facts(D=I2, G=3 * SKEW), [-0.5 + 1j, -0.5 - 1j, -2, -3], [0.1, 0.1, 0.2, 0.3], safety=4.0)
    v = rules.structure_theorems(ev)
    assert v.kind == "asymptotically_stable" and v.theorem == "Thomson-Tait-Chetaev" and v.bounded
    assert v.eigenvalue == -0.5 + 1j and v.error_bound == 0.4 and v.safety == 4.0


def test_structure_theorems_det_sign_divergence():
    f = facts(D=I2, S=np.diag([1.0, -1.0]))
    assert f.det_sign_K == -1
    v = rules.structure_theorems(evidence(f, [0.4, -2.4, -1 + 1j, -1 - 1j], [1e-3] * 4, safety=3.0))
    assert v.kind == "divergence" and v.theorem == "sign of det K" and v.bounded is False
    assert v.eigenvalue == 0.4 and v.error_bound == pytest.approx(3e-3) and "lam = 0.4" in v.reason


def test_structure_theorems_lagrange_dirichlet_with_symmetry():
    v = rules.structure_theorems(evidence(facts(G=2 * SKEW), [1j, -1j, 3j, -3j], [1e-9] * 4, safety=2.0))
    assert v.kind == "marginally_stable" and v.theorem == "Lagrange-Dirichlet + symmetry"
    assert v.error_bound == 2e-9


def test_structure_theorems_refuse_a_mass_matrix_positive_definite_only_within_rounding():
    M = np.array([[1.0, 1.0], [1.0, 1.0 + 4 * EPS]])  # cancellation: pd as stored, not beyond rounding
    f = facts(M=M, D=I2)
    assert f.mass == "positive_semidefinite" and f.det_sign_M == 0
    v = rules.structure_theorems(evidence(f, [-1.0, -2.0, -1e7, -2e7], [1e-9, 1e-9, 1e9, 1e9], safety=1.0))
    assert v.kind == "undecided" and "M is positive definite only within rounding" in v.reason
    assert v.eigenvalue == -2e7 and v.error_bound == 1e9  # the largest eigenvalue, the doubtful one


def test_structure_theorems_decide_nothing_with_circulatory_forces():
    assert rules.structure_theorems(evidence(facts(D=I2, N=SKEW), [-1, -2, -3, -4], [0.1] * 4)) is None


def test_kelvin_tait_chetaev_names_the_kind_from_the_computed_eigenvalues():
    f = facts(D=I2, S=-I2)  # two negative eigenvalues: det K > 0, no sign argument
    assert f.negative_stiffness == 2 and f.det_sign_K == 1
    # two real positive eigenvalues, far apart: divergence
    v = rules.kelvin_tait_chetaev(evidence(f, [0.6, 1.6, -1.6, -2.6], [0.01] * 4, safety=5.0))
    assert v.kind == "divergence" and v.theorem == "Kelvin-Tait-Chetaev" and v.bounded is False
    assert v.eigenvalue == 1.6 and v.error_bound == 0.05
    # the safety factor decides whether the pair is certainly complex: |Im| = 0.3 against r = 0.1 or 1
    lam = [0.5 + 0.3j, 0.5 - 0.3j, -2.0, -3.0]
    assert rules.kelvin_tait_chetaev(evidence(f, lam, [0.1] * 4, safety=1.0)).kind == "flutter"
    v = rules.kelvin_tait_chetaev(evidence(f, lam, [0.1] * 4, safety=10.0))
    assert v.error_bound == 1.0 and "not certainly real or complex" in v.reason
    # S positive definite is not its case
    assert rules.kelvin_tait_chetaev(evidence(facts(D=I2), [-1, -2, -3, -4], [0.1] * 4)) is None


def test_lagrange_dirichlet_needs_the_bounds_for_asymptotic_stability():
    D = np.diag([1.0, 0.0])  # exact zeros: certainly positive semidefinite
    f = facts(D=D)
    assert f.damping == "positive_semidefinite" and f.definiteness_D.certainly_psd
    lam = [-0.05 + 1j, -0.05 - 1j, -1, -2]
    v = rules.lagrange_dirichlet(evidence(f, lam, [0.01] * 4, safety=1.0))
    assert v.kind == "asymptotically_stable" and v.theorem == "Lagrange-Dirichlet" and v.error_bound == 0.01
    v = rules.lagrange_dirichlet(evidence(f, lam, [0.01] * 4, safety=10.0))  # r = 0.1 reaches the axis
    assert v.kind == "undecided" and v.bounded is True and v.error_bound == 0.1
    assert "asymptotic or marginal stability cannot be told apart" in v.reason


def test_lagrange_dirichlet_needs_a_certainly_semidefinite_damping():
    rng = np.random.default_rng(0)
    Q, _ = np.linalg.qr(rng.standard_normal((2, 2)))
    D = Q @ np.diag([1.0, 0.0]) @ Q.T  # psd only within rounding: its zero eigenvalue may be -1e-17
    f = facts(D=(D + D.T) / 2)
    assert f.damping == "positive_semidefinite" and not f.definiteness_D.certainly_psd
    assert rules.lagrange_dirichlet(evidence(f, [-1e-3 + 1j, -1e-3 - 1j, -1, -2], [0.1] * 4)) is None


# ------------------------------------------------------------------ the computed spectrum

GENERAL = facts(D=I2, N=SKEW)  # circulatory: no theorem, the spectrum decides


def test_certainly_unstable_uses_the_safety_factor():
    lam = [0.5 + 1j, 0.5 - 1j, -1, -2]
    assert rules.certainly_unstable(evidence(GENERAL, lam, [0.1] * 4, safety=10.0)) is None  # 0.5 < 1
    v = rules.certainly_unstable(evidence(GENERAL, lam, [0.1] * 4, safety=4.0))
    assert v.kind == "flutter" and v.error_bound == pytest.approx(0.4) and v.safety == 4.0 and v.bounded is False
    v = rules.certainly_unstable(evidence(GENERAL, [0.5, -0.5, -1, -2], [0.01] * 4, safety=10.0))
    assert v.kind == "divergence" and v.eigenvalue == 0.5


def test_certainly_asymptotic_uses_the_safety_factor_and_names_the_closest_call():
    lam = [-0.5 + 1j, -0.5 - 1j, -0.3, -5]
    bound = [0.01, 0.01, 0.02, 0.45]
    assert rules.certainly_asymptotic(evidence(GENERAL, lam, bound, safety=20.0)) is None  # -0.3 + 0.4 > 0
    v = rules.certainly_asymptotic(evidence(GENERAL, lam, bound, safety=10.0))
    assert v.kind == "asymptotically_stable" and v.theorem is None
    assert v.eigenvalue == -0.3 and v.error_bound == pytest.approx(0.2)  # Re + r largest: -0.1


def test_defective_on_axis_is_a_boundary_unless_the_drift_is_exact():
    sym = facts(N=0.0 * SKEW, S=I2)  # D = G = N = 0: reflection symmetric
    lam = [1j + 1e-9, 1j - 1e-9, -1j + 1e-9, -1j - 1e-9]
    clusters = (Cluster(
        indices=(0, 1), center=1j, algebraic=2, geometric=1, partial=(2,), consistent=True,
        kernel_dims=(1, 2),
    ), Cluster(
        indices=(2, 3), center=-1j, algebraic=2, geometric=1, partial=(2,), consistent=True,
        kernel_dims=(1, 2),
    ))
    v = rules.defective_on_axis(evidence(sym, lam, [1e-8] * 4, clusters=clusters, safety=1.0))
    assert v.kind == "undecided" and "flutter onset" in v.reason and v.error_bound == 1e-8
    # a defective zero eigenvalue with K = C = 0 on a coordinate: x = t e_j exactly, divergence
    zero = facts(S=Z2)
    lam0 = [0.0, 1e-9, -1e-9, 0.0]
    c0 = (Cluster(
        indices=(0, 1, 2, 3), center=0j, algebraic=4, geometric=2, partial=(2, 2), consistent=True,
        kernel_dims=(2, 4),
    ),)
    v = rules.defective_on_axis(evidence(zero, lam0, [1e-8] * 4, clusters=c0, K_is_zero=True, exact_drift=True))
    assert v.kind == "divergence" and v.theorem == "Jordan structure + exact drift" and v.bounded is False
    # outside its bound of the axis the cluster is not this rule's business
    assert rules.defective_on_axis(evidence(sym, lam, [1e-10] * 4, clusters=clusters, safety=1.0)) is None


def test_reflection_symmetry_needs_isolation_measured_with_the_safety_factor():
    f = facts(N=2 * SKEW)  # D = G = 0, N != 0: symmetric spectrum
    assert f.reflection_symmetric
    lam = [1e-7 + 1j, -1e-7 + 1j, 1e-7 - 1j, -1e-7 - 1j]  # two close pairs
    # bound 1e-6: isolated needs a gap above 3 r + r = 4e-6 (safety 1) or 4e-5 (safety 10)
    far = np.array([1j, 1.001j, -1j, -1.001j]) + 1e-7
    v = rules.reflection_symmetry(evidence(f, far, [1e-6] * 4, safety=1.0))
    assert v.kind == "marginally_stable" and v.theorem == "reflection symmetry" and v.error_bound == 1e-6
    close = np.array([1j, 1j + 1e-5, -1j, -1j - 1e-5]) + 1e-7
    assert rules.reflection_symmetry(evidence(f, close, [1e-6] * 4, safety=1.0)).kind == "marginally_stable"
    v = rules.reflection_symmetry(evidence(f, close, [1e-6] * 4, safety=10.0))
    assert v.kind == "undecided" and "not isolated" in v.reason and v.error_bound == pytest.approx(1e-5)
    assert rules.reflection_symmetry(evidence(f, lam, [1e-6] * 4)).kind == "undecided"


def test_reflection_symmetry_is_never_claimed_with_damping_or_with_both_G_and_N():
    """D = 0 with G != 0 and N != 0: det L(-lam) != det L(lam), the mirror argument is void (flutter possible)."""
    both = facts(G=SKEW, N=1e-15 * SKEW)
    assert not both.reflection_symmetric
    near_axis = [1e-20 + 1j, 1e-20 - 1j, -1e-20 + 2j, -1e-20 - 2j]
    assert rules.reflection_symmetry(evidence(both, near_axis, [1e-12] * 4)) is None
    assert not facts(D=1e-3 * I2).reflection_symmetric


def test_semisimple_zero_with_every_other_eigenvalue_certainly_left():
    f = facts(D=I2, S=Z2)
    lam = [0.0, 0.0, -1.0, -1.0]
    c = (Cluster(
        indices=(0, 1), center=0j, algebraic=2, geometric=2, partial=(1, 1), consistent=True,
        kernel_dims=(2,),
    ),)
    v = rules.semisimple_zero(evidence(f, lam, [1e-3] * 4, clusters=c, K_is_zero=True, safety=10.0))
    assert v.kind == "marginally_stable" and v.theorem == "Jordan structure" and v.error_bound == 1e-2
    # the safety factor brings the others' bounds to the axis: not decided
    assert rules.semisimple_zero(evidence(f, lam, [0.2] * 4, clusters=c, K_is_zero=True, safety=10.0)) is None
    assert rules.semisimple_zero(evidence(f, lam, [1e-3] * 4, clusters=c, K_is_zero=False)) is None


def test_undecided_always_decides_and_names_the_doubtful_eigenvalue():
    v = rules.undecided(evidence(GENERAL, [1e-4 + 1j, 1e-4 - 1j, -1, -2], [1e-4] * 4, safety=3.0))
    assert v.kind == "undecided" and v.error_bound == pytest.approx(3e-4) and v.bounded is None
    assert v.margin == 0.0 and v.error == 1.0


# ------------------------------------------------------------------ the verdict and its margin


def test_decide_stability_reports_the_margin_it_found():
    """For certainly_asymptotic with simple eigenvalues the margin is known in closed form:
    r_k(delta) = (eta_k + delta) s_k reaches |Re lam_k| / safety at delta = |Re lam_k| / (safety s_k) - eta_k."""
    lam = np.array([-0.5 + 1j, -0.5 - 1j, -2.0, -3.0])
    model = ErrorModel(eta=np.full(4, EPS), sensitivity=np.array([1.0, 1.0, 40.0, 3.0]))
    v = decide_stability(GENERAL, lam, model, (), safety=10.0)
    expected = min(0.5 / 10 - EPS, 2.0 / 400 - EPS, 3.0 / 30 - EPS)  # the real eigenvalue -2 decides
    assert v.kind == "asymptotically_stable" and v.theorem is None
    assert expected * (1 - 1e-4) <= v.margin <= expected
    assert f"margin {v.margin:.1e}" in v.reason and v.error == EPS / v.margin
    # against a stated uncertainty below the margin the verdict stands; above it, it does not
    assert decide_stability(GENERAL, lam, model, (), safety=10.0, uncertainty=0.9 * expected).kind == v.kind
    assert decide_stability(GENERAL, lam, model, (), safety=10.0, uncertainty=1.1 * expected).kind == "undecided"


def test_defective_bounds_grow_with_the_root_of_the_uncertainty():
    model = ErrorModel(
        eta=np.full(2, EPS), sensitivity=np.array([np.inf, np.inf]),
        defective=(DefectiveBound(indices=(0, 1), spread=1e-9, scale=2.0, eta=EPS, index=2),),
    )
    assert model.bound(0.0) == pytest.approx(1e-9 + 2 * np.sqrt(EPS))
    assert model.bound(1e-6) == pytest.approx(1e-9 + 2 * np.sqrt(EPS + 1e-6))
