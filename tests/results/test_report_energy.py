"""The analyze report's energy section: per mode the dominant body and element."""

from __future__ import annotations

import json

import jsonschema
import numpy as np
import pytest

import pinlin
from pinlin.cli import main
from pinlin.report import REPORT_SCHEMA
from pinlin.report.energy import ENERGY_SCHEMA, energy_lines, energy_section


def analyze(args, capsys, tmp_path):
    code = main(["analyze", *args, "--json", str(tmp_path / "r.json")])
    out = capsys.readouterr()
    assert code == 0, out.err
    return out.out, json.loads((tmp_path / "r.json").read_text())


def test_report_lists_the_dominant_body_and_element_of_each_mode(capsys, tmp_path):
    out, report = analyze(["--example", "ur5", "--damping", "1"], capsys, tmp_path)
    jsonschema.validate(report, REPORT_SCHEMA)
    jsonschema.validate(report["energy"], ENERGY_SCHEMA)
    lam_im = report["modes"]["eigenvalues"]["im"]
    assert [e["mode"] for e in report["energy"]] == [k + 1 for k, im in enumerate(lam_im) if im >= 0]
    for entry in report["energy"]:
        for table in ("kinetic", "strain", "dissipation"):
            if entry[table]:
                assert abs(sum(entry[table].values()) - 1) <= 1e-12
        assert entry["dominant_body"] == max(entry["kinetic"], key=entry["kinetic"].get)
    assert "Energy by mode (dominant body: kinetic share; dominant element: strain share)" in out
    first = report["energy"][0]
    assert f"body {first['dominant_body']} " in out
    assert "-0%" not in out


def test_energy_section_equals_modes_energy():
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf())
    scene = pinlin.Scene(robot, [pinlin.JointSpring("joint1", 3.0), pinlin.JointSpring("joint2", 2.0),
                                 pinlin.JointDamper("joint2", 0.1)], gravity=(0, 0, -9.81))
    modes = pinlin.modal_analysis(pinlin.linearize(scene, np.zeros(2)))
    section = energy_section(modes, scene)
    assert len(section) == 2
    for entry in section:
        energy = modes.energy(entry["mode"] - 1, scene)
        assert entry["kinetic"] == energy.kinetic and entry["strain"] == energy.strain
        assert entry["dissipation"] == energy.dissipation == {"damper joint2": pytest.approx(1.0, abs=1e-12)}
        assert entry["dominant_element"] == energy.dominant_element
        assert entry["frequency_hz"] == modes.frequency_hz[entry["mode"] - 1]
    lines = energy_lines({"energy": section})
    assert len(lines) == 2 + len(section) and lines[1].split()[0] == "1"
    assert energy_lines({}) == []
