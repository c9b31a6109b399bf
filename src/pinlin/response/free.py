"""Free vibration from the modal solution (theory: responses)."""

from __future__ import annotations

import time
from math import factorial

import numpy as np

from ..errors import AccuracyWarning, ComputationError, ParameterError, warn_user
from ..errors.deprecated import renamed_keywords, reordered_arguments
from ..frf.engine import DEFAULT_TOL
from ..frf.expansion import ModalExpansion, complex_matmul, modal_expansion
from ..linearization.system import LinearizedSystem, check_system
from ..numerics import check_tolerance
from ..numerics.arrays import check_times, check_vector
from ..results import ResultArray

__all__ = ["FreeResponse", "free_response", "modal_free_motion", "TIME_CHUNK", "DEFAULT_TOL"]

#: Time points evaluated together (bounds the memory of long responses).
TIME_CHUNK = 4096


class FreeResponse(ResultArray):
    """x(t): a (len(t), n) real array (times first), with the figures of the modal solution as attributes.

    A read-only ndarray; the figures live on the returned array only (slices
    and arithmetic results are plain arrays).

    Attributes
    ----------
    t : (len(t),) ndarray
        Times [s].
    xdot : (len(t), n) ndarray
        Velocities, from the same expansion.
    defect : float
        Largest relative defect of the equation over t:
        ||M x'' + C x' + K x|| / (||M|| ||x''|| + ||C|| ||x'|| + ||K|| ||x||)
        (Frobenius matrix norms), with x, x', x'' from the expansion (theory: error figures).
    initial_defect : float
        max(||x(t0) - x0|| / r_x, ||x'(t0) - v0|| / r_v) with r_x = ||x0|| +
        ||v0|| / gamma, r_v = gamma ||x0|| + ||v0|| (gamma the natural
        frequency scale).
    symmetry_defect : float
        Relative departure of the modal data from the conjugate symmetry that
        makes x real (pairs lam, conj(lam) with conjugate terms; real modes with
        real terms); zero in exact arithmetic.  The response is the real part
        of the modal sum, evaluated on one member of each pair.
    projection_residual : float
        ||z0 - V c|| / ||z0||: how well the modal coefficients c reproduce the
        initial state z0 = (x0, v0) in the basis V of modes and chains
        (velocities weighted by 1/gamma), after iterative refinement.
    chain_residual : float
        Largest relative residual of the Jordan chain equations used (0 if none).
    method : str
        ``"modal"`` (simple dynamic stiffness) or ``"modal + Jordan chains"``.
    error : float
        The headline figure: ``max(defect, initial_defect, symmetry_defect)``,
        the largest relative departure of the returned motion from the
        equation, the initial conditions and a real solution.
    modes : Modes
        The modal analysis used (reuse it through ``modes=``; not in ``to_dict()``).
    elapsed : float
        Seconds, modal analysis included unless ``modes`` was given.

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices([[1.0]], None, [[4.0]])  # x = cos(2 t) / 10
    >>> x = pinlin.free_response(sys, [0.0, np.pi / 6], [0.1])
    >>> print(f"{x[-1, 0]:.6f} {x.xdot[-1, 0]:.6f}")
    0.050000 -0.173205
    >>> type(np.asarray(x)).__name__, x.t.shape
    ('ndarray', (2,))
    """

    _fields = (
        "t",
        "xdot",
        "defect",
        "initial_defect",
        "symmetry_defect",
        "projection_residual",
        "chain_residual",
        "method",
        "error",
        "modes",
        "elapsed",
    )

    def _summary(self) -> list[str]:
        return [f"t=[{self.t[0]:g}, {self.t[-1]:g}] s ({len(self.t)} points)", *super()._summary()]

    def __str__(self) -> str:
        """The summary (as the repr): ``print(resp)`` shows what was computed and how well, not the
        len(t) x n numbers (those are ``np.asarray(resp)``)."""
        if self.__dict__.get("_meta") is None:  # a part is a plain ndarray
            return super().__str__()
        return repr(self)
    _dict_exclude = ("modes",)


