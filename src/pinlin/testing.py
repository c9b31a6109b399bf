"""High-precision references and test problems for checking pinlin's results (theory: error figures).

Errors in pinlin's tests and benchmarks are measured against references that
do not share the method; these are the multiprecision ones, computed with
mpmath (``pip install 'pinlin[test]'`` or ``'pinlin[bench]'``): the eigenvalues
of the first-order companion matrix and the characteristic polynomial's
coefficients, both formed and solved at ``dps`` decimal digits from the
(exactly representable) double-precision matrices.  :func:`check_element`
checks a force element's analytic derivatives against central differences on
the configuration manifold (theory: elements between frames): use it for every element you write
(docs/elements.md).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy.optimize import linear_sum_assignment

from .errors import ConfigurationError, MissingDependencyError, ParameterError

__all__ = [
    "mp_eigenvalues",
    "mp_characteristic_coefficients",
    "paired",
    "cantilever_beam",
    "check_element",
    "CHECK_STEP",
    "NOISE_FACTOR",
]

#: Central-difference step of :func:`check_element` [rad, m; rad/s, m/s]: the
#: truncation error (h^2 times third derivatives, ~1e-10 relative) and the rounding
#: error (eps |Q| / h, ~1e-11 relative) are both far below the 1e-6 a test asks for
#: (benchmarks/bench_linearize.py finds the best central step of pinlin's residual near it).
CHECK_STEP = 1e-5
#: Matrices whose analytic and difference values are both below this multiple of the
#: rounding level of the differences (eps |Q| sqrt(nv) / h) are equal to the
#: precision differences can see: their mismatch counts as 0.
NOISE_FACTOR = 100.0


def _mpmath():
    try:
        import mpmath
    except ImportError as exc:  # pragma: no cover - exercised only without the extra
        raise MissingDependencyError("pinlin.testing needs mpmath: pip install 'pinlin[test]'") from exc
    return mpmath


def _matrices(system) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    if isinstance(system, Sequence) and len(system) == 3:
        M, C, K = (np.asarray(a, dtype=float) for a in system)
    else:
        M, C, K = system.M, system.C, system.K
    if M.ndim != 2 or M.shape[0] != M.shape[1] or C.shape != M.shape or K.shape != M.shape:
        raise ParameterError("system", f"expected three square matrices of one size, got {M.shape}, {C.shape}, {K.shape}")
    return M, C, K


def _companion_eigenvalues(mp, M, C, K) -> list:
    """Eigenvalues of [[0, I], [-M^-1 K, -M^-1 C]] in the current mpmath precision."""
    n = M.shape[0]
    Mi = mp.inverse(mp.matrix(M.tolist()))
    B0 = -Mi * mp.matrix(K.tolist())
    B1 = -Mi * mp.matrix(C.tolist())
    A = mp.zeros(2 * n, 2 * n)
    for i in range(n):
        A[i, n + i] = 1
        for j in range(n):
            A[n + i, j] = B0[i, j]
            A[n + i, n + j] = B1[i, j]
    return list(mp.eig(A, left=False, right=False))


def mp_eigenvalues(system, *, dps: int = 50) -> np.ndarray:
    """The 2n eigenvalues of L(lam) = lam^2 M + lam C + K at ``dps`` digits, rounded to complex.

    Parameters
    ----------
    system : LinearizedSystem or (M, C, K)
        M must be nonsingular.
    dps : int
        Working precision in decimal digits.

    Examples
    --------
    >>> pinlin.testing.mp_eigenvalues((np.eye(1), np.zeros((1, 1)), 4 * np.eye(1)))
    array([0.-2.j, 0.+2.j])
    """
    mp = _mpmath()
    M, C, K = _matrices(system)
    with mp.workdps(dps):
        return np.array([complex(x) for x in _companion_eigenvalues(mp, M, C, K)])


def mp_characteristic_coefficients(system, *, dps: int = 50) -> tuple[np.ndarray, np.ndarray]:
    """Coefficients of p(lam) = det L(lam) = det M prod_k (lam - lam_k), ascending powers, and the lam_k.

    Returns
    -------
    coefficients : (2n + 1,) ndarray
        Real parts of the 2n + 1 coefficients (p has real coefficients).
    eigenvalues : (2n,) complex ndarray

    Examples
    --------
    >>> coefficients, lam = pinlin.testing.mp_characteristic_coefficients((np.eye(1), np.zeros((1, 1)), 4 * np.eye(1)))
    >>> coefficients  # p(lam) = 4 + lam^2
    array([4., 0., 1.])
    """
    mp = _mpmath()
    M, C, K = _matrices(system)
    with mp.workdps(dps):
        ev = _companion_eigenvalues(mp, M, C, K)
        c = [mp.mpc(1)]
        for lam in ev:  # multiply by (x - lam); c holds ascending powers
            c = [(c[k - 1] if k > 0 else 0) - lam * (c[k] if k < len(c) else 0) for k in range(len(c) + 1)]
        det_m = mp.det(mp.matrix(M.tolist()))
        return np.array([float(mp.re(det_m * x)) for x in c]), np.array([complex(x) for x in ev])


def paired(computed, reference) -> np.ndarray:
    """``reference`` reordered to match ``computed`` one to one (optimal assignment on distance).

    Examples
    --------
    >>> pinlin.testing.paired(np.array([1.0, 2.0, 3.0]), np.array([3.1, 0.9, 2.0]))
    array([0.9, 2. , 3.1])
    """
    computed = np.asarray(computed)
    reference = np.asarray(reference)
    if computed.shape != reference.shape or computed.ndim != 1:
        raise ParameterError("reference", f"expected shape {computed.shape} like computed, got {reference.shape}")
    i, j = linear_sum_assignment(np.abs(computed[:, None] - reference[None, :]))
    out = np.empty_like(reference)
    out[i] = reference[j]
    return out


def cantilever_beam(
    ne: int = 40,
    L: float = 2.0,
    E: float = 2.1e11,
    I: float = 8.33e-10,
    rhoA: float = 0.785,
    c: float = 50.0,
    at: int | None = None,
):
    """A clamped-free Euler-Bernoulli beam of Hermite cubic elements with one dashpot.

    The textbook element matrices

    .. math::
        k_e = \\frac{EI}{l^3}\\begin{bmatrix}12 & 6l & -12 & 6l\\\\ 6l & 4l^2 & -6l & 2l^2\\\\
              -12 & -6l & 12 & -6l\\\\ 6l & 2l^2 & -6l & 4l^2\\end{bmatrix},\\quad
        m_e = \\frac{\\rho A\\, l}{420}\\begin{bmatrix}156 & 22l & 54 & -13l\\\\ 22l & 4l^2 & 13l & -3l^2\\\\
              54 & 13l & 156 & -22l\\\\ -13l & -3l^2 & -22l & 4l^2\\end{bmatrix}

    are assembled over ``ne`` elements of length l = L / ne; coordinates
    (w_i [m], theta_i [rad]), i = 1..ne, after clamping node 0.  Defaults: a
    2 m steel strip.  Deflections and rotations mix in one vector, so K spans
    many decades: the badly scaled damped beam of theory: spectrum.

    Parameters
    ----------
    ne : int
        Number of elements (n = 2 ne coordinates).
    L, E, I, rhoA : float
        Length [m], Young's modulus [Pa], second moment of area [m^4], mass per length [kg/m].
    c : float
        Dashpot [N s/m] on the transverse displacement of node ``at`` (default the tip).
    at : int, optional
        Node 1..ne carrying the dashpot.

    Returns
    -------
    LinearizedSystem

    Examples
    --------
    >>> beam = pinlin.testing.cantilever_beam(ne=4)
    >>> beam.n, beam.dof_names[:2]
    (8, ('x1', 'x2'))
    """
    from .linearization.system import LinearizedSystem

    if not isinstance(ne, (int, np.integer)) or ne < 1:
        raise ParameterError("ne", f"expected an integer >= 1, got {ne!r}")
    node = ne if at is None else at
    if not isinstance(node, (int, np.integer)) or not 1 <= node <= ne:
        raise ParameterError("at", f"expected a node in 1..{ne}, got {at!r}")
    l = L / ne
    k = E * I / l**3 * np.array(
        [[12, 6 * l, -12, 6 * l], [6 * l, 4 * l * l, -6 * l, 2 * l * l], [-12, -6 * l, 12, -6 * l],
         [6 * l, 2 * l * l, -6 * l, 4 * l * l]]
    )
    m = rhoA * l / 420 * np.array(
        [[156, 22 * l, 54, -13 * l], [22 * l, 4 * l * l, 13 * l, -3 * l * l], [54, 13 * l, 156, -22 * l],
         [-13 * l, -3 * l * l, -22 * l, 4 * l * l]]
    )
    nd = 2 * (ne + 1)
    K = np.zeros((nd, nd))
    M = np.zeros((nd, nd))
    for e in range(ne):
        ix = np.ix_(range(2 * e, 2 * e + 4), range(2 * e, 2 * e + 4))
        K[ix] += k
        M[ix] += m
    K, M = K[2:, 2:], M[2:, 2:]
    D = np.zeros_like(K)
    j = 2 * (node - 1)
    D[j, j] = c
    Z = np.zeros_like(K)
    return LinearizedSystem(M, D, Z, K, Z)


def _relative(a: np.ndarray, b: np.ndarray, noise: float) -> float:
    """||a - b||_F / max(||a||_F, ||b||_F), or 0 when both are below ``noise``."""
    size = max(float(np.linalg.norm(a)), float(np.linalg.norm(b)))
    if size <= noise:
        return 0.0
    return float(np.linalg.norm(a - b)) / size


def check_element(element, scene, q, v=None, *, step: float = CHECK_STEP) -> float:
    """Largest relative mismatch between an element's analytic derivatives and central differences (theory: elements between frames).

    The analytic side is what the element adds to :func:`~pinlin.linearize`'s K and C at
    (q, v), Pinocchio's part of a wrench included; the reference is central differences of
    ``element.generalized_force`` on the manifold:

    .. math::
        K_{fd}[:, k] = -\\frac{Q(q \\oplus h e_k, v) - Q(q \\oplus (-h e_k), v)}{2h},\\qquad
        C_{fd}[:, k] = -\\frac{Q(q, v + h e_k) - Q(q, v - h e_k)}{2h}

    with q (+) dq = ``pin.integrate``.  A matrix's mismatch is ||A - A_fd||_F / max(||A||_F,
    ||A_fd||_F), 0 when both are below :data:`NOISE_FACTOR` times the differences' rounding
    level; check at generic configurations (docs/elements.md, "Checking an element").

    Parameters
    ----------
    element : Element
        In ``scene`` or not (then it is evaluated in a copy holding it too).
    scene : Scene
        Gives the robot, prescribed joints and the other elements (Rayleigh
        damping reads their elastic stiffness).
    q : (nq,) array
        Configuration.
    v : (nv,) array, optional
        Velocity; default ``scene.v0``.
    step : float
        h [rad, m; rad/s, m/s], see :data:`CHECK_STEP`.

    Returns
    -------
    float
        The largest relative mismatch (about 1e-9 for exact derivatives).

    Raises
    ------
    ParameterError
        ``element`` is not an element, or ``step`` is not a positive number.
    ConfigurationError
        ``q`` or ``v`` has the wrong size or non-finite entries.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> spring = pinlin.JointSpring("joint1", 2.0)
    >>> bool(pinlin.testing.check_element(spring, pinlin.Scene(robot, [spring]), np.array([0.3, -0.2])) < 1e-6)
    True
    """
    import pinocchio as pin

    from .linearization.assembly import assemble
    from .model.elements import Element
    from .model.evaluation import Evaluation

    if not isinstance(element, Element):
        raise ParameterError("element", f"expected a pinlin element, got {element!r}")
    if not (isinstance(step, (int, float)) and np.isfinite(step) and step > 0):
        raise ParameterError("step", f"must be a positive number, got {step!r}")
    host = scene if any(e is element for e in scene.elements) else scene.replace(
        elements=scene.elements + (element,), urdf_damping=False
    )
    q = host.check_configuration(q)
    v = np.array(host.v0 if v is None else v, dtype=float)
    nv = host.model.nv
    if v.shape != (nv,) or not np.all(np.isfinite(v)):
        raise ConfigurationError(f"v must be {nv} finite numbers, got {v!r}")

    def force(qq, vv):
        return element.generalized_force(Evaluation(host, qq, vv))

    eps = np.finfo(float).eps
    if element.is_wrench:
        zero_g = dict(gravity=(0.0, 0.0, 0.0), urdf_damping=False)
        alone, bare = (scene.replace(elements=els, **zero_g) for els in ((element,), ()))
        with_, without = (assemble(s, q, v, stiffness=True, damping=True) for s in (alone, bare))
        K, C = with_.K - without.K, with_.C - without.C
        Q_asm = without.residual - with_.residual
        force_noise = NOISE_FACTOR * eps * (np.linalg.norm(with_.residual) + np.linalg.norm(without.residual))
    else:
        ev = Evaluation(host, q, v)
        group = type(element).group((element,), host.robot)
        K, C, Q_asm = np.zeros((nv, nv)), np.zeros((nv, nv)), np.zeros(nv)
        group.add_stiffness(ev, K)
        group.add_damping(ev, C)
        group.add_force(ev, Q_asm)
        force_noise = 0.0
    K_fd, C_fd = np.zeros((nv, nv)), np.zeros((nv, nv))
    size_q, size_v = 0.0, 0.0
    for k in range(nv):
        e = np.zeros(nv)
        e[k] = step
        plus, minus = force(pin.integrate(host.model, q, e), v), force(pin.integrate(host.model, q, -e), v)
        K_fd[:, k] = -(plus - minus) / (2 * step)
        size_q = max(size_q, np.linalg.norm(plus), np.linalg.norm(minus))
        plus, minus = force(q, v + e), force(q, v - e)
        C_fd[:, k] = -(plus - minus) / (2 * step)
        size_v = max(size_v, np.linalg.norm(plus), np.linalg.norm(minus))
    rounding = NOISE_FACTOR * eps * np.sqrt(nv) / step
    return max(
        _relative(K, K_fd, rounding * size_q),
        _relative(C, C_fd, rounding * size_v),
        _relative(Q_asm, force(q, v), force_noise),
    )
