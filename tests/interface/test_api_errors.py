"""The API's last crashes: each a PinlinError (a ValueError) naming the argument."""

import re

import numpy as np
import pytest

import pinlin
from pinlin import JointSpring, PointConstraint, Scene


@pytest.fixture(scope="module")
def four_bar():
    return pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))


@pytest.fixture(scope="module")
def pendulum():
    """A one-DOF pendulum (1 m, 1 kg) hanging along -z; its tip frame is 'tip'."""
    return pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(1, length=1.0, mass=1.0))


def test_a_single_constraint_is_refused_with_a_list_suggested(four_bar):
    loop = PointConstraint("rocker_tip", (0.7, 0, 0), name="loop")
    with pytest.raises(pinlin.ParameterError, match=r"^constraints: expected a list of constraints, got a single one: "
                       r"write constraints=\[PointConstraint\("):
        Scene(four_bar, constraints=loop)
    with pytest.raises(pinlin.ParameterError, match=r"^constraints: expected a list of PointConstraint or "
                       r"FrameConstraint, got 3"):
        Scene(four_bar, constraints=3)
    with pytest.raises(pinlin.ParameterError, match=r"^constraints\[0\]: expected a PointConstraint or FrameConstraint"):
        Scene(four_bar, constraints=["loop"])
    assert Scene(four_bar, constraints=[loop]).constraints == (loop,)
    assert Scene(four_bar, constraints=(c for c in [loop])).constraints == (loop,)  # any iterable


def test_two_constraints_with_one_name_are_refused(four_bar):
    a = PointConstraint("rocker_tip", (0.7, 0, 0), name="loop")
    b = PointConstraint("coupler_link", (0.3, 0, 0.4), name="loop")
    with pytest.raises(pinlin.ParameterError, match=r"^constraints\[1\]: the name 'loop' is already that of "
                       r"constraints\[0\]: give each constraint its own name"):
        Scene(four_bar, constraints=[a, b])


def test_find_equilibrium_refuses_constraints_that_hold_every_dof_as_linearize_does(pendulum):
    scene = Scene(pendulum, [JointSpring("joint1", 1.0)], constraints=[PointConstraint("tip", (0, 0, -1.0))])
    message = r"no motion left: the constraints \['tip'\] have rank J_c = 1 = nv"
    with pytest.raises(pinlin.OverconstrainedError, match=message):
        pinlin.linearize(scene, pendulum.neutral())
    with pytest.raises(pinlin.OverconstrainedError, match=message) as info:
        pinlin.find_equilibrium(scene, pendulum.neutral())
    assert isinstance(info.value, ValueError) and info.value.constraints == ("tip",)


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), "10", True, None, 2.5, 2])
def test_critical_parameter_refuses_a_bad_max_evaluations(bad):
    def func(p):  # never called: the arguments are checked first
        raise AssertionError("computed")

    with pytest.raises(pinlin.ParameterError, match=r"^max_evaluations: expected an integer >= 3, got "):
        pinlin.critical_parameter(func, (0.0, 1.0), max_evaluations=bad)


def test_unknown_coordinates_list_each_valid_name_once(four_bar):
    scene = Scene(four_bar, [JointSpring("crank_joint", 50.0, rest=0.2)],
                  constraints=[PointConstraint("rocker_tip", (0.7, 0, 0), name="loop")])
    q = pinlin.find_equilibrium(scene, np.zeros(3)).q
    with pytest.raises(pinlin.JointNotFoundError, match="unknown joint 'knee' in coordinates") as info:
        pinlin.linearize(scene, q, coordinates=["knee"])
    listed = re.findall(r"'(\w+)'", str(info.value).split("valid joints:")[1])
    assert listed == ["crank_joint", "coupler_joint", "rocker_joint"]
    assert info.value.valid == tuple(listed)


def test_animate_mode_takes_negative_indices_as_its_message_says(tmp_path):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from pinlin import plot

    robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    scene = Scene(robot, [JointSpring("joint1", 3.0), JointSpring("joint2", 2.0)])
    sys = pinlin.linearize(scene, robot.neutral())
    modes = pinlin.modal_analysis(sys)
    count = len(modes.eigenvalues)
    last = plot.animate_mode(scene, sys, -1, modes=modes, n_frames=2, dpi=20)
    last.save(tmp_path / "last.html", writer="html")
    assert (tmp_path / "last.html").stat().st_size > 0
    for bad in (count, -count - 1):
        with pytest.raises(pinlin.ParameterError, match=rf"^mode: expected an index into modes.eigenvalues, 0 to "
                           rf"{count - 1} \(or -{count} to -1 from the end, as in Python\), got {bad}"):
            plot.animate_mode(scene, sys, bad, modes=modes)
    plt.close("all")
