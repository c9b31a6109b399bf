"""The projected pencil's Jordan structure against the block Toeplitz ranks.

``modal_analysis`` decides a cluster it cannot certify semisimple from the m x m
pencil projected on the cluster's deflating subspace
(:func:`pinlin.spectral.projected.projected_structure`) when n is large enough for
that to pay, and from the full Toeplitz ranks otherwise.  Here the projected path
is forced on every cluster of the catalog of ``test_multiplicity_certificate``
(whatever n) and must give the Toeplitz ranks' partial multiplicities and kernel
dimensions whenever it decides, and decide every defective and derogatory
cluster of the catalog; on larger systems (n = 40, talos_full_v2 with four free
gripper joints) modal_analysis itself takes it, with the known structure.
Clusters taken from their conjugates carry bitwise the numbers computed afresh.
"""

from __future__ import annotations

import numpy as np
import pytest
from test_multiplicity_certificate import CATALOG, TALOS, branched_chain

import pinlin
from pinlin import JointDamper, JointSpring, LinearizedSystem, Scene
from pinlin.spectral import clusters
from pinlin.spectral.multiplicity import analyse_cluster, partial_multiplicities, rank_threshold
from pinlin.spectral.problem import as_problem
from pinlin.spectral.projected import PROJECTION_MIN_ORDER, projected_pays, projected_structure

PROJECTED = "dim ker T_k of the m x m pencil"
TOEPLITZ = "dim ker T_k of the block Toeplitz"

#: Catalog entries whose defective or derogatory clusters the projected path must decide itself.
DECIDED = {
    "critically damped oscillator", "hand-derived chain", "rigid-body chains", "derogatory",
    "defective and semisimple, coupled",
}


def _analysed(sys, method, monkeypatch):
    """modal_analysis of sys and, for every cluster it analysed (not taken from a conjugate), the inputs and result."""
    seen = []
    real = clusters.analyse_cluster

    def record(problem, lam, indices, rank_tol, evidence=None):
        c = real(problem, lam, indices, rank_tol, evidence)
        seen.append((problem, lam, indices, rank_tol, evidence, c))
        return c

    monkeypatch.setattr(clusters, "analyse_cluster", record)
    modes = pinlin.modal_analysis(sys, method=method)
    monkeypatch.undo()
    return modes, seen


def _forced(problem, lam, indices, rank_tol, evidence, center):
    """The projected path's (partial, dims) whatever n (None: undecided), and the full Toeplitz ranks'."""
    m = len(indices)
    projected = projected_structure(
        problem, lam, indices, center, evidence, rank_tol, rank_threshold(problem, center, rank_tol)
    )
    toeplitz = partial_multiplicities(problem, center, max_length=m + 1, rank_tol=rank_tol, max_total=m)
    return projected, toeplitz


@pytest.mark.parametrize("name, build, methods, known", CATALOG, ids=[c[0] for c in CATALOG])
def test_forced_projected_path_equals_the_toeplitz_ranks(name, build, methods, known, monkeypatch):
    sys = build()
    for method in methods:
        _, seen = _analysed(sys, method, monkeypatch)
        assert seen, (name, method)
        for problem, lam, indices, rank_tol, evidence, c in seen:
            projected, toeplitz = _forced(problem, lam, indices, rank_tol, evidence, c.center)
            assert toeplitz[0] == c.partial
            if projected is not None:
                assert projected == toeplitz, (name, method, indices)
            if name in DECIDED and not c.semisimple:
                assert projected is not None, (name, method, indices)


def test_a_close_simple_eigenvalue_leaves_the_projected_path_undecided(monkeypatch):
    # the double 2i of test_multiplicity_certificate with a simple eigenvalue 1e-9 away (relative): the full
    # ranks see three small singular values, so the projected path must not decide the cluster alone
    eps = 1e-9
    M, C, K = np.eye(3), np.zeros((3, 3)), np.diag([4.0, 4.0, 4.0 * (1 + eps) ** 2])
    C[0, 1], C[1, 0] = 1e-30, -1e-30
    _, seen = _analysed((M, C, K), "auto", monkeypatch)
    doubles = [s for s in seen if len(s[2]) == 2]
    assert doubles
    for problem, lam, indices, rank_tol, evidence, c in doubles:
        assert _forced(problem, lam, indices, rank_tol, evidence, c.center)[0] is None


