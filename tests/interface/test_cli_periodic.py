"""``pinlin analyze`` on a periodic scene runs the Floquet analysis.

The bundled Kapitza pendulum (``kapitza.toml``: bob 0.1 kg at l = 0.2 m, pivot z_p = 0.02 sin(200 t) m) is
stable upside down: its two multipliers lie on the unit circle; their argument is the Floquet frequency
times the period.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
import pinlin.model
from pinlin import cli
from pinlin.report import periodic as periodic_report

KAPITZA = str(pinlin.data_path("scenes/kapitza.toml"))


def test_analyze_prints_multipliers_and_the_verdict(capsys, tmp_path):
    out_json = tmp_path / "k.json"
    assert cli.main(["analyze", KAPITZA, "--json", str(out_json)]) == 0
    text = capsys.readouterr().out
    assert "periodic" in text.splitlines()[0]
    assert "constant (the free coordinates stay at an equilibrium)" in text
    assert "Stability: MARGINALLY STABLE" in text
    assert f"wrote {out_json}" in text and "(periodic orbit, Floquet analysis)" in text
    doc = json.loads(out_json.read_text())
    assert doc["kind"] == "periodic" and doc["stability"]["kind"] == "marginally_stable"
    mu = np.array(doc["floquet"]["multipliers"]["re"]) + 1j * np.array(doc["floquet"]["multipliers"]["im"])
    assert_allclose(np.abs(mu), 1.0, rtol=1e-10)
    # the same numbers as the Python API
    spec = pinlin.model.load_scene(KAPITZA)
    flo = pinlin.floquet_analysis(spec.scene, pinlin.periodic_orbit(spec.scene, spec.q0))
    assert_allclose(np.sort_complex(mu), np.sort_complex(flo.multipliers), rtol=0, atol=1e-12)
    assert "-0.0" not in text and "e-15" not in text   # a rounding-level exponent prints as 0


@pytest.mark.parametrize("option", ["--plot", "--animate"])
def test_outputs_of_eigenvalues_are_refused_before_anything_is_computed(option, capsys, tmp_path, monkeypatch):
    def fail(*args, **kwargs):
        raise AssertionError("computed")

    monkeypatch.setattr(periodic_report, "analyze_periodic", fail)
    monkeypatch.setattr(cli, "analyze_periodic", fail)
    suffix = ".png" if option == "--plot" else ".gif"
    assert cli.main(["analyze", KAPITZA, option, str(tmp_path / f"a{suffix}")]) == 2
    err = capsys.readouterr().err
    assert option in err and "Floquet multipliers instead" in err
    assert not list(tmp_path.iterdir())


def test_a_steady_scene_is_not_periodic():
    spec = pinlin.model.load_scene(pinlin.data_path("scenes/turntable.toml"))
    assert not periodic_report.is_periodic(spec)
    assert periodic_report.is_periodic(pinlin.model.load_scene(KAPITZA))
