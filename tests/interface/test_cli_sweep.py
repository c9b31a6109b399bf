"""``pinlin sweep`` and the ``[sweep]`` table.

The reference is theory: double pendulum worked by hand: the double pendulum with follower
load P is marginally stable while det(K(P) - mu M) = 0 has two real positive
roots mu = -lam^2, and flutters past the load where its discriminant vanishes;
mpmath finds that load to 30 digits (P_f = 16.4328976483902282632... N for the
the theory's parameters).
"""

from __future__ import annotations

import json
import textwrap

import jsonschema
import mpmath as mp
import numpy as np
import pytest

import pinlin
from pinlin.cli import EXIT_INPUT, default_sweep_scene_path, main
from pinlin.model.scene_file import load_scene
from pinlin.report.sweep import SWEEP_SCHEMA, run_sweep, sweep_plan

#: theory: double pendulum parameters.
M1, L1, M2, L2, K1, G = "1.3", "0.7", "0.9", "0.5", 3, "9.81"
#: The flutter load of the bundled sweep, to the digits the search can reach (its bound is ~1e-12 N).
P_F = 16.4328976483902282632195634474


def discriminant(P, k2=2):
    """Discriminant of det(K_phi(P) - mu M_phi) = a mu^2 + b mu + c (theory: double pendulum; N_phi enters K_phi = S_phi + N_phi)."""
    m1, l1, m2, l2, g = (mp.mpf(x) for x in (M1, L1, M2, L2, G))
    M = mp.matrix([[(m1 / 3 + m2) * l1**2, m2 * l1 * l2 / 2], [m2 * l1 * l2 / 2, m2 * l2**2 / 3]])
    K = mp.matrix([[K1 + k2 + (m1 / 2 + m2) * g * l1 - P * l1, -k2 + P * l1], [-k2, k2 + m2 * g * l2 / 2]])
    b = -(K[0, 0] * M[1, 1] + K[1, 1] * M[0, 0] - K[0, 1] * M[1, 0] - K[1, 0] * M[0, 1])
    return b * b - 4 * mp.det(M) * mp.det(K)


def flutter_load(k2=2) -> float:
    with mp.workdps(30):
        return float(mp.findroot(lambda P: discriminant(P, mp.mpf(k2)), (0, 30), solver="anderson"))


def run(args, capsys):
    code = main(args)
    out = capsys.readouterr()
    assert "Traceback" not in out.err
    return code, out.out, out.err


def test_reference_flutter_load():
    assert flutter_load() == pytest.approx(P_F, rel=1e-15)


