"""The semisimple certificate against the block Toeplitz ranks.

``modal_analysis`` decides a cluster it can certify semisimple without an SVD
(:func:`pinlin.spectral.multiplicity.semisimple_certificate`); every other
cluster still takes the Toeplitz ranks.  On a catalog of systems with known
Jordan structure -- defective pairs, derogatory clusters (chains of different
lengths at one eigenvalue), rigid-body chains, identical oscillators, talos_full_v2
with equal springs on its fingers and grippers (12 double clusters) and a chain
with 8 identical branches (clusters of 7 and 8) -- the partial multiplicities of every
cluster are those of the Toeplitz ranks alone (``analyse_cluster`` without
evidence, the code of pinlin 0.2), on every solver path that applies, and the
known structure where it is known by hand.
"""

from __future__ import annotations

import numpy as np
import pytest

import pinlin
from pinlin import JointDamper, JointSpring, LinearizedSystem, Scene
from pinlin.model.generators import branched_chain_urdf
from pinlin.model.loading import example_urdf_path
from pinlin.spectral.multiplicity import analyse_cluster
from pinlin.spectral.problem import as_problem
from spectral_cases import chain

#: talos_full_v2 (n = 44: legs, torso, arms, head and both grippers) beside talos_reduced in example-robot-data
TALOS = example_urdf_path("talos_reduced").parent / "talos_full_v2.urdf"





def branched_chain(damping: float = 0.0) -> LinearizedSystem:
    robot = pinlin.load_urdf_string(branched_chain_urdf())
    el = [JointSpring(j, 3.0) for j in robot.joint_names]
    el += [JointDamper(j, damping) for j in robot.joint_names] if damping else []
    return pinlin.linearize(Scene(robot, el, gravity=(0, 0, -9.81)), robot.neutral())


def talos(damping: float = 0.0, gravity: bool = False) -> LinearizedSystem:
    robot = pinlin.load_urdf(TALOS)
    el = [JointSpring(j, 100.0) for j in robot.joint_names]
    el += [JointDamper(j, damping) for j in robot.joint_names] if damping else []
    g = (0, 0, -9.81) if gravity else (0, 0, 0)
    return pinlin.linearize(Scene(robot, el, gravity=g), robot.neutral(), balancing=gravity)


def derogatory() -> tuple:
    """L(lam) = diag((lam + 1)^2, lam + 1 times lam + 3, lam^2 + 4): at -1 chains (2, 1); also +-2i."""
    M = np.diag([1.0, 1.0, 1.0])
    C = np.diag([2.0, 4.0, 0.0])
    K = np.diag([1.0, 3.0, 4.0])
    return M, C, K


def two_blocks() -> tuple:
    """Coupled: a Jordan pair at -1 (critical damping) and a semisimple double 2i, mixed by an orthogonal map."""
    rng = np.random.default_rng(7)
    Q, _ = np.linalg.qr(rng.standard_normal((4, 4)))
    C = Q @ np.diag([2.0, 0.0, 0.0, 5.0]) @ Q.T
    K = Q @ np.diag([1.0, 4.0, 4.0, 6.0]) @ Q.T
    return np.eye(4), C, K


#: (name, system builder, methods, the known partial multiplicities of its clusters, sorted; None: not by hand)
CATALOG = [
    ("critically damped oscillator", lambda: LinearizedSystem.from_matrices([[1.0]], [[6.0]], [[9.0]]),
     ("auto", "general"), [(2,)]),
    ("hand-derived chain", lambda: (np.eye(2), np.array([[0.0, 0.0], [1.0, 0.0]]), np.diag([0.0, 1.0])),
     ("auto",), [(2,)]),
    ("rigid-body chains", lambda: chain(3, gravity=(0, 0, 0)), ("auto", "general"), [(2, 2, 2)]),
    ("identical oscillators", lambda: LinearizedSystem.from_matrices(np.diag([2.0, 2.0]), None, np.diag([8.0, 8.0])),
     ("auto", "general"), [(1, 1), (1, 1)]),
    ("derogatory", derogatory, ("auto",), [(2, 1)]),
    ("defective and semisimple, coupled", two_blocks, ("auto",), [(1, 1), (1, 1), (2,)]),
    ("talos_full_v2 undamped", talos, ("auto", "general"), [(1, 1)] * 12),
    ("talos_full_v2 proportional", lambda: talos(0.5), ("auto", "general"), [(1, 1)] * 12),
    ("talos_full_v2 gravity, dampers", lambda: talos(0.5, gravity=True), ("auto",), [(1, 1)] * 12),
    ("8 identical branches", branched_chain, ("auto", "general"), None),
    ("8 identical branches, damped", lambda: branched_chain(0.05), ("auto", "general"), None),
]


