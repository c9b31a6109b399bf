"""MJCF models with closed loops (pinlin.load_mjcf) and constraints in scene files (theory: constraints)."""

import re

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.model.scene_file import load_scene

WELDED = """<mujoco model="welded">
  <compiler angle="radian"/>
  <worldbody>
    <body name="base">
      <body name="upper" pos="0 0 0">
        <joint name="hip" type="hinge" axis="0 1 0"/>
        <inertial pos="0 0 -0.25" mass="1.0" diaginertia="0.02 0.02 0.001"/>
        <body name="lower" pos="0 0 -0.5">
          <joint name="knee" type="ball"/>
          <inertial pos="0 0 -0.2" mass="0.8" diaginertia="0.01 0.01 0.001"/>
        </body>
      </body>
      <body name="post" pos="0.3 0 -0.6">
        <joint name="slide" type="slide" axis="1 0 0"/>
        <inertial pos="0 0 0" mass="0.5" diaginertia="0.001 0.001 0.001"/>
      </body>
    </body>
  </worldbody>
  <equality>
    <weld name="glue" body1="lower" body2="post"/>
    <weld body1="upper"/>
    <connect body1="lower" anchor="0 0 -0.4" active="false"/>
    <joint joint1="hip" joint2="slide"/>
  </equality>
</mujoco>
"""