def modal_free_motion(expansion: ModalExpansion, x0: np.ndarray, v0: np.ndarray, tau: np.ndarray):
    """x, x', x'' (each (len(tau), n) real) of the free motion from (x0, v0) at tau = t - t0.

    Semisimple modes: sum_k c_k exp(lam_k tau) x_k (times lam_k, lam_k^2 for
    the derivatives); when the modes come in conjugate pairs only one member
    of each is evaluated, with twice its real part.  A Jordan block with
    coefficients d_i contributes exp(lam0 tau) p(tau), p(tau) = sum_j
    tau^j/j! g_j with g_j = sum_{i>=j} d_i x_{i-j}; then
    x' = e (lam0 p + p'), x'' = e (lam0^2 p + 2 lam0 p' + p'').

    Returns
    -------
    x, xdot, xddot : (len(tau), n) ndarray
    symmetry : float
        Relative departure of the complex data from the symmetry that makes the
        sum real (conjugate pairs: eigenvalue, and coefficient times vector;
        real modes and Jordan terms: their imaginary part).
    residual : float
        The projection residual of the coefficients (see ``coefficients``).

    Examples
    --------
    >>> from pinlin.frf.expansion import modal_expansion
    >>> from pinlin.response.free import modal_free_motion
    >>> sys = pinlin.LinearizedSystem.from_matrices([[1.0]], None, [[4.0]])  # x = cos(2 tau) / 10
    >>> x, xdot, xddot, symmetry, residual = modal_free_motion(
    ...     modal_expansion(sys, None), np.array([0.1]), np.array([0.0]), np.array([0.0, np.pi / 6]))
    >>> print(f"{x[1, 0]:.6f} {xdot[1, 0]:.6f} {xddot[1, 0]:.6f}")
    0.050000 -0.173205 -0.200000
    """
    c, d, residual = expansion.coefficients(x0.astype(complex), v0.astype(complex))
    lam, X = expansion.lam, expansion.right
    partner = expansion.partner
    total = float(np.sum(np.linalg.norm(X, axis=0) * np.abs(c)))  # size of the modal terms at tau = 0
    symmetry = 0.0
    half = weight = None
    if partner is not None:
        idx = np.arange(lam.size)
        half = np.flatnonzero(partner >= idx)
        weight = np.where(partner[half] == half, 1.0, 2.0)
        pairs = half[partner[half] != half]
        if pairs.size:
            mates = partner[pairs]
            lam_gap = np.abs(lam[pairs] - np.conj(lam[mates])) / np.abs(lam[pairs])
            vec_gap = np.linalg.norm(X[:, pairs] * c[pairs] - np.conj(X[:, mates] * c[mates]), axis=0)
            symmetry = max(float(np.max(lam_gap)), float(np.sum(vec_gap)) / total if total > 0 else 0.0)
        lone = half[partner[half] == half]
        if lone.size and total > 0:
            symmetry = max(symmetry, float(np.sum(np.linalg.norm((X[:, lone] * c[lone]).imag, axis=0))) / total)
    parts = [_evaluate(expansion, c, d, half, weight, tau[i : i + TIME_CHUNK]) for i in range(0, tau.size, TIME_CHUNK)]
    x = np.concatenate([p[0] for p in parts])
    xd = np.concatenate([p[1] for p in parts])
    xdd = np.concatenate([p[2] for p in parts])
    imag = max(p[3] for p in parts)
    size = float(np.max(np.abs(x))) if x.size else 0.0
    if size > 0:
        symmetry = max(symmetry, imag / size)
    return x, xd, xdd, symmetry, residual


def _evaluate(expansion: ModalExpansion, c, d, half, weight, tau):
    """x, x', x'' (real) at tau from coefficients c (modes) and d (blocks), and max |Im| of the complex parts."""
    lam, X = expansion.lam, expansion.right
    T = tau.shape[0]
    imag = 0.0
    if half is not None:
        lam_h = lam[half]
        W = np.exp(np.multiply.outer(tau, lam_h))
        # the three derivatives from one real product: Re(W G) = W.re G.re - W.im G.im,
        # G = [c x^T, lam c x^T, lam^2 c x^T] (one block of columns per derivative)
        G = (c[half] * weight)[:, None] * X[:, half].T
        G = np.concatenate([G, lam_h[:, None] * G, (lam_h * lam_h)[:, None] * G], axis=1)
        stacked = W.real @ G.real - W.imag @ G.imag
        n = X.shape[0]
        x, xd, xdd = stacked[:, :n], stacked[:, n : 2 * n], stacked[:, 2 * n :]
        im = None
    else:
        W = np.exp(np.multiply.outer(tau, lam)) * c
        stacked = complex_matmul(np.vstack([W, W * lam, W * (lam * lam)]), X.T)
        x, xd, xdd = stacked[:T].real, stacked[T : 2 * T].real, stacked[2 * T :].real
        im = stacked[:T].imag
    if expansion.blocks:
        bx = np.zeros((T, X.shape[0]), dtype=complex)
        bxd = np.zeros_like(bx)
        bxdd = np.zeros_like(bx)
        for block, coef in zip(expansion.blocks, d):
            r = block.length
            V = block.vectors
            G = np.array([sum(coef[i] * V[:, i - j] for i in range(j, r)) for j in range(r)])  # (r, n)
            powers = np.stack([tau**j / factorial(j) for j in range(r)], axis=1).astype(complex)  # (T, r)
            p = complex_matmul(powers, G)
            p1 = complex_matmul(powers[:, : r - 1], G[1:]) if r > 1 else np.zeros_like(p)
            p2 = complex_matmul(powers[:, : r - 2], G[2:]) if r > 2 else np.zeros_like(p)
            e = np.exp(block.lam0 * tau)[:, None]
            lam0 = block.lam0
            bx += e * p
            bxd += e * (lam0 * p + p1)
            bxdd += e * (lam0 * lam0 * p + 2 * lam0 * p1 + p2)
        x, xd, xdd = x + bx.real, xd + bxd.real, xdd + bxdd.real
        im = bx.imag if im is None else im + bx.imag
    if im is not None and im.size:
        imag = float(np.max(np.abs(im)))
    return x, xd, xdd, imag


