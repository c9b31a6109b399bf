"""Elements between frames against hand-derived closed forms (theory: turntable, constraints,
elements between frames).

Each case cites its derivation in its docstring; tolerances are those of the elements' acceptance.
"""

import numpy as np
import pinocchio as pin
import pytest
import scipy.linalg
from numpy.testing import assert_allclose

import pinlin
from pinlin.testing import mp_eigenvalues, paired

G = 9.81
LIMIT = '<limit lower="-1e10" upper="1e10" effort="1e10" velocity="1e10"/>'


def _inertial(mass, ixx=0.0, iyy=0.0, izz=0.0, xyz="0 0 0"):
    return (
        f'<inertial><origin xyz="{xyz}"/><mass value="{float(mass)!r}"/>'
        f'<inertia ixx="{float(ixx)!r}" iyy="{float(iyy)!r}" izz="{float(izz)!r}" ixy="0" ixz="0" iyz="0"/></inertial>'
    )


def _joint(name, kind, parent, child, axis="0 0 1", xyz="0 0 0"):
    limit = LIMIT if kind in ("prismatic", "revolute") else ""
    return (
        f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
        f'<origin xyz="{xyz}"/><axis xyz="{axis}"/>{limit}</joint>'
    )


def squared_frequencies(sys):
    """Undamped squared natural frequencies eig(S, M) [rad^2/s^2], ascending."""
    return scipy.linalg.eigh(sys.S, sys.M, eigvals_only=True)


def frequencies(sys):
    """Undamped natural frequencies sqrt(eig(S, M)) [rad/s], ascending (S positive definite)."""
    return np.sqrt(squared_frequencies(sys))


# ----------------------------------------------------------------------------- elastic pendulum


@pytest.mark.parametrize("k, m, l0", [(40.0, 1.3, 0.5), (2500.0, 0.2, 1.2)])
def test_elastic_pendulum(k, m, l0):
    """Point mass m on a spring k (rest length l0) from a world point, in a vertical plane (theory: elements between frames).

    At the hanging equilibrium the spring is stretched to l = l0 + m g / k with
    tension T = m g: bounce omega^2 = k / m; swing omega^2 = (T / l) / m = g / l,
    the transverse stiffness T / l of the preloaded spring acting alone.
    """
    urdf = (
        '<robot name="elastic_pendulum"><link name="base"/><link name="slide"/>'
        f'<link name="bob">{_inertial(m, 1e-3, 1e-3, 1e-3)}</link>'
        + _joint("x", "prismatic", "base", "slide", "1 0 0")
        + _joint("z", "prismatic", "slide", "bob", "0 0 1")
        + "</robot>"
    )
    robot = pinlin.load_urdf_string(urdf)
    anchor = (0.0, 0.0, 0.0)
    scene = pinlin.Scene(robot, [pinlin.LinearSpringDamper("bob", anchor, stiffness=k, rest_length=l0)], gravity=(0, 0, -G))
    l_eq = l0 + m * G / k
    eq = pinlin.find_equilibrium(scene, [0.1, -l0])
    assert_allclose(eq.q, [0.0, -l_eq], atol=1e-12 * l_eq)
    sys = pinlin.linearize(scene, eq.q)
    assert_allclose(frequencies(sys), np.sort([np.sqrt(k / m), np.sqrt(G / l_eq)]), rtol=1e-10)
    assert sys.is_zero("N") and sys.is_zero("D")


def test_elastic_pendulum_free_body():
    """The same pendulum as a free-floating body (nq = 7, nv = 6) in three dimensions.

    The spring acts at the centre of mass: bounce sqrt(k/m), two swings sqrt(g/l),
    and three rotations of zero frequency (no torque about the centre of mass).
    """
    k, m, l0 = 40.0, 1.3, 0.5
    urdf = f'<robot name="bob"><link name="bob">{_inertial(m, 0.02, 0.03, 0.04)}</link></robot>'
    robot = pinlin.load_urdf_string(urdf, free_flyer=True)
    scene = pinlin.Scene(robot, [pinlin.LinearSpringDamper("bob", (0.2, -0.1, 1.0), stiffness=k, rest_length=l0)])
    l_eq = l0 + m * G / k
    q = pin.neutral(robot.model)
    q[:3] = (0.2, -0.1, 1.0 - l_eq)
    q[3:7] = pin.Quaternion(pin.rpy.rpyToMatrix(0.3, -0.2, 0.5)).coeffs()  # any orientation
    sys = pinlin.linearize(scene, q)
    w2 = squared_frequencies(sys)
    assert_allclose(w2[:3], 0.0, atol=1e-12 * k / m)
    assert_allclose(np.sqrt(w2[3:]), np.sort([np.sqrt(G / l_eq), np.sqrt(G / l_eq), np.sqrt(k / m)]), rtol=1e-10)


