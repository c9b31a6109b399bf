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

    __slots__ = ("name", "_rest")

    def __init__(self, name: str, rest: np.ndarray):
        self.name = name  # the Lie group, as Pinocchio names it
        if name == "SE(3)":  # (x, y, z, qx, qy, qz, qw): the position and R0^T as floats
            R0 = pin.Quaternion(rest[3:]).toRotationMatrix()
            self._rest = (tuple(rest[:3].tolist()), tuple(rest[3:].tolist()), tuple(R0.T.ravel().tolist()))
        else:  # SO(3): (qx, qy, qz, qw); SE(2): (x, y, cos, sin)
            self._rest = tuple(rest.tolist())

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
        """:meth:`evaluate` at each row of ``qs`` (P, nq_j): e (P, nv_j) and de/dq (P, nv_j, nv_j), bitwise.

        The same operations as the single evaluation, in the same order, on arrays
        of all rows (elementwise IEEE arithmetic and ``np.sqrt`` round as Python's
        floats do); the transcendental parts (atan2, and beta and gamma with their
        series buckets) are taken per row by the single evaluation's own functions.
        Rows are C-contiguous (P, ...) stacks.
        """
        e, J = _se3_log_many(*self._points(np.ascontiguousarray(np.asarray(qs, dtype=float).T)))
        if self.name == "SE(3)":
            return e, J
        index = [3, 4, 5] if self.name == "SO(3)" else [0, 1, 5]
        return np.ascontiguousarray(e[:, index]), np.ascontiguousarray(J[:, index][:, :, index])

    def _points(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`_point` of each column of ``q`` (nq_j, P): theta and p (3, P)."""
        if self.name == "SO(3)":
            return _quaternion_log_many(*_relative_many(self._rest, q)), np.zeros((3, q.shape[1]))
        if self.name == "SE(3)":
            position, quat0, rotation = self._rest
            R0T = np.array(rotation).reshape(3, 3, 1)
            delta = q[:3] - np.array(position).reshape(3, 1)
            p = R0T[:, 0] * delta[0] + R0T[:, 1] * delta[1] + R0T[:, 2] * delta[2]
            return _quaternion_log_many(*_relative_many(quat0, q[3:])), p
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


def _beta_gamma_many(t2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`beta_gamma` of each entry of ``t2`` (P,): the same series bucket and Horner steps, on arrays.

    Entries beyond the series (t >= 2, and NaN) take the single function itself (its closed forms).
    """
    b, g = np.empty(len(t2)), np.empty(len(t2))
    done = np.zeros(len(t2), dtype=bool)
    for limit, series_b, series_g in _BUCKETS:
        rows = ~done & (t2 < limit)  # the first bucket that holds t^2, as the single function picks it
        if rows.any():
            ts = t2[rows]
            bb, gg = np.zeros(len(ts)), np.zeros(len(ts))
            for cb, cg in zip(series_b, series_g):
                bb = bb * ts + cb
                gg = gg * ts + cg
            b[rows], g[rows] = bb, gg
            done |= rows
    for i in np.flatnonzero(~done).tolist():
        b[i], g[i] = beta_gamma(float(t2[i]))
    return b, g


def _quaternion_log_many(w: np.ndarray, v: np.ndarray) -> np.ndarray:
    """:func:`_quaternion_log` of P quaternions, w (P,) and v (3, P): theta (3, P), exactly 0 where v = 0."""
    x, y, z = v
    n = np.sqrt(x * x + y * y + z * z)
    angle = np.array([
        2.0 * math.atan2(ni, wi) if wi >= 0.0 else -2.0 * math.atan2(ni, -wi) for ni, wi in zip(n.tolist(), w.tolist())
    ])  # fmt: skip
    still = n == 0.0
    if still.any():
        n[still] = 1.0  # the columns are set to exactly 0 below, as the single log returns them
    theta = angle * v / n
    if still.any():
        theta[:, still] = 0.0
    return theta


def _relative_many(a, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_relative` of the quaternion ``a`` (x, y, z, w floats) and the columns of ``b`` (4, P): w (P,), v (3, P).

    The single function's pairs, entry for entry: w = aw bw + ax bx + ay by + az bz and
    v = (aw b_v - a_v bw) + (a_k b_l - a_l b_k) with (k, l) = (z, y), (x, z), (y, x).
    """
    ax, ay, az, aw = a
    w = aw * b[3] + ax * b[0] + ay * b[1] + az * b[2]
    v = (aw * b[:3] - np.array([[ax], [ay], [az]]) * b[3]) + (
        np.array([[az], [ax], [ay]]) * b[[1, 2, 0]] - np.array([[ay], [az], [ax]]) * b[[2, 0, 1]]
    )
    return w, v


def _skew_many(v: np.ndarray, diagonal: np.ndarray) -> np.ndarray:
    """[v]x of each column of v (3, P) with ``diagonal`` (P,) on its diagonal: (3, 3, P)."""
    x, y, z = v
    return np.stack([diagonal, -z, y, z, diagonal, -x, -y, x, diagonal]).reshape(3, 3, -1)


def _se3_log_many(theta: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`se3_log` of P points, theta and p (3, P): e (P, 6) and J_log (P, 6, 6), bitwise.

    Every entry is the single function's expression with the same association: the
    products b theta_i theta_j, u_i theta_j, b p_i theta_j as outer products, the skew
    terms added to the off-diagonal entries only (a -0.0 on the diagonal adds nothing,
    not even to a zero's sign), D A as three rank-one sums in order.  The points run
    along the last axis (long inner loops), transposed once at the end.
    """
    x, y, z = theta
    t2 = x * x + y * y + z * z
    b, g = _beta_gamma_many(t2)
    d = 1.0 - b * t2
    A = (b * theta)[:, None] * theta  # (b theta_i) theta_j, (3, 3, P)
    A += _skew_many(0.5 * theta, d)  # d + b theta_i^2 on the diagonal, b theta_i theta_j -+ theta_k / 2 off it
    e = np.empty((6, len(x)))
    e[:3] = A[0] * p[0] + A[1] * p[1] + A[2] * p[2]  # W p, W = A^T
    e[3:] = theta
    px, py, pz = p
    tp = x * px + y * py + z * pz
    u = g * (theta * tp - t2 * p)
    c = np.stack([y * pz - z * py, z * px - x * pz, x * py - y * px])
    D = u[:, None] * theta
    D += _skew_many(0.5 * p, np.full(len(x), -0.0))  # [p]x / 2 first, off the diagonal: (p / 2) + u theta^T
    D -= (b * p)[:, None] * theta
    D += _skew_many(-(b * c), b * tp)  # b theta.p on the diagonal, -b [theta x p]x off it
    J = np.zeros((6, 6, len(x)))
    J[:3, :3] = A
    J[3:, 3:] = A
    J[:3, 3:] = D[:, 0, None] * A[0] + D[:, 1, None] * A[1] + D[:, 2, None] * A[2]
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
