"""The text report reads well: no "-0", undamped modes called undamped, the verdict once,
normalized paths, rounding-level matrix entries printed as 0, a unit on every printed matrix."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

import pinlin
from pinlin.cli import main
from pinlin.numerics.definiteness import rounding_bound
from pinlin.report.text import matrix_text, mode_table, number
from pinlin.report.units import coordinate_units, matrix_unit

BUNDLED = ["scenes/double_pendulum.toml", "scenes/turntable.toml", "scenes/rotating_ring.toml"]
EPS = np.finfo(float).eps


def analyze(args, capsys, tmp_path):
    code = main(["analyze", *args, "--json", str(tmp_path / "r.json")])
    out = capsys.readouterr()
    assert code == 0, out.err
    return out.out, json.loads((tmp_path / "r.json").read_text())


def printed_matrices(text: str) -> dict[str, tuple[str, list[list[str]]]]:
    """name -> (unit, rows of printed cells) of every matrix block "  X [unit] =" in the text."""
    out, lines = {}, text.splitlines()
    for i, line in enumerate(lines):
        m = re.match(r"^  ([MDGSN]) \[(.+)\] =$", line)
        if m:
            rows = []
            for row in lines[i + 1:]:
                if not row.startswith("    "):
                    break
                rows.append(row.split()[1:])
            out[m.group(1)] = (m.group(2), rows)
    return out


@pytest.mark.parametrize("scene", BUNDLED)
def test_no_negative_zero_and_the_verdict_once(scene, capsys, tmp_path):
    out, report = analyze([str(pinlin.data_path(scene))], capsys, tmp_path)
    assert not re.search(r"(?<![\w.])-0(?![\w.])", out), "a '-0' in the report"
    assert not re.search(r"(?<![\w.])-0\.0*(?![\d])", out)
    reason = report["stability"]["reason"]
    assert out.count(reason) == 1
    assert len(re.findall(r"(?i)stability: ", out)) == 1
    assert report["modes"]["table"] in out  # the JSON's table is the printed one (precision 6)


def test_undamped_modes_are_labelled_undamped(capsys, tmp_path):
    """The paper's double pendulum below flutter (D = G = 0): every mode is undamped, |Re lam| <= its bound."""
    out, report = analyze([], capsys, tmp_path)
    kinds = re.findall(r"^\s+\d+ .*?\s(\w*damped)\s", report["modes"]["table"], flags=re.M)
    assert kinds == ["undamped"] * 4
    assert report["modes"]["kind"] == ["undamped"] * 4  # the result's own kinds, not relabelled
    assert "joint1 88%, joint2 12%" in report["modes"]["table"]  # the dominant coordinates
    # a damped arm's modes stay underdamped
    out, _ = analyze(["--example", "ur5", "--damping", "1"], capsys, tmp_path)
    assert re.findall(r"^\s+\d+ .*?\s(\w*damped)\s", out, flags=re.M) == ["underdamped"] * 12


def test_paths_are_normalized(capsys, tmp_path, monkeypatch):
    bundled = Path(pinlin.data_path("scenes/double_pendulum.toml"))
    monkeypatch.chdir(bundled.parent)
    out, report = analyze(["../scenes/double_pendulum.toml"], capsys, tmp_path)
    assert ".." not in out
    assert report["scene"]["source"] == str(bundled.resolve())
    assert report["scene"]["urdf"] == str((bundled.parent.parent / "urdf" / "double_pendulum.urdf").resolve())
    assert f"scene file: {bundled.resolve()}" in out


def test_rounding_level_entries_print_as_zero():
    """|a_ij| <= c n eps ||A||_2 prints 0: here ||A||_2 = 2 (to 1e-17), so the scale is 2 * 2 eps = 8.9e-16."""
    scale = rounding_bound(2, 2.0)
    assert scale == pytest.approx(4 * EPS, rel=0, abs=0)
    A = np.array([[1.0, 0.5 * scale], [-0.5 * scale, 2.0]])
    text = matrix_text("S", A, ["a", "b"], ["rad", "rad"], 6)
    assert [line.split() for line in text.splitlines()] == [["S", "[N", "m/rad]", "="], ["a", "1", "0"], ["b", "0", "2"]]
    B = np.array([[1.0, 4.0 * scale], [-4.0 * scale, 2.0]])  # above the scale: printed as computed
    assert f"{4.0 * scale:.6g}" in matrix_text("S", B, ["a", "b"], ["rad", "rad"], 6)
    assert number(-0.0, 6) == "0" and number(-1e-20, 6) == "-1e-20" and number(-1e-20, 6, zero_below=1e-19) == "0"