def mixed(n: int, modes, seed: int = 5) -> tuple:
    """M = I, C = Q diag(d) Q^T, K = Q diag(k) Q^T (Q random orthogonal): modes lam^2 + d_i lam + k_i = 0.

    The first modes are given; the others have d in [0.1, 1], k in [1, 10] (complex roots, Re in [-0.5, -0.05]).
    """
    rng = np.random.default_rng(seed)
    Q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    d, k = rng.uniform(0.1, 1.0, n), rng.uniform(1.0, 10.0, n)
    for i, (di, ki) in enumerate(modes):
        d[i], k[i] = di, ki
    return np.eye(n), Q @ np.diag(d) @ Q.T, Q @ np.diag(k) @ Q.T


#: lam = -1 three times critically damped: chains (2, 2, 2).
DEFECTIVE = ([(2.0, 1.0)] * 3, (2, 2, 2), -1.0)
#: lam = -2 critically damped, and lam^2 + 5 lam + 6 = (lam + 2)(lam + 3): chains (2, 1) at -2.
DEROGATORY = ([(4.0, 4.0), (5.0, 6.0)], (2, 1), -2.0)


@pytest.mark.parametrize("modes, partial, at", [DEFECTIVE, DEROGATORY], ids=["defective", "derogatory"])
@pytest.mark.parametrize("as_system", [False, True], ids=["tuple", "LinearizedSystem"])
def test_modal_analysis_takes_the_projected_path_for_large_n(modes, partial, at, as_system):
    data = mixed(40, modes)
    sys = LinearizedSystem.from_matrices(*data) if as_system else data
    result = pinlin.modal_analysis(sys)
    (c,) = result.clusters
    assert c.method.startswith(PROJECTED)
    assert c.partial == partial and c.consistent and c.algebraic == sum(partial)
    assert c.geometric == len(partial)
    assert c.center == pytest.approx(at, abs=1e-12)
    toeplitz = analyse_cluster(as_problem(sys), result.eigenvalues, c.indices, result.tolerances["rank_tol"])
    assert (toeplitz.partial, toeplitz.kernel_dims) == (c.partial, c.kernel_dims)
    assert toeplitz.method.startswith(TOEPLITZ)


def test_talos_with_free_gripper_joints_has_rigid_body_chains_decided_by_projection():
    # four gripper joints without spring or damper: lam = 0 with chains (2, 2, 2, 2) (x0 in ker K = ker D,
    # x1 = x0 solves K x1 = -D x0 = 0); the 12 double clusters of the equal springs stay semisimple
    robot = pinlin.load_urdf(TALOS)
    free = [j for j in robot.joint_names if "gripper" in j][:4]
    el = [JointSpring(j, 100.0) for j in robot.joint_names if j not in free]
    el += [JointDamper(j, 0.5) for j in robot.joint_names if j not in free]
    sys = pinlin.linearize(Scene(robot, el, gravity=(0, 0, 0)), robot.neutral())
    assert sys.n >= PROJECTION_MIN_ORDER
    modes = pinlin.modal_analysis(sys, method="general")
    problem = as_problem(sys)
    zero = [c for c in modes.clusters if c.algebraic == 8]
    assert len(zero) == 1 and zero[0].partial == (2, 2, 2, 2) and zero[0].method.startswith(PROJECTED)
    assert sorted(c.partial for c in modes.clusters if c is not zero[0]) == [(1, 1)] * 12
    for c in modes.clusters:
        assert analyse_cluster(problem, modes.eigenvalues, c.indices, modes.tolerances["rank_tol"]).partial == c.partial


