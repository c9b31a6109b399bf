"""The log of a joint's Lie group and its Jacobian, accurate at every angle: what a joint spring needs.

A spring on a free-flyer, spherical or planar joint has the deflection
e = log(q_rest^{-1} q) and the stiffness K_s de/dq (theory: elements), with
de/dq = J_log(X) at X = q_rest^{-1} q (right perturbations, Pinocchio's
convention: ``difference`` and ``dDifference(..., ARG1)``).  Pinocchio 4.1's
``dDifference`` on these groups (``Jlog6``, ``Jlog3``) loses accuracy for
rotations between about 1e-4 and 2e-3 rad, where a spring near its rest
works: up to 3e-5 relative on SE(3), 2e-9 on SO(3) and 5e-9 on SE(2).  Here
the same closed form as :mod:`.se3` (which the bushings use, checked against
mpmath) is evaluated on arrays of points, one point being a batch of one
(:func:`se3_log`, :class:`JointLog`); :func:`pinlin.linear_coordinates` reads the same log, and
the nonlinear simulator's charts the rate of the exponential chart
(:func:`exp_chart_rate`):

.. math::  J_{log} = \\begin{bmatrix} A & D(p) A \\\\ 0 & A \\end{bmatrix},\\qquad
           A = I + \\tfrac12 [\\theta]_\\times + \\beta [\\theta]_\\times^2,

.. math::  D(p) = \\tfrac12 [p]_\\times + \\gamma\\, [\\theta]_\\times^2 p\\, \\theta^T
           - \\beta \\big([\\theta]_\\times [p]_\\times + [\\theta \\times p]_\\times\\big)

(D(p) omega = DW[omega] p, W = A^T; beta(t) and gamma = beta'(t) / t from their
power series for t < 2, where the closed forms cancel, and from the closed forms
above), and e = (W p, theta).  SO(3) is the rotation block; SE(2) the planar
rows and columns (x, y, rotation) of SE(3) about z.
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin

from .se3 import SERIES_COEFFICIENTS, skew

__all__ = ["beta_gamma", "se3_log", "JointLog", "joint_log", "curved_joints", "exp_chart_rate", "SERIES_BELOW"]

#: beta and gamma come from their series below this t^2 (t < 2 rad), from the closed forms above:
#: gamma's closed form loses about eps / t^4 of its size, its series' terms shrink like (t / 2 pi)^2.
SERIES_BELOW = 4.0

#: Terms of the series of beta and gamma: at t^2 = SERIES_BELOW the truncation stays below 1e-18 relative
#: (successive terms shrink like t^2 / (4 pi^2)).
SERIES_TERMS = 22

#: Coefficients of t^(2m) of beta and gamma (one column each), and the powers m.
_SERIES = SERIES_COEFFICIENTS[:SERIES_TERMS, :2]
_POWERS = np.arange(SERIES_TERMS)


def _series(t2: np.ndarray) -> np.ndarray:
    """beta and gamma from their series at t^2 (any shape): (2, ...).

    A sum of products per entry (``einsum``), whose order does not depend on how many
    points are stacked (a matrix product would hand one point and many to different BLAS
    kernels): a point's log is the same in a batch of one and in a batch of many.
    """
    bg = np.einsum("...k,kc->...c", np.power.outer(t2, _POWERS), _SERIES)
    return bg[..., 0], bg[..., 1]


def beta_gamma(t2) -> tuple[np.ndarray, np.ndarray]:
    """beta(t) = 1/t^2 - (1 + cos t) / (2 t sin t) and gamma = beta'(t) / t at t^2 (any shape).

    Examples
    --------
    >>> b, g = beta_gamma(0.0)
    >>> print(f"{b:.6f} {g:.6f}")  # 1/12 and 1/360 at t = 0
    0.083333 0.002778
    """
    t2 = np.asarray(t2, dtype=float)
    series = t2 < SERIES_BELOW
    if series.all():
        return _series(t2)
    b, g = _series(np.where(series, t2, 0.0))
    closed = np.where(series, SERIES_BELOW, t2)
    t = np.sqrt(closed)
    s = np.sin(0.5 * t)
    cot = np.cos(0.5 * t) / s  # (1 + cos t) / sin t
    b = np.where(series, b, 1.0 / closed - cot / (2.0 * t))
    g = np.where(series, g, (-2.0 / (closed * t) + 1.0 / (4.0 * t * s * s) + cot / (2.0 * closed)) / t)
    return b, g


def se3_log(theta, p, jacobian: bool = True) -> tuple[np.ndarray, np.ndarray | None]:
    """e = log6(X) (linear part first) and J_log(X) (or None) at X = (exp3(theta), p), for points along leading axes.

    ``theta`` (theta = log3 of X's rotation) and ``p`` have shape (..., 3); e has shape (..., 6) and
    J_log (..., 6, 6).  One point is a batch of one: shape (3,) in, (6,) and (6, 6) out.

    Examples
    --------
    >>> e, J = se3_log([0.0, 0.0, 0.0], [1.0, 2.0, 3.0])
    >>> print(e, np.array_equal(J, np.eye(6)))
    [1. 2. 3. 0. 0. 0.] False
    >>> e, J = se3_log(np.zeros((4, 3)), np.zeros((4, 3)))
    >>> print(e.shape, J.shape, np.array_equal(J[0], np.eye(6)))
    (4, 6) (4, 6, 6) True
    """
    theta, p = np.asarray(theta, dtype=float), np.asarray(p, dtype=float)
    b, g = beta_gamma((theta * theta).sum(axis=-1))
    b, g = b[..., None, None], g[..., None, None]
    S, P = skew(theta), skew(p)
    SS = S @ S  # [theta]x^2 = theta theta^T - t^2 I
    A = np.eye(3) + 0.5 * S + b * SS
    e = np.concatenate([(p[..., None, :] @ A)[..., 0, :], theta], axis=-1)  # (W p, theta), W = A^T
    if not jacobian:
        return e, None
    # D(p) = [p]x / 2 + g [theta]x^2 p theta^T - b ([theta]x [p]x + [theta x p]x)
    D = 0.5 * P + g * (SS @ p[..., :, None]) * theta[..., None, :] - b * (S @ P + skew((S @ p[..., :, None])[..., 0]))
    J = np.zeros(theta.shape[:-1] + (6, 6))
    J[..., :3, :3] = A
    J[..., 3:, 3:] = A
    J[..., :3, 3:] = D @ A
    return e, J


#: The coordinates of SE(3)'s (v, omega) that each group's tangent coordinates are.
_TANGENT = {"SE(3)": slice(None), "SO(3)": slice(3, 6), "SE(2)": [0, 1, 5]}


def _quaternion_log(w: np.ndarray, v: np.ndarray) -> np.ndarray:
    """log3 of the rotations of quaternions w (...), v (..., 3): 2 atan2(|v|, w) v / |v|, exactly 0 where v = 0."""
    n = np.sqrt((v * v).sum(axis=-1))
    sign = np.where(w >= 0.0, 2.0, -2.0)  # the rotation of angle <= pi
    angle = sign * np.arctan2(n, 0.5 * sign * w)
    return (angle / np.where(n > 0.0, n, 1.0))[..., None] * v  # v = 0: theta = 0


def _relative(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(w, v) of conj(a) b for quaternions a (4,) and b (..., 4) in Pinocchio's order (x, y, z, w).

    Each pair of terms of v is exactly zero when a = b, so that the log is exactly zero at rest.
    """
    a_v, a_w = a[:3], a[3]
    b_v, b_w = b[..., :3], b[..., 3:]
    return b @ a, (a_w * b_v - b_w * a_v) + _cross(b_v, a_v)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b along the last axis, each entry a difference of two products (exactly 0 when a = b)."""
    return a[..., _NEXT] * b[..., _PREVIOUS] - a[..., _PREVIOUS] * b[..., _NEXT]


#: The index of the next and the previous axis: (a x b)_i = a_{i+1} b_{i-1} - a_{i-1} b_{i+1}.
_NEXT, _PREVIOUS = np.array([1, 2, 0]), np.array([2, 0, 1])


class JointLog:
    """``difference(rest, q_j)`` and ``dDifference(rest, q_j, ARG1)`` of one joint, accurate (module docstring).

    Built once per scene for a free-flyer (SE(3)), spherical (SO(3)) or planar
    (SE(2)) joint and its rest configuration; immutable, shared by threads.  The
    rotation of X = rest^{-1} q comes from a quaternion (or (cos, sin)) product,
    whose vector part is exactly zero at q = rest: there e = 0 and de/dq = I
    exactly, as with Pinocchio.  :meth:`evaluate` is :meth:`evaluate_many` of one row.

    Examples
    --------
    >>> import pinocchio as pin
    >>> model = pin.Model()
    >>> _ = model.addJoint(0, pin.JointModelSpherical(), pin.SE3.Identity(), "ball")
    >>> log = joint_log(model.joints[1], pin.neutral(model))
    >>> q = pin.integrate(model, pin.neutral(model), np.array([0.0, 0.0, 0.3]))
    >>> print(log.name, np.round(log.difference(q), 6))
    SO(3) [0.  0.  0.3]
    """

    __slots__ = ("name", "_rest", "_rotation")

    def __init__(self, name: str, rest: np.ndarray):
        self.name = name  # the Lie group, as Pinocchio names it
        self._rest = np.array(rest, dtype=float)
        self._rest.flags.writeable = False
        # R0^T of an SE(3) rest, or the planar (cos, sin) rotation's R0^T (x, y rows)
        if name == "SE(3)":
            self._rotation = pin.Quaternion(self._rest[3:]).toRotationMatrix().T
        elif name == "SE(2)":
            c0, s0 = self._rest[2:]
            self._rotation = np.array([[c0, s0], [-s0, c0]])
        else:
            self._rotation = None

    def _points(self, qs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(theta, p) of X = rest^{-1} q for each row of ``qs`` (P, nq_j): theta = log3 of X's rotation, (P, 3) each."""
        rest = self._rest
        if self.name == "SO(3)":
            return _quaternion_log(*_relative(rest, qs)), np.zeros((len(qs), 3))
        if self.name == "SE(3)":
            p = (qs[:, :3] - rest[:3]) @ self._rotation.T
            return _quaternion_log(*_relative(rest[3:], qs[:, 3:])), p
        c0, s0 = rest[2:]
        c1, s1 = qs[:, 2], qs[:, 3]
        zero = np.zeros(len(qs))
        angle = np.arctan2(c0 * s1 - s0 * c1, c0 * c1 + s0 * s1)
        p = (qs[:, :2] - rest[:2]) @ self._rotation.T
        return np.stack([zero, zero, angle], axis=1), np.column_stack([p, zero])

    def evaluate_many(self, qs: np.ndarray, jacobian: bool = True) -> tuple[np.ndarray, np.ndarray | None]:
        """The deflection e = log(rest^{-1} q) (P, nv_j) and de/dq = J_log(rest^{-1} q) (P, nv_j, nv_j) or None
        at each row of ``qs`` (P, nq_j)."""
        e, J = se3_log(*self._points(np.asarray(qs, dtype=float).reshape(-1, len(self._rest))), jacobian=jacobian)
        index = _TANGENT[self.name]
        return e[:, index], None if J is None else J[:, index][:, :, index]

    def evaluate(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(e, de/dq): the deflection e = log(rest^{-1} q) (nv_j,) and J_log(rest^{-1} q) (nv_j x nv_j)."""
        e, J = self.evaluate_many(q[None])
        return e[0], J[0]

    def difference(self, q: np.ndarray) -> np.ndarray:
        """e = log(rest^{-1} q) (nv_j,)."""
        return self.evaluate_many(q[None], jacobian=False)[0][0]

    def jacobian(self, q: np.ndarray) -> np.ndarray:
        """de/dq = J_log(rest^{-1} q) (nv_j x nv_j)."""
        return self.evaluate(q)[1]


#: The joint kinds (Pinocchio's short names) whose Lie group JointLog evaluates, and that group.
_KINDS = {"JointModelFreeFlyer": "SE(3)", "JointModelSpherical": "SO(3)", "JointModelPlanar": "SE(2)"}


def joint_log(joint: pin.JointModel, rest: np.ndarray) -> JointLog | None:
    """A :class:`JointLog` for a free-flyer, spherical or planar joint at its rest configuration, else None.

    Examples
    --------
    >>> import pinocchio as pin
    >>> print(joint_log(pin.JointModelFreeFlyer(), np.r_[0, 0, 0, 0, 0, 0, 1.0]).name)
    SE(3)
    >>> print(joint_log(pin.JointModelRY(), np.zeros(1)))
    None
    """
    kind = _KINDS.get(joint.shortname())
    return None if kind is None else JointLog(kind, rest)


def curved_joints(model: pin.Model, q0: np.ndarray) -> list[tuple[slice, slice, JointLog]]:
    """(q slice, v slice, log at q0's part) of every free-flyer, spherical and planar joint of the model.

    ``pin.difference(model, q0, q)`` and ``pin.dDifference(model, q0, q, ARG1)`` are
    block diagonal over the joints: these blocks, replaced by the logs', are accurate
    at every angle (module docstring).

    Examples
    --------
    >>> import pinocchio as pin
    >>> model = pin.Model()
    >>> _ = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "root")
    >>> [(qs, vs, log.name) for qs, vs, log in curved_joints(model, pin.neutral(model))]
    [(slice(0, 7, None), slice(0, 6, None), 'SE(3)')]
    """
    out = []
    for jid in range(1, model.njoints):
        joint = model.joints[jid]
        qs, vs = slice(joint.idx_q, joint.idx_q + joint.nq), slice(joint.idx_v, joint.idx_v + joint.nv)
        log = joint_log(joint, q0[qs])
        if log is not None:
            out.append((qs, vs, log))
    return out


#: Taylor coefficients of c1 = (1 - cos t) / t^2 and c2 = (t - sin t) / t^3 in t^2, from the highest
#: (12 terms: below 1e-19 relative for t < 1, where the closed forms cancel).
_C1 = [(-1) ** k / math.factorial(2 * k + 2) for k in range(12)][::-1]
_C2 = [(-1) ** k / math.factorial(2 * k + 3) for k in range(12)][::-1]


def _left_jacobian(theta: np.ndarray) -> np.ndarray:
    """J_l(theta) = I + c1 [theta]x + c2 [theta]x^2 (3 x 3): the inverse of W = A^T."""
    t2 = float(theta @ theta)
    if t2 < 1.0:
        c1, c2 = np.polyval(_C1, t2), np.polyval(_C2, t2)
    else:
        t = math.sqrt(t2)
        c1, c2 = (1.0 - math.cos(t)) / t2, (t - math.sin(t)) / (t2 * t)
    # [theta]x^2 = theta theta^T - t^2 I
    return (1.0 - c2 * t2) * np.eye(3) + c1 * skew(theta) + c2 * np.outer(theta, theta)


def exp_chart_rate(name: str, dq: np.ndarray, v: np.ndarray) -> np.ndarray:
    """d(dq)/dt of the exponential chart q = q_b exp(dq) for the velocity v of one joint (nv_j,).

    (d integrate / d dq)^{-1} v = J_r(dq)^{-1} v = J_log(exp(dq)) v on SE(3), SO(3)
    and SE(2) (``name``); exp(dq) has rotation theta and translation p = J_l(theta) rho
    for dq = (rho, theta), so e = log(exp dq) = dq and :func:`se3_log` gives J_log.
    Pinocchio 4.1's ``dIntegrate`` on SE(3) (``Jexp6``) gives rates up to 3e-5
    relative off between about 1e-4 and 2e-3 rad.

    Examples
    --------
    >>> print(exp_chart_rate("SO(3)", np.zeros(3), np.array([1.0, 2.0, 3.0])))
    [1. 2. 3.]
    """
    index = _TANGENT[name]
    twist = np.zeros(6)
    twist[index] = dq
    rho, theta = twist[:3], twist[3:]
    _, J = se3_log(theta, _left_jacobian(theta) @ rho)
    return J[index][:, index] @ v