def _write(tmp_path, text, name="model.xml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_bundled_four_bar_mjcf():
    robot = pinlin.load_mjcf(pinlin.data_path("mjcf/four_bar.xml"))
    (loop,) = robot.constraints
    assert isinstance(loop, pinlin.PointConstraint) and loop.name == "loop" and loop.frame == "loop_1"
    assert_allclose(loop.target, [0.7, 0.0, 0.0], atol=1e-15)
    assert robot.joint_names == ("crank_joint", "coupler_joint", "rocker_joint")
    scene = pinlin.Scene(robot)  # the robot's constraints come along
    assert scene.constraints == robot.constraints
    assert pinlin.Scene(robot, constraints=[]).constraints == ()
    assert "constraints=1" in repr(robot)


def test_welds_become_frame_constraints(tmp_path):
    with pytest.warns(UserWarning, match=r"<equality><joint> is not a constraint pinlin models"):
        robot = pinlin.load_mjcf(_write(tmp_path, WELDED))
    glue, world = robot.constraints  # the inactive connect is left out
    assert isinstance(glue, pinlin.FrameConstraint) and (glue.frame, glue.target) == ("glue_1", "glue_2")
    assert isinstance(world, pinlin.FrameConstraint) and world.name == "weld2" and world.target.shape == (4, 4)
    # both welds hold in the file's configuration (q = 0): MuJoCo's rule, kept by Pinocchio's parser
    scene = pinlin.Scene(robot)
    from pinlin.linearization.constraint_set import evaluate_constraints

    state = evaluate_constraints(scene, scene.neutral())
    assert np.abs(state.phi).max() < 1e-15
    # the weld to the world leaves nothing of the hip; the glue holds the ball and the slide
    with pytest.raises(pinlin.OverconstrainedError, match="no motion left"):
        pinlin.linearize(scene, scene.neutral(), balancing=True)


def test_free_flyer_and_locked_joints(tmp_path):
    text = WELDED.replace('<weld body1="upper"/>', "").replace('<joint joint1="hip" joint2="slide"/>', "")
    robot = pinlin.load_mjcf(_write(tmp_path, text), free_flyer=True, locked=["slide"])
    assert robot.joint_names[0] == "root_joint" and "slide" not in robot.joint_names
    assert [c.name for c in robot.constraints] == ["glue"]
    pinlin.Scene(robot)  # the glue's frames survive the reduction


@pytest.mark.parametrize(
    "text, match",
    [
        ("<robot/>", r"root element is <robot>, expected <mujoco>"),
        ("<mujoco><worldbody>", r"malformed XML"),
        (
            '<mujoco><worldbody><body name="a"><joint type="hinge"/><inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/>'
            '</body><body name="c"><joint type="hinge"/><inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/></body>'
            "</worldbody></mujoco>",
            r"2 bodies directly under <worldbody> \(\['a', 'c'\]\).*keeps only the first",
        ),
        (
            '<mujoco><worldbody><body name="a"><joint name="j1" type="hinge"/><joint name="j2" type="hinge" axis="1 0 0"/>'
            '<inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/></body></worldbody></mujoco>',
            r"body 'a' has 2 joints \['j1', 'j2'\].*composite joint whose analytic derivatives are wrong",
        ),
        ('<mujoco><include file="other.xml"/></mujoco>', r"<include> is not followed"),
        ('<mujoco><worldbody><body name="a"><inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/></body></worldbody></mujoco>', r"no movable joint"),
    ],
)
def test_bad_mjcf(tmp_path, text, match):
    with pytest.raises(pinlin.MjcfError, match=match) as info:
        pinlin.load_mjcf(_write(tmp_path, text))
    assert info.value.source.endswith("model.xml")


def test_missing_mjcf_file(tmp_path):
    with pytest.raises(pinlin.MjcfError, match="MJCF file not found"):
        pinlin.load_mjcf(tmp_path / "nothing.xml")


def test_composite_derivatives_are_wrong_in_pinocchio(tmp_path):
    """Why load_mjcf refuses bodies with several joints: Pinocchio 4.1's gravity derivative of a
    composite joint disagrees with central differences (the reason given in the error)."""
    text = (
        '<mujoco><worldbody><body name="a"><joint name="j1" type="hinge" axis="0 1 0"/>'
        '<joint name="j2" type="hinge" axis="1 0 0"/><inertial pos="0.1 0.2 -0.3" mass="1" diaginertia="1 1 1"/>'
        "</body></worldbody></mujoco>"
    )
    model = pin.buildModelFromMJCF(str(_write(tmp_path, text)))
    assert model.joints[1].shortname() == "JointModelComposite"
    data = model.createData()
    q = np.array([0.3, -0.4])
    analytic = pin.computeGeneralizedGravityDerivatives(model, data, q).copy()
    h = 1e-6
    fd = np.column_stack([
        (pin.computeGeneralizedGravity(model, data, q + h * e) - pin.computeGeneralizedGravity(model, data, q - h * e)) / (2 * h)
        for e in np.eye(2)
    ])  # fmt: skip
    assert np.abs(analytic - fd).max() > 1e-3 * np.abs(fd).max()


# ----------------------------------------------------------------------------- scene files


def test_bundled_four_bar_scene_file():
    spec = load_scene(pinlin.data_path("scenes/four_bar.toml"))
    (loop,) = spec.scene.constraints
    assert loop.name == "loop" and loop.frame == "rocker_tip"
    eq = pinlin.find_equilibrium(spec.scene, spec.q0)
    assert pinlin.linearize(spec.scene, eq.q).n == 1


def _scene_file(tmp_path, constraint):
    urdf = pinlin.data_path("urdf/four_bar.urdf")
    return _write(tmp_path, f'[robot]\nurdf = "{urdf}"\n\n[[constraint]]\n{constraint}\n', "scene.toml")


def test_scene_file_contact_and_frame_constraints(tmp_path):
    spec = load_scene(_scene_file(tmp_path, 'frame = "rocker_tip"\ntarget = [0.7, 0, 0]\ncontact = true\nfriction = 0.4\nnormal = [0, 0, 2]'))
    (c,) = spec.scene.constraints
    assert c.contact and c.friction == 0.4
    assert_allclose(c.normal, [0, 0, 1])  # normalized
    spec = load_scene(_scene_file(tmp_path, 'type = "frame"\nframe = "rocker_tip"\ntarget = { xyz = [0.7, 0, 0], rpy = [0, 0.5, 0] }'))
    (c,) = spec.scene.constraints
    assert isinstance(c, pinlin.FrameConstraint)
    assert_allclose(c.target[:3, 3], [0.7, 0, 0])


@pytest.mark.parametrize(
    "body, key, match",
    [
        ('type = "hinge"\nframe = "rocker_tip"\ntarget = [0, 0, 0]', r"constraint\[1\]\.type", r"expected 'point' or 'frame'"),
        ('frame = "toe"\ntarget = [0, 0, 0]', r"constraint\[1\]", r"unknown frame 'toe'"),
        ('frame = "rocker_tip"', r"constraint\[1\]\.target", r"missing required key"),
        ('frame = "rocker_tip"\ntarget = [0, 0, 0]\nstiffness = 3.0', r"constraint\[1\]\.stiffness", r"unknown key"),
        ('type = "frame"\nframe = "rocker_tip"\ntarget = "crank"\ncontact = true', r"constraint\[1\]", r"point constraints only"),
        ('frame = "rocker_tip"\ntarget = [0, 0, 0]\nfriction = 0.3', r"constraint\[1\]", r"friction applies to contacts only"),
    ],
)
def test_scene_file_bad_constraints(tmp_path, body, key, match):
    with pytest.raises(pinlin.SceneFileError, match=match) as info:
        load_scene(_scene_file(tmp_path, body))
    assert info.value.key is not None and re.fullmatch(key, info.value.key)
