"""The log of a joint's Lie group and its Jacobian, accurate at every angle: what a joint spring needs.

A spring on a free-flyer, spherical or planar joint has the deflection
e = log(q_rest^{-1} q) and the stiffness K_s de/dq (theory: elements), with
de/dq = J_log(X) at X = q_rest^{-1} q (right perturbations, Pinocchio's
convention: ``difference`` and ``dDifference(..., ARG1)``).  Pinocchio 4.1's
``dDifference`` on these groups (``Jlog6``, ``Jlog3``) loses accuracy for
rotations between about 1e-4 and 2e-3 rad, where a spring near its rest
works: up to 3e-5 relative on SE(3), 2e-9 on SO(3) and 5e-9 on SE(2).  Here
the same closed form as :mod:`.se3` (which the bushings use, checked against
mpmath) is evaluated for one joint on Python floats, a few microseconds per call
(:class:`JointLog`); :func:`pinlin.linear_coordinates` reads the same log, and
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

from ...numerics.arrays import readonly
from .se3 import SERIES_COEFFICIENTS

__all__ = ["beta_gamma", "se3_log", "JointLog", "joint_log", "curved_joints", "exp_chart_rate", "SERIES_BELOW"]

#: beta and gamma come from their series below this t^2 (t < 2 rad), from the closed forms above:
#: gamma's closed form loses about eps / t^4 of its size, its series' terms shrink like (t / 2 pi)^2.
SERIES_BELOW = 4.0

#: (largest t^2, coefficients of t^(2m) from the highest) of beta and gamma: the fewest terms whose
#: truncation stays below 1e-18 relative there (successive terms shrink like t^2 / (4 pi^2)).
_BUCKETS = tuple(
    (limit, [float(c) for c in SERIES_COEFFICIENTS[:terms, 0]][::-1], [float(c) for c in SERIES_COEFFICIENTS[:terms, 1]][::-1])
    for limit, terms in ((1e-6, 3), (1e-2, 5), (0.25, 9), (1.0, 12), (SERIES_BELOW, 22))
)


def beta_gamma(t2: float) -> tuple[float, float]:
    """beta(t) = 1/t^2 - (1 + cos t) / (2 t sin t) and gamma = beta'(t) / t at t^2 (module docstring)."""
    if t2 < SERIES_BELOW:
        for limit, series_b, series_g in _BUCKETS:  # noqa: B007 (the first bucket that holds t^2)
            if t2 < limit:
                break
        b = g = 0.0
        for cb, cg in zip(series_b, series_g):
            b = b * t2 + cb
            g = g * t2 + cg
        return b, g
    t = math.sqrt(t2)
    s = math.sin(0.5 * t)
    cot = math.cos(0.5 * t) / s  # (1 + cos t) / sin t
    return 1.0 / t2 - cot / (2.0 * t), (-2.0 / (t2 * t) + 1.0 / (4.0 * t * s * s) + cot / (2.0 * t2)) / t