def _relative_defect(sys: LinearizedSystem, x, xd, xdd) -> float:
    """max_t ||M x'' + C x' + K x|| / (||M|| ||x''|| + ||C|| ||x'|| + ||K|| ||x||), Frobenius matrix norms."""
    r = xdd @ sys.M.T + xd @ sys.C.T + x @ sys.K.T
    nM, nC, nK = (float(np.linalg.norm(a)) for a in (sys.M, sys.C, sys.K))

    def rows(a):
        return np.sqrt(np.einsum("ij,ij->i", a, a))

    scale = nM * rows(xdd) + nC * rows(xd) + nK * rows(x)
    num = rows(r)
    ok = scale > 0
    return float(np.max(num[ok] / scale[ok])) if np.any(ok) else 0.0


def _old_order(args: tuple, kwargs: dict) -> bool:
    """Whether a call uses the 0.3 order ``(sys, x0, v0, t)``: ``t`` given by keyword after positional
    initial conditions, or a third that is an increasing time grid after a first that is None or an (n,)
    vector, the third being no (n,) vector or (when n equals len(t)) the first not increasing."""
    rest = args[1:]
    if "t" in kwargs:
        return bool(rest)
    if len(rest) < 3:
        return False
    first, _, third = rest[:3]
    if first is not None:
        first = _real_array(first)
        if first is None or first.shape != (getattr(args[0], "n", None),):
            return False  # no (n,) vector first: the new order (its checks name what is wrong)
    third = None if third is None else _real_array(third)
    if third is None or third.ndim != 1 or not _increasing(third):
        return False
    return first is None or third.size != first.size or not _increasing(first)


def _real_array(values) -> np.ndarray | None:
    try:
        a = np.asarray(values)
    except (TypeError, ValueError):
        return None
    return a if a.dtype.kind in "iuf" else None


def _increasing(a: np.ndarray) -> bool:
    return bool(np.all(np.diff(a) > 0))


