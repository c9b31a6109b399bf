"""xacro files with arguments, ``package://`` includes and ``$(find pkg)``."""

import sys

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.model.xacro import find_package, package_search_path

LINK = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="bar" params="name parent mass length">
    <link name="${name}">
      <inertial>
        <origin xyz="0 0 ${-length / 2}"/>
        <mass value="${mass}"/>
        <inertia ixx="${mass * length**2 / 12}" iyy="${mass * length**2 / 12}" izz="0" ixy="0" ixz="0" iyz="0"/>
      </inertial>
      <visual><geometry><mesh filename="package://bars/meshes/bar.stl"/></geometry></visual>
    </link>
    <joint name="${name}_joint" type="revolute">
      <parent link="${parent}"/><child link="${name}"/><axis xyz="0 1 0"/>
      <limit lower="-3" upper="3" effort="1" velocity="1"/>
    </joint>
  </xacro:macro>
</robot>
"""

ROBOT = """<?xml version="1.0"?>
<robot name="pendulum" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="mass" default="1.0"/>
  <xacro:arg name="length" default="0.5"/>
  <xacro:include filename="{include}"/>
  <link name="base"/>
  <xacro:bar name="bar1" parent="base" mass="$(arg mass)" length="$(arg length)"/>
</robot>
"""


@pytest.fixture
def workspace(tmp_path):
    """A ROS-like workspace: <ws>/bars/urdf/bar.xacro, and the robot elsewhere."""
    (tmp_path / "ws" / "bars" / "urdf").mkdir(parents=True)
    (tmp_path / "ws" / "bars" / "urdf" / "bar.xacro").write_text(LINK)
    return tmp_path


def _robot(tmp_path, include):
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(ROBOT.format(include=include))
    return path


@pytest.mark.parametrize("include", ["package://bars/urdf/bar.xacro", "$(find bars)/urdf/bar.xacro"])
def test_xacro_with_arguments_and_a_package_include(workspace, include, monkeypatch):
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    path = _robot(workspace, include)
    m, length = 2.5, 0.8
    robot = pinlin.load_urdf(path, xacro_args={"mass": m, "length": length}, package_dirs=[workspace / "ws"],
                             trust_xacro=True)
    assert robot.joint_names == ("bar1_joint",) and robot.source == str(path)
    body = robot.model.inertias[1]
    assert_allclose(body.mass, m, rtol=1e-15)
    assert_allclose(body.lever, [0, 0, -length / 2], rtol=1e-15)
    # a rod about its end: the pendulum's mass matrix is m L^2 / 3
    sys = pinlin.linearize(pinlin.Scene(robot, gravity=(0, 0, -9.81)), np.zeros(1))
    assert_allclose(sys.M, [[m * length**2 / 3]], rtol=1e-12)
    assert_allclose(sys.S, [[m * 9.81 * length / 2]], rtol=1e-12)  # hanging: g m L / 2
    default = pinlin.load_urdf(path, package_dirs=[workspace / "ws"], trust_xacro=True)  # the <xacro:arg> defaults
    assert_allclose(default.model.inertias[1].mass, 1.0)


def test_ros_package_path_is_searched_after_package_dirs(workspace, monkeypatch, tmp_path):
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(workspace / "ws"))
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(tmp_path / "install"))
    robot = pinlin.load_urdf(_robot(workspace, "package://bars/urdf/bar.xacro"), trust_xacro=True)
    assert robot.nv == 1
    assert package_search_path(["/first"])[0].as_posix() == "/first"
    assert package_search_path()[1].as_posix() == (tmp_path / "install" / "share").as_posix()
    (tmp_path / "install" / "share" / "other").mkdir(parents=True)
    assert find_package("other", package_search_path()) == tmp_path / "install" / "share" / "other"


def test_missing_package_names_the_search_path(workspace, monkeypatch):
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    with pytest.raises(pinlin.UrdfError, match=r"package 'bars' not found; searched \['/nowhere'\]"):
        pinlin.load_urdf(_robot(workspace, "package://bars/urdf/bar.xacro"), package_dirs=["/nowhere"], trust_xacro=True)


def test_bad_xacro_input(workspace, tmp_path):
    path = _robot(workspace, "package://bars/urdf/bar.xacro")
    with pytest.raises(pinlin.ParameterError, match="xacro_args: expected a mapping"):
        pinlin.load_urdf(path, xacro_args=["mass", 1.0], package_dirs=[workspace / "ws"])
    with pytest.raises(pinlin.ParameterError, match="package_dirs: expected a list of directories"):
        pinlin.load_urdf(path, package_dirs=str(workspace / "ws"))
    with pytest.raises(pinlin.ParameterError, match="xacro_args apply to .xacro files only"):
        pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"), xacro_args={"a": 1})
    broken = tmp_path / "broken.xacro"
    broken.write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="${undefined}"/></robot>')
    with pytest.raises(pinlin.UrdfError, match=r"broken.xacro: xacro could not expand the file .*undefined"):
        pinlin.load_urdf(broken, trust_xacro=True)


def test_missing_xacro_package_names_the_extra(workspace, monkeypatch):
    monkeypatch.setitem(sys.modules, "xacro", None)  # import xacro now raises ImportError
    with pytest.raises(pinlin.MissingDependencyError, match=r"pip install 'pinlin\[xacro\]'"):
        pinlin.load_urdf(_robot(workspace, "package://bars/urdf/bar.xacro"), trust_xacro=True)