def test_small_motion_matches_the_nonlinear_simulation():
    """The linearized spring-damper pendulum (bounce and swing, damped) against pinlin.simulate.

    From 0.1 mm off equilibrium the nonlinear and linear responses differ by the
    second-order terms only, about (1e-4 m)^2 / l: a wrong K or C (a frequency off
    by 1e-3) would show as 1e-5 m within the 3 s simulated.
    """
    k, m, l0 = 40.0, 1.3, 0.5
    urdf = f"""<robot name="p"><link name="base"/><link name="slide"/>
      <link name="bob"><inertial><mass value="{m}"/><inertia ixx="1e-3" iyy="1e-3" izz="1e-3" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <joint name="x" type="prismatic"><parent link="base"/><child link="slide"/><axis xyz="1 0 0"/><limit lower="-9" upper="9" effort="1" velocity="1"/></joint>
      <joint name="z" type="prismatic"><parent link="slide"/><child link="bob"/><axis xyz="0 0 1"/><limit lower="-9" upper="9" effort="1" velocity="1"/></joint></robot>"""
    robot = pinlin.load_urdf_string(urdf)
    scene = pinlin.Scene(robot, [pinlin.LinearSpringDamper("bob", (0, 0, 0), stiffness=k, damping=0.3, rest_length=l0)])
    q_eq = np.array([0.0, -(l0 + m * 9.81 / k)])
    t = np.linspace(0.0, 3.0, 301)
    x0 = np.array([1e-4, 1e-4])
    nonlinear = np.asarray(pinlin.simulate(scene, q_eq + x0, None, t).q) - q_eq
    linear = np.asarray(pinlin.free_response(pinlin.linearize(scene, q_eq), x0, [0.0, 0.0], t))
    assert np.abs(nonlinear - linear).max() < 5e-8


# ----------------------------------------------------------------------------- turntable (theory: turntable)

A, MASS, K, L0 = 0.5, 1.3, 10.0, 0.3


def cartesian_turntable(omega, damping=0.0):
    """theory: turntable rebuilt in Cartesian coordinates: table (prescribed) -> x -> y -> particle; A fixed on the table."""
    urdf = (
        '<robot name="cartesian_turntable"><link name="ground"/>'
        f'<link name="table">{_inertial(1.0, 1.0, 1.0, 1.0)}</link><link name="slide_x"/>'
        f'<link name="particle">{_inertial(MASS)}</link><link name="A"/>'
        + _joint("table", "continuous", "ground", "table")
        + _joint("x", "prismatic", "table", "slide_x", "1 0 0")
        + _joint("y", "prismatic", "slide_x", "particle", "0 1 0")
        + f'<joint name="A_fixed" type="fixed"><parent link="table"/><child link="A"/><origin xyz="{A!r} 0 0"/></joint>'
        + "</robot>"
    )
    robot = pinlin.load_urdf_string(urdf)
    spring = pinlin.LinearSpringDamper("particle", "A", stiffness=K, damping=damping, rest_length=L0)
    return pinlin.Scene(robot, [spring], prescribed={"table": omega})


