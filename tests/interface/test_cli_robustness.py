"""The command line never crashes, hangs or lies on bad input.

Each test drives :func:`pinlin.cli.main` (or the scene-file reader) with one
bad input and checks the exit code (2 bad input, 3 failed
computation, never 1), the one-line message naming what was wrong, and what
was or was not computed and written.
"""

from __future__ import annotations

import json
import os
import re
import sys
import textwrap

import jsonschema
import pytest

import pinlin
from pinlin.cli import EXIT_COMPUTATION, EXIT_INPUT, EXIT_OK, main
from pinlin.model.scene_file import load_scene
from pinlin.report import REPORT_SCHEMA, analyze
from pinlin.report.sweep import sweep_plan

DP = "[robot]\nurdf = 'double_pendulum.urdf'\n"
SPRINGS = "[[spring]]\njoint = 'joint1'\nstiffness = 3.0\n[[spring]]\njoint = 'joint2'\nstiffness = 2.0\n"


def run(args, capsys):
    code = main(args)
    out = capsys.readouterr()
    assert "Traceback" not in out.err
    return code, out.out, out.err


def write(tmp_path, text, name="scene.toml"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return path


# ---------------------------------------------------------------- item 8: options checked before computing


def test_unsupported_plot_format_is_refused_before_computing(capsys, tmp_path):
    code, out, err = run(["analyze", "--plot", str(tmp_path / "out.xyz"), "--json", str(tmp_path / "r.json")], capsys)
    assert code == EXIT_INPUT
    assert "--plot: cannot write a figure as 'out.xyz': the suffix must name a format" in err and "png" in err
    assert out == "" and not (tmp_path / "r.json").exists()  # nothing was computed


@pytest.mark.parametrize(
    "option, path, match",
    [
        ("--plot", "no/dir/r.png", "--plot: cannot write .*: the directory .* does not exist"),
        ("--plot", "figure", "--plot: cannot write a figure as 'figure'"),
        ("--json", "no/dir/r.json", "--json: cannot write .*: the directory .* does not exist"),
        ("--json", ".", "--json: . is a directory"),
        ("--animate", "mode.xyz", "--animate: cannot write an animation as 'mode.xyz'"),
    ],
)
def test_bad_output_paths_are_refused_before_computing(capsys, tmp_path, monkeypatch, option, path, match):
    monkeypatch.chdir(tmp_path)
    code, out, err = run(["analyze", option, path], capsys)
    assert code == EXIT_INPUT and out == ""
    assert re.search(match, err), err


def test_plot_without_matplotlib_is_refused_before_computing(capsys, tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # `import matplotlib` now raises ImportError
    code, out, err = run(["analyze", "--plot", str(tmp_path / "r.png")], capsys)
    assert code == EXIT_INPUT and "--plot needs matplotlib: pip install 'pinlin[plot]'" in err
    assert out == ""
    code, out, err = run(["sweep", "--plot", str(tmp_path / "s.png")], capsys)
    assert code == EXIT_INPUT and "--plot needs matplotlib" in err and out == ""


def test_a_failed_figure_loses_neither_the_report_nor_the_json(capsys, tmp_path):
    """Writing the figure fails only after the analysis (a full disk): the text and the JSON are out first."""
    if not os.path.exists("/dev/full"):
        pytest.skip("needs /dev/full to make a write fail")
    figure = tmp_path / "r.png"
    figure.symlink_to("/dev/full")
    code, out, err = run(["analyze", "--json", str(tmp_path / "r.json"), "--plot", str(figure)], capsys)
    assert code == EXIT_INPUT and "--plot: cannot write" in err
    assert "Stability: MARGINALLY STABLE" in out
    jsonschema.validate(json.loads((tmp_path / "r.json").read_text()), REPORT_SCHEMA)


def test_a_bad_mode_row_fails_before_anything_is_computed(capsys, tmp_path):
    code, out, err = run(["analyze", "--json", str(tmp_path / "r.json"), "--animate", str(tmp_path / "m.gif"),
                          "--mode", "5"], capsys)
    assert code == EXIT_INPUT and "--mode: expected a row of the mode table, 1 to 4 (2n for the scene's n = 2" in err
    assert out == "" and not (tmp_path / "r.json").exists() and not (tmp_path / "m.gif").exists()
    code, out, err = run(["analyze", "--mode", "1"], capsys)
    assert code == EXIT_INPUT and "--mode: chooses the mode of --animate" in err and out == ""
    code, out, err = run(["analyze", "--animate", str(tmp_path / "m.gif"), "--mode", "0"], capsys)
    assert code == EXIT_INPUT and "--mode: expected a row of the mode table (1, 2, ...), got 0" in err and out == ""


def test_toml_nested_500_deep_is_bad_input(capsys, tmp_path):
    path = write(tmp_path, DP + "[scene]\ngravity = " + "[" * 500 + "]" * 500 + "\n")
    with pytest.raises(pinlin.SceneFileError, match="invalid TOML: arrays or tables nested too deeply"):
        load_scene(path)
    code, _, err = run(["analyze", str(path)], capsys)
    assert code == EXIT_INPUT and str(path) in err


@pytest.mark.parametrize("mass", [1e-300, 1e300])
def test_extreme_link_masses_give_a_report_or_a_clear_failure(capsys, tmp_path, mass):
    """Every link of mass 1e-300 (M ~ 1e-302) or 1e300: an answer or exit code 2/3, never a traceback."""
    (tmp_path / "chain.urdf").write_text(pinlin.pendulum_chain_urdf(2, mass=mass, tip_frame=True))
    path = write(tmp_path, "[robot]\nurdf = 'chain.urdf'\n" + SPRINGS)
    code, out, err = run(["analyze", str(path), "--json", str(tmp_path / "r.json")], capsys)
    assert code in (EXIT_OK, EXIT_INPUT, EXIT_COMPUTATION), err
    if code == EXIT_OK:
        report = json.loads((tmp_path / "r.json").read_text())
        jsonschema.validate(report, REPORT_SCHEMA)
        assert "Stability:" in out
    else:
        assert err.startswith("pinlin: ") and err.count("\n") == 1


# ---------------------------------------------------------------- item 9: errors name the file and the key


@pytest.mark.parametrize(
    "text, key, cause",
    [
        (DP + SPRINGS + "[start]\nq = [0.3, 0.0]\nequilibrium = false\n", r"\[start\] q is not an equilibrium",
         pinlin.NotAnEquilibriumError),
        ("[robot]\nurdf = 'massless.urdf'\n[[spring]]\njoint = 'joint2'\nstiffness = 3.0\n",
         r"\[robot\] the mass matrix is singular.*'joint2'", pinlin.SingularMassError),
    ],
)
def test_analysis_errors_name_the_scene_file_and_key(capsys, tmp_path, text, key, cause):
    urdf = pinlin.pendulum_chain_urdf(2, tip_frame=True)
    start = urdf.index('<link name="link2">')
    (tmp_path / "massless.urdf").write_text(urdf[:start] + '<link name="link2"/>' + urdf[urdf.index("</link>", start) + 7:])
    path = write(tmp_path, text)
    with pytest.raises(pinlin.SceneFileError, match=key) as info:
        analyze(load_scene(path))
    assert isinstance(info.value.__cause__, cause) and info.value.path == str(path)
    code, out, err = run(["analyze", str(path)], capsys)
    assert code == EXIT_INPUT and err.startswith(f"pinlin: error: {path}: [") and out == ""


def test_a_time_periodic_scene_is_blamed_in_the_steady_report_and_analysed_by_floquet_in_the_cli(capsys, tmp_path):
    """The steady report refuses it naming [prescribed.joint1]; the CLI runs the periodic path instead
    (theory: Floquet), whose shooting finds no periodic motion of the spun double pendulum near q = 0 and says so."""
    path = write(tmp_path, DP + "[prescribed]\njoint1 = 2.0\n[start]\nequilibrium = false\n")
    with pytest.raises(pinlin.SceneFileError, match=r"\[prescribed.joint1\] the linearized equations depend on "
                       r"the position of prescribed joint 'joint1'.*pinlin.floquet_analysis") as info:
        analyze(load_scene(path))
    assert isinstance(info.value.__cause__, pinlin.TimePeriodicError)
    code, out, err = run(["analyze", str(path)], capsys)
    assert code == EXIT_COMPUTATION and err.startswith(f"pinlin: computation failed: {path}: periodic_orbit: ")
    assert "relative residuals ||x(T) - x(0)|| per step" in err


def test_a_failed_computation_names_the_scene_file(capsys, tmp_path):
    (tmp_path / "chain.urdf").write_text(pinlin.pendulum_chain_urdf(2, radius=0.05))
    path = write(tmp_path, "[robot]\nurdf = 'chain.urdf'\nfree_flyer = true\n")
    code, _, err = run(["analyze", str(path)], capsys)
    assert code == EXIT_COMPUTATION and err.startswith(f"pinlin: computation failed: {path}: ")


@pytest.mark.parametrize(
    "text, match",
    [
        (DP + "[[spring]]\njoint = 'joint1'\nstiffness = '3.0'\n",
         r"\[spring\[1\].stiffness\] expected a number or a \(rectangular\) list of numbers, got '3.0'"),
        (DP + "[[spring]]\njoint = 'joint1'\nstiffness = ['3.0', 1.0]\n", r"\[spring\[1\].stiffness\] expected a number"),
        (DP + "[[spring]]\njoint = 'joint1'\nstiffness = [true]\n", r"\[spring\[1\].stiffness\] expected a number"),
        (DP + "[[spring]]\njoint = 'joint1'\nstiffness = [[1.0], [2.0, 3.0]]\n", r"\(rectangular\) list of numbers"),
        (DP + "[[spring]]\njoint = 'joint1'\nstiffness = " + "9" * 400 + "\n", r"\[spring\[1\].stiffness\] expected"),
        (DP + "[[spring_damper]]\nframe = 'tip'\ntarget = 'base'\nstiffness = " + "9" * 400 + "\n",
         r"\[spring_damper\[1\].stiffness\] expected a finite number"),
        (DP + "[prescribed]\njoint1 = nan\n", r"\[prescribed.joint1\] expected a finite number, got nan"),
        ("[robot]\nurdf = ''\n", r"\[robot.urdf\] is empty; expected a URDF file"),
        ("[robot]\nurdf = '   '\n", r"\[robot.urdf\] is empty"),
        (DP + "[prescribed]\nknee = 1.0\n", r"\[prescribed.knee\] unknown joint 'knee'"),
        (DP + "[sweep]\nparameter = 'spring.joint1.stiffness'\nvalues = [1.0]\n",
         r"\[sweep.parameter\] 'spring.joint1.stiffness': no spring on joint 'joint1'"),
        (DP + "[sweep]\nparameter = 'gravity'\nvalues = [1.0, 1.0]\n", r"\[sweep.values\] must be strictly"),
    ],
)
def test_scene_file_values_are_checked(capsys, tmp_path, text, match):
    path = write(tmp_path, text)
    code, out, err = run(["analyze", str(path)], capsys)
    assert code == EXIT_INPUT and out == ""
    with pytest.raises(pinlin.SceneFileError, match=match):
        spec = load_scene(path)
        sweep_plan(spec, spec.sweep)  # what `pinlin analyze` checks of a [sweep] table


# ---------------------------------------------------------------- item 10: the --help example runs as printed


def _printed_example(capsys) -> str:
    with pytest.raises(SystemExit) as info:
        main(["analyze", "--help"])
    assert info.value.code == 0
    text = capsys.readouterr().out
    block = text.split("Scene file format (TOML):\n", 1)[1].splitlines()
    lines = []
    for line in block:  # the indented block up to the first line that is not part of it
        if line and not line.startswith("    "):
            break
        lines.append(line)
    return textwrap.dedent("\n".join(lines))


def test_help_example_runs_as_printed(capsys, tmp_path):
    example = _printed_example(capsys)
    assert "[[spring]]" in example and "[sweep]" in example and "[[bushing]]" in example
    path = tmp_path / "example.toml"
    path.write_text(example)
    code, out, err = run(["analyze", str(path)], capsys)
    assert code == EXIT_OK, err
    assert "nonzero: M, D, S, N" in out
    code, out, err = run(["sweep", str(path), "--no-boundaries"], capsys)
    assert code == EXIT_OK, err
    assert "follower.tip.force [N]: 31 values from 0 to 30" in out
