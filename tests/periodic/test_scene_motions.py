"""Periodic prescribed motions: Harmonic, FourierMotion, PeriodicMotion, the scene's
period (least common multiple, quasi-periodic refused), scene files, and linearize's refusal."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scene_cases import pivot_pendulum_urdf, pivot_scene

import pinlin
from pinlin.model.motions import common_period
from pinlin.model.scene_file import load_scene


def test_harmonic_values_and_derivatives():
    h = pinlin.Harmonic(0.02, -60.0, offset=0.1, phase=0.4)
    t = 0.0123
    assert h.q(t) == 0.1 + 0.02 * math.sin(-60.0 * t + 0.4)
    assert h.v(t) == 0.02 * -60.0 * math.cos(-60.0 * t + 0.4)
    assert h.a(t) == -0.02 * 3600.0 * math.sin(-60.0 * t + 0.4)
    assert h.period == 2 * math.pi / 60.0
    # the same motion as a checked PeriodicMotion (its derivatives pass the central-difference check)
    pinlin.PeriodicMotion(h.q, h.v, h.a, h.period)


def test_fourier_motion_against_its_series():
    f = pinlin.FourierMotion([0.1, 0.0, -0.03], [0.02, 0.05], omega=-3.0, offset=0.5)
    t = 0.77
    w = 3.0  # a negative omega folds into the sines
    q = 0.5 + 0.1 * math.cos(w * t) - 0.03 * math.cos(3 * w * t) - 0.02 * math.sin(w * t) - 0.05 * math.sin(2 * w * t)
    assert_allclose(f.q(t), q, rtol=1e-15)
    assert_allclose(f.period, 2 * math.pi / 3.0, rtol=1e-15)
    g = pinlin.PeriodicMotion(f.q, f.v, f.a, f.period)  # derivatives consistent
    assert_allclose(g.a(t), f.a(t), rtol=1e-15)


def test_periodic_motion_refuses_inconsistent_derivatives_and_bad_periods():
    with pytest.raises(pinlin.ParameterError, match="v.*disagrees with the central difference of q"):
        pinlin.PeriodicMotion(np.sin, lambda t: 1.01 * math.cos(t), lambda t: -math.sin(t), 2 * math.pi)
    with pytest.raises(pinlin.ParameterError, match="a.*disagrees with the central difference of v"):
        pinlin.PeriodicMotion(np.sin, np.cos, np.sin, 2 * math.pi)
    with pytest.raises(pinlin.ParameterError, match="does not repeat after T"):
        pinlin.PeriodicMotion(np.sin, np.cos, lambda t: -math.sin(t), 3.0)
    for bad in (0.0, -1.0, math.inf, math.nan):
        with pytest.raises(pinlin.ParameterError, match="period"):
            pinlin.PeriodicMotion(np.sin, np.cos, lambda t: -math.sin(t), bad)
    with pytest.raises(pinlin.ParameterError, match="not finite"):
        pinlin.PeriodicMotion(lambda t: math.nan, np.cos, np.sin, 1.0)
    with pytest.raises(pinlin.ParameterError, match="omega: must be nonzero"):
        pinlin.Harmonic(0.1, 0.0)
    with pytest.raises(pinlin.ParameterError, match="amplitude: must be finite"):
        pinlin.Harmonic(math.inf, 1.0)


def test_common_period_rule():
    assert_allclose(common_period({"a": 1.0, "b": 1.5}), 3.0, rtol=1e-15)
    assert_allclose(common_period({"a": 2 * math.pi / 2.0, "b": 2 * math.pi / 3.0}), 2 * math.pi, rtol=1e-15)
    assert common_period({}) is None
    assert_allclose(common_period({"a": 1.0, "b": 12.0 / 11.0}), 12.0, rtol=1e-14)
    with pytest.raises(pinlin.QuasiPeriodicError, match="'a'.*'b'.*quasi-periodic") as info:
        common_period({"a": 1.0, "b": math.sqrt(2.0)})
    assert info.value.periods == {"a": 1.0, "b": math.sqrt(2.0)}
    with pytest.raises(pinlin.QuasiPeriodicError):
        common_period({"a": 1.0, "b": 14.0 / 13.0})  # denominator 13 > 12


def test_scene_with_motions():
    scene = pivot_scene({"pivot_x": pinlin.Harmonic(0.01, 2.0), "pivot_z": pinlin.Harmonic(0.02, 3.0, phase=1.0)})
    assert set(scene.motions) == {"pivot_x", "pivot_z"} and dict(scene.prescribed) == {}
    assert scene.dof_names == ("swing",) and scene.n == 1
    assert_allclose(scene.motion_period, 2 * math.pi, rtol=1e-15)
    assert_allclose(pinlin.scene_period(scene), 2 * math.pi, rtol=1e-15)
    assert_allclose(scene.v0[:2], [0.02, 0.06 * math.cos(1.0)], rtol=1e-15)
    assert "Harmonic" in repr(scene)
    again = scene.replace(gravity=(0.0, 0.0, -1.0))
    assert set(again.motions) == {"pivot_x", "pivot_z"}
    with pytest.raises(pinlin.QuasiPeriodicError, match="quasi-periodic"):
        pivot_scene({"pivot_x": pinlin.Harmonic(0.01, 1.0), "pivot_z": pinlin.Harmonic(0.02, math.sqrt(2))})
    robot = pinlin.load_urdf_string(pivot_pendulum_urdf())
    with pytest.raises(pinlin.PrescribedJointError, match="constraints cannot have prescribed joint velocities or motions"):
        pinlin.Scene(robot, prescribed={"pivot_x": pinlin.Harmonic(0.01, 1.0)},
                     constraints=[pinlin.PointConstraint("bob1", [0.0, 0.0, -0.5])])


def test_constant_speed_joint_sets_a_period_only_when_the_equations_depend_on_it():
    robot = pinlin.load_urdf_string(pinlin.turntable_urdf())
    scene = pinlin.Scene(robot, prescribed={"table": 3.0})
    assert pinlin.scene_period(scene) is None  # proved invariant (a root joint along gravity)


def test_linearize_refuses_periodic_motions_naming_floquet():
    scene = pivot_scene({"pivot_z": pinlin.Harmonic(0.01, 30.0)})
    with pytest.raises(pinlin.TimePeriodicError, match="pinlin.floquet_analysis") as info:
        pinlin.linearize(scene, np.zeros(scene.model.nq))
    assert info.value.joint == "pivot_z" and "periodic_orbit" in str(info.value)


def test_scene_file_harmonics(tmp_path):
    spec = load_scene(pinlin.data_path("scenes/kapitza.toml"))
    motion = spec.scene.motions["pivot"]
    assert (motion.amplitude, motion.frequency, motion.offset, motion.phase) == (0.02, 200.0, 0.0, 0.0)
    orbit = pinlin.periodic_orbit(spec.scene, spec.q0)
    assert orbit.constant
    flo = pinlin.floquet_analysis(spec.scene, orbit)
    assert flo.stability.kind == "marginally_stable"  # Kapitza: upside down and stable
    urdf = tmp_path / "p.urdf"
    urdf.write_text(pivot_pendulum_urdf())
    for table, match in [("{ amplitude = 0.02 }", "prescribed.pivot_z.*omega"),
                         ("{ amplitude = 0.02, omega = 1.0, speed = 2 }", "prescribed.pivot_z.*speed"),
                         ("{ amplitude = 0.02, omega = 0.0 }", "prescribed.pivot_z.*omega"),
                         ("{ amplitude = 'x', omega = 1.0 }", "prescribed.pivot_z.*amplitude")]:
        f = tmp_path / "s.toml"
        f.write_text(f'[robot]\nurdf = "p.urdf"\n[prescribed]\npivot_x = 0.0\npivot_z = {table}\n')
        with pytest.raises(pinlin.SceneFileError, match=match):
            load_scene(f)
    f.write_text('[robot]\nurdf = "p.urdf"\n[prescribed]\npivot_x = 2.0\npivot_z = { amplitude = 0.1, omega = 5.0, phase = 0.5 }\n')
    scene = load_scene(f).scene
    assert scene.prescribed["pivot_x"] == 2.0 and scene.motions["pivot_z"].phase == 0.5


def test_batch_linearization_and_equilibrium_refuse_periodic_motions():
    scene = pivot_scene({"pivot_z": pinlin.Harmonic(0.01, 30.0)})
    q0 = np.zeros(scene.model.nq)
    with pytest.raises(pinlin.TimePeriodicError, match="pinlin.periodic_orbit"):
        pinlin.linearize_many(scene, [q0])
    with pytest.raises(pinlin.TimePeriodicError, match="pinlin.floquet_analysis"):
        pinlin.find_equilibrium(scene, q0)


@pytest.mark.parametrize("bad", ["0.02", True, None, [0.02]])
def test_motion_numbers_given_as_text_or_flags_are_refused(bad):
    with pytest.raises(pinlin.ParameterError, match="amplitude: expected a number"):
        pinlin.Harmonic(bad, 60.0)
    with pytest.raises(pinlin.ParameterError, match=r"cosines\[0\]: expected a number"):
        pinlin.FourierMotion([bad], omega=2.0)
    with pytest.raises(pinlin.ParameterError, match="period: expected a number"):
        pinlin.PeriodicMotion(math.sin, math.cos, lambda t: -math.sin(t), bad)


def test_motions_are_immutable_once_made():
    """A scene holding a motion is shared by threads: the motion cannot change under it."""
    motions = [pinlin.Harmonic(0.02, 60.0), pinlin.FourierMotion([0.1, 0.2], omega=3.0),
               pinlin.PeriodicMotion(math.sin, math.cos, lambda t: -math.sin(t), 2 * math.pi)]
    for m in motions:
        with pytest.raises(AttributeError, match="immutable"):
            m.period = 1.0
    with pytest.raises(ValueError, match="read-only"):
        motions[1].cosines[0] = 5.0
    assert motions[0].q(0.1) == 0.02 * math.sin(6.0)   # unchanged