def test_printed_matrices_agree_with_the_json(capsys, tmp_path):
    """A 6-DOF arm (M has entries ~1e-45 beside ~4): each printed entry is the JSON's to 6 digits, or 0 exactly
    when it is at or below the matrix's rounding scale."""
    out, report = analyze(["--example", "ur5", "--damping", "1"], capsys, tmp_path)
    lin = report["linearization"]
    printed = printed_matrices(out)
    assert set(printed) == set(lin["nonzero"])
    zeros = 0
    for name, (unit, rows) in printed.items():
        A = np.array(lin[name])
        assert unit == matrix_unit(name, ["rad"] * 6)
        scale = rounding_bound(6, float(np.linalg.norm(A, 2)))
        for i, row in enumerate(rows):
            for j, cell in enumerate(row):
                if abs(A[i, j]) <= scale:
                    assert cell == "0"
                    zeros += A[i, j] != 0
                else:
                    assert float(cell) == pytest.approx(A[i, j], rel=5e-6)
    assert zeros > 0  # the arm does have rounding-level entries
    assert "e-45" not in out and "e-68" not in out


def test_every_printed_matrix_has_its_unit(capsys, tmp_path):
    """The turntable (theory: turntable): coordinates theta [rad] and r [m], so M, G, S have mixed units."""
    out, report = analyze([str(pinlin.data_path("scenes/turntable.toml"))], capsys, tmp_path)
    assert report["scene"]["dof_units"] == ["rad", "m"]
    assert "free joint coordinates n = 2: arm [rad], slider [m]" in out
    printed = printed_matrices(out)
    assert set(printed) == {"M", "G", "S"}
    assert printed["M"][0] == "kg m^2 (rad, rad), kg m (rad, m), kg m (m, rad), kg (m, m) for (row, column) units"
    assert printed["S"][0].startswith("N m/rad (rad, rad), N (rad, m), N/rad (m, rad), N/m (m, m)")
    assert printed["G"][0].startswith("N m s/rad (rad, rad), N s (rad, m), N s/rad (m, rad), N s/m (m, m)")


@pytest.mark.parametrize(
    "names, units",
    [(["M", "D", "S"], ["kg m^2", "N m s/rad", "N m/rad"]), (["M", "G", "N"], ["kg m^2", "N m s/rad", "N m/rad"])],
)
def test_matrix_units_of_angles_and_lengths(names, units):
    for name, unit in zip(names, units):
        assert matrix_unit(name, ["rad", "rad"]) == unit
    assert [matrix_unit(n, ["m"]) for n in ("M", "D", "S")] == ["kg", "N s/m", "N/m"]
    assert matrix_unit("S", ["rad", "?"]) == "row's force / column's coordinate"


def test_coordinate_units_of_a_free_flyer():
    robot = pinlin.load_example("solo12")
    units = coordinate_units(robot)
    assert units[:6] == ("m", "m", "m", "rad", "rad", "rad") and set(units[6:]) == {"rad"}
    assert len(units) == robot.nv


def test_mode_table_has_no_verdict(capsys, tmp_path):
    _, report = analyze([], capsys, tmp_path)
    table = mode_table(report["modes"], precision=4)
    assert "stability" not in table.lower() and "3.977" in table and "12.06" in table


def test_constrained_report_names_the_independent_coordinates_and_the_constraint_forces(capsys, tmp_path):
    """The four-bar: the matrices are labelled with the system's coordinate (not the scene's first joint), and
    the loop's force on the rocker tip is listed; it equals the equilibrium result's own."""
    scene_file = str(pinlin.data_path("scenes/four_bar.toml"))
    out, report = analyze([scene_file], capsys, tmp_path)
    (name,) = report["linearization"]["dof_names"]
    assert re.search(rf"  M \[kg m\^2\] =\n\s+{name}\s+{number(report['linearization']['M'][0][0], 6)}\n", out)
    force = report["equilibrium"]["constraint_forces"][0]
    assert f"constraint 'loop' on 'rocker_tip': force [{number(force['force'][0], 6)}," in out
