"""The asymmetric shaft through URDF scenes (theory: Floquet reference case).

A disk of mass m held by two springs k1, k2 (rest length R, unloaded at the centre) from anchors at (R, 0)
and (0, R) on a rotor turning at Omega: along the rotor's x and y the disk sees k1 and k2.

- Rotating coordinates (x_r, y_r on the rotor): time-invariant, ``linearize`` gives M = m I,
  G = 2 m Omega J, S = diag(k1, k2) - m Omega^2 I; undamped, unstable exactly for sqrt(k1/m) < Omega < sqrt(k2/m).
- Inertial coordinates (x, y fixed in the world): K(t) = R(Omega t) diag(k1, k2) R(Omega t)^T, periodic;
  x_inertial = R(Omega t) x_rotating, and R(2 pi) = I, so over T = 2 pi / Omega the two monodromies are
  equal: the Floquet multipliers are exp(lambda_r T) with lambda_r the rotating system's eigenvalues.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg
from numpy.testing import assert_allclose

import pinlin

M_DISK, K1, K2, R = 2.0, 50.0, 80.0, 1.0


def _inertial(I=1e-3, mass=M_DISK):
    return (f'<inertial><mass value="{mass}"/>'
            f'<inertia ixx="{I}" iyy="{I}" izz="{I}" ixy="0" ixz="0" iyz="0"/></inertial>')


def _urdf(rotating: bool) -> str:
    lim = '<limit lower="-1e10" upper="1e10" effort="1e10" velocity="1e10"/>'
    disk_parent = "rotor" if rotating else "world"
    return (
        '<robot name="shaft"><link name="world"/>'
        f'<link name="rotor">{_inertial()}</link><link name="anchor1"/><link name="anchor2"/>'
        f'<link name="sx">{_inertial(0.0, 0.0)}</link><link name="disk">{_inertial()}</link>'
        '<joint name="spin" type="continuous"><parent link="world"/><child link="rotor"/><axis xyz="0 0 1"/></joint>'
        '<joint name="a1" type="fixed"><parent link="rotor"/><child link="anchor1"/><origin xyz="1 0 0"/></joint>'
        '<joint name="a2" type="fixed"><parent link="rotor"/><child link="anchor2"/><origin xyz="0 1 0"/></joint>'
        f'<joint name="x" type="prismatic"><parent link="{disk_parent}"/><child link="sx"/><axis xyz="1 0 0"/>{lim}</joint>'
        f'<joint name="y" type="prismatic"><parent link="sx"/><child link="disk"/><axis xyz="0 1 0"/>{lim}</joint>'
        '</robot>'
    )


def _scene(rotating: bool, omega: float) -> pinlin.Scene:
    robot = pinlin.load_urdf_string(_urdf(rotating))
    springs = [pinlin.LinearSpringDamper("anchor1", "disk", stiffness=K1, rest_length=R),
               pinlin.LinearSpringDamper("anchor2", "disk", stiffness=K2, rest_length=R)]
    return pinlin.Scene(robot, springs, gravity=(0.0, 0.0, 0.0), prescribed={"spin": omega})


@pytest.mark.parametrize("omega", [3.0, 5.6, 7.5])
def test_inertial_floquet_equals_rotating_linearization(omega):
    rot = _scene(True, omega)
    q0 = rot.neutral()
    assert pinlin.scene_period(rot, q0) is None  # time-invariant in rotating coordinates
    sys = pinlin.linearize(rot, q0)
    assert_allclose(sys.M, M_DISK * np.eye(2), rtol=1e-12)
    assert_allclose(sys.G, 2 * M_DISK * omega * np.array([[0.0, -1.0], [1.0, 0.0]]), rtol=1e-12)
    assert_allclose(sys.S, np.diag([K1, K2]) - M_DISK * omega**2 * np.eye(2), rtol=1e-12, atol=1e-12 * K2)
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-np.linalg.solve(sys.M, sys.S + sys.N), -np.linalg.solve(sys.M, sys.D + sys.G)]])
    T = 2 * math.pi / omega
    mu_r = np.linalg.eigvals(scipy.linalg.expm(A * T))

    ine = _scene(False, omega)
    assert_allclose(pinlin.scene_period(ine, ine.neutral()), T, rtol=1e-15)
    orbit = pinlin.periodic_orbit(ine, ine.neutral())
    assert orbit.constant
    co = pinlin.variational_coefficients(ine, orbit)
    t = 0.3 * T
    c, s = math.cos(omega * t), math.sin(omega * t)
    Rt = np.array([[c, -s], [s, c]])
    assert_allclose(co.K(t), Rt @ np.diag([K1, K2]) @ Rt.T, rtol=1e-12, atol=1e-12 * K2)
    flo = pinlin.floquet_analysis(ine, orbit)
    key = lambda z: (round(abs(z), 6), z.imag)  # noqa: E731
    assert_allclose(sorted(flo.multipliers, key=key), sorted(mu_r, key=key), rtol=1e-8, atol=1e-8)
    unstable = math.sqrt(K1 / M_DISK) < omega < math.sqrt(K2 / M_DISK)
    assert (np.max(np.abs(flo.multipliers)) > 1 + 1e-6) == unstable
    print(f"shaft omega={omega}: max |mu| = {np.max(np.abs(flo.multipliers)):.6f}, "
          f"difference from rotating {np.max(np.abs(np.sort_complex(flo.multipliers) - np.sort_complex(mu_r))):.1e}")


def test_offset_anchor_forces_the_disk_and_the_orbit_turns_with_the_rotor():
    """One spring anchored off its rest length pulls the disk round with the rotor: the orbit is not
    constant (the equilibrium residual is zero at spin angle 0 only if the force vanishes there: here it does
    not), and the forced orbit in inertial coordinates is the rotating equilibrium turned by Omega t."""
    omega = 2.0
    robot = pinlin.load_urdf_string(_urdf(False))
    springs = [pinlin.LinearSpringDamper("anchor1", "disk", stiffness=K1, rest_length=0.9 * R, damping=0.5),
               pinlin.LinearSpringDamper("anchor2", "disk", stiffness=K2, rest_length=R, damping=0.5)]
    scene = pinlin.Scene(robot, springs, gravity=(0.0, 0.0, 0.0), prescribed={"spin": omega})
    q0 = scene.neutral()
    orbit = pinlin.periodic_orbit(scene, q0)
    assert not orbit.constant and orbit.residual <= 1e-10
    assert_allclose(orbit.period, 2 * math.pi / omega, rtol=1e-15)
    # the disk's radius stays constant along a circular orbit (the rotating equilibrium, turned)
    radii = [np.hypot(*orbit.q(t)[2:4]) for t in np.linspace(0.0, orbit.period, 7)]
    assert_allclose(radii, radii[0], rtol=1e-8)
    assert radii[0] > 0.01
    rotating = pinlin.Scene(pinlin.load_urdf_string(_urdf(True)), springs, gravity=(0.0, 0.0, 0.0),
                            prescribed={"spin": omega})
    eq = pinlin.find_equilibrium(rotating, rotating.neutral())
    assert_allclose(radii[0], np.hypot(*eq.q[2:4]), rtol=1e-8)
