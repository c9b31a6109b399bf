"""The Whipple bicycle benchmark, checked without pinlin's linearization.

Source of the numbers: Meijaard, Papadopoulos, Ruina and Schwab, Proc. R. Soc. A 463 (2007)
1955-1982 (see ``bicycle_cases``).  Two independent checks:

1. transcription: the published matrices alone (numpy, scipy) give the published eigenvalues
   and the weave and capsize speeds;
2. the URDF of :func:`pinlin.model.vehicles.whipple_bicycle_urdf`, loaded with bare Pinocchio,
   gives the published mass matrix (from the null space of the rolling constraints) and gravity
   stiffness (the Hessian of the potential on the contact manifold).

Sign mapping between the benchmark (x forward, y right, z down) and the URDF (x forward, y left,
z up): the benchmark's roll phi (to the right positive) is a right-handed rotation about the
forward axis, which both frames share, so phi is the rear frame's rotation about its own x; its
steer delta (to the right positive) is a right-handed rotation about the steer axis pointing
down, which is the URDF's ``steer`` axis, so delta is the ``steer`` joint angle.  Both maps are
the identity; the off-diagonal entries of M and K0 would change sign with either flipped.
"""

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_allclose
from scipy.linalg import null_space
from scipy.optimize import brentq

from bicycle_cases import C1, CAPSIZE_SPEED, EIGENVALUES, G, K0, K2, M, WEAVE_SPEED
from pinlin.model.vehicles import WhippleParameters, rolling_disk_urdf, whipple_bicycle_urdf

P = WhippleParameters()
UP = np.array([0.0, 0.0, 1.0])


# ---------------------------------------------------------------- 1. transcription

def eigenvalues(v):
    """Eigenvalues of M s^2 + v C1 s + g K0 + v^2 K2, sorted by (real, imaginary) part."""
    Minv = np.linalg.inv(M)
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-Minv @ (G * K0 + v**2 * K2), -v * Minv @ C1]])
    return np.sort_complex(np.linalg.eigvals(A))


@pytest.mark.parametrize("v", sorted(EIGENVALUES))
def test_published_matrices_give_published_eigenvalues(v):
    assert_allclose(eigenvalues(v), EIGENVALUES[v], rtol=1e-12)


def weave_real_part(v):
    lam = eigenvalues(v)
    return lam[lam.imag > 0].real.max()


def capsize_eigenvalue(v):
    lam = eigenvalues(v)
    return lam[lam.imag == 0].real.max()


def test_published_matrices_give_weave_and_capsize_speeds():
    weave = brentq(weave_real_part, 4.0, 4.6, xtol=1e-15)
    capsize = brentq(capsize_eigenvalue, 5.5, 6.5, xtol=1e-15)
    assert_allclose(weave, WEAVE_SPEED, rtol=1e-11)
    assert_allclose(capsize, CAPSIZE_SPEED, rtol=1e-11)
    # Self-stable in between: every real part negative at the published 5 m/s.
    assert eigenvalues(5.0).real.max() < 0


# ---------------------------------------------------------------- 2. the URDF in bare Pinocchio

@pytest.fixture(scope="module")
def bike():
    model = pin.buildModelFromXML(whipple_bicycle_urdf(), pin.JointModelFreeFlyer())
    model.gravity.linear = np.array([0.0, 0.0, -9.81])
    return model, model.createData()


def wheels(model):
    return ((model.getFrameId("rear_wheel_body"), P.rR), (model.getFrameId("front_wheel_body"), P.rF))


def contact_point(data, fid, radius):
    """The rim's lowest point c = o - r u, u the unit vector of the wheel plane closest to up."""
    placement = data.oMf[fid]
    axle = placement.rotation[:, 1]
    u = UP - axle[2] * axle
    return placement.translation - radius * u / np.linalg.norm(u)


