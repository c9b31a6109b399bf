"""Linearization: analytic (pinlin.linearize) against finite differences, with honest baselines.

For each scene of the table (springs and dampers on every joint, a follower
wrench; the turntable with its prescribed speed), in one process:

- ``linearize``: ``pinlin.linearize(scene, q)`` with every check pinlin makes;
- the **floor**: the cheapest Pinocchio calls the scene needs, replayed bare:
  exactly the algorithms ``sys.calls`` lists (``computeStaticTorqueDerivatives``
  + ``crba`` for a loaded arm, one ``computeRNEADerivatives`` for the turntable),
  so ``linearize / floor`` is the price of pinlin's Python around them;
- **central differences with bare Pinocchio residuals** (:class:`BareResidual`),
  written as a competent user would: ``computeStaticTorque`` (or
  ``computeGeneralizedGravity``, or ``rnea`` with the prescribed velocity) with
  the follower wrenches' constant ``fext``, the springs' and dampers' forces in
  plain numpy (multi-DOF springs through one ``pin.difference``), steps in q
  through ``pin.integrate``, M from ``crba``: 4n residual evaluations;
  forward differences likewise (2n + 1);
- central differences of pinlin's own residual (``assemble`` without derivatives),
  the baseline of the first benchmark suite, for the record: it is 2-4x slower
  than the bare one, which flattered ``linearize``;
- MuJoCo's ``mjd_inverseFD`` on the same URDF (meshes stripped, joints mapped by
  name), when the optional ``mujoco`` package is importable;
- ``linearize`` before and after the per-thread Pinocchio workspaces,
  and a fresh ``Data`` per call against the reused workspace: :mod:`.bench_workspace`.

Times are thread CPU times (``time.thread_time``: the machine is shared, and
another process's load shows in wall time), medians of samples taken in turn
(:func:`common.interleaved_medians`); the load average is reported.

References (never the method under test):

- closed forms for the paper's double pendulum (theory: double pendulum) and the turntable
  (theory: turntable): they bound the error of every method directly;
- for fixed-base arms of 1-DOF joints (ur5, panda), an independent model in
  mpmath at 50 digits (:func:`mp_reference`: forward kinematics from the model's
  numbers, gravity, springs and follower wrenches by virtual work, K by
  50-digit differences, M from link Jacobians; no Pinocchio algorithm);
- for the floating bases (solo12, talos_reduced), Richardson extrapolation
  (Ridders' tableau, steps 0.1 / 1.4^i) of central differences of the bare
  residual: its own error estimate is reported.  The gap between the analytic
  result and this reference bounds the analytic error from above; the difference
  methods' errors, 1e3 times larger and more, are measured by it reliably.

Error of a method: the largest relative Frobenius error of M, C and K; for a C
whose reference is zero the denominator is sqrt(||M|| ||K||), the critical
damping scale (consistent units).
"""

from __future__ import annotations

import os
import re
import time

import numpy as np
import pinocchio as pin

import pinlin
from pinlin.model.loading import example_urdf_path

from .bench_workspace import workspace_section
from .common import (
    Report,
    Table,
    interleaved_medians,
    load_average,
    median_time,
    result_path,
    save_figure,
    work_precision_plot,
    write_report,
)

#: Steps [rad, m, rad/s] of the finite-difference sweep.
H_SWEEP = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9)
QUICK_H_SWEEP = (1e-3, 1e-5, 1e-7, 1e-9)
#: Steps used for timing (the cost does not depend on the step).
TIMED_H = {"forward": 1e-7, "central": 1e-5}
#: MuJoCo finite-difference steps compared.
MUJOCO_EPS = (1e-4, 1e-6, 1e-8)
#: Issue 14's targets: linearize within this factor of the floor, and faster than bare central differences.
FLOOR_TARGET = 3.0
#: Points per linearize_many call timed (its cost is reported per point): a small batch and the
#: issue's 100-point batch, where the fixed costs of the stacked work are spread thin.
BATCH = 10
LARGE_BATCH = 100


# ----------------------------------------------------------------------------- differences


