"""One Gauss-Legendre collocation step with step doubling, on a stack of steps (theory: Floquet).

One step of the s-stage Gauss-Legendre method (collocation at the zeros of the shifted Legendre polynomial
P_s(2 c - 1); order 2 s, symplectic) applied to the matrix equation Y' = A(t) Y, Y(t_0) = I, is one linear
solve: with A_i = A(t_0 + c_i h),

.. math::

    (I - h\\,[a_{ij} A_j])\\, Z = \\mathbf{1} \\otimes I, \\qquad
    P = I + h \\sum_i b_i A_i Z_i,

an (s m) x (s m) system with m right-hand columns.  Each step [t_0, t_0 + h] is taken twice: once whole
(s evaluations of A) and as two halves (2 s more); the halves' product is kept and

.. math::  E = \\| P_{1/2} P_{1/2}' - P_h \\|_2 / (2^{2s} - 1)

is its error estimate (Richardson: the local error is C h^{2s+1}).  A step is accepted when E <= rtol ||P||_2
and h ||D^-1 A D||_2 stays within the cap where the estimate is trusted.  When A has the first-order form
[[0, I], [X, Y]] of a second-order system at every node, the positions are eliminated from the stage equations
(an (s n)-square solve instead of (2 s n)).  Each step tried costs 3 s evaluations of A (none reused: the half
steps' nodes differ from the whole step's).  :func:`try_steps` takes a stack of steps: the sequential
controller of :mod:`.collocation` tries a stack of one, the grid of :mod:`.collocation_grid` every pending
step of a round.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..errors import IntegrationError

__all__ = ["gauss_legendre", "stage_solve", "Step", "Trial", "try_steps", "two_norms", "ROUNDING_FACTOR"]

#: Rounding error of one step's transition, in units of eps ||P||_2 times sqrt(s m): the stage solve and the
#: weighted sum each round at about that level (measured on constant random A, m = 4..12, rtol = 1e-15,
#: against a 40-digit expm: the true step error is 0.03-0.13 of this floor).
ROUNDING_FACTOR = 1.0

_EPS = float(np.finfo(float).eps)

@functools.lru_cache(maxsize=16)
def gauss_legendre(stages: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Butcher tableau (c, a, b) of the ``stages``-stage Gauss-Legendre method on [0, 1].

    c are the Gauss nodes, b the Gauss weights, and a_ij = int_0^{c_i} l_j(tau) d tau with l_j the
    Lagrange polynomials on the nodes (collocation).

    Examples
    --------
    >>> from pinlin.periodic.gauss_step import gauss_legendre
    >>> c, a, b = gauss_legendre(2)
    >>> print(np.round(c, 6), b, np.allclose(a.sum(axis=1), c))
    [0.211325 0.788675] [0.5 0.5] True
    """
    x, w = np.polynomial.legendre.leggauss(stages)
    c, b = (x + 1) / 2, w / 2
    # a_ij = int_0^{c_i} l_j: solve the Vandermonde system sum_j a_ij c_j^(k-1) = c_i^k / k (k = 1..s)
    powers = np.arange(1, stages + 1)
    V = c[None, :] ** (powers[:, None] - 1)
    R = c[:, None] ** powers[None, :] / powers[None, :]
    a = np.linalg.solve(V, R.T).T
    for x in (c, a, b):
        x.flags.writeable = False      # cached and shared: read-only
    return c, a, b