@pytest.mark.parametrize("omega, c", [(0.5, 0.0), (1.5, 0.0), (2.5, 0.0), (1.5, 0.7)])
def test_turntable_cartesian_matches_polar_closed_form(omega, c):
    """Example 6.1 (theory: turntable): same eigenvalues in Cartesian coordinates with a spring-damper to A.

    Polar form in (theta, r): M = diag(m r0^2, m), G = 2 m W r0 [[0, 1], [-1, 0]],
    S = diag(m W^2 a r0, k - m W^2), r0 = (k l0 + m W^2 a) / (k - m W^2); a dashpot
    c along AP adds D = diag(0, c).  The Cartesian linearization is congruent to it
    (dx = dr, dy = r0 dtheta at theta = 0), so the eigenvalues agree.  With c > 0
    the dashpot's rate ldot vanishes for every particle position at rest on the
    table while its parts (the turning line, the changing relative velocity) do not:
    their q-derivatives at v = v0 must cancel exactly.
    """
    scene = cartesian_turntable(omega, c)
    m = MASS
    r0 = (K * L0 + m * omega**2 * A) / (K - m * omega**2)
    q = scene.neutral()
    q[2], q[3] = 1.2 * (A + r0), 0.1
    eq = pinlin.find_equilibrium(scene, q)
    assert_allclose(eq.q[2:], [A + r0, 0.0], atol=1e-12)
    sys = pinlin.linearize(scene, eq.q)
    M = np.diag([m * r0**2, m])
    D = np.diag([0.0, c])
    Gm = 2 * m * omega * r0 * np.array([[0.0, 1.0], [-1.0, 0.0]])
    S = np.diag([m * omega**2 * A * r0, K - m * omega**2])
    reference = mp_eigenvalues((M, D + Gm, S))
    lam = mp_eigenvalues(sys)  # the linearization's own eigenvalues, free of the eigensolver's rounding
    assert_allclose(lam, paired(lam, reference), rtol=1e-9, atol=1e-9 * np.abs(reference).max())
    assert sys.is_zero("N")


# ----------------------------------------------------------------------------- half-car


def test_half_car_bounce_and_pitch():
    """Half-car (theory: elements between frames): body m, pitch inertia I, springs k_f at a ahead and k_r at b behind.

    With z the bounce and theta the pitch (about y, so the front point moves by
    z - a theta and the rear by z + b theta): K = [[k_f + k_r, k_r b - k_f a],
    [k_r b - k_f a, k_f a^2 + k_r b^2]], C likewise with c_f, c_r, and the two
    frequencies are the roots of det(K - w^2 diag(m, I)) = 0.  Gravity is
    carried by the preloaded springs (rest lengths chosen for equilibrium at
    z = theta = 0); the attachment points lie on the pitch axis's level, so the
    preload adds no stiffness in these coordinates.
    """
    m, I, a, b = 1200.0, 1800.0, 1.1, 1.6
    kf, kr, cf, cr, h = 3.0e4, 2.6e4, 1.5e3, 1.2e3, 0.4
    urdf = (
        '<robot name="half_car"><link name="ground"/><link name="heave"/>'
        f'<link name="body">{_inertial(m, 300.0, I, 2000.0)}</link><link name="front"/><link name="rear"/>'
        + _joint("z", "prismatic", "ground", "heave", "0 0 1")
        + _joint("pitch", "continuous", "heave", "body", "0 1 0")
        + f'<joint name="f" type="fixed"><parent link="body"/><child link="front"/><origin xyz="{a!r} 0 0"/></joint>'
        + f'<joint name="r" type="fixed"><parent link="body"/><child link="rear"/><origin xyz="{-b!r} 0 0"/></joint>'
        + "</robot>"
    )
    robot = pinlin.load_urdf_string(urdf)
    # static compressions: k_f d_f + k_r d_r = m g, k_f d_f a = k_r d_r b
    df, dr = m * G * b / (kf * (a + b)), m * G * a / (kr * (a + b))
    springs = [
        pinlin.LinearSpringDamper("front", (a, 0.0, -h), stiffness=kf, damping=cf, rest_length=h + df),
        pinlin.LinearSpringDamper("rear", (-b, 0.0, -h), stiffness=kr, damping=cr, rest_length=h + dr),
    ]
    scene = pinlin.Scene(robot, springs, gravity=(0, 0, -G))
    sys = pinlin.linearize(scene, scene.neutral())
    K = np.array([[kf + kr, kr * b - kf * a], [kr * b - kf * a, kf * a**2 + kr * b**2]])
    C = np.array([[cf + cr, cr * b - cf * a], [cr * b - cf * a, cf * a**2 + cr * b**2]])
    assert_allclose(sys.K, K, rtol=1e-12)
    assert_allclose(sys.D, C, rtol=1e-12)
    # det([[K11 - m w2, K12], [K12, K22 - I w2]]) = m I w2^2 - (m K22 + I K11) w2 + det K = 0
    w2 = np.roots([m * I, -(m * K[1, 1] + I * K[0, 0]), np.linalg.det(K)])
    assert_allclose(frequencies(sys), np.sqrt(np.sort(w2.real)), rtol=1e-10)