def _residual(scene: pinlin.Scene, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    from pinlin.linearization.assembly import assemble  # internal: imported where used (see _pinlin_crba)

    return assemble(scene, q, v, stiffness=False).residual


def _pinlin_crba(scene: pinlin.Scene, q: np.ndarray) -> np.ndarray:
    """``crba`` on the scene's own Pinocchio workspace.

    pinlin's internal modules are imported in the functions that use them, so that the
    scene builders of this module import with any revision of pinlin (bench_compare).
    """
    from pinlin.model.evaluation import workspace

    return pin.crba(scene.model, workspace(scene).data, q)


def fd_linearization(scene: pinlin.Scene, q: np.ndarray, h: float, scheme: str = "central"):
    """(M, C, K) on the free coordinates: M by crba, C and K by differences of r(q, v).

    ``scheme`` "central": (r(x + h e_k) - r(x - h e_k)) / 2h; "forward":
    (r(x + h e_k) - r(x)) / h; steps in q through ``pin.integrate``.
    """
    model = scene.model
    f = scene.free_dofs
    v0 = np.asarray(scene.v0)
    nv = model.nv
    K = np.zeros((nv, nv))
    C = np.zeros((nv, nv))
    r0 = _residual(scene, q, v0) if scheme == "forward" else None
    for k in f:
        e = np.zeros(nv)
        e[k] = h
        rp = _residual(scene, pin.integrate(model, q, e), v0)
        vp = _residual(scene, q, v0 + e)
        if scheme == "central":
            K[:, k] = (rp - _residual(scene, pin.integrate(model, q, -e), v0)) / (2 * h)
            C[:, k] = (vp - _residual(scene, q, v0 - e)) / (2 * h)
        else:
            K[:, k] = (rp - r0) / h
            C[:, k] = (vp - r0) / h
    M = _pinlin_crba(scene, q)
    M = np.triu(M) + np.triu(M, 1).T
    ix = np.ix_(f, f)
    return M[ix], C[ix], K[ix]


class BareResidual:
    """r(q, v) = tau(q, v, 0, fext) - Q_e(q, v) with bare Pinocchio and plain numpy, as a competent user writes it.

    Supports what the benchmark's scenes contain: joint springs, joint dampers,
    follower wrenches (a constant ``fext``), gravity and prescribed velocities.
    Everything that does not depend on (q, v) is prepared once (the
    leanest honest baseline, no per-call index arrays): the springs as one
    full-length stiffness vector on q - q_rest when every joint has nq = nv
    (one multiply-add), otherwise one ``pin.difference`` from the rest
    configuration and one product with the assembled stiffness matrix; the
    dampers as one matrix (or vector) on v, applied only where v varies; the
    cheapest Pinocchio call for the point (``computeGeneralizedGravity`` or
    ``computeStaticTorque`` at the rest velocity v = 0, ``rnea`` otherwise).
    Other elements raise ``ValueError`` (then no bare baseline exists).
    """

    def __init__(self, scene: pinlin.Scene):
        model = self.model = scene.model
        self.data = model.createData()
        self.fext = scene.constant_fext
        self.v0 = np.array(scene.v0)
        self.moving = bool(np.any(self.v0))
        nv = model.nv
        self.zero = np.zeros(nv)
        rest = pin.neutral(model)
        Ks = np.zeros((nv, nv))
        Cd = np.zeros((nv, nv))
        for e in scene.elements:
            if isinstance(e, pinlin.JointSpring):
                j = scene.robot.joint(e.joint)
                if j.nq == 1:
                    Ks[j.idx_v, j.idx_v] += float(np.ravel(e.stiffness)[0])
                    rest[j.idx_q] = 0.0 if e.rest is None else float(np.ravel(e.rest)[0])
                else:
                    rest[j.q_slice] = e.rest_configuration(scene.robot)
                    Ks[j.v_slice, j.v_slice] += e.matrix(j)
            elif isinstance(e, pinlin.JointDamper):
                j = scene.robot.joint(e.joint)
                Cd[j.v_slice, j.v_slice] += np.diag(np.broadcast_to(e.damping, (j.nv,))) if np.ndim(e.damping) < 2 else e.damping
            elif not isinstance(e, pinlin.FollowerWrench):
                raise ValueError(f"no bare residual for {type(e).__name__}")
        self.rest = rest
        # nq = nv and diagonal springs: r += k * (q - q_rest), one ufunc pair; else difference and a product
        self.vector_springs = model.nq == nv and not np.count_nonzero(Ks - np.diag(np.diag(Ks)))
        self.k = np.diag(Ks).copy() if self.vector_springs else None
        self.Ks = Ks
        diag_d = not np.count_nonzero(Cd - np.diag(np.diag(Cd)))
        self.d = np.diag(Cd).copy() if diag_d else None
        self.Cd = Cd
        self.damped = bool(np.count_nonzero(Cd))

    def tau(self, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        model, data, fext = self.model, self.data, self.fext
        if self.moving or v is not self.v0:
            if fext is None:
                return pin.rnea(model, data, q, v, self.zero)
            return pin.rnea(model, data, q, v, self.zero, fext)
        if fext is not None:
            return pin.computeStaticTorque(model, data, q, fext)
        return pin.computeGeneralizedGravity(model, data, q)

    def __call__(self, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        r = self.tau(q, v)
        if self.vector_springs:
            r += self.k * (q - self.rest)
        else:
            r += self.Ks @ pin.difference(self.model, self.rest, q)
        if self.damped and (self.moving or v is not self.v0):  # dampers act on a velocity
            r += self.d * v if self.d is not None else self.Cd @ v
        return r


def bare_differences(scene: pinlin.Scene, q: np.ndarray, h: float, scheme: str = "central"):
    """(M, C, K) on the free coordinates by differences of :class:`BareResidual`, M by ``crba``.

    The loop a user writes: per free coordinate two ``pin.integrate`` steps of q
    and two of v (four residuals, central) or one each (forward); the columns
    written into preallocated arrays; the free rows and columns taken once at
    the end (plain slices when the free coordinates are contiguous, as in every
    scene of this benchmark).  Returns a function computing them (the
    residual's setup is not timed).
    """
    r = BareResidual(scene)
    model, free, v0 = scene.model, list(scene.free_dofs), r.v0
    nv = model.nv
    contiguous = free == list(range(free[0], free[0] + len(free))) if free else True
    rows = slice(free[0], free[-1] + 1) if free and contiguous else np.asarray(free, dtype=int)
    crba = pin.crba
    integrate = pin.integrate
    steps = []
    for k in free:
        e = np.zeros(nv)
        e[k] = h
        steps.append((e, -e, v0 + e, v0 - e))
    inv = 1.0 / (2 * h) if scheme == "central" else 1.0 / h

    def run():
        K = np.empty((nv, len(free)))
        C = np.empty((nv, len(free)))
        if scheme == "central":
            for col, (ep, em, vp, vm) in enumerate(steps):
                K[:, col] = r(integrate(model, q, ep), v0) - r(integrate(model, q, em), v0)
                C[:, col] = r(q, vp) - r(q, vm)
        else:
            r0 = r(q, v0)
            for col, (ep, _, vp, _) in enumerate(steps):
                K[:, col] = r(integrate(model, q, ep), v0) - r0
                C[:, col] = r(q, vp) - r0
        K *= inv
        C *= inv
        M = crba(model, r.data, q)
        if contiguous:
            return M[rows, rows], C[rows], K[rows]
        return M[np.ix_(free, free)], C[free], K[free]

    return run


def pinocchio_floor(scene: pinlin.Scene, q: np.ndarray, calls) -> callable:
    """The Pinocchio algorithms of ``calls`` (a linearization's ``sys.calls``), replayed bare on a Data of its own."""
    model = scene.model
    data = model.createData()
    v0, zero, fext = np.array(scene.v0), np.zeros(model.nv), scene.constant_fext
    extra = () if fext is None else (fext,)
    plan = {
        "crba": (pin.crba, (model, data, q)),
        "computeStaticTorqueDerivatives": (pin.computeStaticTorqueDerivatives, (model, data, q, fext)),
        "computeStaticTorque": (pin.computeStaticTorque, (model, data, q, fext)),
        "computeGeneralizedGravityDerivatives": (pin.computeGeneralizedGravityDerivatives, (model, data, q)),
        "computeGeneralizedGravity": (pin.computeGeneralizedGravity, (model, data, q)),
        "computeRNEADerivatives": (pin.computeRNEADerivatives, (model, data, q, v0, zero, *extra)),
        "rnea": (pin.rnea, (model, data, q, v0, zero, *extra)),
        "computeJointJacobians": (pin.computeJointJacobians, (model, data, q)),
        "updateFramePlacements": (pin.updateFramePlacements, (model, data)),
    }
    steps = [plan[name] for name in calls]

    def run():
        for algorithm, args in steps:
            algorithm(*args)

    return run


def bare_richardson(scene: pinlin.Scene, q: np.ndarray):
    """(M, C, K, error estimates): C and K by Ridders extrapolation of the bare residual, M by crba."""
    r = BareResidual(scene)
    model, free, v0 = scene.model, scene.free_dofs, r.v0
    nv = model.nv
    K = np.zeros((nv, len(free)))
    C = np.zeros((nv, len(free)))
    eK = eC = 0.0
    for col, k in enumerate(free):
        e = np.zeros(nv)
        e[k] = 1.0
        K[:, col], err = ridders(lambda h, e=e: (r(pin.integrate(model, q, h * e), v0) - r(pin.integrate(model, q, -h * e), v0)) / (2 * h))
        eK = np.hypot(eK, err)
        C[:, col], err = ridders(lambda h, e=e: (r(q, v0 + h * e) - r(q, v0 - h * e)) / (2 * h))
        eC = np.hypot(eC, err)
    M = pin.crba(model, r.data, q)
    return M[np.ix_(free, free)], C[free], K[free], (eC, eK)


def ridders(fn, h0: float = 0.1, con: float = 1.4, ntab: int = 10) -> tuple[np.ndarray, float]:
    """Richardson extrapolation of central differences of a vector function (Ridders' tableau).

    ``fn(h)`` returns the central difference quotient at step h.  Returns the
    extrapolated derivative and its error estimate (2-norm), the smallest over
    the tableau; stops when the estimate has grown twice past its minimum.
    """
    con2 = con * con
    a = [[fn(h0)]]
    best, err = a[0][0], np.inf
    h = h0
    for i in range(1, ntab):
        h /= con
        row = [fn(h)]
        fac = con2
        for j in range(1, i + 1):
            row.append((row[j - 1] * fac - a[i - 1][j - 1]) / (fac - 1.0))
            fac *= con2
            e = max(np.linalg.norm(row[j] - row[j - 1]), np.linalg.norm(row[j] - a[i - 1][j - 1]))
            if e <= err:
                err, best = e, row[j]
        a.append(row)
        if np.linalg.norm(row[i] - a[i - 1][i - 1]) >= 2.0 * err:
            break
    return best, float(err)


def richardson_reference(scene: pinlin.Scene, q: np.ndarray):
    """(M, C, K, error estimates) with C and K by Ridders extrapolation, M by crba."""
    model = scene.model
    f = scene.free_dofs
    v0 = np.asarray(scene.v0)
    nv = model.nv
    K = np.zeros((nv, nv))
    C = np.zeros((nv, nv))
    eK = eC = 0.0
    for k in f:
        e = np.zeros(nv)
        e[k] = 1.0

        def dq(h, e=e):
            return (_residual(scene, pin.integrate(model, q, h * e), v0) - _residual(scene, pin.integrate(model, q, -h * e), v0)) / (2 * h)

        def dv(h, e=e):
            return (_residual(scene, q, v0 + h * e) - _residual(scene, q, v0 - h * e)) / (2 * h)

        K[:, k], err = ridders(dq)
        eK = np.hypot(eK, err)
        C[:, k], err = ridders(dv)
        eC = np.hypot(eC, err)
    M = _pinlin_crba(scene, q)
    M = np.triu(M) + np.triu(M, 1).T
    ix = np.ix_(f, f)
    return M[ix], C[ix], K[ix], (eC, eK)


def matrix_error(M, C, K, ref) -> float:
    """max of the relative Frobenius errors of M, C, K (C against sqrt(||M|| ||K||) when its reference is 0)."""
    Mr, Cr, Kr = ref
    nM, nK = np.linalg.norm(Mr), np.linalg.norm(Kr)
    nC = max(np.linalg.norm(Cr), np.sqrt(nM * nK))
    return float(max(np.linalg.norm(M - Mr) / nM, np.linalg.norm(C - Cr) / nC, np.linalg.norm(K - Kr) / nK))


# ----------------------------------------------------------------------------- mpmath reference


def _mp_axis(jm) -> tuple[str, np.ndarray]:
    """("R" or "P", unit axis in the joint frame) of a 1-DOF Pinocchio joint, else ValueError."""
    name = jm.shortname()
    for kind, prefix in (("R", "JointModelR"), ("P", "JointModelP")):
        if name in (prefix + "X", prefix + "Y", prefix + "Z"):
            return kind, np.eye(3)["XYZ".index(name[-1])]
    if name == "JointModelRevoluteUnaligned":
        return "R", np.asarray(jm.extract().axis, dtype=float)
    if name == "JointModelPrismaticUnaligned":
        return "P", np.asarray(jm.extract().axis, dtype=float)
    raise ValueError(f"joint type {name} not supported by the mpmath reference")


def mp_reference(scene: pinlin.Scene, q: np.ndarray, dps: int = 50):
    """(M, C, K) of a fixed-base scene of 1-DOF joints from an independent forward-kinematics model in mpmath.

    Uses only the model's numbers (joint placements and axes, link inertias, frame
    placements) and the scene's springs, dampers and follower wrenches; no
    Pinocchio algorithm.  In ``dps``-digit arithmetic:

    - residual r(q) = g(q) - J_F(q)^T w_F(q) + k (q - q_rest), with the gravity
      torque g_j = -sum_i m_i g . (omega_j x (c_i - p_j)) over the links i moved by
      joint j (omega_j its world axis, p_j its origin; a prismatic joint moves c_i
      along omega_j) and the follower wrench w_F rotated into world axes;
    - K = dr/dq by central differences at h = 10^-(dps/2.5) (error ~ 10^-(dps/2.5 * 2));
    - M = sum_i m_i J_ci^T J_ci + J_wi^T I_i J_wi (world inertia about the centre of mass);
    - C = the joint dampers (at v = 0 Coriolis terms vanish).
    """
    import mpmath as mp

    model = scene.model
    n = model.nv
    if model.nq != n:
        raise ValueError("the mpmath reference handles 1-DOF joints only")
    joints = []
    for i in range(1, model.njoints):
        jm = model.joints[i]
        kind, axis = _mp_axis(jm)
        joints.append((i, jm.idx_q, kind, axis))
    springs, dampers, follows = {}, {}, []
    for e in scene.elements:
        if isinstance(e, pinlin.JointSpring):
            springs[scene.robot.joint(e.joint).idx_v] = (float(np.ravel(e.stiffness)[0]), 0.0 if e.rest is None else float(np.ravel(e.rest)[0]))
        elif isinstance(e, pinlin.JointDamper):
            dampers[scene.robot.joint(e.joint).idx_v] = float(np.ravel(e.damping)[0])
        elif isinstance(e, pinlin.FollowerWrench):
            follows.append(e)
        else:
            raise ValueError(f"element {e!r} not supported by the mpmath reference")
    with mp.workdps(dps):
        def mat(a):
            return mp.matrix(np.asarray(a, dtype=float).tolist())

        placements = [(mat(model.jointPlacements[i].rotation), mat(model.jointPlacements[i].translation)) for i in range(model.njoints)]
        g = mat(model.gravity.linear)

        def rot(axis, t):
            x, y, z = (mp.mpf(float(c)) for c in axis)
            c, s_ = mp.cos(t), mp.sin(t)
            C1 = 1 - c
            return mp.matrix([[c + x * x * C1, x * y * C1 - z * s_, x * z * C1 + y * s_],
                              [y * x * C1 + z * s_, c + y * y * C1, y * z * C1 - x * s_],
                              [z * x * C1 - y * s_, z * y * C1 + x * s_, c + z * z * C1]])

        def kinematics(qq):
            R = {0: mp.eye(3)}
            p = {0: mp.matrix(3, 1)}
            world = {}
            for i, iq, kind, axis in joints:
                par = model.parents[i]
                Rp, tp = placements[i]
                Rj = R[par] * Rp
                pj = p[par] + R[par] * tp
                w = Rj * mat(axis)
                world[i] = (w, pj, kind)
                if kind == "R":
                    R[i] = Rj * rot(axis, qq[iq])
                    p[i] = pj
                else:
                    R[i] = Rj
                    p[i] = pj + w * qq[iq]
            return R, p, world

        def ancestors(i):
            out = []
            while i > 0:
                out.append(i)
                i = model.parents[i]
            return out

        def cross(a, b):
            return mp.matrix([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])

        def dot(a, b):
            return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]

        def jac_point(world, i, point):
            """Linear velocity of a point on body i per joint velocity (n columns)."""
            cols = [mp.matrix(3, 1) for _ in range(n)]
            for j in ancestors(i):
                w, pj, kind = world[j]
                cols[model.joints[j].idx_v] = cross(w, point - pj) if kind == "R" else w
            return cols

        def residual(qq):
            R, p, world = kinematics(qq)
            r = [mp.mpf(0)] * n
            for i in range(1, model.njoints):
                m_i = mp.mpf(model.inertias[i].mass)
                if m_i == 0:
                    continue
                c = p[i] + R[i] * mat(model.inertias[i].lever)
                for k, col in enumerate(jac_point(world, i, c)):
                    r[k] -= m_i * dot(g, col)
            for f in follows:
                fr = model.frames[scene.robot.frame_id(f.frame)]
                i = fr.parentJoint
                Rf = R[i] * mat(fr.placement.rotation)
                pf = p[i] + R[i] * mat(fr.placement.translation)
                F, T = Rf * mat(f.force), Rf * mat(f.torque)
                for k, col in enumerate(jac_point(world, i, pf)):
                    r[k] -= dot(F, col)
                for j in ancestors(i):
                    w, _, kind = world[j]
                    if kind == "R":
                        r[model.joints[j].idx_v] -= dot(T, w)
            for k, (stiff, rest) in springs.items():
                r[k] += stiff * (qq[k] - rest)
            return r

        q_mp = [mp.mpf(float(x)) for x in q]
        h = mp.mpf(10) ** (-int(dps / 2.5))
        K = np.zeros((n, n))
        for k in range(n):
            qp, qm = list(q_mp), list(q_mp)
            qp[k] += h
            qm[k] -= h
            rp, rm = residual(qp), residual(qm)
            K[:, k] = [float((a - b) / (2 * h)) for a, b in zip(rp, rm)]
        R, p, world = kinematics(q_mp)
        M = mp.zeros(n, n)
        for i in range(1, model.njoints):
            m_i = mp.mpf(model.inertias[i].mass)
            c = p[i] + R[i] * mat(model.inertias[i].lever)
            Jv = jac_point(world, i, c)
            Iw = R[i] * mat(model.inertias[i].inertia) * R[i].T
            Jw = [mp.matrix(3, 1) for _ in range(n)]
            for j in ancestors(i):
                w, _, kind = world[j]
                if kind == "R":
                    Jw[model.joints[j].idx_v] = w
            for a in range(n):
                for b in range(n):
                    M[a, b] += m_i * dot(Jv[a], Jv[b]) + dot(Jw[a], Iw * Jw[b])
        M = np.array([[float(M[a, b]) for b in range(n)] for a in range(n)])
    C = np.zeros((n, n))
    for k, c in dampers.items():
        C[k, k] = c
    return M, C, K


# ----------------------------------------------------------------------------- cases


class Case:
    def __init__(self, label, scene, q, exact=None, balancing=False, urdf=None, free_flyer=False):
        self.label, self.scene, self.q, self.exact = label, scene, q, exact
        self.balancing, self.urdf, self.free_flyer = balancing, urdf, free_flyer


def double_pendulum_case(theta=(0.4, 0.5), k=(3.0, 2.0), c=(0.2, 0.1), P=4.0) -> Case:
    """The paper's double pendulum (theory: double pendulum) posed at relative angles ``theta``, with its closed form.

    The spring rests are chosen so that ``theta`` is an equilibrium.  Absolute
    angles phi = T theta; in phi, with gravity potential V = -(m1/2 + m2) g l1
    cos phi1 - m2 g l2/2 cos phi2 and the follower's Q1 = -P l1 sin(phi2 - phi1):

        M_phi = [[(m1/3 + m2) l1^2, m2 l1 l2/2 cos(phi2 - phi1)], [., m2 l2^2/3]]
        K_phi = Hess V - dQ/dphi = diag((m1/2 + m2) g l1 cos phi1, m2 g l2/2 cos phi2)
                + P l1 cos(phi2 - phi1) [[-1, 1], [0, 0]]

    and M = T^T M_phi T, K = T^T K_phi T + diag(k), C = diag(c).  At theta = 0
    this is theory: double pendulum's printed matrices; away from 0 gravity loads the joints,
    so difference quotients suffer rounding as on a real robot.
    """
    m1, l1, m2, l2, g = 1.3, 0.7, 0.9, 0.5, 9.81
    T = np.array([[1.0, 0.0], [1.0, 1.0]])
    th = np.asarray(theta, dtype=float)
    p1, p2 = T @ th
    cr = np.cos(p2 - p1)
    Q_phi = np.array([-(m1 / 2 + m2) * g * l1 * np.sin(p1) - P * l1 * np.sin(p2 - p1), -m2 * g * l2 / 2 * np.sin(p2)])
    rest = th - (T.T @ Q_phi) / np.asarray(k)  # springs balance gravity and the follower at theta
    text = pinlin.double_pendulum_urdf(m1, l1, m2, l2)
    robot = pinlin.load_urdf_string(text)
    elements = [pinlin.JointSpring(f"joint{i + 1}", k[i], rest=float(rest[i])) for i in range(2)]
    elements += [pinlin.JointDamper(f"joint{i + 1}", c[i]) for i in range(2)]
    elements.append(pinlin.FollowerWrench("tip", force=(0, 0, P)))
    scene = pinlin.Scene(robot, elements, gravity=(0, 0, -g))
    M = np.array([[(m1 / 3 + m2) * l1**2, m2 * l1 * l2 / 2 * cr], [m2 * l1 * l2 / 2 * cr, m2 * l2**2 / 3]])
    K = np.diag([(m1 / 2 + m2) * g * l1 * np.cos(p1), m2 * g * l2 / 2 * np.cos(p2)])
    K = K + P * l1 * cr * np.array([[-1.0, 1.0], [0.0, 0.0]])
    exact = (T.T @ M @ T, np.diag(c), T.T @ K @ T + np.diag(k))
    return Case(f"double pendulum at theta = {tuple(theta)} (theory: double pendulum closed form)", scene, th, exact, urdf=text)


def turntable_case() -> Case:
    a, m, k, l0, W = 0.5, 1.0, 10.0, 0.3, 2.0
    robot = pinlin.load_urdf_string(pinlin.turntable_urdf(a, m))
    scene = pinlin.Scene(robot, [pinlin.JointSpring("slider", k, rest=l0)], prescribed={"table": W})
    r0 = (k * l0 + m * W**2 * a) / (k - m * W**2)
    q = scene.neutral()
    q[3] = r0
    exact = (
        np.diag([m * r0**2, m]),
        2 * m * W * r0 * np.array([[0.0, 1.0], [-1.0, 0.0]]),
        np.diag([m * W**2 * a * r0, k - m * W**2]),
    )
    return Case("turntable, Omega = 2 rad/s (theory: turntable)", scene, q, exact)


def _arm_case(name: str, q_ref, tool: str, k: float = 100.0) -> Case:
    robot = pinlin.load_example(name)
    elements = []
    for j, qj in zip(robot.joint_names, q_ref):
        elements += [pinlin.JointSpring(j, k, rest=float(qj)), pinlin.JointDamper(j, 0.5)]
    elements.append(pinlin.FollowerWrench(tool, force=(0.0, 0.0, 5.0)))
    scene = pinlin.Scene(robot, elements)
    q = pinlin.find_equilibrium(scene, np.asarray(q_ref, dtype=float)).q
    text = example_urdf_path(name).read_text(encoding="utf-8")
    return Case(f"{name}: springs, dampers, follower at {tool}", scene, q, urdf=text)


def ur5_case() -> Case:
    return _arm_case("ur5", [0.3, -1.2, 1.4, -0.8, 1.1, 0.4], "tool0")


def panda_case() -> Case:
    q_ref = pinlin.load_example("panda").reference_configurations["default"]
    return _arm_case("panda", q_ref, "panda_hand")


def _floating_case(name: str, tool: str, k: float = 100.0, c: float = 0.5) -> Case:
    """A floating base on a 6-DOF spring mount: springs and dampers on every joint, root included, a follower wrench."""
    robot = pinlin.load_example(name, free_flyer=True)
    q_ref = next(iter(robot.reference_configurations.values()))
    elements = []
    for j in robot.joint_names:
        info = robot.joint(j)
        rest = q_ref[info.q_slice] if info.nq > 1 else float(q_ref[info.idx_q])
        elements += [pinlin.JointSpring(j, k, rest=rest), pinlin.JointDamper(j, c)]
    elements.append(pinlin.FollowerWrench(tool, force=(0.0, 0.0, 5.0)))
    scene = pinlin.Scene(robot, elements)
    q = pinlin.find_equilibrium(scene, q_ref).q
    return Case(f"{name}: floating base on a spring mount, springs, dampers, follower at {tool}", scene, q)


def solo_case() -> Case:
    return _floating_case("solo12", "FL_FOOT")


def talos_case() -> Case:
    return _floating_case("talos_reduced", "gripper_left_joint")


# ----------------------------------------------------------------------------- MuJoCo peer


def _strip_meshes(urdf: str) -> str:
    urdf = re.sub(r"<visual\b.*?</visual>", "", urdf, flags=re.S)
    urdf = re.sub(r"<collision\b.*?</collision>", "", urdf, flags=re.S)
    return urdf.replace("</robot>", '<mujoco><compiler discardvisual="true" fusestatic="false"/></mujoco></robot>')


def _mujoco_case(mujoco, m, label: str, urdf: str, q: np.ndarray, quick: bool):
    """Rows of one robot (one per MuJoCo eps), or a note saying why it was not compared."""
    out = []
    robot = pinlin.load_urdf_string(urdf)
    model = pin.Model(robot.model)
    model.gravity = pin.Motion(np.array([0.0, 0.0, -9.81]), np.zeros(3))
    data = model.createData()
    names = robot.joint_names
    try:
        jid = [mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, n) for n in names]
    except Exception:  # noqa: BLE001
        jid = [-1]
    if min(jid) < 0 or m.nv != model.nv:
        return f"{label}: joints do not map one to one (MuJoCo nv = {m.nv}, Pinocchio nv = {model.nv})"
    qadr = np.array([m.jnt_qposadr[j] for j in jid])
    vadr = np.array([m.jnt_dofadr[j] for j in jid])
    d = mujoco.MjData(m)
    d.qpos[qadr] = q
    d.qvel[:] = 0.0
    mujoco.mj_forward(m, d)
    d.qacc[:] = 0.0  # mj_forward wrote the forward acceleration; linearize at a = 0
    nv = m.nv
    DfDq, DfDv, DfDa = np.zeros((nv, nv)), np.zeros((nv, nv)), np.zeros((nv, nv))

    def mj_derivs(eps):
        mujoco.mjd_inverseFD(m, d, eps, False, DfDq, DfDv, DfDa, None, None, None, None)
        ix = np.ix_(vadr, vadr)
        return DfDa.T[ix].copy(), DfDq.T[ix].copy()  # MuJoCo stores the transposes

    # reference of the rigid-body part (gravity only): Ridders on Pinocchio's gravity torque
    def g(qq):
        return pin.computeGeneralizedGravity(model, data, qq).copy()

    Kref = np.zeros((nv, nv))
    for k in range(nv):
        e = np.zeros(nv)
        e[k] = 1.0
        Kref[:, k], _ = ridders(lambda h, e=e: (g(pin.integrate(model, q, h * e)) - g(pin.integrate(model, q, -h * e))) / (2 * h))
    Mref = pin.crba(model, data, q)
    Mref = np.triu(Mref) + np.triu(Mref, 1).T

    def analytic():
        pin.crba(model, data, q)
        return pin.computeGeneralizedGravityDerivatives(model, data, q)

    Kan = np.array(analytic())
    t_an = median_time(analytic, repeats=5 if quick else 9)
    err_an = float(np.linalg.norm(Kan - Kref) / np.linalg.norm(Kref))
    for eps in MUJOCO_EPS:
        Mm, Km = mj_derivs(eps)
        t_mj = median_time(lambda eps=eps: mj_derivs(eps), repeats=5 if quick else 9)
        out.append(
            [label, nv, eps, t_mj * 1e6, t_an * 1e6, t_mj / t_an,
             float(np.linalg.norm(Km - Kref) / np.linalg.norm(Kref)), err_an,
             float(np.linalg.norm(Mm - Mref) / np.linalg.norm(Mref))]
        )
    return out


def mujoco_rows(cases, quick: bool):
    """Rows comparing MuJoCo's mjd_inverseFD with Pinocchio's analytic rigid-body derivatives, or a reason.

    ``cases``: (label, URDF text, q) of fixed-base robots; Pinocchio loads the same text.
    """
    try:
        import mujoco
    except ImportError:
        return None, "mujoco is not importable here: the MuJoCo peer (mjd_inverseFD) was skipped (pip install mujoco to add it)"
    rows = []
    notes = []
    for label, urdf, q in cases:
        try:
            m = mujoco.MjModel.from_xml_string(_strip_meshes(urdf))
        except Exception as exc:  # noqa: BLE001 - MuJoCo raises ValueError subclasses of its own
            notes.append(f"{label}: MuJoCo could not compile the URDF ({str(exc).splitlines()[0][:120]})")
            continue
        # inverse dynamics of the free tree: no equality (mimic joints) or contact forces
        m.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONSTRAINT)
        row_or_note = _mujoco_case(mujoco, m, label, urdf, q, quick)
        if isinstance(row_or_note, str):
            notes.append(row_or_note)
        else:
            rows += row_or_note
    note = (
        f"mujoco {mujoco.__version__}: rigid-body part only (MuJoCo knows neither pinlin's springs nor its "
        "follower loads): dtau/dq of gravity and M = dtau/da at the same q, v = 0, a = 0. "
        "mjd_inverseFD computes dtau/dq, dtau/dv and dtau/da by forward differences in C; Pinocchio's analytic "
        "counterpart is crba + computeGeneralizedGravityDerivatives. Reference for dtau/dq: Ridders extrapolation "
        "of Pinocchio's computeGeneralizedGravity; for M: crba. Constraints (the panda's mimic finger joint) are "
        "disabled in MuJoCo. Floating bases are not compared (MuJoCo's free joint has other velocity "
        "coordinates). The slender bars of theory: double pendulum have no inertia about their axis, which MuJoCo refuses: "
        "its double pendulum has 1 cm bars."
    )
    if notes:
        note += " " + " ".join(notes)
    return rows, note