@dataclass(frozen=True)
class Step:
    """One accepted step: [t0, t0 + h] [s], its transition P (m x m), the estimated error matrix
    ``estimate`` (Richardson, m x m), the ``rounding`` floor [2-norm] and their sum ``error`` = ||estimate||_2 +
    rounding, and the node data for dense output (``nodes`` [s], ``stage``:
    the transitions from t0 to each node, s x m x m, order-s accurate, and the quadrature ``weights`` [s]);
    ``norm`` = ||P||_2 and ``estimate_norm`` = ||estimate||_2 as the integrator measured them;
    ``coefficient_error``: None when A was evaluated exactly at the nodes, else a (g, g) block bound on the
    error of the coefficients integrated (an interpolant of A): |v^H dA u| <= sum_ab E_ab ||v_a|| ||u_b|| with
    the rows split into g equal blocks (:mod:`.bounds` adds its effect).

    Examples
    --------
    >>> from pinlin.periodic.collocation import integrate_transitions
    >>> A = lambda t: np.array([[0.0, 1.0], [-(1.3 + 0.4 * np.cos(t)), 0.0]])       # Mathieu, undamped
    >>> tr = integrate_transitions(A, 2 * np.pi, 2)
    >>> step = tr.steps[0]
    >>> print(step.t0, step.P.shape, step.stage.shape, step.error <= 1e-13 * step.norm)
    0.0 (2, 2) (12, 2, 2) True
    """

    t0: float
    h: float
    P: np.ndarray
    estimate: np.ndarray
    rounding: float
    error: float
    nodes: np.ndarray
    stage: np.ndarray
    weights: np.ndarray
    coefficient_error: np.ndarray | None = None
    norm: float = float("nan")
    estimate_norm: float = float("nan")


def stage_solve(An: np.ndarray, h: np.ndarray, a: np.ndarray, b: np.ndarray,
                second_order: bool) -> tuple[np.ndarray, np.ndarray]:
    """(P, Z) of a batch of Gauss steps: ``An`` (B, s, m, m) the coefficients at each step's nodes, ``h`` (B,)
    the step lengths, (a, b) the tableau.  P (B, m, m) are the step transitions, Z (B, s, m, m) the stage
    transitions from each step's start to its nodes.

    ``second_order``: every A has the first-order form [[0, I], [X, Y]] of a second-order system; with
    Z_i = (Zx_i, Zv_i), Zx_i = E_x + h sum_j a_ij Zv_j eliminates the positions, leaving the (s n)-square

    .. math::  Zv_i - h \\sum_k (a_{ik} Y_k + h \\sum_j a_{ij} a_{jk} X_j) Zv_k
               = E_v + h \\sum_j a_{ij} X_j E_x,

    eight times cheaper to factor than the (2 s n)-square system.

    Examples
    --------
    One step of y' = -y (A = [[-1]]) with s = 2 stages: P = exp(-h) to order 4:

    >>> from pinlin.periodic.gauss_step import gauss_legendre, stage_solve
    >>> c, a, b = gauss_legendre(2)
    >>> P, Z = stage_solve(np.full((1, 2, 1, 1), -1.0), np.array([0.1]), a, b, second_order=False)
    >>> print(f"{P[0, 0, 0]:.6f}", f"{np.exp(-0.1):.6f}", Z.shape)
    0.904837 0.904837 (1, 2, 1, 1)
    """
    B, s, m = An.shape[0], An.shape[1], An.shape[2]
    hh = np.asarray(h, dtype=float).reshape(B)
    if not second_order:
        # L = I - h [a_ij A_j]: block (i, j) is -h a_ij A_j
        blocks = a[None, :, None, :, None] * An.transpose(0, 2, 1, 3)[:, None]
        L = np.eye(s * m) - hh[:, None, None] * blocks.reshape(B, s * m, s * m)
        rhs = np.broadcast_to(np.tile(np.eye(m), (s, 1)), (B, s * m, m))
        Z = np.linalg.solve(L, rhs).reshape(B, s, m, m)
        P = np.eye(m) + hh[:, None, None] * np.sum((An * b[None, :, None, None]) @ Z, axis=1)
    else:
        n = m // 2
        X, Y = An[:, :, n:, :n], An[:, :, n:, n:]
        aa = (a[:, None, :] * a.T[None, :, :]).reshape(s * s, s)      # aa[i k, j] = a_ij a_jk
        XX = (aa @ X.reshape(B, s, n * n)).reshape(B, s, s, n, n)
        # L = I - h a_ik Y_k - h^2 XX_ik: block (i, k) of the (s n)-square matrix
        h5 = hh[:, None, None, None, None]
        blocks = (-a[None, :, None, :, None] * Y.transpose(0, 2, 1, 3)[:, None]) * h5 - h5 * h5 * XX.transpose(
            0, 1, 3, 2, 4)
        L = np.eye(s * n) + blocks.reshape(B, s * n, s * n)
        rhs = np.zeros((B, s, n, 2 * n))
        rhs[..., :n] = hh[:, None, None, None] * (a @ X.reshape(B, s, n * n)).reshape(B, s, n, n)
        rhs[..., n:] = np.eye(n)
        Zv = np.linalg.solve(L, rhs.reshape(B, s * n, 2 * n)).reshape(B, s, n, 2 * n)
        Zx = np.eye(n, 2 * n)[None, None] + hh[:, None, None, None] * (
            a @ Zv.reshape(B, s, 2 * n * n)).reshape(B, s, n, 2 * n)
        Z = np.concatenate([Zx, Zv], axis=2)
        # A_i Z_i = [[Zv_i], [X_i Zx_i + Y_i Zv_i]]: only the lower half needs a product
        P = np.empty((B, m, m))
        P[:, :n] = np.eye(n, m) + hh[:, None, None] * (b @ Zv.reshape(B, s, 2 * n * n)).reshape(B, n, m)
        # sum_i b_i A_i[n:] Z_i as one product per step: [b_1 A_1[n:], ..., b_s A_s[n:]] [Z_1; ...; Z_s]
        weighted = (b[None, :, None, None] * An[:, :, n:, :]).transpose(0, 2, 1, 3).reshape(B, n, s * m)
        P[:, n:] = np.eye(n, m, n) + hh[:, None, None] * (weighted @ Z.reshape(B, s * m, m))
    return P, Z


