"""Physically valid inertial data is checked at load: links' mass and inertia tensors."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.model.inertia import INERTIA_TOL

BASE = pinlin.pendulum_chain_urdf(1)
IYY = 'iyy="0.08333333333333333"'


def with_inertia(**values):
    attrs = " ".join(f'{k}="{v}"' for k, v in values.items())
    return BASE.replace(
        '<inertia ixx="0.08333333333333333" ixy="0.0" ixz="0.0" iyy="0.08333333333333333" iyz="0.0" izz="0.0"/>',
        f"<inertia {attrs}/>",
    )


@pytest.mark.parametrize("bad", ["nan", "inf", "1e999", "abc", "-inf"])
def test_unparsable_inertia_is_an_error_not_zero(bad):
    with pytest.raises(pinlin.UrdfError, match=rf"link 'link1' has iyy = '{bad}', not a finite number"):
        pinlin.load_urdf_string(BASE.replace(IYY, f'iyy="{bad}"'))


@pytest.mark.parametrize("bad", ["nan", "abc", "inf"])
def test_unparsable_mass_is_an_error_not_a_dropped_inertial(bad):
    with pytest.raises(pinlin.UrdfError, match=rf"link 'link1' has mass = '{bad}'"):
        pinlin.load_urdf_string(BASE.replace('<mass value="1.0"/>', f'<mass value="{bad}"/>'))


def test_negative_mass():
    with pytest.raises(pinlin.UrdfError, match=r"link 'link1' has a negative mass \(-1 kg\)"):
        pinlin.load_urdf_string(BASE.replace('<mass value="1.0"/>', '<mass value="-1.0"/>'))


def test_indefinite_inertia_tensor():
    text = with_inertia(ixx=1, iyy=1, izz=1, ixy=2, ixz=0, iyz=0)  # eigenvalues -1, 1, 3
    with pytest.raises(pinlin.UrdfError, match="link 'link1' is not positive semi-definite"):
        pinlin.load_urdf_string(text)


def test_triangle_inequality():
    with pytest.raises(pinlin.UrdfError, match="link 'link1' breaks the triangle inequality"):
        pinlin.load_urdf_string(with_inertia(ixx=1, iyy=1, izz=5, ixy=0, ixz=0, iyz=0))


def test_limits_of_the_triangle_inequality_are_accepted():
    """A lamina (I1 + I2 = I3) and a rod rounded to six digits load; the model keeps the values."""
    robot = pinlin.load_urdf_string(with_inertia(ixx=1, iyy=2, izz=3, ixy=0, ixz=0, iyz=0))
    assert_allclose(np.diag(robot.model.inertias[1].inertia), [1, 2, 3])
    rounded = 1 - 0.5 * INERTIA_TOL
    pinlin.load_urdf_string(with_inertia(ixx=0, iyy=rounded, izz=1, ixy=0, ixz=0, iyz=0))


def test_bundled_and_example_models_pass_the_checks():
    for name in ["ur5", "panda", "solo12", "talos_reduced"]:
        pinlin.load_example(name)


def test_a_link_with_two_parent_joints_is_refused():
    """Found by the fuzzer: a duplicated joint under another name loaded with repeated joint names."""
    joint = BASE[BASE.index('<joint name="joint1"'):BASE.index("</joint>") + len("</joint>")]
    text = BASE.replace(joint, joint + joint.replace('name="joint1"', 'name="joint1b"'))
    with pytest.raises(pinlin.UrdfError, match="link 'link1' is the child of two joints \\('joint1' and 'joint1b'\\)"):
        pinlin.load_urdf_string(text)


def test_duplicate_names_are_refused():
    link = '<link name="tip"/>'
    with pytest.raises(pinlin.UrdfError, match="two <link> elements are named 'tip'"):
        pinlin.load_urdf_string(BASE.replace(link, link + link))