# ----------------------------------------------------------------------------- run


def _reference(case: Case):
    """(reference (M, C, K), its name, its own error estimate, Richardson's error where a better reference exists)."""
    scene, q = case.scene, case.q
    try:
        mp_ref = mp_reference(scene, q)
    except ValueError:  # floating base: not modelled by the mpmath kinematics
        mp_ref = None
    if case.exact is None and mp_ref is None:
        Mr, Cr, Kr, (eC, eK) = bare_richardson(scene, q)
        est = max(eK / np.linalg.norm(Kr), eC / max(np.linalg.norm(Cr), np.sqrt(np.linalg.norm(Mr) * np.linalg.norm(Kr))))
        return (Mr, Cr, Kr), "Richardson", est, float("nan")
    ref, name = (case.exact, "closed form") if case.exact is not None else (mp_ref, "mpmath 50 digits")
    rich = bare_richardson(scene, q)[:3] if len(scene.free_dofs) <= 9 else None
    return ref, name, 0.0, (matrix_error(*rich, ref) if rich is not None else float("nan"))


def _case_row(case: Case, sweep, repeats: int) -> dict:
    """Times, errors and ratios of one scene."""
    scene, q, bal = case.scene, case.q, case.balancing
    sys = pinlin.linearize(scene, q, balancing=bal)
    ref, ref_name, ref_err, rich_err = _reference(case)
    err_lin = matrix_error(sys.M, sys.C, sys.K, ref)
    qs, qs_large = np.tile(q, (BATCH, 1)), np.tile(q, (LARGE_BATCH, 1))
    fns = {
        "linearize": lambda: pinlin.linearize(scene, q, balancing=bal),
        "linearize_many": lambda: pinlin.linearize_many(scene, qs, balancing=bal),
        "linearize_many (large)": lambda: pinlin.linearize_many(scene, qs_large, balancing=bal),
        "floor": pinocchio_floor(scene, q, sys.calls),
        "central": bare_differences(scene, q, TIMED_H["central"], "central"),
        "forward": bare_differences(scene, q, TIMED_H["forward"], "forward"),
        "central (pinlin residual)": lambda: fd_linearization(scene, q, TIMED_H["central"], "central"),
    }
    times = dict(zip(fns, interleaved_medians(list(fns.values()), repeats=repeats, min_time=0.01, clock=time.thread_time)))
    times["linearize_many"] /= BATCH  # per point
    times["linearize_many (large)"] /= LARGE_BATCH
    errs = {scheme: [matrix_error(*bare_differences(scene, q, h, scheme)(), ref) for h in sweep] for scheme in ("forward", "central")}
    best = {scheme: (min(v), sweep[int(np.argmin(v))]) for scheme, v in errs.items()}
    return {
        "sys": sys, "times": times, "errs": errs, "best": best, "err_lin": err_lin, "ref": ref_name,
        "ref_err": ref_err, "rich_err": rich_err,
        "acc_ratio": best["central"][0] / max(err_lin, np.finfo(float).eps / 2),
    }  # fmt: skip