def configuration(model, height, roll, pitch, steer, heading=0.0, xy=(0.0, 0.0), wheel_angles=(0.0, 0.0)):
    """Rear frame at height ``height`` with orientation Rz(heading) Rx(roll) Ry(pitch); joints set."""
    q = pin.neutral(model)
    q[:3] = xy[0], xy[1], height
    R = pin.utils.rotate("z", heading) @ pin.utils.rotate("x", roll) @ pin.utils.rotate("y", pitch)
    q[3:7] = pin.Quaternion(R).coeffs()
    q[model.joints[model.getJointId("steer")].idx_q] = steer
    for name, angle in zip(("rear_wheel", "front_wheel"), wheel_angles):
        i = model.joints[model.getJointId(name)].idx_q
        q[i:i + 2] = np.cos(angle), np.sin(angle)
    return q


def contact_heights(model, data, q):
    pin.framesForwardKinematics(model, data, q)
    return np.array([contact_point(data, fid, r)[2] for fid, r in wheels(model)])


def test_upright_bicycle_stands_on_both_wheels(bike):
    model, data = bike
    heights = contact_heights(model, data, configuration(model, P.rR, 0.0, 0.0, 0.0))
    assert_allclose(heights, 0.0, rtol=0, atol=1e-15)
    front = contact_point(data, model.getFrameId("front_wheel_body"), P.rF)
    assert_allclose(front, [P.w, 0.0, 0.0], rtol=0, atol=1e-15)  # the wheelbase


