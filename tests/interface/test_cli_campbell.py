"""``pinlin campbell``: frequencies, damping and critical speeds against a prescribed speed.

Acceptance: on the bundled rotating ring (theory: rotating ring; Example 11.1) the critical
speed is found to 1e-10 against its closed form.  In the ring's frame the
particle (mass m, springs k on x and y, dampers c) obeys, with z = x + i y,

    m z'' + (c + 2 i m Omega) z' + (k - m Omega^2) z = 0,

whose constant term changes sign at Omega_c = sqrt(k / m): below it every
eigenvalue has Re lam < 0, above it one branch grows (the rotating damping
destabilizes).  m is read from the URDF (the particle link; the ring itself is
prescribed), k and c from the scene file.
"""

from __future__ import annotations

import json
import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import tomllib
from numpy.testing import assert_allclose

import pinlin
from pinlin.cli import EXIT_INPUT, EXIT_OK, main

RING = pinlin.data_path("scenes/rotating_ring.toml")
#: Tolerance of the acceptance test on the critical speed [rad/s].
CRITICAL_SPEED_ATOL = 1e-10


def ring_parameters() -> tuple[float, float, float]:
    """(m, k, c) of the bundled rotating ring: m from its URDF, k and c from its scene file."""
    scene = tomllib.loads(RING.read_text())
    urdf = ET.parse(RING.parent / scene["robot"]["urdf"]).getroot()
    m = float(urdf.find("./link[@name='particle']/inertial/mass").get("value"))
    (k,) = {s["stiffness"] for s in scene["spring"]}  # the same spring on x and y
    (c,) = {d["damping"] for d in scene["damper"]}
    return m, k, c


def run(args, capsys):
    code = main([str(a) for a in args])
    out = capsys.readouterr()
    assert "Traceback" not in out.err
    return code, out.out, out.err


def test_the_critical_speed_of_the_rotating_ring_matches_the_closed_form(capsys, tmp_path):
    m, k, c = ring_parameters()
    closed_form = math.sqrt(k / m)
    code, out, _ = run(["campbell", RING, "--json", tmp_path / "c.json"], capsys)
    assert code == EXIT_OK
    doc = json.loads((tmp_path / "c.json").read_text())
    (critical,) = doc["campbell"]["critical_speeds"]
    assert abs(critical["speed"] - closed_form) <= CRITICAL_SPEED_ATOL
    assert float(critical["error_bound"]) <= CRITICAL_SPEED_ATOL and critical["verified"]
    assert critical["verdicts"] == ["asymptotically_stable", "flutter"]
    assert f"{critical['speed']:.15g} +- " in out and "Critical speeds" in out
    assert f"wrote {tmp_path / 'c.json'}" in out


def test_the_tracked_frequencies_and_damping_match_the_closed_form(capsys, tmp_path):
    m, k, c = ring_parameters()
    code, _, _ = run(["campbell", "--speeds", "0:6:25", "--json", tmp_path / "c.json"], capsys)  # default scene
    assert code == EXIT_OK
    section = json.loads((tmp_path / "c.json").read_text())["campbell"]
    assert section["joint"] == "ring" and section["unit"] == "rad/s"
    speeds = np.array(section["speeds"])
    assert_allclose(speeds, np.linspace(0, 6, 25), rtol=0, atol=0)
    got = np.array([[b["frequency"] for b in section["branches"]], [b["damping_ratio"] for b in section["branches"]]])
    for i, omega in enumerate(speeds):
        # one root of each conjugate pair: the two roots of the complex quadratic in z
        roots = np.roots([m, c + 2j * m * omega, k - m * omega**2])
        want = sorted((abs(r.imag), -r.real / abs(r)) for r in roots)
        have = sorted(zip(got[0, :, i], got[1, :, i]))
        assert_allclose(have, want, rtol=1e-10, atol=1e-12)


def test_the_joint_and_speeds_options_replace_the_table(capsys, tmp_path):
    code, out, _ = run(["campbell", RING, "--joint", "ring", "--speeds", "1,2,4", "--plot", tmp_path / "c.png"], capsys)
    assert code == EXIT_OK and "3 values from 1 to 4" in out and (tmp_path / "c.png").stat().st_size > 0
    assert f"wrote {tmp_path / 'c.png'}" in out and out.splitlines()[-1].startswith("Total ")
    assert "campbell " in out.splitlines()[-1]  # the study's own part of the total


