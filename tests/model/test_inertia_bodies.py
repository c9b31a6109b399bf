"""Inertia checks on the bodies the dynamics uses, after fixed joints are merged."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.model.inertia import nearest_valid_moments


def _inertial(mass, ixx, iyy, izz, ixy=0.0, xyz="0 0 0"):
    return (f'<inertial><origin xyz="{xyz}"/><mass value="{mass}"/><inertia ixx="{ixx}" iyy="{iyy}" izz="{izz}" '
            f'ixy="{ixy}" ixz="0" iyz="0"/></inertial>')


def arm(body: str, dummy: str = "", dummy_on_world: str = "") -> str:
    """A base, an arm on a revolute joint, a dummy link fixed to the arm and one fixed to the base."""
    return f"""<robot name="arm">
  <link name="base">{dummy_on_world}</link>
  <link name="arm">{body}</link>
  <link name="dummy">{dummy}</link>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="weld" type="fixed"><parent link="arm"/><child link="dummy"/><origin xyz="0 0 -1"/></joint>
</robot>"""


VALID = _inertial(2.0, 0.2, 0.2, 0.02)
#: go1's base link: principal moments [-2e-22, 8.5e-23, 3e-6] (a dummy link carrying the IMU's point mass)
DEGENERATE = _inertial(0.001, -2e-22, 8.5e-23, 3e-6)


def test_a_dummy_link_merged_into_a_valid_body_warns_and_loads():
    with pytest.warns(pinlin.InertiaWarning, match=r"link 'dummy' breaks the triangle inequality.*merges it by fixed "
                      r"joints with 'arm' into the body moved by joint 'hinge', which is valid"):
        robot = pinlin.load_urdf_string(arm(VALID, DEGENERATE))
    body = robot.model.inertias[1]
    assert_allclose(body.mass, 2.001, rtol=1e-15)
    assert_allclose(body.lever, [0, 0, -0.001 / 2.001], rtol=1e-12)  # the dummy's 1 g sits 1 m below


def test_a_dummy_link_fixed_to_the_world_warns():
    with pytest.warns(pinlin.InertiaWarning, match=r"link 'base' breaks the triangle.*fixed to the world"):
        pinlin.load_urdf_string(arm(VALID, dummy_on_world=DEGENERATE))


def test_an_impossible_body_is_refused_naming_its_links_and_joint():
    """Merged about the common centre of mass: Ixx = Iyy = 1 + 0.01 + (1 * 0.5 / 1.5) * 1^2, Izz = 5.01."""
    text = arm(_inertial(1.0, 1, 1, 5), _inertial(0.5, 0.01, 0.01, 0.01))
    with pytest.raises(pinlin.UrdfError, match=r"link 'arm' \+ 'dummy' breaks the triangle inequality I1 \+ I2 >= I3 "
                       r"of a rigid body \(the links merged by fixed joints into the body moved by joint 'hinge'; "
                       r"principal moments \[1.34333333333333\d*, 1.34333333333333\d*, 5.01\].*inertia='repair'"):
        pinlin.load_urdf_string(text)


@pytest.mark.parametrize(
    "inertial, moments, repaired",
    [
        # triangle broken: the nearest point of the plane I1 + I2 = I3, e + (3/3) (1, 1, -1)
        (_inertial(1.0, 1, 1, 5), [1, 1, 5], [2, 2, 4]),
        # indefinite, eigenvalues -1, 1, 3: again e + (1, 1, -1) = (0, 2, 2), a rod
        (_inertial(1.0, 1, 1, 1, ixy=2), [-1, 1, 3], [0, 2, 2]),
    ],
)
def test_repair_gives_the_nearest_valid_tensor(inertial, moments, repaired):
    with pytest.warns(pinlin.InertiaWarning, match=rf"link 'arm' \(the body moved by joint 'hinge'\).*repaired to the "
                      rf"nearest valid tensor: principal moments \[{float(moments[0])}, .* -> \["):
        robot = pinlin.load_urdf_string(arm(inertial), inertia="repair")
    body = robot.model.inertias[1]
    assert_allclose(np.linalg.eigvalsh(body.inertia), repaired, atol=1e-12)
    assert body.mass == 1.0 and np.all(body.lever == 0)
    assert_allclose(nearest_valid_moments(moments), repaired, atol=1e-12)


def test_repair_keeps_the_principal_axes():
    with pytest.warns(pinlin.InertiaWarning, match="repaired"):
        robot = pinlin.load_urdf_string(arm(_inertial(1.0, 1, 1, 1, ixy=2)), inertia="repair")
    # principal axes of [[1, 2, 0], [2, 1, 0], [0, 0, 1]]: (1, -1, 0)/sqrt2 (-1), (0, 0, 1) (1), (1, 1, 0)/sqrt2 (3)
    a, b = np.array([1, -1, 0]) / np.sqrt(2), np.array([1, 1, 0]) / np.sqrt(2)
    expected = 0 * np.outer(a, a) + 2 * np.outer([0, 0, 1], [0, 0, 1]) + 2 * np.outer(b, b)
    assert_allclose(robot.model.inertias[1].inertia, expected, atol=1e-12)


def test_valid_moments_are_left_alone():
    for e in ([1, 2, 3], [0, 1, 1], [0, 0, 0], [2, 2, 2]):
        assert_allclose(nearest_valid_moments(e), e, atol=1e-15)


def test_the_tolerance_is_relative_to_the_body():
    """A milligram body rounded to six digits loads; a 0.1 % violation is refused at any scale."""
    pinlin.load_urdf_string(arm(_inertial(1e-6, 0, 1e-12 * (1 - 5e-7), 1e-12)))
    with pytest.raises(pinlin.UrdfError, match="breaks the triangle inequality"):
        pinlin.load_urdf_string(arm(_inertial(1e-6, 0, 1e-12 * (1 - 1e-3), 1e-12)))


@pytest.mark.parametrize("bad", ["fix", "", None, 1, "CHECK"])
def test_bad_inertia_option(bad):
    with pytest.raises(pinlin.ParameterError, match=r"inertia: expected one of \['check', 'repair'\]"):
        pinlin.load_urdf_string(arm(VALID), inertia=bad)


def test_go1_loads_with_a_warning_naming_its_dummy_base():
    with pytest.warns(pinlin.InertiaWarning, match=r"example:go1: the inertia tensor of link 'base' breaks the "
                      r"triangle inequality.*principal moments \[-1.99\d*e-22.*'root_joint', which is valid"):
        robot = pinlin.load_example("go1")
    assert robot.nv == 18


def test_romeo_small_is_refused_and_repaired_with_a_warning():
    with pytest.raises(pinlin.UrdfError, match=r"example:romeo_small: the inertia tensor of link 'RShoulderYawLink' breaks the triangle inequality"):
        pinlin.load_example("romeo_small")
    with pytest.warns(pinlin.InertiaWarning) as record:
        robot = pinlin.load_example("romeo_small", inertia="repair")
    repaired = [str(w.message) for w in record if "repaired" in str(w.message)]
    assert len(repaired) == 2  # one warning per body: RShoulderYaw and RElbowYaw
    assert "joint 'RShoulderYaw')" in repaired[0] and "joint 'RElbowYaw')" in repaired[1]
    moments = np.linalg.eigvalsh(robot.model.inertias[robot.model.getJointId("RShoulderYaw")].inertia)
    assert moments[0] + moments[1] >= moments[2] * (1 - 1e-12)
