"""The logarithm of SE(3) to second order: what a bushing needs beyond Pinocchio's ``log6`` and ``Jlog6``.

A bushing's deflection is e = log6(X) (theory: elements between frames).  Its stiffness away
from e = 0 needs how the Jacobian of the log changes, i.e. the second-order
expansion of

.. math::  e(X \\exp \\xi) = e + J_{log}(X)\\, \\xi + \\tfrac12 E_2[\\xi, \\xi] + O(|\\xi|^3),
           \\qquad \\xi = (v, \\omega)

(right perturbation, Pinocchio's convention: linear part first).  With
X = (R, p), theta = log3(R) and t = |theta|, the log is e = (W(theta) p, theta)
where W = J_l^{-1} is the inverse left Jacobian of SO(3), and the inverse right
Jacobian is

.. math::  A(\\theta) = J_r^{-1}(\\theta) = I + \\tfrac12[\\theta]_\\times
           + \\beta(t)\\,[\\theta]_\\times^2,\\qquad
           \\beta(t) = \\frac{1}{t^2} - \\frac{1 + \\cos t}{2 t \\sin t}
           = \\sum_{n\\ge 1} \\frac{2\\zeta(2n)}{(2\\pi)^{2n}} t^{2n-2},

W = A^T.  Differentiating this closed form (no third derivative of log3 is
needed) gives, with theta' = log(exp(theta) exp(omega)) and
p' = p + R J_l(omega) v:

- J_log = [[A, B], [0, A]] with B omega = DW[A omega] p (equal to Pinocchio's ``Jlog6``);
- E_2 in the rotation rows: DA[A omega_2] omega_1 - (1/2) A (omega_2 x omega_1);
- in the translation rows: D^2 W[A omega_1, A omega_2] p + DW[theta_2] p
  + DW[A omega_1] R v_2 + DW[A omega_2] R v_1 + (1/2) A (omega_1 x v_2 + omega_2 x v_1)
  (theta_2 the rotation rows' second-order term).

beta and its derivatives are summed from their power series in t^2, which
converges for t < 2 pi (log3 gives t <= pi) without the cancellation of the
closed form at small angles.  Tests compare everything with finite
differences of ``pin.log6``.
"""

from __future__ import annotations

import numpy as np
from scipy.special import zeta

__all__ = ["skew", "LogExpansion", "log_expansion", "log_jacobian_derivative", "ad_matrix", "SERIES_TERMS", "SERIES_COEFFICIENTS"]

#: Terms of the series of beta(t): at t = pi the ratio of successive terms is 1/4,
#: so 40 terms leave a truncation below 1e-20 even for the second derivative.
SERIES_TERMS = 40

_n = np.arange(1, SERIES_TERMS + 1)
_B = 2.0 * zeta(2.0 * _n) / (2.0 * np.pi) ** (2 * _n)  # coefficient of t^(2n-2) in beta(t)
#: Coefficients of t^(2m), m = 0, 1, ... of beta, gamma = beta'(t)/t and gamma2 = gamma'(t)/t
#: (zero-padded to SERIES_TERMS): beta, gamma, gamma2 = powers(t^2) @ SERIES_COEFFICIENTS.
SERIES_COEFFICIENTS = np.zeros((SERIES_TERMS, 3))
SERIES_COEFFICIENTS[:, 0] = _B
SERIES_COEFFICIENTS[: SERIES_TERMS - 1, 1] = _B[1:] * (2 * _n[1:] - 2)
SERIES_COEFFICIENTS[: SERIES_TERMS - 2, 2] = _B[2:] * (2 * _n[2:] - 2) * (2 * _n[2:] - 4)

#: Levi-Civita symbol: (a x b)_k = eps_ijk a_i b_j.
_EPS = np.zeros((3, 3, 3))
for _i, _j, _k in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
    _EPS[_i, _j, _k] = 1.0
    _EPS[_j, _i, _k] = -1.0
#: _S[:, :, j] = [e_j]x: ([u]x)_ac = eps_abc u_b.
_S = np.einsum("ajc->acj", _EPS)
#: [e_j]x [e_k]x + [e_k]x [e_j]x, indexed [a, b, j, k].
_SS = np.einsum("abj,bck->acjk", _S, _S)
_SS = _SS + _SS.transpose(0, 1, 3, 2)


