"""A robot with one degree of freedom: Pinocchio's binding returns its Jacobians as (6,) vectors, not (6, 1)."""

from __future__ import annotations

import math

import numpy as np
from numpy.testing import assert_allclose

import pinlin

#: One uniform-mass point pendulum: mass 1 kg at 0.5 m below a hinge about y, with Iyy = 0.01 kg m^2 at the mass.
ONE_DOF = """<robot name="one">
  <link name="base"/>
  <link name="arm"><inertial><origin xyz="0 0 -0.5"/><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
</robot>"""


def _scene(elements):
    return pinlin.Scene(pinlin.load_urdf_string(ONE_DOF), elements, gravity=(0, 0, -9.81))


def test_mode_energy_of_a_one_dof_pendulum_by_hand():
    scene = _scene([pinlin.JointSpring("j", 2.0)])
    modes = pinlin.modal_analysis(pinlin.linearize(scene, np.zeros(1)))
    stiffness = 2.0 + 1.0 * 9.81 * 0.5  # spring plus gravity [N m/rad]
    inertia = 1.0 * 0.5**2 + 0.01  # about the hinge [kg m^2]
    assert_allclose(np.abs(modes.eigenvalues), math.sqrt(stiffness / inertia), rtol=1e-13)
    energy = modes.energy(0)  # raised a ValueError (a (6,) Jacobian times u) before
    assert_allclose(list(energy.kinetic.values()), [1.0], rtol=1e-12)  # one body carries all the kinetic energy
    assert_allclose(list(energy.strain.values()), [1.0], rtol=1e-12)  # one elastic element

def test_frame_element_on_a_one_dof_robot_against_its_closed_form():
    # a vertical spring k = 40 N/m from the mass point to a world point 1 m below the hinge: at theta = 0 it is
    # stretched by 0.5 m less its rest length 0.5 m, so unloaded; its stiffness about the hinge is k (l sin)^2 -> 0
    # in the vertical direction and its transverse term T / l = 0: the pendulum's frequency is unchanged
    spring = pinlin.LinearSpringDamper("arm", (0.0, 0.0, -1.0), stiffness=40.0, rest_length=0.5)
    sys = pinlin.linearize(_scene([spring]), np.zeros(1))
    assert_allclose(sys.S, [[1.0 * 9.81 * 0.5]], rtol=1e-12)