def test_no_critical_speed_in_range_is_said(capsys):
    code, out, _ = run(["campbell", RING, "--speeds", "0:2:5"], capsys)
    assert code == EXIT_OK and "Critical speeds: none in the range of speeds" in out


def test_a_change_at_the_edge_of_the_range_keeps_its_honest_bound(capsys, tmp_path):
    """The turntable (theory: turntable) at rest has a free arm (lam = 0: divergence) and is gyroscopically stable at
    any spin: the verdict changes right after 0, and the reported speed's error bound reaches back to 0."""
    code, _, _ = run(["campbell", pinlin.data_path("scenes/turntable.toml"), "--speeds", "0:3:7",
                      "--json", tmp_path / "t.json"], capsys)
    assert code == EXIT_OK
    section = json.loads((tmp_path / "t.json").read_text())["campbell"]
    (first,) = section["critical_speeds"]
    assert section["joint"] == "table" and first["verdicts"] == ["divergence", "marginally_stable"]
    assert first["speed"] - float(first["error_bound"]) <= 1e-12 and first["between"] == [0.0, 0.5]


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--joint", "x"], r"--joint: expected a prescribed joint of the scene \(\['ring'\]\), got 'x'"),
        (["--speeds", "1"], r"--speeds: expected at least two speeds"),
        (["--speeds", "0:1:1"], r"--speeds: num: expected an integer in \[2, 10000\], got 1"),
        (["--speeds", "0:1:100000"], r"--speeds: num: expected an integer in \[2, 10000\], got 100000"),
        (["--speeds", "1,3,2"], r"--speeds: must be strictly increasing or strictly decreasing"),
        (["--speeds", "a:b"], r"--speeds: expected START:STOP:NUM or a comma-separated list of numbers, got 'a:b'"),
        (["--speeds", "0,nan"], r"--speeds: expected a finite number, got nan"),
    ],
)
def test_bad_options_are_named(args, message, capsys, monkeypatch):
    import pinlin.report.sweep.run as run_module

    monkeypatch.setattr(run_module, "modal_analysis", lambda *a, **k: pytest.fail("computed"))
    code, out, err = run(["campbell", RING, *args], capsys)
    assert code == EXIT_INPUT and out == ""
    assert re.search(message, err), err


@pytest.mark.parametrize(
    ("table", "key", "message"),
    [
        ("[campbell]\njoint = 'ring'\n", "campbell.speeds", "no speeds: give --speeds"),
        ("[campbell]\nspeeds = [0.0, 1.0]\nspeed = 3\n", "campbell.speed", "unknown key"),
        ("[campbell]\njoint = 'x'\nspeeds = [0.0, 1.0]\n", "campbell.joint", "expected a prescribed joint"),
        ("[campbell]\nspeeds = { start = 0.0, stop = 1.0 }\n", "campbell.speeds", "expected { start"),
        ("[campbell]\nspeeds = [0.0, true]\n", "campbell.speeds", "expected a finite number, got True"),
    ],
)
def test_a_bad_campbell_table_names_the_file_and_key(table, key, message, capsys, tmp_path):
    text = RING.read_text().split("[campbell]")[0].replace('"../urdf/rotating_ring.urdf"', '"rotating_ring.urdf"')
    path = tmp_path / "ring.toml"
    path.write_text(text + table)
    code, out, err = run(["campbell", path], capsys)
    assert code == EXIT_INPUT and out == ""
    assert str(path) in err and key in err and message in err, err
    if key != "campbell.speeds" or "no speeds" not in message:  # analyze checks the table it does not use
        code, out, err = run(["analyze", path], capsys)
        assert code == EXIT_INPUT and out == "" and key in err, err


def test_a_scene_without_a_prescribed_joint_is_refused(capsys):
    code, _, err = run(["campbell", pinlin.data_path("scenes/double_pendulum.toml"), "--speeds", "0:1:3"], capsys)
    assert code == EXIT_INPUT
    assert "campbell.joint" in err and "the scene prescribes no joint" in err