def test_constrained_mass_matrix_is_the_benchmark_M(bike):
    """B^T M B with v = B u the velocities that keep both wheels' contact points at rest.

    u = (roll rate, steer rate, rear wheel rate).  The benchmark's M multiplies the second
    derivatives of roll and steer in the reduced equations (whose kinetic energy is
    u^T B^T M B u / 2); at v = 0 no velocity term enters, so M is the (roll, steer) block of
    B^T M B at the upright configuration.  The bicycle is symmetric about its mid-plane there:
    roll and steer rates are odd under that reflection and the forward rate even, so their
    cross terms vanish (checked) and setting the rear wheel rate to 0 selects the block.
    """
    model, data = bike
    q = configuration(model, P.rR, 0.0, 0.0, 0.0)
    pin.computeJointJacobians(model, data, q)
    pin.framesForwardKinematics(model, data, q)
    rows = []
    for fid, radius in wheels(model):
        # [v_o; w] of the wheel frame in world axes; the material point at c moves with v_o + w x (c - o).
        J = pin.getFrameJacobian(model, data, fid, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
        arm = contact_point(data, fid, radius) - data.oMf[fid].translation
        rows.append(J[:3] - pin.skew(arm) @ J[3:])
    A = np.vstack(rows)
    assert np.linalg.matrix_rank(A) == 6
    N = null_space(A)  # the free flyer's velocity is local: (linear, angular) in rear frame axes
    chosen = [3] + [model.joints[model.getJointId(n)].idx_v for n in ("steer", "rear_wheel")]
    B = N @ np.linalg.inv(N[chosen])  # roll rate = the rear frame's w_x at the upright
    Mq = pin.crba(model, data, q)
    Mr = B.T @ (np.triu(Mq) + np.triu(Mq, 1).T) @ B
    assert_allclose(Mr[:2, :2], M, rtol=1e-12)
    assert_allclose(Mr[:2, 2], 0.0, rtol=0, atol=1e-14 * np.abs(M).max())
    # Forward rolling by hand: m_total rR^2 + IRyy + IFyy (rR / rF)^2.
    forward = (P.mR + P.mB + P.mH + P.mF) * P.rR**2 + P.IRyy + P.IFyy * (P.rR / P.rF) ** 2
    assert_allclose(Mr[2, 2], forward, rtol=1e-13)


def on_ground(model, data, roll, steer, **where):
    """(height, pitch) of the rear frame with both lowest rim points at z = 0 (Newton)."""

    def heights(x):
        return contact_heights(model, data, configuration(model, x[0], roll, x[1], steer, **where))

    x, step = np.array([P.rR, 0.0]), 1e-6
    for _ in range(20):
        residual = heights(x)
        if np.abs(residual).max() <= 4e-16:
            return x
        # Central differences: the Jacobian's accuracy sets the rate, not the converged point.
        jac = np.column_stack([(heights(x + d) - heights(x - d)) / (2 * step) for d in step * np.eye(2)])
        x = x - np.linalg.solve(jac, residual)
    raise AssertionError(f"no contact configuration at roll={roll}, steer={steer}: residual {residual}")


def potential(model, data, roll, steer, **where):
    height, pitch = on_ground(model, data, roll, steer, **where)
    q = configuration(model, height, roll, pitch, steer, **where)
    return pin.computeTotalMass(model) * P.g * pin.centerOfMass(model, data, q)[2]


def central_hessian(V, h):
    f0 = V(0.0, 0.0)
    return np.array([
        [V(h, 0.0) - 2 * f0 + V(-h, 0.0), (V(h, h) - V(h, -h) - V(-h, h) + V(-h, -h)) / 4],
        [(V(h, h) - V(h, -h) - V(-h, h) + V(-h, -h)) / 4, V(0.0, h) - 2 * f0 + V(0.0, -h)],
    ]) / h**2


def test_potential_depends_only_on_roll_and_steer(bike):
    model, data = bike
    base = potential(model, data, 0.05, -0.1)
    moved = potential(model, data, 0.05, -0.1, heading=0.7, xy=(3.0, -2.0), wheel_angles=(1.1, -2.3))
    assert_allclose(moved, base, rtol=1e-14)


def test_gravity_stiffness_is_the_benchmark_K0(bike):
    """Hessian of the potential on the contact manifold in (roll, steer) = g K0.

    Central differences at h, h/2, h/4 (h = 0.05 rad), two Richardson steps (errors h^2, h^4):
    the truncation error left is O(h^6) and the rounding error about 1e-13 J / (h/4)^2, so the
    achieved accuracy is about 1e-10 per entry (7e-11 measured), against an aim of 1e-9.
    The nominal upright state is a critical point of the potential (it is even in (roll,
    steer)), so the Hessian does not depend on how roll and steer are defined beyond first order.
    """
    model, data = bike

    def V(roll, steer):
        return potential(model, data, roll, steer)

    h = 0.05
    table = [central_hessian(V, h / 2**k) for k in range(3)]
    for j in (1, 2):
        table = [(4**j * fine - coarse) / (4**j - 1) for coarse, fine in zip(table, table[1:])]
    assert_allclose(table[0], G * K0, rtol=1e-9)


# ---------------------------------------------------------------- the same construction on a closed form

def test_rolling_disk_constrained_mass_matrix_and_potential_by_hand():
    """Upright rolling disk: B^T M B = diag(A + m r^2, A, C + m r^2) in (lean, heading, spin) rates,
    and the potential m g r cos(lean) has the Hessian -m g r: the two constructions above on a case
    whose answer is known in closed form (A = m r^2 / 4, C = m r^2 / 2)."""
    r, m = 0.4, 3.0
    model = pin.buildModelFromXML(rolling_disk_urdf(r, m))
    data = model.createData()
    fid = model.getFrameId("disk")
    q = pin.neutral(model)
    q[2] = r
    pin.computeJointJacobians(model, data, q)
    pin.framesForwardKinematics(model, data, q)
    J = pin.getFrameJacobian(model, data, fid, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    c = contact_point(data, fid, r)
    assert_allclose(c, 0.0, rtol=0, atol=1e-16)
    N = null_space(J[:3] - pin.skew(c - data.oMf[fid].translation) @ J[3:])
    B = N @ np.linalg.inv(N[[4, 3, 5]])  # v = (x, y, z, heading, lean, spin) rates
    Mq = pin.crba(model, data, q)
    A, C = m * r * r / 4, m * r * r / 2
    assert_allclose(B.T @ (np.triu(Mq) + np.triu(Mq, 1).T) @ B, np.diag([A + m * r * r, A, C + m * r * r]),
                    rtol=1e-15, atol=1e-16)

    def V(lean):
        q = pin.neutral(model)
        q[4] = lean
        pin.framesForwardKinematics(model, data, q)
        q[2] = -contact_point(data, fid, r)[2]  # the centre's height that puts the rim on the ground
        return m * P.g * pin.centerOfMass(model, data, q)[2]

    h = 0.05
    second = [(V(s) - 2 * V(0.0) + V(-s)) / s**2 for s in (h, h / 2)]
    assert_allclose((4 * second[1] - second[0]) / 3, -m * P.g * r, rtol=1e-7)  # relative error h^4 / 1440
