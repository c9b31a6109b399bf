"""The command line does what it says: options checked before anything is computed, every
file written named, the total time broken down, and the print artefacts gone."""

from __future__ import annotations

import json
import re
import time

import pytest

import pinlin
from pinlin.cli import EXIT_INPUT, EXIT_OK, main
from pinlin.report import command
from pinlin.report.command import Stopwatch, duration, plain_text

SCENES = pinlin.data_path("scenes/four_bar.toml").parent


def run(args, capsys):
    code = main([str(a) for a in args])
    out = capsys.readouterr()
    assert "Traceback" not in out.err
    return code, out.out, out.err


@pytest.fixture
def nothing_computed(monkeypatch):
    """Every analysis of the report fails the test if called (the report imports them by name)."""
    import pinlin.report.document as document

    def computed(*args, **kwargs):
        raise AssertionError("an analysis ran although an option was bad")

    for name in ("find_equilibrium", "linearize", "modal_analysis"):
        monkeypatch.setattr(document, name, computed)


def test_a_mode_beyond_the_system_fails_at_once_with_nothing_computed(capsys, tmp_path, nothing_computed):
    pytest.importorskip("PIL")
    gif = tmp_path / "a.gif"
    t0 = time.perf_counter()
    code, out, err = run(["analyze", "--animate", gif, "--mode", "9"], capsys)
    elapsed = time.perf_counter() - t0
    assert code == EXIT_INPUT and out == "" and not gif.exists()
    assert "--mode: expected a row of the mode table, 1 to 4 (2n for the scene's n = 2 coordinates), got 9" in err
    assert elapsed < 2.0  # the one timed check: refused at once, nothing computed (the fixture proves that)


def test_with_constraints_the_bound_is_checked_first_and_the_exact_count_after(capsys, tmp_path, monkeypatch):
    pytest.importorskip("PIL")
    four_bar = SCENES / "four_bar.toml"
    import pinlin.report.document as document

    calls = []
    real = document.linearize
    monkeypatch.setattr(document, "linearize", lambda *a, **k: calls.append(1) or real(*a, **k))
    code, out, err = run(["analyze", four_bar, "--animate", tmp_path / "a.gif", "--mode", "7"], capsys)
    assert code == EXIT_INPUT and "1 to at most 6 (2n for the scene's n = 3 coordinates), got 7" in err
    assert out == "" and calls == []
    code, out, err = run(["analyze", four_bar, "--animate", tmp_path / "a.gif", "--mode", "3"], capsys)
    assert code == EXIT_INPUT and "--mode: expected a row of the mode table, 1 to 2, got 3" in err
    assert calls == [1] and "Stability:" in out  # n - rank J_c = 1: known once linearized


@pytest.mark.parametrize("command", ["analyze", "sweep", "campbell"])
def test_bad_outputs_fail_before_anything_is_computed(command, capsys, tmp_path, nothing_computed):
    same = tmp_path / "out.svg"
    code, out, err = run([command, "--json", same, "--plot", same], capsys)
    assert code == EXIT_INPUT and out == ""
    assert f"--plot: {same} is also the file of --json: give each output its own file" in err
    code, _, err = run([command, "--json", tmp_path / "missing" / "r.json"], capsys)
    assert code == EXIT_INPUT and "--json: cannot write" in err and "does not exist" in err
    code, _, err = run([command, "--plot", tmp_path / "r.unknown"], capsys)
    assert code == EXIT_INPUT and "--plot: cannot write a figure as 'r.unknown'" in err


