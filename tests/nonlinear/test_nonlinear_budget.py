"""The budget of a nonlinear simulation: long runs stop early and say how far they got."""

from __future__ import annotations

import time

import numpy as np
import pytest

import pinlin
from pinlin.errors import ComputationError, IntegrationBudgetError, IntegrationError
from pinlin.model.scene_file import default_scene_path, load_scene
from pinlin.nonlinear import DEFAULT_MAX_STEPS, PROJECTION_FACTOR, PROJECTION_MIN_STEPS

#: A hopeless request must fail within this wall time [s] (it takes about 0.3 s; generous for a loaded CI).
FAIL_FAST_SECONDS = 10.0


@pytest.fixture(scope="module")
def pendulum():
    """The paper's double pendulum with follower load (theory: double pendulum), the bundled default scene."""
    return load_scene(default_scene_path()).scene


def test_a_billion_seconds_fails_fast_and_says_how_far_it_got(pendulum):
    t0 = time.perf_counter()
    with pytest.raises(IntegrationBudgetError, match=r"reached t = [0-9.]+ s of \[0, 1e\+09\] s") as info:
        pinlin.simulate(pendulum, [0.1, 0], [0, 0], [0, 1e9])
    took = time.perf_counter() - t0
    err = info.value
    assert took < FAIL_FAST_SECONDS
    assert isinstance(err, IntegrationError) and isinstance(err, ComputationError)  # the CLI's exit code 3
    # the projection decides after PROJECTION_MIN_STEPS steps: ~40 steps per period of ~1 s, so ~25 s done
    assert err.steps == PROJECTION_MIN_STEPS
    assert 1.0 < err.t_reached < 1e3 and err.t_end == 1e9
    assert err.budget == "max_steps" and err.elapsed <= took
    projected = err.steps * 1e9 / err.t_reached
    assert projected > PROJECTION_FACTOR * DEFAULT_MAX_STEPS
    assert f"{projected:.2g}" in str(err) and "max_steps" in str(err)


def test_step_budget_counts_exactly_the_steps_a_run_takes(pendulum):
    t = np.linspace(0.0, 5.0, 6)
    full = pinlin.simulate(pendulum, [0.1, 0], [0, 0], t, estimate_error=False)
    steps = full.steps
    assert steps > 50 and full.max_steps == DEFAULT_MAX_STEPS and full.max_time is None
    exact = pinlin.simulate(pendulum, [0.1, 0], [0, 0], t, estimate_error=False, max_steps=steps)
    np.testing.assert_array_equal(exact.q, full.q)  # the budget does not change the run
    with pytest.raises(IntegrationBudgetError, match=f"{steps - 1} steps used up") as info:
        pinlin.simulate(pendulum, [0.1, 0], [0, 0], t, estimate_error=False, max_steps=steps - 1)
    assert info.value.steps == steps - 1 and 0.0 < info.value.t_reached < 5.0


def test_comparison_run_has_its_own_budget_and_is_named(pendulum):
    t = np.linspace(0.0, 5.0, 6)
    steps = pinlin.simulate(pendulum, [0.1, 0], [0, 0], t, estimate_error=False).steps
    # the comparison run at rtol / 10 needs more steps than the run itself
    with pytest.raises(IntegrationBudgetError, match="comparison run for the error estimate"):
        pinlin.simulate(pendulum, [0.1, 0], [0, 0], t, max_steps=steps)


def test_wall_time_budget(pendulum):
    with pytest.raises(IntegrationBudgetError, match=r"max_time = 0.001 s used up|max_time = 0.001 s") as info:
        pinlin.simulate(pendulum, [0.1, 0], [0, 0], [0, 50], max_time=1e-3, max_steps=None)
    assert info.value.budget == "max_time" and info.value.elapsed >= 1e-3
    assert info.value.t_reached < 50


def test_no_limit_and_the_summary(pendulum):
    sim = pinlin.simulate(pendulum, [0.1, 0], [0, 0], np.linspace(0, 2, 5), max_steps=None, max_time=None)
    assert sim.max_steps is None and sim.steps > 0
    text = str(sim)  # printing a simulation shows its summary, not the numbers
    assert text == repr(sim) and text.startswith("Simulation(shape=(5, 2)") and f"steps={sim.steps}" in text
    assert "\n" not in text


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"max_steps": 0}, "max_steps: expected a positive integer, got 0"),
        ({"max_steps": -5}, "max_steps: expected a positive integer"),
        ({"max_steps": 2.5}, "max_steps: expected a positive integer, got 2.5"),
        ({"max_steps": True}, "max_steps: expected a positive integer, got True"),
        ({"max_steps": "100"}, "max_steps: expected a positive integer"),
        ({"max_time": 0.0}, "max_time: expected a finite positive number"),
        ({"max_time": -1.0}, "max_time: expected a finite positive number"),
        ({"max_time": float("nan")}, "max_time: expected a finite positive number"),
        ({"max_time": float("inf")}, "max_time: expected a finite positive number"),
        ({"max_time": "10"}, "max_time: expected a positive number"),
    ],
)
def test_bad_budgets_raise(pendulum, kwargs, match):
    with pytest.raises(pinlin.ParameterError, match=match):
        pinlin.simulate(pendulum, [0.1, 0], [0, 0], [0, 1], **kwargs)


def test_constrained_scenes_are_refused_not_integrated_as_open_trees():
    """Forward dynamics of the tree alone would silently drop the loop's forces."""
    robot = pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))
    loop = pinlin.PointConstraint("rocker_tip", (0.7, 0.0, 0.0), name="loop")
    scene = pinlin.Scene(robot, [pinlin.JointSpring("crank_joint", 50.0)], constraints=[loop])
    with pytest.raises(pinlin.ConstraintError, match="simulate integrates open trees only.*'loop'"):
        pinlin.simulate(scene, robot.neutral(), None, [0.0, 0.1])