def test_projection_pays_from_its_order_for_clusters_of_half_the_size():
    n = PROJECTION_MIN_ORDER
    assert projected_pays(n, n // 2) and not projected_pays(n - 1, 2) and not projected_pays(n, n // 2 + 1)


def test_conjugate_clusters_carry_the_numbers_computed_afresh(monkeypatch):
    # the damped 8-branch chain (general path): clusters of 8 and 7 in conjugate pairs; the second of each pair
    # takes the first's structure and conjugate left vectors -- bitwise what computing them again gives
    sys = branched_chain(0.05)
    modes = pinlin.modal_analysis(sys)
    taken = [c for c in modes.clusters if c.method.endswith("real coefficients)")]
    assert len(taken) == 2 and len(modes.clusters) == 4
    for c in taken:
        assert c.partial == (1,) * c.algebraic
        assert c.center == complex(np.add.reduce(modes.eigenvalues[list(c.indices)]) / c.algebraic)
    monkeypatch.setattr(clusters, "_conjugate_groups", lambda lam, fig, groups: (np.zeros(len(groups), bool),) * 2)
    fresh = pinlin.modal_analysis(sys)
    assert all(c.method.startswith("semisimple certificate") and not c.method.endswith("coefficients)")
               for c in fresh.clusters)
    assert [(c.indices, c.center, c.partial, c.kernel_dims) for c in fresh.clusters] == [
        (c.indices, c.center, c.partial, c.kernel_dims) for c in modes.clusters
    ]
    for name in ("left", "right", "eigenvalues", "error_bound", "left_normalized"):
        np.testing.assert_array_equal(getattr(fresh, name), getattr(modes, name), err_msg=name, strict=True)
    np.testing.assert_array_equal(fresh.condition, modes.condition, strict=True)


def _pairwise_conjugate(partner, lam, indices) -> bool:
    """The check cluster by cluster: the members at ``indices`` are exactly (bit for bit) the conjugates of a
    complex ``partner``'s."""
    return (len(indices) == partner.algebraic and partner.center.imag != 0
            and np.array_equal(lam[list(indices)], lam[list(partner.indices)].conj()))


def _pairwise_mates(fig, lam, clusters) -> dict:
    """{k: k - 1} for the clusters k of chains of length one whose eigenvalues, right and unit left vectors are
    exactly the conjugates of those of cluster k - 1 (also of chains of length one), checked cluster by cluster."""
    mates = {}
    for k in range(1, len(clusters)):
        a, b = clusters[k], clusters[k - 1]
        if a.algebraic != b.algebraic or a.index != 1 or b.index != 1 or k - 1 in mates:
            continue
        ii, pp = list(a.indices), list(b.indices)
        if (np.array_equal(lam[ii], lam[pp].conj()) and np.array_equal(fig.right[:, ii], fig.right[:, pp].conj())
                and np.array_equal(fig.left_unit[:, ii], fig.left_unit[:, pp].conj())):
            mates[k] = k - 1
    return mates


def test_conjugate_groups_find_the_clusters_and_mates_of_the_pairwise_checks():
    # analyse_clusters compares each group with the one before it once, for all groups together; the structure
    # it takes from a partner and the mates it hands to cluster_figures are those of conjugate_cluster and of
    # _conjugate_mates (the checks made cluster by cluster before)
    from pinlin.spectral.analysis import _check_options, _figures
    from pinlin.spectral.clusters import analyse_clusters
    from pinlin.spectral.paths import choose_path, solve_path

    for sys in (branched_chain(0.05), branched_chain()):
        problem = as_problem(sys)
        tol = _check_options("auto", True, cluster_tol=1e-5, rank_tol=1e-10, structure_tol=1e-10, uncertainty=0.0,
                             safety=2.0, eigh_tol=1e-15)
        name, reason, raw = choose_path(problem, "auto", tol["structure_tol"], tol["eigh_tol"])
        raw = solve_path(problem, name, reason, raw, True, tol["eigh_tol"])[0]
        lam, _, fig = _figures(problem, raw)
        found, _, mates = analyse_clusters(problem, lam, fig, tol, raw.second is not None)
        assert mates == _pairwise_mates(fig, lam, found)
        for k in range(1, len(found)):
            assert _pairwise_conjugate(found[k - 1], lam, found[k].indices) == found[k].method.endswith(
                "real coefficients)")