# ----------------------------------------------------------------------------- bushing on a free body


def test_bushing_on_free_body_six_frequencies():
    """A free-floating body held by a bushing at its centre of mass, at zero deflection (theory: elements between frames).

    The body's principal axes are the bushing frame's axes, so K = diag(k_i)
    (J_r = I for the free-flyer's body frame) and M = diag(m, m, m, I_1, I_2, I_3):
    frequencies sqrt(k_i / m) and sqrt(k_{i+3} / I_i), with damping D = diag(d_i).
    """
    m, inertia = 2.5, np.array([0.04, 0.07, 0.09])
    k = np.array([1.0e4, 2.0e4, 3.5e4, 40.0, 90.0, 160.0])
    d = np.array([3.0, 4.0, 5.0, 0.1, 0.2, 0.3])
    urdf = f'<robot name="block"><link name="block">{_inertial(m, *inertia)}</link></robot>'
    robot = pinlin.load_urdf_string(urdf, free_flyer=True)
    placement = pin.SE3(pin.rpy.rpyToMatrix(0.4, -0.3, 1.1), np.array([0.5, -0.2, 1.3]))
    scene = pinlin.Scene(robot, [pinlin.Bushing("block", placement, stiffness=k, damping=d)], gravity=(0, 0, 0))
    q = pin.SE3ToXYZQUAT(placement)
    sys = pinlin.linearize(scene, q)
    assert_allclose(sys.K, np.diag(k), rtol=1e-12, atol=1e-12 * k.max())
    assert_allclose(sys.D, np.diag(d), rtol=1e-12, atol=1e-12 * d.max())
    expected = np.concatenate([np.sqrt(k[:3] / m), np.sqrt(k[3:] / inertia)])
    assert_allclose(frequencies(sys), np.sort(expected), rtol=1e-10)


# ----------------------------------------------------------------------------- four-bar


FOURBAR = dict(a=0.3, b=0.8, c=0.6, d=0.7, m=(0.4, 1.1, 0.8))


def _fourbar_angles(phi1):
    """Absolute angles (phi1, phi2, phi3) of crank, coupler, rocker closing a e1 + b e2 + c e3 = d (complex)."""
    a, b, c, d = (FOURBAR[x] for x in "abcd")
    B = a * np.exp(1j * phi1)  # crank tip
    dist = abs(d - B)
    # coupler tip C: |C - B| = b, |D - C| = c; take the intersection above the ground line
    base = np.angle(d - B)
    alpha = np.arccos((b**2 + dist**2 - c**2) / (2 * b * dist))
    phi2 = base + alpha
    C = B + b * np.exp(1j * phi2)
    phi3 = np.angle(d - C)
    return phi1, phi2, phi3


def _fourbar_rigid_frequency(phi1, k1, k3):
    """Energy method (theory: constraints): omega^2 = K_eff / M_eff along the loop, theta = phi1.

    Velocity loop: i a w1 e1 + i b w2 e2 + i c w3 e3 = 0 gives w2, w3 per unit w1.
    M_eff = sum m_k |v_ck|^2 + I_k w_k^2 (uniform bars, I = m l^2 / 12);
    K_eff = k1 * 1^2 + k3 (w3 - w2)^2 for torsion springs at the crank pivot and
    between coupler and rocker, unstressed in the assembled position.
    """
    a, b, c = FOURBAR["a"], FOURBAR["b"], FOURBAR["c"]
    m1, m2, m3 = FOURBAR["m"]
    _, phi2, phi3 = _fourbar_angles(phi1)
    e1, e2, e3 = np.exp(1j * phi1), np.exp(1j * phi2), np.exp(1j * phi3)
    # real and imaginary parts of b w2 i e2 + c w3 i e3 = -a i e1
    Amat = np.array([[(1j * b * e2).real, (1j * c * e3).real], [(1j * b * e2).imag, (1j * c * e3).imag]])
    rhs = -np.array([(1j * a * e1).real, (1j * a * e1).imag])
    w2, w3 = np.linalg.solve(Amat, rhs)
    v1 = 1j * a / 2 * e1
    v2 = 1j * a * e1 + 1j * b / 2 * e2 * w2
    v3 = 1j * a * e1 + 1j * b * e2 * w2 + 1j * c / 2 * e3 * w3
    M_eff = sum(
        mk * abs(vk) ** 2 + mk * lk**2 / 12 * wk**2
        for mk, vk, lk, wk in ((m1, v1, a, 1.0), (m2, v2, b, w2), (m3, v3, c, w3))
    )
    K_eff = k1 + k3 * (w3 - w2) ** 2
    return np.sqrt(K_eff / M_eff)