def test_sweep_of_the_bundled_double_pendulum_finds_the_flutter_load(capsys, tmp_path):
    code, out, err = run(["sweep", "--json", str(tmp_path / "s.json"), "--plot", str(tmp_path / "s.png")], capsys)
    assert code == 0, err
    doc = json.loads((tmp_path / "s.json").read_text())
    jsonschema.validate(doc, SWEEP_SCHEMA)
    assert doc["scene"]["source"] == str(default_sweep_scene_path().resolve())
    assert doc["parameters"] == [{"path": "follower.tip.force", "unit": "N", "values": list(np.linspace(0, 30, 31))}]
    (change,) = doc["changes"]
    boundary = change["boundary"]
    assert change["between"] == [16.0, 17.0] and change["verdicts"] == ["marginally_stable", "flutter"]
    assert boundary["kind"] == "flutter" and boundary["verified"]
    assert abs(boundary["value"] - flutter_load()) <= boundary["error_bound"] <= 1e-9
    # the verdict at every point agrees with the sign of the discriminant
    for point in doc["points"]:
        P = point["values"][0]
        assert point["verdict"] == ("marginally_stable" if discriminant(mp.mpf(P)) > 0 else "flutter")
    assert "flutter at follower.tip.force = 16.43289764839" in out and out.count("Verdict changes") == 1
    assert (tmp_path / "s.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert doc["tracked"]["error"] < 0.5 and len(doc["tracked"]["values"]) == 31


def write(tmp_path, sweep: str, name="scene.toml"):
    base = default_sweep_scene_path().read_text().split("[sweep]")[0].replace("../urdf/", "")
    path = tmp_path / name
    path.write_text(base + textwrap.dedent(sweep))
    return path


def test_stability_map_over_two_parameters(capsys, tmp_path):
    """Boundaries along P at each k2 against the discriminant's root."""
    path = write(tmp_path, """
        [sweep]
        parameter = "follower.tip.force"
        values = { start = 10.0, stop = 24.0, num = 8 }
        [sweep.second]
        parameter = "spring.joint2.stiffness"
        values = [1.5, 2.0, 2.5]
    """)
    code, out, err = run(["sweep", str(path), "--json", str(tmp_path / "m.json"), "--plot", str(tmp_path / "m.png")],
                         capsys)
    assert code == 0, err
    doc = json.loads((tmp_path / "m.json").read_text())
    jsonschema.validate(doc, SWEEP_SCHEMA)
    assert len(doc["points"]) == 24 and doc["tracked"] is None
    found = {c["second"]: c["boundary"] for c in doc["changes"]}
    assert sorted(found) == [1.5, 2.0, 2.5]
    for k2, boundary in found.items():
        assert abs(boundary["value"] - flutter_load(k2)) <= boundary["error_bound"] <= 1e-9
    assert "Verdicts: rows spring.joint2.stiffness [N m/rad]" in out
    rows = {float(line.split("|")[0]): line.split("|")[1].strip() for line in out.splitlines() if " | " in line}
    P = np.linspace(10.0, 24.0, 8)
    for k2, letters in rows.items():  # M below the flutter load, F above, from the discriminant's sign
        assert letters == "".join("M" if discriminant(mp.mpf(p), mp.mpf(k2)) > 0 else "F" for p in P)
    assert sorted(rows) == [1.5, 2.0, 2.5]


def test_failed_points_are_recorded_not_dropped(capsys, tmp_path):
    """A point the scene refuses (a negative spring) is a recorded failure, with its error, in the text too."""
    path = write(tmp_path, """
        [sweep]
        parameter = "spring.joint1.stiffness"
        values = [-1.0, 1.0, 3.0]
        boundaries = false
    """)
    spec = load_scene(path)
    outcome = run_sweep(sweep_plan(spec, spec.sweep))
    assert list(outcome.verdicts) == ["failed", "marginally_stable", "marginally_stable"]
    assert isinstance(outcome.modes[0], pinlin.studies.SweepFailure)
    assert "1 of 3 points failed" in outcome.notes[0]
    code, out, _ = run(["sweep", str(path)], capsys)
    assert code == 0 and "failed: ParameterError" in out and "stiffness" in out


def test_parameter_paths_set_the_scene():
    spec = load_scene(default_sweep_scene_path())

    def plan(parameter, **extra):
        return sweep_plan(spec, {"parameter": parameter, "values": [1.0, 2.0], **extra})

    follower = plan("follower.tip.force").scene_at([7.5]).elements[2]
    np.testing.assert_array_equal(follower.force, [0.0, 0.0, 7.5])  # along the scene's own line
    np.testing.assert_array_equal(plan("follower[1].force[0]").scene_at([2.0]).elements[2].force, [2.0, 0.0, 4.0])
    np.testing.assert_array_equal(plan("follower.tip.torque", direction=[0.0, 1.0, 0.0]).scene_at([3.0]).elements[2].torque,
                                  [0.0, 3.0, 0.0])
    assert plan("spring.joint2.stiffness").scene_at([5.0]).elements[1].stiffness == 5.0
    assert plan("spring.joint2.stiffness").parameters[0].unit == "N m/rad"
    np.testing.assert_allclose(plan("gravity").scene_at([3.0]).gravity, [0.0, 0.0, -3.0])
    rayleigh = plan("rayleigh.beta").scene_at([0.01]).elements[-1]
    assert (rayleigh.kind, rayleigh.alpha, rayleigh.beta) == ("rayleigh", 0.0, 0.01)
    two = sweep_plan(spec, {"parameter": "follower.tip.force", "values": [1.0],
                            "second": {"parameter": "spring.joint1.stiffness", "values": [4.0]}})
    scene = two.scene_at([2.0, 4.0])
    assert scene.elements[0].stiffness == 4.0 and scene.elements[2].force[2] == 2.0
    assert spec.scene.elements[2].force[2] == 4.0  # the spec's scene is unchanged


@pytest.mark.parametrize(
    "table, key, match",
    [
        ({"parameter": "follower.tip.force"}, "sweep.values", "expected a non-empty list"),
        ({"parameter": "follower.tip.force", "values": []}, "sweep.values", "expected a non-empty list"),
        ({"parameter": "follower.tip.force", "values": [1, "2"]}, r"sweep.values\[1\]", "expected a finite number"),
        ({"parameter": "follower.tip.force", "values": [1.0, float("nan")]}, r"sweep.values\[1\]", "finite"),
        ({"parameter": "follower.tip.force", "values": [1.0, 10**400]}, r"sweep.values\[1\]", "finite"),
        ({"parameter": "follower.tip.force", "values": {"start": 0, "stop": 1, "num": 10**6}}, "sweep.values.num",
         r"expected an integer in \[2, 10000\]"),
        ({"parameter": "follower.tip.force", "values": {"start": 0, "stop": 1}}, "sweep.values", "start = ..."),
        ({"parameter": "follower.tip.force", "values": [1.0], "colour": 1}, "sweep.colour", "unknown key"),
        ({"parameter": 3, "values": [1.0]}, "sweep.parameter", "expected a parameter path"),
        ({"parameter": "follower.base.force", "values": [1.0]}, "sweep.parameter", "no follower on frame 'base'"),
        ({"parameter": "follower[2].force", "values": [1.0]}, "sweep.parameter", "the scene has 1 follower"),
        ({"parameter": "follower.tip.colour", "values": [1.0]}, "sweep.parameter", "has no field 'colour'"),
        ({"parameter": "follower.tip.force[3]", "values": [1.0]}, "sweep.parameter", "entry 3 of a field with 3"),
        ({"parameter": "follower.tip.torque", "values": [1.0]}, "sweep.direction", "is zero in the scene"),
        ({"parameter": "follower.tip.force", "values": [1.0], "direction": [0, 0]}, "sweep.direction",
         r"expected \(3,\) finite numbers"),
        ({"parameter": "follower.tip.force", "values": [1.0], "direction": [0, 0, 10**400]}, "sweep.direction",
         "expected a list of numbers"),
        ({"parameter": "follower.tip.force", "values": [1.0], "direction": [0, "1", 1]}, "sweep.direction",
         "expected a list of numbers"),
        ({"parameter": "prescribed.knee", "values": [1.0]}, "sweep.parameter", "unknown joint 'knee'"),
        ({"parameter": "spring.stiffness", "values": [1.0]}, "sweep.parameter", "unknown parameter path"),
        ({"parameter": "gravity", "values": [1.0], "boundaries": "yes"}, "sweep.boundaries", "expected true or false"),
        ({"parameter": "gravity", "values": [1.0], "second": {"parameter": "gravity", "values": [2.0]}},
         "sweep.second.parameter", "the two parameters are the same"),
        ({"parameter": "gravity", "values": [1.0], "second": 5}, "sweep.second", "expected a table"),
        ({"parameter": "gravity", "values": list(range(200)), "second": {"parameter": "rayleigh.beta",
                                                                         "values": list(range(200))}},
         "sweep", "200 x 200 points; at most 10000"),
    ],
)
def test_bad_sweep_tables(table, key, match):
    spec = load_scene(default_sweep_scene_path())
    with pytest.raises(pinlin.SceneFileError, match=rf"\[{key}\] .*{match}"):
        sweep_plan(spec, table)


def test_sweep_options(capsys, tmp_path):
    code, out, err = run(["sweep", "--parameter", "spring.joint1.stiffness", "--values", "2,3,4", "--no-boundaries"],
                         capsys)
    assert code == 0, err
    assert "spring.joint1.stiffness [N m/rad]: 3 values from 2 to 4" in out
    code, _, err = run(["sweep", "--parameter", "spring.joint1.stiffness"], capsys)
    assert code == EXIT_INPUT and "--parameter and --values go together" in err
    code, _, err = run(["sweep", "--parameter", "spring.knee.stiffness", "--values", "1:2:3"], capsys)
    assert code == EXIT_INPUT and err.startswith("pinlin: error: --parameter: 'spring.knee.stiffness': no spring")
    code, _, err = run(["sweep", "--parameter", "gravity", "--values", "1:2"], capsys)
    assert code == EXIT_INPUT and "--values: expected START:STOP:NUM" in err
    (tmp_path / "plain.toml").write_text("[robot]\nurdf = 'double_pendulum.urdf'\n")
    code, out, err = run(["sweep", str(tmp_path / "plain.toml")], capsys)
    assert code == EXIT_INPUT and "[sweep] no [sweep] table" in err and out == ""


def test_stability_map_with_failed_points(capsys, tmp_path):
    """A row the scene refuses (a negative spring) is marked x in the text and drawn, with a note, in the map."""
    path = write(tmp_path, """
        [sweep]
        parameter = "follower.tip.force"
        values = [10.0, 20.0]
        [sweep.second]
        parameter = "spring.joint1.stiffness"
        values = [-1.0, 3.0]
    """)
    code, out, err = run(["sweep", str(path), "--plot", str(tmp_path / "m.png"), "--json", str(tmp_path / "m.json")],
                         capsys)
    assert code == 0, err
    rows = {line.split("|")[0].strip(): line.split("|")[1].strip() for line in out.splitlines() if " | " in line}
    assert rows == {"-1": "xx", "3": "MF"}
    doc = json.loads((tmp_path / "m.json").read_text())
    assert [p["verdict"] for p in doc["points"]] == ["failed", "marginally_stable", "failed", "flutter"]
    (change,) = doc["changes"]
    assert change["second"] == 3.0 and abs(change["boundary"]["value"] - flutter_load()) <= 1e-9
    assert (tmp_path / "m.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_sweep_help_prints_the_table_format(capsys):
    with pytest.raises(SystemExit) as info:
        main(["sweep", "--help"])
    assert info.value.code == 0
    out = capsys.readouterr().out
    assert "[sweep.second]" in out and "prescribed.<joint>" in out and "Exit codes" in out