#: skew(a) = (a @ _SKEW).reshape(3, 3): _SKEW[j, 3 a + b] = _S[a, b, j].
_SKEW = np.ascontiguousarray(_S.reshape(9, 3).T)
#: _S_J[j] = [e_j]x, the generators stacked first (for products with a matrix per generator).
_S_J = np.ascontiguousarray(_S.transpose(2, 0, 1))
#: (A @ _EPS_K).reshape(3, 3, 3)[m, i, j] = sum_k A[m, k] eps_ijk.
_EPS_K = np.ascontiguousarray(_EPS.reshape(9, 3).T)
_I3 = np.eye(3)


def skew(a: np.ndarray) -> np.ndarray:
    """[a]x, the matrix of the cross product a x . ((..., 3) -> (..., 3, 3))."""
    return (a @ _SKEW).reshape(a.shape[:-1] + (3, 3))


def ad_matrix(xi: np.ndarray) -> np.ndarray:
    """ad(xi) for twists xi = (v, omega): ad(xi) eta = [xi, eta] ((..., 6) -> (..., 6, 6))."""
    out = np.zeros(xi.shape[:-1] + (6, 6))
    w = skew(xi[..., 3:])
    out[..., :3, :3] = w
    out[..., 3:, 3:] = w
    out[..., :3, 3:] = skew(xi[..., :3])
    return out


class LogExpansion:
    """The expansion of e(X exp xi) at X = (R, p), stacked over leading axes: J_log now, E_2 on first use.

    The first-order terms (A = J_r^{-1}(theta), its derivative, the series of beta)
    are kept for :attr:`E2`, so a caller that needs both pays for them once.
    Products are written as matrix products over the small axes (``np.einsum``
    with three or four operands loops in C without BLAS and costs more than the
    arithmetic on these (..., 3, 3, 3) arrays).

    Parameters
    ----------
    R : (..., 3, 3) rotations, p : (..., 3) translations [m] of X.
    theta : (..., 3) log3(R) [rad].
    """

    def __init__(self, R: np.ndarray, p: np.ndarray, theta: np.ndarray):
        self.R, self.p, self.theta = R, p, theta
        t2 = (theta * theta).sum(axis=-1)
        powers = np.empty(t2.shape + (SERIES_TERMS,))  # 1, t^2, t^4, ...: a running product (no pow calls)
        powers[..., 0] = 1.0
        powers[..., 1:] = t2[..., None]
        np.cumprod(powers, axis=-1, out=powers)
        self._series = np.moveaxis(powers @ SERIES_COEFFICIENTS, -1, 0)  # beta, gamma, gamma2
        beta, gamma = self._series[0], self._series[1]
        T = skew(theta)
        self._T2 = T2 = T @ T
        self.A = A = _I3 + 0.5 * T + beta[..., None, None] * T2
        Tj = T[..., None, :, :]
        self._ST = ST = np.moveaxis(_S_J @ Tj + Tj @ _S_J, -3, -1)  # [a, c, j]: S_j T + T S_j
        # dA[a, b, j] = dA[a, b] / dtheta_j
        self._dA = dA = (
            0.5 * _S
            + gamma[..., None, None, None] * (T2[..., None] * theta[..., None, None, :])
            + (beta[..., None, None, None] * ST)
        )
        self._dW_A = np.swapaxes(dA, -3, -2) @ A[..., None, :, :]  # DW[A e_j], indexed [a, b, j] (W = A^T)
        self.J = np.zeros(A.shape[:-2] + (6, 6))  # de/dxi at xi = 0 (Pinocchio's Jlog6(X))
        self.J[..., :3, :3] = A
        self.J[..., 3:, 3:] = A
        self.J[..., :3, 3:] = (p[..., None, None, :] @ self._dW_A)[..., 0, :]
        self._E2: np.ndarray | None = None

    def _d2A(self) -> np.ndarray:
        """d2A[..., a, b, j, k] = d^2 A[a, b] / dtheta_j dtheta_k."""
        beta, gamma, gamma2 = self._series
        theta, T2, ST = self.theta, self._T2, self._ST
        g = gamma[..., None, None, None, None]
        tt = theta[..., :, None] * theta[..., None, :]
        return (
            T2[..., None, None]
            * (gamma2[..., None, None] * tt + gamma[..., None, None] * _I3)[..., None, None, :, :]
            + g
            * (
                theta[..., None, None, :, None] * ST[..., None, :]
                + theta[..., None, None, None, :] * ST[..., None]
            )
            + beta[..., None, None, None, None] * _SS
        )

    @property
    def E2(self) -> np.ndarray:
        """E2[..., m, i, j] = d^2 e_m / dxi_i dxi_j at xi = 0 (symmetric in i, j), formed on first access."""
        if self._E2 is None:
            A, p, dA, dW_A = self.A, self.p, self._dA, self._dW_A
            lead = A.shape[:-2]
            d2A = self._d2A()
            half_A_eps = 0.5 * (A @ _EPS_K).reshape(lead + (3, 3, 3))  # (1/2) A (e_i x e_j)
            H3 = dA @ A[..., None, :, :] + half_A_eps  # rotation rows: DA[A e_j] e_i - (1/2) A (e_j x e_i)
            pr = p[..., None, :]
            Y = (pr @ d2A.reshape(lead + (3, 27))).reshape(
                lead + (3, 3, 3)
            )  # D^2 W[., .] p, indexed [a, c, d]
            Z = (pr @ dA.reshape(lead + (3, 9))).reshape(lead + (3, 3))  # DW[e_c] p, indexed [a, c]
            E2 = np.zeros(lead + (6, 6, 6))
            E2[..., 3:, 3:, 3:] = H3
            At = np.swapaxes(A, -1, -2)[..., None, :, :]
            E2[..., :3, 3:, 3:] = At @ Y @ A[..., None, :, :] + (Z @ H3.reshape(lead + (3, 9))).reshape(
                lead + (3, 3, 3)
            )
            mixed = np.swapaxes(self.R, -1, -2)[..., None, :, :] @ dW_A - half_A_eps  # [a, v_i, omega_j]
            E2[..., :3, :3, 3:] = mixed
            E2[..., :3, 3:, :3] = np.swapaxes(mixed, -1, -2)
            self._E2 = E2
        return self._E2