@pytest.mark.parametrize("closure", ["spring_damper", "bushing"])
def test_fourbar_stiff_closure_converges_to_rigid(closure):
    """A planar four-bar (theory: constraints check case) closed at the rocker tip by a stiff element.

    An open chain crank - coupler - rocker whose tip is tied to the ground pivot
    D = (d, 0) by a zero-length spring (or a bushing with translational stiffness
    only) of stiffness k_c: two modes go to infinity like sqrt(k_c) and the
    lowest tends to the rigid four-bar's frequency from the energy method, with an
    error O(1 / k_c).
    """
    phi1, k1, k3 = 1.1, 5.0, 3.0
    a, b, c, d = (FOURBAR[x] for x in "abcd")
    rigid = _fourbar_rigid_frequency(phi1, k1, k3)
    p1, p2, p3 = _fourbar_angles(phi1)
    q = np.array([p1, p2 - p1, p3 - p2])
    links = ""
    for name, mass, length in zip(("crank", "coupler", "rocker"), FOURBAR["m"], (a, b, c)):
        izz = mass * length**2 / 12
        links += f'<link name="{name}">{_inertial(mass, izz, izz, izz, xyz=f"{length / 2!r} 0 0")}</link>'
    urdf = (
        f'<robot name="fourbar"><link name="ground"/>{links}<link name="tip"/>'
        + _joint("j1", "revolute", "ground", "crank")
        + _joint("j2", "revolute", "crank", "coupler", xyz=f"{a!r} 0 0")
        + _joint("j3", "revolute", "coupler", "rocker", xyz=f"{b!r} 0 0")
        + f'<joint name="tip_fixed" type="fixed"><parent link="rocker"/><child link="tip"/><origin xyz="{c!r} 0 0"/></joint>'
        + "</robot>"
    )
    robot = pinlin.load_urdf_string(urdf)
    springs = [pinlin.JointSpring("j1", k1, rest=q[0]), pinlin.JointSpring("j3", k3, rest=q[2])]
    tip = pin.SE3(pin.rpy.rpyToMatrix(0.0, 0.0, p3), np.array([d, 0.0, 0.0]))  # the tip frame when closed
    errors, closure_modes = [], []
    for kc in (1e3, 1e5, 1e7):
        if closure == "spring_damper":
            closing = pinlin.LinearSpringDamper("tip", (d, 0.0, 0.0), stiffness=kc)
        else:
            closing = pinlin.Bushing("tip", tip, stiffness=[kc, kc, kc, 0.0, 0.0, 0.0])
        scene = pinlin.Scene(robot, springs + [closing], gravity=(0, 0, 0))
        sys = pinlin.linearize(scene, q)
        w = frequencies(sys)
        closure_modes.append(w[1:])
        errors.append(abs(w[0] - rigid) / rigid)
    assert errors[-1] < 1e-5
    # the closure's own modes grow like sqrt(k_c): a factor 10 per factor 100
    assert_allclose(closure_modes[-1] / closure_modes[-2], 10.0, rtol=0.01)
    # O(1 / k_c): each factor 100 in stiffness divides the error by about 100
    assert_allclose(np.array(errors[:-1]) / np.array(errors[1:]), 100.0, rtol=0.05)
