"""The time-invariance check uses both of its probes (theory: elements).

A prescribed joint's position is probed at two offsets (PERIODIC_TEST_ANGLES, 1.0 and 2.5 rad) because one
probe can land where a periodic dependence happens to repeat.  Here it does: a radial slider (mass m,
coordinate x) on a turntable spinning about z, tied by a spring to the world point (R, 0, 0).  Its equations
depend on the table angle theta only through cos(theta) (the spring's length and the radial projection of
its force, |d|^2 = (r + x)^2 + R^2 - 2 (r + x) R cos theta), so from theta = -0.5 the first probe (theta =
0.5) sees exactly no change and only the second (theta = 2.0) proves the equations time-periodic.  A check
whose second probe is dead (it reuses the first one's kinematics or result) lets this scene through.
"""

import numpy as np
import pytest

import pinlin

URDF = """<?xml version="1.0"?>
<robot name="radial_slider">
  <link name="base"/>
  <link name="table"><inertial><mass value="1.0"/>
    <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="table" type="revolute"><parent link="base"/><child link="table"/><axis xyz="0 0 1"/>
    <limit lower="-100" upper="100" effort="1" velocity="100"/></joint>
  <link name="carriage"><inertial><mass value="0.7"/>
    <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
  <joint name="slider" type="prismatic"><parent link="table"/><child link="carriage"/>
    <origin xyz="0.4 0 0"/><axis xyz="1 0 0"/>
    <limit lower="-10" upper="10" effort="1" velocity="10"/></joint>
</robot>
"""


def test_only_the_second_probe_sees_the_dependence():
    robot = pinlin.load_urdf_string(URDF)
    spring = pinlin.LinearSpringDamper("carriage", (1.5, 0.0, 0.0), stiffness=20.0, damping=0.0, rest_length=0.5)
    scene = pinlin.Scene(robot, [spring, pinlin.JointSpring("slider", 3.0)], gravity=(0, 0, 0),
                         prescribed={"table": 0.8})
    q = np.array([-0.5, 0.1])
    # the premise: theta = -0.5 and theta + 1.0 give the same equations, theta + 2.5 does not
    same = [pinlin.linearize(pinlin.Scene(robot, scene.elements, gravity=(0, 0, 0)), np.array([t, 0.1]),
                             balancing=True) for t in (-0.5, 0.5, 2.0)]
    k = [s.S[1, 1] for s in same]
    assert abs(k[0] - k[1]) <= 1e-12 * abs(k[0]) and abs(k[2] - k[0]) > 1e-3 * abs(k[0])
    with pytest.raises(pinlin.TimePeriodicError, match=r"after 2\.5 rad") as info:
        pinlin.linearize(scene, q, balancing=True)
    assert info.value.joint == "table"