def se3_log(theta, p, jacobian: bool = True) -> tuple[list[float], np.ndarray | None]:
    """e = log6(X) (6 floats, linear part first) and J_log(X) (6 x 6, or None) at X = (exp3(theta), p).

    ``theta`` and ``p`` are 3 floats each (theta = log3 of X's rotation).
    """
    x, y, z = theta
    px, py, pz = p
    t2 = x * x + y * y + z * z
    b, g = beta_gamma(t2)
    d = 1.0 - b * t2
    # A = (1 - b t^2) I + b theta theta^T + [theta]x / 2
    a00, a01, a02 = d + b * x * x, b * x * y - 0.5 * z, b * x * z + 0.5 * y
    a10, a11, a12 = b * y * x + 0.5 * z, d + b * y * y, b * y * z - 0.5 * x
    a20, a21, a22 = b * z * x - 0.5 * y, b * z * y + 0.5 * x, d + b * z * z
    e = [a00 * px + a10 * py + a20 * pz, a01 * px + a11 * py + a21 * pz, a02 * px + a12 * py + a22 * pz, x, y, z]
    if not jacobian:
        return e, None
    tp = x * px + y * py + z * pz
    # D = [p]x / 2 + g (theta (theta . p) - t^2 p) theta^T - b (p theta^T - (theta . p) I + [theta x p]x)
    ux, uy, uz = g * (x * tp - t2 * px), g * (y * tp - t2 * py), g * (z * tp - t2 * pz)
    cx, cy, cz = y * pz - z * py, z * px - x * pz, x * py - y * px
    btp = b * tp
    d00, d01, d02 = ux * x - b * px * x + btp, -0.5 * pz + ux * y - b * px * y + b * cz, 0.5 * py + ux * z - b * px * z - b * cy
    d10, d11, d12 = 0.5 * pz + uy * x - b * py * x - b * cz, uy * y - b * py * y + btp, -0.5 * px + uy * z - b * py * z + b * cx
    d20, d21, d22 = -0.5 * py + uz * x - b * pz * x + b * cy, 0.5 * px + uz * y - b * pz * y - b * cx, uz * z - b * pz * z + btp
    b00, b01, b02 = d00 * a00 + d01 * a10 + d02 * a20, d00 * a01 + d01 * a11 + d02 * a21, d00 * a02 + d01 * a12 + d02 * a22
    b10, b11, b12 = d10 * a00 + d11 * a10 + d12 * a20, d10 * a01 + d11 * a11 + d12 * a21, d10 * a02 + d11 * a12 + d12 * a22
    b20, b21, b22 = d20 * a00 + d21 * a10 + d22 * a20, d20 * a01 + d21 * a11 + d22 * a21, d20 * a02 + d21 * a12 + d22 * a22
    J = np.array([
        a00, a01, a02, b00, b01, b02,
        a10, a11, a12, b10, b11, b12,
        a20, a21, a22, b20, b21, b22,
        0.0, 0.0, 0.0, a00, a01, a02,
        0.0, 0.0, 0.0, a10, a11, a12,
        0.0, 0.0, 0.0, a20, a21, a22,
    ]).reshape(6, 6)  # fmt: skip (a flat list: cheaper than nested rows)
    return e, J


#: The rows and columns of SE(3)'s (v, omega) that SE(2)'s (v_x, v_y, omega_z) are.
_PLANAR = np.ix_([0, 1, 5], [0, 1, 5])


def _quaternion_log(w: float, x: float, y: float, z: float) -> list[float]:
    """log3 of the rotation of a quaternion (w, x, y, z): 2 atan2(|v|, w) v / |v|, exactly 0 when v = 0."""
    n = math.sqrt(x * x + y * y + z * z)
    if n == 0.0:
        return [0.0, 0.0, 0.0]
    angle = 2.0 * math.atan2(n, w) if w >= 0.0 else -2.0 * math.atan2(n, -w)  # the rotation of angle <= pi
    return [angle * x / n, angle * y / n, angle * z / n]