@renamed_keywords(tol="rtol")
@reordered_arguments(("sys", "x0", "v0", "t"), _old_order)
def free_response(
    sys: LinearizedSystem,
    t,
    x0,
    v0=None,
    *,
    t0: float = 0.0,
    modes=None,
    rtol: float = DEFAULT_TOL,
) -> FreeResponse:
    """Free vibration x(t) of M x'' + (D + G) x' + (S + N) x = 0 by the modal solution (theory: responses).

    For a simple dynamic stiffness (theory: spectrum: every eigenvalue semisimple)

    .. math::
        x(t) = \\sum_{k=1}^{2n} e^{\\lambda_k (t - t_0)}\\, x_k\\, y_k^T
               \\left((\\lambda_k M + C)\\, x_0 + M v_0\\right),
        \\qquad y_k^T L'(\\lambda_k)\\, x_k = 1,

    with the eigenvalues, right and normalized left vectors of :func:`pinlin.modal_analysis`.  A
    defective eigenvalue contributes the exponential polynomial of its Jordan chains
    (:func:`pinlin.jordan_chains`); the coefficients are refined on the initial state.  The solution
    is exact up to the accuracy of the eigen-data (no time stepping), and x', x'' come from the same
    expansion, so the equation's defect is a genuine check (theory: responses).  The returned array
    is read-only.

    Parameters
    ----------
    sys : LinearizedSystem
    t : (len(t),) array
        Strictly increasing times [s] (they may start before or after t0).
    x0, v0 : (n,) arrays
        Displacement and velocity at t0 (None: zero).  The 0.3 order ``(sys, x0, v0, t)`` still works
        with a :class:`DeprecationWarning` where the arguments tell it apart (always with ``t=``).
    t0 : float
        Time of the initial conditions [s].
    modes : Modes, optional
        A modal analysis of ``sys`` to reuse.
    rtol : float
        The relative accuracy aimed at: an :class:`~pinlin.AccuracyWarning` is issued when
        ``defect``, ``initial_defect`` or ``symmetry_defect`` exceeds it (``tol`` before 0.4).

    Returns
    -------
    FreeResponse
        The (len(t), n) real array x(t); ``.xdot``, ``.defect``,
        ``.initial_defect``, ``.elapsed`` and the other figures as attributes.

    Raises
    ------
    ParameterError
        Wrong shapes, non-finite values, non-increasing t, modes of another system.
    ComputationError
        The spectral data cannot be turned into an expansion (ambiguous Jordan structure), or the
        motion or its error figures overflow double precision.

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.2]], [[4.0]])  # x'' + 0.2 x' + 4 x = 0
    >>> t = np.linspace(0.0, 1.0, 5)
    >>> x = pinlin.free_response(sys, t, [0.1])
    >>> x.shape, x.method
    ((5, 1), 'modal')
    >>> np.round(x[:, 0], 6)
    array([ 0.1     ,  0.087959,  0.055499,  0.011368, -0.033325])
    >>> bool(x.error < 1e-12)
    True
    """
    t_start = time.perf_counter()
    check_system(sys)
    n = sys.n
    x0 = check_vector(x0, n, "x0")
    v0 = check_vector(v0, n, "v0")
    if t is None:
        raise ParameterError("t", "the output times are required")
    times = check_times(t)
    try:
        t0 = float(t0)
    except (TypeError, ValueError):
        raise ParameterError("t0", f"expected a time [s], got {t0!r:.80}") from None
    if not np.isfinite(t0):
        raise ParameterError("t0", f"must be finite, got {t0!r}")
    rtol = check_tolerance(rtol, "rtol")

    expansion = modal_expansion(sys, modes)
    tau = times - t0
    # one evaluation for t0 (the initial defect) and the output times
    x, xd, xdd, symmetry, projection = modal_free_motion(expansion, x0, v0, np.concatenate([[0.0], tau]))
    xs, xds = x[:1], xd[:1]
    x, xd, xdd = x[1:], xd[1:], xdd[1:]
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(xd)) and np.all(np.isfinite(xs)) and np.all(np.isfinite(xds))):
        raise ComputationError(
            "free_response: the motion overflows double precision (initial conditions near the largest "
            "double, or times so far from t0 that exp(lam t) overflows); rescale the initial state or the time span"
        )
    defect = _relative_defect(sys, x, xd, xdd)
    g = expansion.gamma
    rx = np.linalg.norm(x0) + np.linalg.norm(v0) / g
    rv = g * np.linalg.norm(x0) + np.linalg.norm(v0)
    initial = 0.0
    if rx > 0:
        initial = float(max(np.linalg.norm(xs[0] - x0) / rx, np.linalg.norm(xds[0] - v0) / rv))
    method = expansion.method
    worst = max(defect, initial, symmetry)
    if not np.isfinite(worst):
        raise ComputationError(
            f"free_response: the error figures overflow (defect {defect}, initial defect {initial}); "
            f"rescale the initial state"
        )
    if worst > rtol:
        warn_user(
            f"free_response: the {method} solution has defect {defect:.1e}, initial defect {initial:.1e}, "
            f"symmetry defect {symmetry:.1e} (largest above rtol {rtol:g}); the eigen-data may be ill-conditioned "
            f"(max eigenvalue condition {np.max(expansion.modes.condition):.1e}); forced_response(sys, t, "
            f"None, ...) gives the exact discretization instead",
            AccuracyWarning,
        )
    return FreeResponse(
        x,
        t=times,
        xdot=xd,
        defect=defect,
        initial_defect=initial,
        symmetry_defect=symmetry,
        projection_residual=projection,
        chain_residual=expansion.chain_residual,
        method=method,
        error=float(worst),
        modes=expansion.modes,
        elapsed=time.perf_counter() - t_start,
    )