@dataclass(frozen=True)
class Trial:
    """A stack of B steps tried at once.

    Attributes
    ----------
    steps : list of Step
        The accepted ones, in the order of the stack.
    accepted : (B,) bool ndarray
        ||E||_2 <= rtol ||P||_2 and h ||D^-1 A D||_2 <= 1.2 ``max_step_norm`` at the middle node.
    ratio : (B,) ndarray
        ||E||_2 / (rtol ||P||_2), for the step-size controller.
    rate : (B,) ndarray
        ||D^-1 A D||_2 at each step's middle node [1/s].
    evaluations : int
        Times A was evaluated at (3 s per step).

    Examples
    --------
    >>> from pinlin.periodic.gauss_step import try_steps
    >>> A = lambda times: np.full((np.size(times), 1, 1), -1.0)      # y' = -y at every time
    >>> trial = try_steps(A, np.array([0.0, 0.5]), np.array([0.5, 0.5]), stages=4, rtol=1e-10,
    ...                   scaling=np.ones((1, 1)), max_step_norm=2.0)
    >>> print(trial.accepted, np.round(trial.rate, 6), trial.evaluations)
    [ True  True] [1. 1.] 24
    """

    steps: list
    accepted: np.ndarray
    ratio: np.ndarray
    rate: np.ndarray
    evaluations: int


def two_norms(X: np.ndarray) -> np.ndarray:
    """The 2-norms of a stack of matrices (..., m, m) -> (...).

    Examples
    --------
    >>> from pinlin.periodic.gauss_step import two_norms
    >>> two_norms(np.stack([np.eye(2), np.diag([3.0, -4.0])]))
    array([1., 4.])
    """
    return np.linalg.norm(X, 2, axis=(-2, -1))


