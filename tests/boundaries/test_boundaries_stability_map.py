"""stability_map: verdicts over a grid and the exact boundary over them."""

from __future__ import annotations

import builtins

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from boundary_cases import double_pendulum  # noqa: E402
from numpy.testing import assert_allclose  # noqa: E402

import pinlin  # noqa: E402
from pinlin.plot.stability_map import stability_map  # noqa: E402


@pytest.fixture(scope="module")
def curve():
    return pinlin.stability_boundary(lambda c, P: double_pendulum(c)(P), [0.1, 0.5, 1.0], (1.0, 40.0))


def test_boundary_over_the_verdict_map(curve):
    loads, dampings = np.linspace(1.0, 30.0, 8), np.array([0.1, 0.5, 1.0])
    kinds = [[pinlin.modal_analysis(double_pendulum(c)(P)).stability.kind for P in loads] for c in dampings]
    fig, ax = plt.subplots()
    out = stability_map(loads, dampings, kinds, ax, boundary=curve, p1_axis="y", xlabel="P [N]")
    assert out is ax and len(ax.collections) >= 2  # the verdict mesh and the error bars
    (line,) = [ln for ln in ax.get_lines() if ln.get_label() == "boundary"]
    assert_allclose(line.get_xdata(), curve.p2)
    assert_allclose(line.get_ydata(), curve.p1)
    assert ax.get_xlabel() == "P [N]" and ax.get_ylabel() == "p1"
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "boundary" in labels and "asymptotically stable" in labels
    plt.close(fig)


def test_boundary_alone(curve):
    ax = stability_map(boundary=curve, error_bars=False, label="P*(c)")
    (line,) = ax.get_lines()
    assert_allclose(line.get_xdata(), curve.p1) and line.get_label() == "P*(c)"
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("p1", "p2")
    plt.close(ax.figure)


def test_bad_input(curve):
    with pytest.raises(pinlin.ParameterError, match="give all three"):
        stability_map([1.0], None, None, boundary=curve)
    with pytest.raises(pinlin.ParameterError, match="nothing to draw"):
        stability_map()
    with pytest.raises(pinlin.ParameterError, match="p1_axis: expected 'x' or 'y'"):
        stability_map(boundary=curve, p1_axis="z")
    with pytest.raises(pinlin.ParameterError, match=r"kinds: expected shape \(1, 2\)"):
        stability_map([1.0, 2.0], [1.0], [["flutter"]])
    with pytest.raises(pinlin.ParameterError, match="unknown verdicts"):
        stability_map([1.0], [1.0], [["wobbly"]])
    plt.close("all")


def test_without_matplotlib(monkeypatch, curve):
    real_import = builtins.__import__

    def no_matplotlib(name, *args, **kwargs):
        if name.startswith("matplotlib"):
            raise ImportError("No module named 'matplotlib'")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_matplotlib)
    with pytest.raises(pinlin.errors.MissingDependencyError, match=r"pip install 'pinlin\[plot\]'"):
        stability_map(boundary=curve)
