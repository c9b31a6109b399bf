"""The structured solver paths agree with the general path.

Agreement is measured against the error bounds both paths report; the paths'
eigenvalues are also checked against closed forms where one exists.
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin import LinearizedSystem
from pinlin.errors import ParameterError
from spectral_cases import chain, double_pendulum, match

FIELDS = ("eigenvalues", "right", "left", "backward_error", "condition", "error_bound", "natural_frequency",
          "damping_ratio", "multiplicity", "left_normalized", "block")


def agree(a, b, factor=10.0):
    """Eigenvalues of two results agree within factor * (bound_a + bound_b)."""
    lb = match(a.eigenvalues, b.eigenvalues)
    idx = [int(np.flatnonzero(b.eigenvalues == x)[0]) for x in lb]
    gap = np.abs(a.eigenvalues - lb)
    allowed = factor * (a.error_bound + b.error_bound[idx])
    assert np.all(gap <= allowed), (gap / allowed).max()
    return gap


def same_shapes(a, b):
    for f in FIELDS:
        assert np.shape(getattr(a, f)) == np.shape(getattr(b, f)), f
    assert len(a.kind) == len(b.kind) == len(a.eigenvalues)


@pytest.fixture(scope="module")
def spring_chain():
    return chain(12, 10.0 ** np.linspace(-3, 3, 12))


def test_symmetric_path_agrees_with_general(spring_chain):
    s = pinlin.modal_analysis(spring_chain)
    g = pinlin.modal_analysis(spring_chain, method="general")
    assert s.method == "symmetric" and "D = G = N = 0" in s.method.reason
    assert g.method == "general"
    same_shapes(s, g)
    agree(s, g)
    assert np.all(s.eigenvalues.real == 0)  # exactly on the axis by construction
    assert s.max_backward_error < 1e-14 and g.max_backward_error < 1e-14
    assert s.stability.kind == g.stability.kind == "marginally_stable"


def test_symmetric_path_with_negative_stiffness_gives_real_pairs():
    # the chain standing upright (gravity reversed) without springs: S negative definite
    sys = chain(2, gravity=(0, 0, 9.81))
    s = pinlin.modal_analysis(sys)
    g = pinlin.modal_analysis(sys, method="general")
    assert s.method == "symmetric"
    assert np.all(s.eigenvalues.imag == 0)
    agree(s, g)
    assert s.stability.kind == g.stability.kind == "divergence"


@pytest.mark.parametrize("P", [4.0, 40.0])
def test_squared_path_agrees_with_general(P):
    sys = double_pendulum(P=P)
    s = pinlin.modal_analysis(sys)
    g = pinlin.modal_analysis(sys, method="general")
    assert s.method == "squared" and "lam^2" in s.method.reason
    same_shapes(s, g)
    agree(s, g)
    # lam -> -lam symmetry holds exactly on the squared path
    assert_allclose(np.sort_complex(-s.eigenvalues), np.sort_complex(s.eigenvalues), rtol=0, atol=0)
    assert s.stability.kind == g.stability.kind


def rayleigh_chain(n=10, a=0.3, b=2e-3):
    base = chain(n, 10.0 ** np.linspace(-1, 2, n))
    D = a * base.M + b * base.S
    return base.replace(D=D)


def test_proportional_path_agrees_with_general():
    sys = rayleigh_chain()
    p = pinlin.modal_analysis(sys)
    g = pinlin.modal_analysis(sys, method="general")
    assert p.method == "proportional" and "commutator" in p.method.reason
    same_shapes(p, g)
    agree(p, g)
    # closed form per mode: lam^2 + (a + b w^2) lam + w^2 = 0 with w^2 the eigenvalues of (S, M)
    w2 = np.linalg.eigvals(np.linalg.solve(sys.M, sys.S)).real
    d = 0.3 + 2e-3 * w2
    roots = np.concatenate([(-d + np.sqrt(d * d - 4 * w2 + 0j)) / 2, (-d - np.sqrt(d * d - 4 * w2 + 0j)) / 2])
    assert_allclose(p.eigenvalues, match(p.eigenvalues, roots), rtol=1e-12, atol=0)
    assert p.stability.kind == g.stability.kind == "asymptotically_stable"


def test_non_proportional_damping_falls_back_to_general_and_says_why():
    sys = chain(4, [1.0] * 4, dampers=[0.3, 0.0, 0.0, 0.0])
    m = pinlin.modal_analysis(sys)
    assert m.method == "general"
    assert "not proportional" in m.method.reason
    with pytest.raises(ParameterError, match="'proportional' needs D M\\^-1 S = S M\\^-1 D"):
        pinlin.modal_analysis(sys, method="proportional")


def test_critically_damped_modes_on_proportional_path():
    sys = LinearizedSystem.from_matrices(np.diag([1.0, 2.0]), np.diag([4.0, 2.0]), np.diag([4.0, 9.0]))
    p = pinlin.modal_analysis(sys)
    assert p.method == "proportional"
    # mode 1: lam^2 + 4 lam + 4 (critical, -2 twice); mode 2: lam^2 + lam + 4.5
    crit = [c for c in p.clusters if c.partial == (2,)]
    assert len(crit) == 1 and crit[0].center == -2.0
    assert not p.is_simple
    osc = p.eigenvalues[np.abs(p.eigenvalues.imag) > 0]
    assert_allclose(np.sort_complex(osc), np.sort_complex(np.roots([1, 1, 4.5])), rtol=1e-15, atol=0)


@pytest.mark.parametrize(
    "method, sys_kind, match",
    [
        ("symmetric", "damped", "'symmetric' needs D = G = N = 0"),
        ("squared", "damped", "'squared' needs D = G = 0"),
        ("proportional", "gyro", "'proportional' needs G = N = 0"),
        ("symmetric", "tuple", "needs a LinearizedSystem"),
        ("eigh", "damped", "expected 'auto' or one of"),
        (3, "damped", "method: expected a string"),
    ],
)
def test_forced_method_that_does_not_apply(method, sys_kind, match):
    systems = {
        "damped": LinearizedSystem.from_matrices(np.eye(2), np.eye(2), np.eye(2)),
        "gyro": LinearizedSystem.from_matrices(np.eye(2), [[0, 1.0], [-1.0, 0]], np.eye(2)),
        "tuple": (np.eye(2), np.zeros((2, 2)), np.eye(2)),
    }
    with pytest.raises(ParameterError, match=match):
        pinlin.modal_analysis(systems[sys_kind], method=method)


def _reference_order(lam: np.ndarray) -> list[int]:
    """The documented order by Python's stable sort: leaders (Im >= 0) by (|lam|, Re lam, -|Im lam|), each
    Im > 0 leader followed by its mate, the first unused Im < 0 member equal to its conjugate."""
    mates = {}
    for i in (int(i) for i in np.flatnonzero(lam.imag > 0)):
        mates[i] = next(j for j in np.flatnonzero(lam == lam[i].conj()) if int(j) not in mates.values())
    leaders = sorted(np.flatnonzero(lam.imag >= 0).tolist(),
                     key=lambda i: (abs(lam[i]), lam[i].real, -abs(lam[i].imag)))
    return [j for i in leaders for j in ((i, int(mates[i])) if i in mates else (i,))]


def test_spectrum_order_follows_the_documented_order_including_ties():
    from pinlin.spectral.ordering import spectrum_order

    rng = np.random.default_rng(27)
    for trial in range(300):
        p = int(rng.integers(1, 12))
        z = rng.choice([-1.0, -0.5, 0.0, 0.5], p) + 1j * rng.choice([0.5, 1.0, 2.0], p)
        if trial % 3 == 0:
            z = rng.standard_normal(p) + 1j * np.abs(rng.standard_normal(p))
        lam = np.empty(2 * p, dtype=complex)
        lam[0::2], lam[1::2] = z, z.conj()
        perm, at = spectrum_order(lam)
        assert perm.tolist() == _reference_order(lam)
        assert at.tolist() == list(range(0, 2 * p, 2))
    # a real eigenvalue and a pair apart
    lam = np.array([1 + 2j, 1 - 2j, -3.0 + 0j, 0.5 + 1j, 2.0 + 0j, 0.5 - 1j])
    perm, at = spectrum_order(lam)
    assert perm.tolist() == [3, 5, 4, 0, 1, 2]
    assert at.tolist() == [0, 3]