def try_steps(A: Callable[[np.ndarray], np.ndarray], t0: np.ndarray, h: np.ndarray, *, stages: int, rtol: float,
              scaling: np.ndarray, max_step_norm: float, second_order: bool | None = None,
              coefficient_error: np.ndarray | None = None) -> Trial:
    """Each step [t0_k, t0_k + h_k] taken whole and as two halves, with one evaluation of A at all their
    nodes and one stacked stage solve; the Richardson estimate, the rounding floor and the accept test.

    ``A``: times [s] (1-d array) -> (len(times), m, m).  ``scaling``: D^-1 A D = ``A * scaling``
    (:func:`balancing`).  ``second_order``: A has the form [[0, I], [X, Y]] at every time; None: decided
    from the values at the nodes.  ``coefficient_error``: carried by every accepted step (see :class:`Step`).

    Raises
    ------
    IntegrationError
        A step's transition is not finite.

    Examples
    --------
    >>> from pinlin.periodic.gauss_step import try_steps
    >>> A = lambda times: np.full((np.size(times), 1, 1), -1.0)      # y' = -y
    >>> trial = try_steps(A, np.array([0.0]), np.array([0.5]), stages=4, rtol=1e-10, scaling=np.ones((1, 1)),
    ...                   max_step_norm=2.0)
    >>> print(bool(trial.accepted[0]), f"{trial.steps[0].P[0, 0]:.10f}", f"{np.exp(-0.5):.10f}")
    True 0.6065306597 0.6065306597
    """
    c, a, b = gauss_legendre(stages)
    B, s = t0.size, stages
    half = h / 2
    nodes = np.concatenate([t0[:, None] + c[None] * h[:, None], t0[:, None] + c[None] * half[:, None],
                            (t0 + half)[:, None] + c[None] * half[:, None]], axis=1)      # (B, 3 s)
    values = A(nodes.ravel())
    m = values.shape[-1]
    if second_order is None:
        n = m // 2
        top = np.eye(n, m, n)        # [0, I]: the top block row of a second-order system's first-order form
        second_order = m % 2 == 0 and bool(np.all(values[:, :n] == top))
    P3, Z3 = stage_solve(values.reshape(B * 3, s, m, m), np.stack([h, half, half], axis=1).ravel(), a, b,
                         second_order)
    P3, Z3 = P3.reshape(B, 3, m, m), Z3.reshape(B, 3, s, m, m)
    whole, P1, P2 = P3[:, 0], P3[:, 1], P3[:, 2]
    P = P2 @ P1
    difference = (P - whole) / (4.0 ** s - 1)
    estimate, norm = two_norms(difference), two_norms(P)
    if not np.all(np.isfinite(estimate)):
        bad = int(np.argmin(np.isfinite(estimate)))
        raise IntegrationError(f"the step transition at t = {t0[bad]:.6g} s is not finite", float(t0[bad]))
    rate = two_norms(values.reshape(B, 3, s, m, m)[:, 0, s // 2] * scaling)
    ratio = estimate / (rtol * norm)
    accepted = (ratio <= 1.0) & (h * rate <= 1.2 * max_step_norm)
    steps = []
    if accepted.any():
        k = np.flatnonzero(accepted)
        # the halves' norms by Frobenius (an upper bound of their 2-norms, without an SVD each)
        halves = np.linalg.norm(P1[k], axis=(1, 2)) * np.linalg.norm(P2[k], axis=(1, 2))
        rounding = ROUNDING_FACTOR * _EPS * np.sqrt(s * m) * (halves + norm[k])
        stage = np.concatenate([Z3[k, 1], Z3[k, 2] @ P1[k, None]], axis=1)     # t0 -> each half's nodes
        weights = np.concatenate([b, b])[None, :] * half[k, None]
        steps = [Step(float(t0[j]), float(h[j]), P[j], difference[j], float(rounding[i]),
                      float(estimate[j] + rounding[i]), nodes[j, s:], stage[i], weights[i], coefficient_error,
                      float(norm[j]), float(estimate[j])) for i, j in enumerate(k)]
    return Trial(steps, accepted, ratio, rate, nodes.size)
