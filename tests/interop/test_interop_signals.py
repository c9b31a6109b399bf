"""The written form of inputs and outputs (pinlin.interop.signal_names): names, expansion, bad input."""

import numpy as np
import pytest
from interop_cases import double_pendulum
from numpy.testing import assert_allclose

import pinlin
from pinlin.interop import WRENCH_AXES, parse_inputs, parse_outputs

DOFS = ("joint1", "joint2")


def names(signals):
    return tuple(s.name for s in signals)


def test_defaults_follow_dof_names():
    assert names(parse_inputs(None, DOFS)) == ("force:joint1", "force:joint2")
    assert names(parse_outputs(None, DOFS)) == DOFS


def test_coordinates_written_three_ways():
    assert names(parse_inputs(["joint2", 0], DOFS)) == ("force:joint2", "force:joint1")
    assert names(parse_inputs("force:joint2", DOFS)) == ("force:joint2",)
    assert names(parse_outputs([1, "coordinate:joint1", "rate:joint2"], DOFS)) == (
        "joint2",
        "joint1",
        "rate:joint2",
    )
    assert names(parse_outputs(("joint1", "joint2"), DOFS)) == DOFS


def test_frame_signals_expand_over_axes():
    assert names(parse_inputs("dead:tip", DOFS)) == tuple(f"dead:tip:{a}" for a in WRENCH_AXES)
    assert names(parse_outputs("velocity:tip", DOFS)) == (
        "velocity:tip:x",
        "velocity:tip:y",
        "velocity:tip:z",
    )
    (s,) = parse_inputs("follower:tip:ty", DOFS)
    assert isinstance(s.wrench, pinlin.FollowerWrench) and s.wrench.frame == "tip"
    assert_allclose(np.concatenate([s.wrench.force, s.wrench.torque]), [0, 0, 0, 0, 1, 0], rtol=0, atol=0)


def test_coordinate_names_with_colons_match_whole():
    dofs = ("arm:left", "arm:right")
    assert names(parse_inputs("arm:right", dofs)) == ("force:arm:right",)
    assert names(parse_outputs(["arm:left", "rate:arm:right"], dofs)) == ("arm:left", "rate:arm:right")


def test_bad_signals():
    with pytest.raises(
        pinlin.ParameterError,
        match=r"inputs: unknown coordinate 'joint9'; valid coordinates: \['joint1', 'joint2'\]",
    ):
        parse_inputs(["joint1", "force:joint9"], DOFS)
    with pytest.raises(pinlin.ParameterError, match="'joint9' is neither a coordinate"):
        parse_outputs("joint9", DOFS)
    with pytest.raises(
        pinlin.ParameterError,
        match=r"'torque:joint1' is neither a coordinate .* kind in \['force', 'follower', 'dead'\]",
    ):
        parse_inputs("torque:joint1", DOFS)
    with pytest.raises(pinlin.ParameterError, match="unknown axis 'fw'; valid axes"):
        parse_inputs("follower:tip:fw", DOFS)
    with pytest.raises(pinlin.ParameterError, match="unknown axis 'fx'"):
        parse_outputs("position:tip:fx", DOFS)
    with pytest.raises(pinlin.ParameterError, match="expected 'kind:frame' or 'kind:frame:axis'"):
        parse_outputs("position:tip:x:y", DOFS)
    with pytest.raises(pinlin.ParameterError, match="the target name is empty"):
        parse_outputs("position::x", DOFS)
    with pytest.raises(pinlin.ParameterError, match="coordinate index 2 out of range for n = 2"):
        parse_outputs([0, 2], DOFS)
    with pytest.raises(pinlin.ParameterError, match="non-empty list"):
        parse_inputs([], DOFS)
    with pytest.raises(pinlin.ParameterError, match="signal 'joint1' appears twice"):
        parse_outputs(["joint1", 0], DOFS)
    with pytest.raises(pinlin.ParameterError, match=r"'dead:tip' appears twice \(name wrenches with pairs"):
        parse_inputs(
            [pinlin.DeadWrench("tip", force=(1, 0, 0)), pinlin.DeadWrench("tip", force=(0, 1, 0))], DOFS
        )
    with pytest.raises(pinlin.ParameterError, match="expected a pair"):
        parse_inputs([("pull", "follower:tip:fx")], DOFS)
    with pytest.raises(
        pinlin.ParameterError, match="expected a coordinate, a 'kind:frame:axis' string or a wrench, got 1.5"
    ):
        parse_inputs([1.5], DOFS)
    with pytest.raises(pinlin.ParameterError, match="or a wrench, got JointSpring"):
        parse_inputs([pinlin.JointSpring("joint1", 1.0)], DOFS)


def test_bad_signals_through_state_space():
    scene, sys = double_pendulum()
    with pytest.raises(pinlin.ParameterError, match="outputs: unknown coordinate 'joint3'"):
        pinlin.state_space(sys, outputs="rate:joint3", scene=scene)
    with pytest.raises(pinlin.ParameterError, match="inputs: 'tip' is neither a coordinate"):
        pinlin.state_space(sys, inputs="tip", scene=scene)