def _toeplitz_structure(sys, modes) -> list[tuple[int, ...]]:
    """The partial multiplicities the Toeplitz ranks alone give for each of the analysis' clusters."""
    problem = as_problem(sys)
    rank_tol = modes.tolerances["rank_tol"]
    return [analyse_cluster(problem, modes.eigenvalues, c.indices, rank_tol).partial for c in modes.clusters]


@pytest.mark.parametrize("name, build, methods, known", CATALOG, ids=[c[0] for c in CATALOG])
def test_partial_multiplicities_equal_the_toeplitz_ranks(name, build, methods, known):
    sys = build()
    for method in methods:
        modes = pinlin.modal_analysis(sys, method=method)
        partial = [c.partial for c in modes.clusters]
        assert partial == _toeplitz_structure(sys, modes), (name, method)
        assert all(c.consistent for c in modes.clusters)
        if known is not None:
            assert sorted(partial) == sorted(known), (name, method)


def test_branched_chain_has_clusters_of_seven_and_eight():
    # each branch swings about x (uncoupled from the trunk at the hanging pose: 8 equal modes) and about y
    # (coupled to the trunk through the branches' sum: 7 equal antisymmetric modes and one symmetric)
    modes = pinlin.modal_analysis(branched_chain())
    assert modes.method.name == "symmetric"
    assert sorted(c.algebraic for c in modes.clusters) == [7, 7, 8, 8]
    assert all(c.partial == (1,) * c.algebraic for c in modes.clusters)


@pytest.mark.parametrize("damping, path, how", [
    # the proportional path hands its pairs over expanded (no shared-vector pairing): the residual certificate
    (0.0, "symmetric", "semisimple by structure"), (0.5, "proportional", "semisimple certificate"),
])
def test_symmetric_definite_clusters_are_decided_without_an_svd(damping, path, how):
    modes = pinlin.modal_analysis(talos(damping))
    assert modes.method.name == path
    assert len(modes.clusters) == 12
    assert all(c.method.startswith(how) and c.kernel_dims == (2,) for c in modes.clusters)
    general = pinlin.modal_analysis(talos(damping), method="general")
    assert all(c.method.startswith("semisimple certificate") for c in general.clusters)


def test_defective_and_derogatory_clusters_take_the_toeplitz_ranks():
    for sys in (derogatory(), two_blocks(), chain(3, gravity=(0, 0, 0))):
        modes = pinlin.modal_analysis(sys)
        defective = [c for c in modes.clusters if not c.semisimple]
        assert defective
        assert all(c.method.startswith("dim ker T_k") for c in defective)
        assert all(len(c.kernel_dims) >= 2 for c in defective)


def test_critically_damped_pair_on_the_proportional_path_is_not_taken_as_semisimple():
    # both roots of one mode in the cluster: the structure argument does not apply, the ranks decide
    sys = LinearizedSystem.from_matrices(np.eye(2), np.diag([2.0, 6.0]), np.diag([1.0, 9.0]))
    modes = pinlin.modal_analysis(sys)
    assert modes.method.name == "proportional"
    assert sorted(c.partial for c in modes.clusters) == [(2,), (2,)]
    assert all(c.method.startswith("dim ker T_k") for c in modes.clusters)


def test_a_close_simple_eigenvalue_defeats_the_certificate():
    # a double 2i and a simple eigenvalue 1e-9 away (relative): within the rank threshold, so the
    # certificate must not claim dim ker L = 2; the Toeplitz ranks see three small singular values
    eps = 1e-9
    M, C, K = np.eye(3), np.zeros((3, 3)), np.diag([4.0, 4.0, 4.0 * (1 + eps) ** 2])
    C[0, 1], C[1, 0] = 1e-30, -1e-30  # not symmetric: the general path
    modes = pinlin.modal_analysis((M, C, K))
    structure = _toeplitz_structure((M, C, K), modes)
    assert [c.partial for c in modes.clusters] == structure
    assert not any(c.method.startswith("semisimple") for c in modes.clusters if c.algebraic == 2)