def _tables(rows: dict, sweep) -> tuple[list[Table], dict]:
    timing, accuracy, sweep_rows, summary = [], [], [], {}
    for label, r in rows.items():
        t, n = r["times"], r["sys"].n
        lin_floor, cd_lin = t["linearize"] / t["floor"], t["central"] / t["linearize"]
        timing.append([label, n, " + ".join(r["sys"].calls), t["floor"] * 1e6, t["linearize"] * 1e6, lin_floor,
                       "yes" if lin_floor <= FLOOR_TARGET else "no", t["central"] * 1e6, cd_lin,
                       "yes" if cd_lin > 1 else "no", t["forward"] * 1e6, t["forward"] / t["linearize"],
                       t["central (pinlin residual)"] * 1e6, t["central (pinlin residual)"] / t["central"],
                       t["linearize_many"] * 1e6, t["linearize_many"] / t["floor"], t["linearize_many (large)"] * 1e6,
                       t["linearize_many (large)"] / t["floor"]])  # fmt: skip
        accuracy.append([label, n, r["err_lin"], r["best"]["forward"][0], r["best"]["forward"][1], r["best"]["central"][0],
                         r["best"]["central"][1], r["acc_ratio"], r["ref"], r["ref_err"], r["rich_err"]])  # fmt: skip
        for scheme in ("forward", "central"):
            for h, e in zip(sweep, r["errs"][scheme]):
                sweep_rows.append([label, scheme, h, e, e / max(r["err_lin"], 1e-300)])
        summary[label] = (
            f"linearize {t['linearize'] * 1e6:.1f} us = {lin_floor:.1f}x the floor ({t['floor'] * 1e6:.1f} us, "
            f"{' + '.join(r['sys'].calls)}); linearize_many {t['linearize_many'] * 1e6:.1f} us per point = "
            f"{t['linearize_many'] / t['floor']:.1f}x the floor ({BATCH} points), "
            f"{t['linearize_many (large)'] / t['floor']:.1f}x ({LARGE_BATCH} points); bare central differences {cd_lin:.1f}x linearize's time; error "
            f"{r['err_lin']:.1e} vs best central {r['best']['central'][0]:.1e}: {r['acc_ratio']:.1e}x more accurate "
            f"(reference: {r['ref']})"
        )
    t1 = Table(
        "Run time: linearize against the cheapest Pinocchio calls and bare-Pinocchio finite differences",
        ["scene", "n", "floor: Pinocchio calls the scene needs", "floor [us]", "linearize [us]", "linearize / floor",
         f"within {FLOOR_TARGET:g}x", "bare central FD [us]", "bare central FD / linearize", "linearize faster",
         "bare forward FD [us]", "bare forward FD / linearize", "central FD of pinlin's residual [us]",
         "pinlin residual / bare (the old baseline's flattery)", f"linearize_many per point [us] ({BATCH} points)",
         "linearize_many per point / floor", f"linearize_many per point [us] ({LARGE_BATCH} points)",
         f"linearize_many per point / floor ({LARGE_BATCH} points)"],
        timing,
        note=(
            "Thread CPU times (time.thread_time), medians of samples taken in turn in one process (interleaved), "
            "BLAS on one thread. Floor: exactly the Pinocchio algorithms of sys.calls, replayed bare on a Data of "
            "their own. Bare FD: differences of the residual computed with bare Pinocchio (computeStaticTorque, "
            "computeGeneralizedGravity or rnea with the follower wrenches' fext) and the springs' and dampers' "
            "forces in plain numpy (benchmarks.bench_linearize.BareResidual), steps through pin.integrate, M by "
            "crba: 4n (central) or 2n + 1 (forward) residual evaluations. The last columns time central "
            "differences of pinlin's own residual (assemble without derivatives), the first suite's baseline. "
            f"linearize_many: one call on {BATCH} (and {LARGE_BATCH}) configurations (the same q repeated), its "
            f"time divided by the number of points: the per-point cost of the batched linearization (the checks, "
            f"norms, splits and result objects on stacked arrays; Pinocchio per point)."
        ),
    )  # fmt: skip
    t2 = Table(
        "Accuracy: analytic linearization against finite differences",
        ["scene", "n", "linearize error", "best forward error", "at h", "best central error", "at h",
         "best central error / linearize error", "reference", "reference's own error estimate",
         "Richardson's error against the exact reference"],
        accuracy,
        note=(
            "Max relative Frobenius error of M, C, K against the reference. With a closed form or the mpmath "
            "reference (an independent forward-kinematics model of the fixed-base arm in 50-digit arithmetic) the "
            "errors are exact to double precision; with Richardson (the floating bases) the linearize error is the "
            "gap to the reference, an upper bound dominated by Richardson's own error. Ratios use an error floor of "
            "eps/2. Differences use the bare residual of the timing table."
        ),
    )  # fmt: skip
    t3 = Table(
        "Error of finite differences against the step h",
        ["scene", "scheme", "h", "error", "error / linearize error"],
        sweep_rows,
        note=(
            "Truncation error falls like h (forward) or h^2 (central) until rounding, eps ||r|| / h, takes over: "
            "the best step balances them and is problem dependent."
        ),
    )
    return [t1, t2, t3], summary