class JointLog:
    """``difference(rest, q_j)`` and ``dDifference(rest, q_j, ARG1)`` of one joint, accurate (module docstring).

    Built once per scene for a free-flyer (SE(3)), spherical (SO(3)) or planar
    (SE(2)) joint and its rest configuration; immutable, shared by threads.  The
    rotation of X = rest^{-1} q comes from a quaternion (or (cos, sin)) product,
    whose vector part is exactly zero at q = rest: there e = 0 and de/dq = I
    exactly, as with Pinocchio.
    """

    __slots__ = ("name", "_rest", "_columns")

    def __init__(self, name: str, rest: np.ndarray):
        self.name = name  # the Lie group, as Pinocchio names it
        if name == "SE(3)":  # (x, y, z, qx, qy, qz, qw): the position and R0^T as floats
            R0 = pin.Quaternion(rest[3:]).toRotationMatrix()
            self._rest = (tuple(rest[:3].tolist()), tuple(rest[3:].tolist()), tuple(R0.T.ravel().tolist()))
        else:  # SO(3): (qx, qy, qz, qw); SE(2): (x, y, cos, sin)
            self._rest = tuple(rest.tolist())
        self._columns = self._batch_constants()

    def _batch_constants(self) -> tuple | None:
        """The rest as the column arrays :meth:`evaluate_many` multiplies with (read-only); None on SE(2)."""
        if self.name == "SE(2)":
            return None
        ax, ay, az, aw = self._rest[1] if self.name == "SE(3)" else self._rest
        columns = ([aw, ax, ay, az], [ax, ay, az], [az, ax, ay], [ay, az, ax])
        quaternion = tuple(readonly(np.reshape(c, (-1, 1))) for c in columns)
        if self.name == "SO(3)":
            return quaternion
        return readonly(np.reshape(self._rest[0], (3, 1))), readonly(np.reshape(self._rest[2], (3, 3, 1))), quaternion

    def _point(self, q: np.ndarray) -> tuple[list[float], list[float]]:
        """(theta, p) of X = rest^{-1} q, theta = log3 of X's rotation (its axis times its angle)."""
        if self.name == "SO(3)":
            return _quaternion_log(*_relative(self._rest, q.tolist())), [0.0, 0.0, 0.0]
        if self.name == "SE(3)":
            (x0, y0, z0), quat0, (r00, r01, r02, r10, r11, r12, r20, r21, r22) = self._rest
            x1, y1, z1, *quat1 = q.tolist()
            dx, dy, dz = x1 - x0, y1 - y0, z1 - z0
            p = [r00 * dx + r01 * dy + r02 * dz, r10 * dx + r11 * dy + r12 * dz, r20 * dx + r21 * dy + r22 * dz]
            return _quaternion_log(*_relative(quat0, quat1)), p
        x0, y0, c0, s0 = self._rest
        x1, y1, c1, s1 = q.tolist()
        dx, dy = x1 - x0, y1 - y0
        angle = math.atan2(c0 * s1 - s0 * c1, c0 * c1 + s0 * s1)
        return [0.0, 0.0, angle], [c0 * dx + s0 * dy, c0 * dy - s0 * dx, 0.0]

    def evaluate(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(e, de/dq): the deflection e = log(rest^{-1} q) (nv_j,) and J_log(rest^{-1} q) (nv_j x nv_j)."""
        e, J = se3_log(*self._point(q))
        return self._restrict(e), _restrict_jacobian(self.name, J)

    def difference(self, q: np.ndarray) -> np.ndarray:
        """e = log(rest^{-1} q) (nv_j,)."""
        e, _ = se3_log(*self._point(q), jacobian=False)
        return self._restrict(e)

    def _restrict(self, e: list[float]) -> np.ndarray:
        """SE(3)'s (v, omega) restricted to the group's tangent coordinates."""
        return np.array(e[3:] if self.name == "SO(3)" else (e if self.name == "SE(3)" else (e[0], e[1], e[5])))

    def jacobian(self, q: np.ndarray) -> np.ndarray:
        """de/dq = J_log(rest^{-1} q) (nv_j x nv_j)."""
        return self.evaluate(q)[1]

    def evaluate_many(self, qs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`evaluate` at each row of ``qs`` (P, nq_j): e (P, nv_j) and de/dq (P, nv_j, nv_j), C-contiguous, bitwise.

        The single evaluation's operations in its order on arrays of all rows (IEEE arithmetic and
        ``np.sqrt`` round as Python's floats do); atan2 and the closed forms of beta, gamma per row.
        """
        e, J = _se3_log_many(*self._points(np.ascontiguousarray(np.asarray(qs, dtype=float).T)))
        if self.name == "SE(3)":
            return e, J
        index = [3, 4, 5] if self.name == "SO(3)" else [0, 1, 5]
        return np.ascontiguousarray(e[:, index]), np.ascontiguousarray(J[:, index][:, :, index])

    def _points(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`_point` of each column of ``q`` (nq_j, P): theta and p (3, P)."""
        if self.name == "SO(3)":
            return _quaternion_log_many(*_relative_many(self._columns, q)), np.zeros((3, q.shape[1]))
        if self.name == "SE(3)":
            position, R0T, quaternion = self._columns
            rotated = R0T * (q[:3] - position)  # r_ij (q_j - x_j), summed over j in order
            p = rotated[:, 0] + rotated[:, 1] + rotated[:, 2]
            return _quaternion_log_many(*_relative_many(quaternion, q[3:])), p
        x0, y0, c0, s0 = self._rest
        x1, y1, c1, s1 = q
        dx, dy = x1 - x0, y1 - y0
        sines, cosines = (c0 * s1 - s0 * c1).tolist(), (c0 * c1 + s0 * s1).tolist()
        zero = np.zeros(q.shape[1])
        angle = np.array([math.atan2(s, c) for s, c in zip(sines, cosines)])
        return np.stack([zero, zero, angle]), np.stack([c0 * dx + s0 * dy, c0 * dy - s0 * dx, zero])


def _relative(a, b) -> tuple[float, float, float, float]:
    """(w, x, y, z) of conj(a) b for quaternions a, b given as (x, y, z, w) (Pinocchio's order)."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (  # paired so that each pair, and the vector part, is exactly zero when a = b
        aw * bw + ax * bx + ay * by + az * bz,
        (aw * bx - ax * bw) + (az * by - ay * bz),
        (aw * by - ay * bw) + (ax * bz - az * bx),
        (aw * bz - az * bw) + (ay * bx - ax * by),
    )


#: For :meth:`JointLog.evaluate_many` (read-only): the buckets' limits of t^2 and Horner coefficients of (beta,
#: gamma) as (terms, 2, 1) arrays; the signs of [v]x and [-v]x from (d, v_z, v_y, v_z, d, v_x, v_y, v_x, d);
#: theta x p = theta[next] p[prev] - theta[prev] p[next]; 0-d operands (cheaper than Python floats, the same products).
_LIMITS = readonly([limit for limit, _, _ in _BUCKETS])
_HORNER = tuple(readonly(np.array(list(zip(series_b, series_g)))[:, :, None]) for _, series_b, series_g in _BUCKETS)
_SKEW, _NEGATIVE_SKEW = readonly([[1, -1, 1, 1, 1, -1, -1, 1, 1], [1, 1, -1, -1, 1, 1, 1, -1, 1]], float)[:, :, None]
_NEXT, _PREVIOUS, _HALF, _ONE = readonly([1, 2, 0]), readonly([2, 0, 1]), readonly(0.5), readonly(1.0)


def _beta_gamma_many(t2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`beta_gamma` of each entry of ``t2`` (P,): its series bucket and Horner steps on arrays, else itself."""
    which = np.searchsorted(_LIMITS, t2, side="right")  # the first bucket whose limit exceeds t^2
    first, last = int(which.min()), int(which.max())
    bg = np.empty((2, len(t2)))
    for k in range(first, min(last, len(_BUCKETS) - 1) + 1):
        rows = slice(None) if first == last else which == k
        ts = t2[rows]
        acc = np.zeros((2, len(ts)))
        for coefficients in _HORNER[k]:  # b = b t^2 + c_b and g = g t^2 + c_g, from the highest
            acc *= ts
            acc += coefficients
        bg[:, rows] = acc
    for i in np.flatnonzero(which == len(_BUCKETS)).tolist():
        bg[:, i] = beta_gamma(float(t2[i]))
    return bg[0], bg[1]


def _quaternion_log_many(w: np.ndarray, v: np.ndarray) -> np.ndarray:
    """:func:`_quaternion_log` of P quaternions, w (P,) and v (3, P): theta (3, P), exactly 0 where v = 0."""
    squares = v * v
    n = np.sqrt(squares[0] + squares[1] + squares[2])
    angle = np.array([
        2.0 * math.atan2(ni, wi) if wi >= 0.0 else -2.0 * math.atan2(ni, -wi) for ni, wi in zip(n.tolist(), w.tolist())
    ])  # fmt: skip
    still = n == 0.0
    n[still] = 1.0  # those columns are set to exactly 0 below, as the single log returns them
    theta = angle * v / n
    theta[:, still] = 0.0
    return theta


def _relative_many(a: tuple[np.ndarray, ...], b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_relative` of a quaternion ``a`` (columns, :meth:`JointLog._batch_constants`) and the columns of
    ``b`` (4, P; x, y, z, w): w (P,), v (3, P), the single function's pairs entry for entry."""
    a_w, a_v, a_next, a_previous = a
    terms = a_w * b[[3, 0, 1, 2]]
    w = terms[0] + terms[1] + terms[2] + terms[3]
    v = (a_w[0] * b[:3] - a_v * b[3]) + (a_next * b[_NEXT] - a_previous * b[_PREVIOUS])
    return w, v


def _skew_many(v: np.ndarray, diagonal: np.ndarray, signs: np.ndarray = _SKEW) -> np.ndarray:
    """[v]x (``signs`` _NEGATIVE_SKEW: [-v]x) of each column of v (3, P), ``diagonal`` (P,) on the diagonal: (3, 3, P)."""
    x, y, z = v
    out = np.stack([diagonal, z, y, z, diagonal, x, y, x, diagonal])
    out *= signs  # a sign change is exact, zeros included
    return out.reshape(3, 3, -1)


def _se3_log_many(theta: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`se3_log` of P points, theta and p (3, P): e (P, 6) and J_log (P, 6, 6), bitwise.

    Each entry is the single function's expression, associated alike: b theta_i theta_j, u_i theta_j,
    b p_i theta_j as outer products, skew terms added off the diagonal only (a -0.0 on it adds nothing,
    not even to a zero's sign), sums over an index in order.  Points run along the last axis.
    """
    P = theta.shape[1]
    squares = theta * theta
    t2 = squares[0] + squares[1] + squares[2]
    b, g = _beta_gamma_many(t2)
    A = (b * theta)[:, None] * theta  # (b theta_i) theta_j, (3, 3, P)
    A += _skew_many(_HALF * theta, _ONE - b * t2)  # d + b theta_i^2 on the diagonal, -+ theta_k / 2 off it
    e = np.empty((6, P))
    Wp = A * p[:, None]  # a_ij p_i, summed over i in order: W p with W = A^T
    e[:3] = Wp[0] + Wp[1] + Wp[2]
    e[3:] = theta
    products = theta * p
    tp = products[0] + products[1] + products[2]
    u = g * (theta * tp - t2 * p)
    c = theta[_NEXT] * p[_PREVIOUS] - theta[_PREVIOUS] * p[_NEXT]
    D = u[:, None] * theta
    D += _skew_many(_HALF * p, np.full(P, -0.0))  # [p]x / 2 first, off the diagonal: (p / 2) + u theta^T
    D -= (b * p)[:, None] * theta
    D += _skew_many(b * c, b * tp, _NEGATIVE_SKEW)  # b theta.p on the diagonal, -b [theta x p]x off it
    J = np.zeros((6, 6, P))
    J[:3, :3] = A
    J[3:, 3:] = A
    DA = D[:, :, None] * A  # d_ik a_kj, summed over k in order
    J[:3, 3:] = DA[:, 0] + DA[:, 1] + DA[:, 2]
    return np.ascontiguousarray(e.T), np.ascontiguousarray(J.transpose(2, 0, 1))


#: The joint kinds (Pinocchio's short names) whose Lie group JointLog evaluates, and that group.
_KINDS = {"JointModelFreeFlyer": "SE(3)", "JointModelSpherical": "SO(3)", "JointModelPlanar": "SE(2)"}


def joint_log(joint: pin.JointModel, rest: np.ndarray) -> JointLog | None:
    """A :class:`JointLog` for a free-flyer, spherical or planar joint at its rest configuration, else None."""
    kind = _KINDS.get(joint.shortname())
    return None if kind is None else JointLog(kind, rest)


def curved_joints(model: pin.Model, q0: np.ndarray) -> list[tuple[slice, slice, JointLog]]:
    """(q slice, v slice, log at q0's part) of every free-flyer, spherical and planar joint of the model.

    ``pin.difference(model, q0, q)`` and ``pin.dDifference(model, q0, q, ARG1)`` are
    block diagonal over the joints: these blocks, replaced by the logs', are accurate
    at every angle (module docstring).
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


def _left_jacobian(x: float, y: float, z: float) -> tuple[float, ...]:
    """J_l(theta) = I + c1 [theta]x + c2 [theta]x^2 (row-major, 9 floats): the inverse of W = A^T."""
    t2 = x * x + y * y + z * z
    if t2 < 1.0:
        c1 = c2 = 0.0
        for a, b in zip(_C1, _C2):
            c1 = c1 * t2 + a
            c2 = c2 * t2 + b
    else:
        t = math.sqrt(t2)
        c1, c2 = (1.0 - math.cos(t)) / t2, (t - math.sin(t)) / (t2 * t)
    d = 1.0 - c2 * t2  # [theta]x^2 = theta theta^T - t^2 I
    return (
        d + c2 * x * x, c2 * x * y - c1 * z, c2 * x * z + c1 * y,
        c2 * y * x + c1 * z, d + c2 * y * y, c2 * y * z - c1 * x,
        c2 * z * x - c1 * y, c2 * z * y + c1 * x, d + c2 * z * z,
    )  # fmt: skip


def exp_chart_rate(name: str, dq: np.ndarray, v: np.ndarray) -> np.ndarray:
    """d(dq)/dt of the exponential chart q = q_b exp(dq) for the velocity v of one joint (nv_j,).

    (d integrate / d dq)^{-1} v = J_r(dq)^{-1} v = J_log(exp(dq)) v on SE(3), SO(3)
    and SE(2) (``name``); exp(dq) has rotation theta and translation p = J_l(theta) rho
    for dq = (rho, theta), so e = log(exp dq) = dq and :func:`se3_log` gives J_log.
    Pinocchio 4.1's ``dIntegrate`` on SE(3) (``Jexp6``) gives rates up to 3e-5
    relative off between about 1e-4 and 2e-3 rad.
    """
    d = dq.tolist()
    if name == "SO(3)":
        theta, rho = d, [0.0, 0.0, 0.0]
    elif name == "SE(3)":
        theta, rho = d[3:], d[:3]
    else:  # SE(2): (x, y, angle)
        theta, rho = [0.0, 0.0, d[2]], [d[0], d[1], 0.0]
    L = _left_jacobian(*theta)
    p = [L[0] * rho[0] + L[1] * rho[1] + L[2] * rho[2], L[3] * rho[0] + L[4] * rho[1] + L[5] * rho[2],
         L[6] * rho[0] + L[7] * rho[1] + L[8] * rho[2]]  # fmt: skip
    _, J = se3_log(theta, p)
    return _restrict_jacobian(name, J) @ v


def _restrict_jacobian(name: str, J: np.ndarray) -> np.ndarray:
    """SE(3)'s J_log (6 x 6) restricted to a group's tangent coordinates: all, the rotation block, or the planar ones."""
    if name == "SE(3)":
        return J
    return J[3:, 3:].copy() if name == "SO(3)" else J[_PLANAR]
