"""Shared test helpers: finite differences taken on the configuration manifold."""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from pinlin.linearization.assembly import assemble


def residual(scene, q, v):
    """r(q, v) = tau(q, v, 0, fext) - Q_e(q, v) on the whole tangent space."""
    return assemble(scene, q, v, stiffness=False).residual


def fd_jacobians(scene, q, v=None, h=1e-6):
    """Central differences of r in q (through pin.integrate) and in v: (K_fd, C_fd), nv x nv."""
    v = np.array(scene.v0 if v is None else v, dtype=float)
    nv = scene.model.nv
    K = np.zeros((nv, nv))
    C = np.zeros((nv, nv))
    for k in range(nv):
        e = np.zeros(nv)
        e[k] = h
        K[:, k] = (residual(scene, pin.integrate(scene.model, q, e), v) - residual(scene, pin.integrate(scene.model, q, -e), v)) / (2 * h)
        C[:, k] = (residual(scene, q, v + e) - residual(scene, q, v - e)) / (2 * h)
    return K, C


def rel_err(a, b):
    return float(np.linalg.norm(np.asarray(a) - np.asarray(b)) / max(np.linalg.norm(b), 1e-300))


#: A hinge carrying a bar, and a second hinge carrying a link without mass or inertia ("ghost_joint"):
#: its mass matrix is singular, and the error should name that joint.
#: One rigid box (2 kg, principal inertias 0.1, 0.2, 0.3 kg m^2): load it with ``free_flyer=True``.
BOX_URDF = (
    '<robot name="box"><link name="box"><inertial><mass value="2"/>'
    '<inertia ixx="0.1" iyy="0.2" izz="0.3" ixy="0" ixz="0" iyz="0"/></inertial></link></robot>'
)

MASSLESS_LINK_URDF = """<robot name="x"><link name="base"/>
      <link name="bar"><inertial><mass value="1"/><origin xyz="0 0 -0.5"/>
        <inertia ixx="0.1" iyy="0.1" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <link name="ghost"/>
      <joint name="hinge" type="revolute"><parent link="base"/><child link="bar"/><axis xyz="0 1 0"/>
        <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
      <joint name="ghost_joint" type="revolute"><parent link="bar"/><child link="ghost"/><axis xyz="0 1 0"/>
        <limit lower="-3" upper="3" effort="1" velocity="1"/></joint></robot>"""


def _mp_se3():
    """mpmath's (exp3, left Jacobian of SO(3), log6 of (R, p)): closed forms, at the caller's precision."""
    import mpmath as mp

    def skew(a):
        return mp.matrix([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])

    def exp3(w):
        t = mp.sqrt(sum(x * x for x in w))
        if t == 0:
            return mp.eye(3)
        W = skew(w)
        return mp.eye(3) + mp.sin(t) / t * W + (1 - mp.cos(t)) / t**2 * W * W

    def left_jacobian(w):
        t = mp.sqrt(sum(x * x for x in w))
        if t == 0:
            return mp.eye(3)
        W = skew(w)
        return mp.eye(3) + (1 - mp.cos(t)) / t**2 * W + (t - mp.sin(t)) / t**3 * W * W

    def log6(Rm, pm):
        t = mp.acos((Rm[0, 0] + Rm[1, 1] + Rm[2, 2] - 1) / 2)
        th = mp.matrix([Rm[2, 1] - Rm[1, 2], Rm[0, 2] - Rm[2, 0], Rm[1, 0] - Rm[0, 1]]) * (t / (2 * mp.sin(t)))
        T = skew(th)
        beta = 1 / t**2 - (1 + mp.cos(t)) / (2 * t * mp.sin(t))
        return list((mp.eye(3) - T / 2 + beta * T * T) * pm) + list(th)

    return exp3, left_jacobian, log6


def mp_log6(R, p):
    """log6(X) (linear part first) at 50 digits, X = (R, p), rounded to doubles (0 < angle < pi)."""
    import mpmath as mp

    with mp.workdps(50):
        _, _, log6 = _mp_se3()
        return np.array([float(x) for x in log6(mp.matrix(R.tolist()), mp.matrix(p.tolist()))])


def mp_log6_jacobian(R, p, _exact=None):
    """d log6(X exp(xi)) / d xi at 50 digits (central differences with h = 1e-20), X = (R, p)."""
    import mpmath as mp

    with mp.workdps(50):
        exp3, left_jacobian, log6 = _mp_se3()
        Rm, pm = (mp.matrix(R.tolist()), mp.matrix(p.tolist())) if _exact is None else _exact
        h = mp.mpf(10) ** -20
        J = np.zeros((6, 6))
        for i in range(6):
            cols = []
            for sign in (1, -1):
                xi = [mp.mpf(0)] * 6
                xi[i] = sign * h
                v, w = mp.matrix(xi[:3]), mp.matrix(xi[3:])
                cols.append(log6(Rm * exp3(w), pm + Rm * left_jacobian(w) * v))
            J[:, i] = [float((a - b) / (2 * h)) for a, b in zip(*cols)]
    return J


def mp_exp6_log_jacobian(xi):
    """J_log(exp6(xi)) at 50 digits, exp6 taken in mpmath too (xi = (rho, theta), linear part first)."""
    import mpmath as mp

    with mp.workdps(50):
        exp3, left_jacobian, _ = _mp_se3()
        rho, theta = mp.matrix([mp.mpf(x) for x in xi[:3]]), [mp.mpf(x) for x in xi[3:]]
        exact = (exp3(theta), left_jacobian(theta) * rho)
        return mp_log6_jacobian(None, None, _exact=exact)
