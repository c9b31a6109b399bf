"""The pinlin command line and the TOML scene format."""

import json
import subprocess
import sys
import textwrap

import jsonschema
import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.cli import EXIT_COMPUTATION, EXIT_INPUT, main
from pinlin.model.scene_file import default_scene_path, load_scene
from pinlin.numerics import definiteness
from pinlin.report import REPORT_SCHEMA, REPORT_VERSION, analyze, matrix_structure


def run(args, capsys):
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


def write(tmp_path, text, name="scene.toml"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return path


def test_default_scene_reports_the_paper_matrices(capsys, tmp_path):
    code, out, err = run(["analyze", "--json", str(tmp_path / "r.json")], capsys)
    assert code == 0, err
    assert "nonzero: M, S, N; zero: D, G" in out
    assert "15.8511" in out and "4.20725" in out and "1.4" in out
    report = json.loads((tmp_path / "r.json").read_text())
    jsonschema.validate(report, REPORT_SCHEMA)
    assert set(report) >= {"scene", "equilibrium", "linearization", "elapsed", "pinlin_version"}
    assert report["report_version"] == REPORT_VERSION == 2
    lin = report["linearization"]
    assert lin["nonzero"] == ["M", "S", "N"]
    assert_allclose(lin["N"], [[0, 1.4], [-1.4, 0]], rtol=1e-12)
    assert report["scene"]["dof_names"] == ["joint1", "joint2"]
    assert report["equilibrium"]["residual"] == 0.0


def test_console_script_runs_without_arguments():
    proc = subprocess.run([sys.executable, "-m", "pinlin.cli", "analyze"], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert "double_pendulum" in proc.stdout


def test_help_documents_the_scene_format(capsys):
    with pytest.raises(SystemExit) as info:
        main(["analyze", "--help"])
    assert info.value.code == 0
    out = capsys.readouterr().out
    assert "[[spring]]" in out and "[prescribed]" in out and "Exit codes" in out


def test_toml_scene_with_every_element(tmp_path, capsys):
    path = write(
        tmp_path,
        """
        [robot]
        urdf = "chain.urdf"
        [scene]
        gravity = [0.0, 0.0, -9.81]
        [[spring]]
        joint = "joint1"
        stiffness = 40.0
        [[spring]]
        joint = "joint2"
        stiffness = 30.0
        rest = 0.0
        [[damper]]
        joint = "joint2"
        damping = 0.5
        [rayleigh]
        beta = 0.01
        [[follower]]
        frame = "tip"
        force = [0.0, 0.0, 2.0]
        [[dead]]
        frame = "tip"
        force = [0.0, 0.0, -1.0]
        [start]
        joints = { joint1 = 0.05 }
        """,
    )
    (tmp_path / "chain.urdf").write_text(pinlin.pendulum_chain_urdf(2))
    spec = load_scene(path)
    assert [e.kind for e in spec.scene.elements] == ["spring", "spring", "damper", "follower", "dead", "rayleigh"]
    assert_allclose(spec.q0, [0.05, 0.0])
    code, out, err = run(["analyze", str(path)], capsys)
    assert code == 0, err
    assert "nonzero: M, D, S, N" in out


def test_turntable_scene_file(capsys):
    code, out, err = run(["analyze", str(pinlin.data_path("scenes/turntable.toml"))], capsys)
    assert code == 0, err
    assert "nonzero: M, G, S" in out
    assert "0.833333" in out  # r0 = (k l0 + m W^2 a) / (k - m W^2)


def test_example_robot(capsys, tmp_path):
    code, out, err = run(["analyze", "--example", "ur5", "--json", str(tmp_path / "u.json")], capsys)
    assert code == 0, err
    report = json.loads((tmp_path / "u.json").read_text())
    jsonschema.validate(report, REPORT_SCHEMA)
    assert report["scene"]["n"] == 6
    S = np.array(report["linearization"]["S"])
    assert np.all(np.linalg.eigvalsh(S) > 900)  # 1000 N m/rad springs, softened a little by gravity


def test_floating_example_is_held_by_balancing(capsys):
    code, out, err = run(["analyze", "--example", "solo12"], capsys)
    assert code == 0, err
    assert "held by constant actuator forces" in out


@pytest.mark.parametrize(
    "text, match",
    [
        ("[robot]\nurdf = 'missing.urdf'\n", r"\[robot.urdf\] URDF file not found"),
        ("[robot\n", "invalid TOML"),
        ("[robot]\nurdf = 'double_pendulum.urdf'\n[colour]\n", r"\[colour\] unknown key"),
        ("[scene]\ngravity = [0, 0, -9.81]\n", r"\[robot\] missing the \[robot\] table"),
        ("[robot]\nurdf = 'double_pendulum.urdf'\nexample = 'ur5'\n", "exactly one of"),
        ("[robot]\nurdf = 'double_pendulum.urdf'\n[[spring]]\njoint = 'knee'\nstiffness = 1.0\n", r"\[spring\[1\]\] unknown joint 'knee'"),
        ("[robot]\nurdf = 'double_pendulum.urdf'\n[[spring]]\njoint = 'joint1'\nstiffness = 'hard'\n", r"\[spring\[1\].stiffness\] expected a number"),
        ("[robot]\nurdf = 'double_pendulum.urdf'\n[[spring]]\njoint = 'joint1'\n", r"\[spring\[1\].stiffness\] missing required key"),
        ("[robot]\nurdf = 'double_pendulum.urdf'\n[[spring]]\njoint = 'joint1'\nstiffness = -2.0\n", r"\[spring\[1\]\].*non-negative"),
        ("[robot]\nurdf = 'double_pendulum.urdf'\n[[damper]]\njoint = 'joint1'\ndamping = 1\nextra = 2\n", r"\[damper\[1\].extra\] unknown key"),
        ("[robot]\nurdf = 'double_pendulum.urdf'\n[spring]\njoint = 'joint1'\n", r"\[spring\] use \[\[spring\]\]"),
        ("[robot]\nurdf = 'double_pendulum.urdf'\n[start]\nq = [0.0]\n", r"\[start.q\] expected 2 numbers"),
        ("[robot]\nurdf = 'double_pendulum.urdf'\n[start]\nreference = 'home'\n", r"\[start.reference\] unknown reference"),
        ("[robot]\nurdf = 'double_pendulum.urdf'\n[start]\nequilibrium = true\nbalancing = true\n", "exclude each other"),
        ("[robot]\nurdf = 'double_pendulum.urdf'\n[prescribed]\njoint1 = 'fast'\n", r"\[prescribed.joint1\] expected a finite number, got 'fast'"),
        ("[robot]\nurdf = 'double_pendulum.urdf'\n[scene]\ngravity = [0, 0]\n", r"\[scene\] gravity: expected 3 numbers"),
        ("[robot]\nurdf = 'double_pendulum.urdf'\n[rayleigh]\nalpha = -1.0\n", r"\[rayleigh\].*alpha"),
        ("[robot]\nurdf = 'double_pendulum.urdf'\nlocked = 3\n", r"\[robot.locked\] expected a list"),
    ],
)
def test_bad_scene_files(tmp_path, capsys, text, match):
    path = write(tmp_path, text)
    with pytest.raises(pinlin.SceneFileError, match=match):
        load_scene(path)
    code, out, err = run(["analyze", str(path)], capsys)
    assert code == EXIT_INPUT
    assert err.startswith("pinlin: error:") and "Traceback" not in err
    assert str(path) in err


def test_missing_scene_file(tmp_path, capsys):
    code, _, err = run(["analyze", str(tmp_path / "none.toml")], capsys)
    assert code == EXIT_INPUT and "scene file not found" in err


def test_failed_computation_exit_code(tmp_path, capsys):
    """A floating chain under gravity has no equilibrium: a failed computation, not bad input."""
    (tmp_path / "chain.urdf").write_text(pinlin.pendulum_chain_urdf(2, radius=0.05))
    path = write(tmp_path, "[robot]\nurdf = 'chain.urdf'\nfree_flyer = true\n")
    code, _, err = run(["analyze", str(path)], capsys)
    assert code == EXIT_COMPUTATION
    assert "computation failed" in err and "Traceback" not in err


def test_bad_cli_arguments(capsys):
    assert run(["analyze", "--example", "r2d2"], capsys)[0] == EXIT_INPUT
    assert run(["analyze", "--example", "ur5", "--stiffness", "-1"], capsys)[0] == EXIT_INPUT
    code, _, err = run(["analyze", "scene.toml", "--example", "ur5"], capsys)
    assert code == EXIT_INPUT and "not both" in err


def test_report_modes_and_verdict(tmp_path, capsys):
    """Default scene: undamped, circulatory, below flutter: lam^2 are the eigenvalues of -M^-1 K (theory: double pendulum)."""
    code, out, err = run(["analyze", "--json", str(tmp_path / "r.json")], capsys)
    assert code == 0, err
    report = json.loads((tmp_path / "r.json").read_text())
    T = np.array([[1.0, 0.0], [1.0, 1.0]])
    m1, l1, m2, l2, k1, k2, P, g = 1.3, 0.7, 0.9, 0.5, 3.0, 2.0, 4.0, 9.81
    M = T.T @ np.array([[(m1 / 3 + m2) * l1**2, m2 * l1 * l2 / 2], [m2 * l1 * l2 / 2, m2 * l2**2 / 3]]) @ T
    K = T.T @ np.array([[k1 + k2 + (m1 / 2 + m2) * g * l1 - P * l1, -k2 + P * l1], [-k2, k2 + m2 * g * l2 / 2]]) @ T
    mu = np.linalg.eigvals(-np.linalg.solve(M, K))  # real negative below the flutter load
    expected = np.sort(np.sqrt(-mu.real))
    imag = np.array(report["modes"]["eigenvalues"]["im"])
    assert_allclose(np.sort(imag[imag > 0]), expected, rtol=1e-12)
    assert_allclose(report["modes"]["eigenvalues"]["re"], 0.0, atol=1e-12)
    assert report["stability"]["kind"] == "marginally_stable"
    assert max(report["modes"]["backward_error"]) < 1e-14
    assert "Stability: MARGINALLY STABLE" in out and "eta" in out and "kappa" in out


@pytest.mark.parametrize(
    "scene, verdict",
    [("scenes/rotating_ring.toml", "asymptotically_stable"), ("scenes/turntable.toml", "marginally_stable")],
)
def test_bundled_scene_verdicts(scene, verdict, tmp_path, capsys):
    code, _, err = run(["analyze", str(pinlin.data_path(scene)), "--json", str(tmp_path / "r.json")], capsys)
    assert code == 0, err
    assert json.loads((tmp_path / "r.json").read_text())["stability"]["kind"] == verdict


def test_plot_file_is_written(tmp_path, capsys):
    target = tmp_path / "report.png"
    code, _, err = run(["analyze", "--plot", str(target)], capsys)
    assert code == 0, err
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    code, _, err = run(["analyze", "--plot", str(tmp_path / "no" / "dir.png")], capsys)
    assert code == EXIT_INPUT and "cannot write" in err


def test_schema_rejects_a_broken_report(tmp_path, capsys):
    run(["analyze", "--json", str(tmp_path / "r.json")], capsys)
    report = json.loads((tmp_path / "r.json").read_text())
    report["stability"]["kind"] = "stable-ish"
    with pytest.raises(jsonschema.ValidationError, match="stable-ish"):
        jsonschema.validate(report, REPORT_SCHEMA)


def test_report_sections_are_the_results_to_dict(capsys):
    """Version 2: each section is its result's to_dict() (docs/conventions.md), plus report-only keys."""
    report, sys_, modes = analyze(load_scene(default_scene_path()))
    assert json.loads(json.dumps(report, allow_nan=False)) == report
    jsonschema.validate(report, REPORT_SCHEMA)
    for section, result, extra in [
        ("linearization", sys_, {"nonzero", "structure"}),
        ("modes", modes, {"method_reason", "table"}),
        ("stability", modes.stability, set()),
    ]:
        expected = result.to_dict()
        assert set(report[section]) == set(expected) | extra
        for key in ("type", "method", "error"):
            assert report[section][key] == expected[key]
    assert report["modes"]["error"] == float(np.max(modes.backward_error))  # Modes.error: the largest eta
    assert report["modes"]["method_reason"] == modes.method.reason
    assert report["equilibrium"]["type"] == "EquilibriumResult"
    assert report["equilibrium"]["residual"] == 0.0


@pytest.mark.parametrize("small", [1e-12, 1e-15, 1e-17, 0.0, -1e-17, -1e-15, -1e-12])
def test_report_structure_agrees_with_the_verdicts_structure(small):
    """One definiteness decision (pinlin.numerics.definiteness), the one modes.structure and the stability
    theorems use: near the semidefinite boundary (S with eigenvalues 1 and ``small``) the report cannot
    disagree with the verdict.  pinlin 0.1's report had its own test (n eps ||S|| instead of the verdict's
    1e-10 ||S||) and called S with eigenvalues 1 and 1e-12 positive definite where modes.structure said
    semidefinite."""
    Q = np.array([[1.0, 1.0], [-1.0, 1.0]]) / np.sqrt(2)
    S = Q @ np.diag([1.0, small]) @ Q.T
    sys_ = pinlin.LinearizedSystem.from_matrices(np.diag([2.0, 1.0]), 0.1 * np.eye(2), S)
    modes = pinlin.modal_analysis(sys_)
    structure = matrix_structure(modes)
    assert structure["S"]["kind"] == modes.structure.stiffness
    assert structure["D"]["kind"] == modes.structure.damping == "positive_definite"
    for name in ("M", "D", "S"):
        assert structure[name] == definiteness(getattr(sys_, name), modes.structure.uncertainty).to_dict()
    assert sum(structure["S"][k] for k in ("negative", "zero", "positive")) == 2
    assert_allclose(structure["S"]["max_eigenvalue"], 1.0, rtol=1e-14)
    assert_allclose(structure["M"]["min_eigenvalue"], 1.0, rtol=1e-14)
    with pytest.raises(pinlin.ParameterError, match="modes: has no definiteness of M, D, S"):
        matrix_structure(pinlin.modal_analysis((np.eye(2), 0.1 * np.eye(2), S)))


def test_schema_version_is_checked(tmp_path, capsys):
    run(["analyze", "--json", str(tmp_path / "r.json")], capsys)
    report = json.loads((tmp_path / "r.json").read_text())
    report["report_version"] = 1
    with pytest.raises(jsonschema.ValidationError, match="2 was expected"):
        jsonschema.validate(report, REPORT_SCHEMA)
    del report["modes"]["error"]
    report["report_version"] = 2
    with pytest.raises(jsonschema.ValidationError, match="'error' is a required property"):
        jsonschema.validate(report, REPORT_SCHEMA)


@pytest.mark.parametrize("precision", ["0", "-5", "18"])
def test_bad_precision(capsys, precision):
    code, out, err = run(["analyze", "--precision", precision], capsys)
    assert code == EXIT_INPUT and f"--precision: must be 1 to 17 significant digits, got {precision}" in err
    assert out == "" and "Traceback" not in err  # refused before computing
