"""A double eigenvalue by Newton's method on its defining system (theory: boundaries).

Where two eigenvalues meet and leave an axis of symmetry of the spectrum -- two
imaginary eigenvalues of an undamped circulatory or gyroscopic system (flutter),
a pair through zero (divergence), a complex pair landing on the real axis -- the
real part of each grows like sqrt(p - p*) and Newton's method on it fails.  The
double eigenvalue s* of A(s, p) = sum_j s^j A_j(p) at p* is instead a regular
solution of

.. math::
    A(s, p)\\, x = 0, \\qquad A'(s, p)\\, x + A(s, p)\\, y = 0, \\qquad
    c^H x = 1, \\qquad c^H y = 0

in (p, s, x, y) (x, y a Jordan chain; c fixes the scale of x and the free
multiple of x in y).  Two forms are used:

- D = G = 0: s = mu = lam^2 and A(mu) = K + mu M, real: a double real eigenvalue
  of the pencil (-K, M); the system is real and square (2n + 2 unknowns);
- otherwise s = lam and A(lam) = K + lam C + lam^2 M, complex; with the real
  parameter p the real form of the system has one equation more than unknowns and
  is solved by Gauss-Newton (least squares), which converges quadratically
  because the structure (a spectrum symmetric about the axis) makes it consistent.

The derivatives A_j' = dA_j / dp come from the user's ``derivative`` or from
secants between consecutive iterates (exact when the matrices are affine in p).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from .derivatives import EPS, exact_derivatives
from .evaluation import Evaluator

__all__ = ["DoubleEigenvalue", "solve_double", "coefficients", "RESIDUAL_ROUNDING", "MAX_NEWTON_STEPS"]

#: Rounding of the defining system's residual: a few eps times the size of its terms (a matrix-vector
#: product of each coefficient and the sums), with the coefficients themselves correct to about eps.
RESIDUAL_ROUNDING = 8.0
#: Newton steps allowed on the defining system: from a predictor within the basin it converges
#: quadratically in 3 to 6 steps; more means the predictor was outside the basin.
MAX_NEWTON_STEPS = 12


@dataclass
class DoubleEigenvalue:
    """The solution (or the last iterate) of the defining system."""

    p: float
    s: complex
    x: np.ndarray
    y: np.ndarray
    converged: bool
    last_step: float
    floor: float
    steps: int
    history: list[float] = field(default_factory=list)
    reason: str = ""


def coefficients(stack: np.ndarray, squared: bool) -> list[np.ndarray]:
    """The coefficients A_0, A_1, ... of A(s) from a (M, C, K) stack: (K, M) for mu, (K, C, M) for lam."""
    M, C, K = stack
    return [K, M] if squared else [K, C, M]


def _poly(A: list[np.ndarray], s, order: int) -> np.ndarray:
    """The ``order``-th derivative in s of sum_j s^j A_j."""
    out = np.zeros_like(A[0], dtype=complex if np.iscomplexobj(s) else float)
    for j in range(order, len(A)):
        factor = float(np.prod(np.arange(j - order + 1, j + 1))) if order else 1.0
        out = out + factor * s ** (j - order) * A[j]
    return out


def _system(A, dA, p_s_x_y, c):
    """Residual F and Jacobian columns (for p: jp; for s, x, y: Jc) of the defining system."""
    s, x, y = p_s_x_y
    n = x.shape[0]
    A0, A1, A2 = _poly(A, s, 0), _poly(A, s, 1), _poly(A, s, 2)
    P0, P1 = _poly(dA, s, 0), _poly(dA, s, 1)
    F = np.concatenate([A0 @ x, A1 @ x + A0 @ y, [c.conj() @ x - 1.0], [c.conj() @ y]])
    jp = np.concatenate([P0 @ x, P1 @ x + P0 @ y, [0.0], [0.0]])
    Jc = np.zeros((2 * n + 2, 2 * n + 1), dtype=np.result_type(A0, s, x, y))
    Jc[:n, 0], Jc[:n, 1 : n + 1] = A1 @ x, A0
    Jc[n : 2 * n, 0], Jc[n : 2 * n, 1 : n + 1], Jc[n : 2 * n, n + 1 :] = A2 @ x + A1 @ y, A1, A0
    Jc[2 * n, 1 : n + 1] = c.conj()
    Jc[2 * n + 1, n + 1 :] = c.conj()
    size = sum(abs(s) ** j * np.linalg.norm(Aj) for j, Aj in enumerate(A)) * (np.linalg.norm(x) + np.linalg.norm(y))
    return F, jp, Jc, RESIDUAL_ROUNDING * EPS * size


def _realify(F, jp, Jc, real: bool):
    if real:
        return np.real(F), np.column_stack([np.real(jp), np.real(Jc)])
    J = np.block([[np.real(jp)[:, None], Jc.real, -Jc.imag], [np.imag(jp)[:, None], Jc.imag, Jc.real]])
    return np.concatenate([F.real, F.imag]), J


def _unpack(step, n, real: bool):
    if real:
        return step[0], step[1], step[2 : n + 2], step[n + 2 :]
    m = 2 * n + 1
    z = step[1 : m + 1] + 1j * step[m + 1 :]
    return step[0], z[0], z[1 : n + 1], z[n + 1 :]


def solve_double(
    evaluator: Evaluator,
    p0: float,
    s0: complex,
    x0: np.ndarray,
    *,
    squared: bool,
    interval: tuple[float, float],
    derivative: Callable | None = None,
    tol: float = 0.0,
    max_steps: int = MAX_NEWTON_STEPS,
) -> DoubleEigenvalue:
    """Newton (Gauss-Newton) on the defining system of a double eigenvalue from (p0, s0, x0).

    Stops when the parameter step is below ``max(tol, floor)``, ``floor`` being the
    parameter's uncertainty from rounding (the p-row of the Jacobian's
    pseudo-inverse times the residual's rounding level), or fails (``converged``
    False, with the reason) when an iterate leaves ``interval``, the steps stop
    shrinking, or ``max_steps`` is reached.  Each step calls ``func`` once.
    """
    real = squared and np.isrealobj(x0) and np.imag(s0) == 0
    dtype = float if real else complex
    x = np.asarray(x0, dtype=dtype)
    s = float(np.real(s0)) if real else complex(s0)
    c = x / np.vdot(x, x).real
    n = x.shape[0]
    p = float(p0)
    A = coefficients(evaluator.matrices(p), squared)
    lhs = np.vstack([_poly(A, s, 0), c.conj()[None, :]])
    y = np.linalg.lstsq(lhs, np.concatenate([-_poly(A, s, 1) @ x, [0.0]]), rcond=None)[0]
    previous = evaluator.nearest(p, exclude=p)
    out = DoubleEigenvalue(p, s, x, y, False, np.inf, np.inf, 0)
    for step_no in range(1, max_steps + 1):
        stack = evaluator.matrices(p)
        A = coefficients(stack, squared)
        if derivative is not None:
            dA = coefficients(exact_derivatives(derivative, p, n).stack, squared)
        else:
            dA = coefficients((stack - evaluator.matrices(previous)) / (p - previous), squared)
        F, jp, Jc, rounding = _system(A, dA, (s, x, y), c)
        rhs, J = _realify(F, jp, Jc, real)
        U, sv, Vt = np.linalg.svd(J, full_matrices=False)
        if sv[-1] <= EPS * sv[0]:
            out.reason = "the Jacobian of the defining system is singular (a degenerate double eigenvalue)"
            return out
        delta = -(Vt.T @ ((U.T @ rhs) / sv))
        floor = float(np.linalg.norm(Vt[:, 0] / sv)) * rounding
        dp, ds, dx, dy = _unpack(delta, n, real)
        previous, p = p, p + float(dp)
        s, x, y = s + ds, x + dx, y + dy
        out = DoubleEigenvalue(p, s, x, y, False, abs(float(dp)), floor, step_no, out.history + [abs(float(dp))])
        if not interval[0] <= p <= interval[1]:
            out.reason = f"the iterate p = {p:.6g} left the bracket [{interval[0]:.6g}, {interval[1]:.6g}]"
            return out
        if abs(dp) <= max(tol, floor, 2 * EPS * abs(p)):
            out.converged = True
            return out
        if step_no >= 3 and out.history[-1] > 0.5 * out.history[-2]:
            out.reason = f"the steps stopped shrinking (last {out.history[-2]:.2e}, {out.history[-1]:.2e})"
            return out
    out.reason = f"no convergence in {max_steps} steps"
    return out