def test_analyze_names_every_file_it_writes_and_times_each(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    paths = {"--json": tmp_path / "r.json", "--plot": tmp_path / "r.png", "--animate": tmp_path / "m.html"}
    code, out, _ = run(["analyze", *[x for option, path in paths.items() for x in (option, path)], "--mode", "2"], capsys)
    assert code == EXIT_OK
    lines = out.splitlines()
    for path in paths.values():
        assert path.exists() and f"wrote {path}" in lines
    total = lines[-1]
    assert re.fullmatch(
        rf"Total [0-9.]+ m?s: checking options [0-9.<]+ m?s, loading [0-9.]+ m?s, analysis [0-9.]+ m?s, "
        rf"json {re.escape(str(paths['--json']))} [0-9.]+ m?s, plot {re.escape(str(paths['--plot']))} [0-9.]+ m?s, "
        rf"animate {re.escape(str(paths['--animate']))} [0-9.]+ m?s, other [0-9.<]+ m?s "
        rf"\(Python start-up and imports not included\)", total), total
    assert "Analysis " in out and "(equilibrium, linearization, modal analysis)" in out


def test_the_stopwatch_parts_and_other_sum_to_the_total(monkeypatch):
    ticks = iter([0.0, 1.0, 1.5, 2.0, 4.0, 10.0])  # start; part a 1.0-1.5; part b 2.0-4.0; summary at 10
    monkeypatch.setattr(command.time, "perf_counter", lambda: next(ticks))
    clock = Stopwatch()
    with clock.part("a"):
        pass
    with clock.part("b"):
        pass
    assert clock.parts == {"a": 0.5, "b": 2.0}
    assert clock.summary() == "Total 10 s: a 500 ms, b 2 s, other 7.5 s (Python start-up and imports not included)"
    assert (duration(2e-6), duration(0.0155), duration(7.52)) == ("<0.01 ms", "15.5 ms", "7.52 s")


def test_one_iteration_is_singular(capsys):
    code, out, _ = run(["analyze", SCENES / "turntable.toml"], capsys)
    assert code == EXIT_OK and "1 iteration," in out and "1 iterations" not in out


def test_the_four_bar_redundancy_note_is_printed_once(capsys):
    code, out, _ = run(["analyze", SCENES / "four_bar.toml"], capsys)
    assert code == EXIT_OK
    assert out.count("1 of the 3 constraint equations is redundant (rank J_c = 2)") == 1
    assert "1 coordinate z (" in out and "for 1 constraint (" in out


def test_sweep_writes_complex_numbers_with_i_as_analyze_does(capsys):
    code, out, _ = run(["sweep"], capsys)
    assert code == EXIT_OK
    assert re.search(r"lam = 0\+6\.22919i;", out), out
    assert not re.search(r"[0-9]j\b", out)
    code, out, _ = run(["analyze", SCENES / "double_pendulum_flutter.toml"], capsys)
    assert not re.search(r"[0-9]j\b", out)


@pytest.mark.parametrize("command", [[], ["analyze"], ["sweep"], ["campbell"]])
def test_help_is_plain_text(command, capsys):
    with pytest.raises(SystemExit) as info:
        main([*command, "--help"])
    assert info.value.code == 0
    out = capsys.readouterr().out
    assert "``" not in out and not re.search(r":(func|class|mod|data|meth):`", out)
    if not command:
        assert "campbell" in out


def test_plain_text_removes_the_markup():
    assert plain_text("``a.b`` and :func:`~pinlin.studies.track_modes`, :class:`pinlin.Modes`") == (
        "a.b and track_modes, pinlin.Modes")


CART_POLE = """<?xml version="1.0"?>
<robot name="cart_pole">
  <link name="ground"/>
  <link name="cart"><inertial><mass value="2.0"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/>
  </inertial></link>
  <joint name="cart" type="prismatic"><parent link="ground"/><child link="cart"/><axis xyz="1 0 0"/>
    <limit lower="-1e10" upper="1e10" effort="1e10" velocity="1e10"/></joint>
  <link name="pole"><inertial><origin xyz="0 0 -1"/><mass value="1.0"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="pole" type="continuous"><parent link="cart"/><child link="pole"/><axis xyz="0 1 0"/></joint>
</robot>
"""


def test_units_follow_the_joint_type(capsys, tmp_path):
    """A prismatic joint's speed is in m/s and its stiffness in N/m: a cart driven at 0.5 m/s under a pendulum."""
    (tmp_path / "cart_pole.urdf").write_text(CART_POLE)
    scene = tmp_path / "cart.toml"
    scene.write_text("[robot]\nurdf = 'cart_pole.urdf'\n[prescribed]\ncart = 0.5\n"
                     "[[spring]]\njoint = 'pole'\nstiffness = 2.0\n")
    code, out, _ = run(["analyze", scene, "--json", tmp_path / "r.json"], capsys)
    assert code == EXIT_OK and "prescribed velocities cart = 0.5 m/s" in out
    assert "n = 1: pole [rad]" in out and "S [N m/rad] =" in out
    report = json.loads((tmp_path / "r.json").read_text())
    assert report["scene"]["prescribed_units"] == {"cart": "m/s"}
    code, out, _ = run(["sweep", scene, "--parameter", "prescribed.cart", "--values", "0,1"], capsys)
    assert code == EXIT_OK and "prescribed.cart [m/s]" in out
    code, out, _ = run(["analyze", SCENES / "turntable.toml"], capsys)
    assert "prescribed velocities table = 2 rad/s" in out and "slider [m]" in out and "N/m (m, m)" in out
    code, out, _ = run(["sweep", SCENES / "turntable.toml", "--parameter", "spring.slider.stiffness",
                        "--values", "5,10"], capsys)
    assert code == EXIT_OK and "spring.slider.stiffness [N/m]" in out and "N m/rad" not in out
    with pytest.raises(SystemExit):
        main(["analyze", "--help"])
    assert "N/m on prismatic joints" in " ".join(capsys.readouterr().out.split())


def test_a_prismatic_prescribed_joint_is_measured_in_metres_when_refused(tmp_path):
    """The check of time invariance moves a prescribed slider by 1.0 m, not "1.0 rad"."""
    from pinlin.linearization.periodicity import PERIODIC_TEST_ANGLES

    robot = pinlin.load_urdf(str(pinlin.data_path("urdf/rotating_ring.urdf")))
    scene = pinlin.Scene(robot, [pinlin.JointSpring("ring", 2.0), pinlin.JointSpring("y", 10.0)],
                         prescribed={"x": 0.5})
    with pytest.raises(pinlin.TimePeriodicError, match=rf"prescribed joint 'x' \(relative change .* after "
                       rf"{PERIODIC_TEST_ANGLES[0]} m,"):
        pinlin.linearize(scene, scene.neutral())