def run(quick: bool = False) -> Report:
    t_start = time.perf_counter()
    load_before = load_average()
    cases = [double_pendulum_case(), ur5_case(), panda_case(), solo_case(), talos_case(), turntable_case()]
    sweep = QUICK_H_SWEEP if quick else H_SWEEP
    rows = {case.label: _case_row(case, sweep, repeats=5 if quick else 15) for case in cases}
    tables, summary = _tables(rows, sweep)
    short = {label: label.split(":")[0].split(" (")[0].split(" at theta")[0].split(",")[0] for label in rows}
    summary["headline"] = (
        "linearize / floor (cheapest Pinocchio calls): "
        + ", ".join(f"{short[k]} {r['times']['linearize'] / r['times']['floor']:.1f}x" for k, r in rows.items())
        + f" (target <= {FLOOR_TARGET:g}x); bare central differences / linearize: "
        + ", ".join(f"{short[k]} {r['times']['central'] / r['times']['linearize']:.1f}x" for k, r in rows.items())
        + " (target > 1); accuracy ratio (best central error / linearize error): "
        + ", ".join(f"{short[k]} {r['acc_ratio']:.1e} ({r['ref']})" for k, r in rows.items())
    )
    robots = [r for k, r in rows.items() if not k.startswith(("double", "turntable"))]
    summary["robots (n >= 6)"] = (
        f"min speed ratio against bare central differences "
        f"{min(r['times']['central'] / r['times']['linearize'] for r in robots):.1f}x; min accuracy ratio against "
        f"exact references {min(r['acc_ratio'] for r in rows.values() if r['ref'] != 'Richardson'):.1e}"
    )
    mj_cases = [
        ("double pendulum (bars of radius 1 cm)", pinlin.pendulum_chain_urdf(2, [0.7, 0.5], [1.3, 0.9], radius=0.01),
         np.array([0.4, 0.5]))
    ] + [(c.label.split(":")[0], c.urdf, c.q) for c in cases if c.urdf is not None and c.label.startswith(("ur5", "panda"))]
    mj_rows, mj_note = mujoco_rows(mj_cases, quick)
    if mj_rows is None:
        summary["MuJoCo peer"] = mj_note
    else:
        tables.append(
            Table(
                "MuJoCo mjd_inverseFD against Pinocchio's analytic derivatives (rigid-body part, same URDF)",
                ["robot", "n", "MuJoCo eps", "mjd_inverseFD [us]", "Pinocchio analytic [us]", "MuJoCo / analytic",
                 "MuJoCo dtau/dq error", "analytic dtau/dq error", "MuJoCo M error"],
                mj_rows,
                note=mj_note,
            )
        )
        summary["MuJoCo peer"] = "compared (rigid-body part); see its table"
    ws_table, ws_summary = workspace_section(quick)
    summary.update(ws_summary)
    if ws_table is not None:
        tables.append(ws_table)
    plot_series = {}
    sweep_plot = {}
    for label, r in rows.items():
        t = r["times"]
        plot_series[f"{short[label]}: linearize"] = [(t["linearize"], r["err_lin"])]
        plot_series[f"{short[label]}: bare central FD (best h)"] = [(t["central"], r["best"]["central"][0])]
        plot_series[f"{short[label]}: bare forward FD (best h)"] = [(t["forward"], r["best"]["forward"][0])]
        sweep_plot[short[label]] = {"forward": r["errs"]["forward"], "central": r["errs"]["central"], "analytic": r["err_lin"]}
    figures = _plot(plot_series, sweep_plot, sweep, quick)
    summary["machine load (1-minute load average, before / after)"] = f"{load_before} / {load_average()} on {os.cpu_count()} CPUs"
    text = (
        "Analytic linearization (pinlin.linearize: Pinocchio's analytic derivatives plus the elements' own) against "
        "the cheapest Pinocchio calls the scene needs (the floor) and against finite differences of bare-Pinocchio "
        "residuals, the honest baselines; MuJoCo's finite-difference inverse-dynamics derivatives as a "
        "peer when mujoco is importable. The last table (benchmarks/bench_workspace.py) times linearize before and "
        "after the per-thread Pinocchio workspaces, and a fresh Data per call against the reused one."
    )
    report = Report("linearize", tables, summary, figures, text=text)
    for label, r in rows.items():
        t = r["times"]
        ratio, batch = t["linearize"] / t["floor"], t["linearize_many"] / t["floor"]
        large = t["linearize_many (large)"] / t["floor"]
        report.target(14, f"linearize at most {FLOOR_TARGET:g}x the cheapest Pinocchio calls: {short[label]}",
                      f"{ratio:.1f}x (linearize_many per point: {batch:.1f}x at {BATCH} points, {large:.1f}x at "
                      f"{LARGE_BATCH})", bool(ratio <= FLOOR_TARGET),
                      " + ".join(r["sys"].calls) + " (thread CPU time)")
        report.target(14, f"linearize faster than bare-Pinocchio central differences: {short[label]}",
                      f"{t['central'] / t['linearize']:.1f}x faster, {r['acc_ratio']:.0e}x more accurate",
                      bool(t["central"] > t["linearize"]), "central differences of bare-Pinocchio residuals")
    report.elapsed = time.perf_counter() - t_start
    return report


def _plot(series, sweep_plot, sweep, quick: bool) -> list[str]:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return []
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(13, 5))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, (label, d) in enumerate(sweep_plot.items()):
        c = colors[i % len(colors)]
        ax1.loglog(sweep, np.maximum(d["forward"], 1e-17), "--", color=c, marker="v", label=f"{label}: forward")
        ax1.loglog(sweep, np.maximum(d["central"], 1e-17), "-", color=c, marker="o", label=f"{label}: central")
        ax1.axhline(max(d["analytic"], 1e-17), color=c, lw=0.8, ls=":")
    ax1.set_xlabel("step h")
    ax1.set_ylabel("max relative error of M, C, K")
    ax1.set_title("Finite differences against the step (dotted: analytic)", fontsize=10)
    ax1.grid(True, which="both", alpha=0.3)
    ax1.legend(fontsize=6, ncol=2)
    work_precision_plot(None, series, "Linearization: error against run time", ax=ax2)
    path = save_figure(fig, result_path("linearize", quick))
    return [path]


if __name__ == "__main__":
    report = run()
    print(report.markdown())
    print("written to", write_report(report))