def log_expansion(
    R: np.ndarray, p: np.ndarray, theta: np.ndarray, second_order: bool = True
) -> tuple[np.ndarray, np.ndarray | None]:
    """J_log (..., 6, 6) and E_2 (..., 6, 6, 6, symmetric in its last two indices) of e(X exp xi) at X = (R, p).

    Parameters
    ----------
    R : (..., 3, 3) rotations, p : (..., 3) translations [m] of X.
    theta : (..., 3) log3(R) [rad].
    second_order : bool
        Compute E_2 (else it is returned as None).

    Returns
    -------
    J : (..., 6, 6) ndarray
        de/dxi at xi = 0 (Pinocchio's ``Jlog6(X)``).
    E2 : (..., 6, 6, 6) ndarray
        E2[m, i, j] = d^2 e_m / dxi_i dxi_j at xi = 0.
    """
    ex = LogExpansion(R, p, theta)
    return ex.J, (ex.E2 if second_order else None)


#: _AD_BASIS[i] = ad(e_i) (6 x 6 each).
_AD_BASIS = ad_matrix(np.eye(6))
#: (J @ _AD_K).reshape(6, 6, 6)[m, i, j] = sum_k J[m, k] ad(e_i)[k, j].
_AD_K = np.ascontiguousarray(_AD_BASIS.transpose(1, 0, 2).reshape(6, 36))


def log_jacobian_derivative(J: np.ndarray, E2: np.ndarray) -> np.ndarray:
    """L[..., m, i, j] = d J_log[m, i] / d eta_j for X -> X exp(eta) (..., 6, 6, 6).

    From exp(eta) exp(zeta) = exp(eta + zeta + [eta, zeta]/2 + ...):
    d(J_log e_i)/d eta = E2[:, i, :] + (1/2) J_log ad(.) e_i, i.e.
    L[:, i, j] = E2[:, i, j] - (1/2) J_log ad(e_i) e_j.
    """
    return E2 - 0.5 * (J @ _AD_K).reshape(J.shape[:-2] + (6, 6, 6))
