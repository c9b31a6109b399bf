"""pinlin.plot (headless, Agg) and pinlin.tracking: the figures carry the expected artists."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.collections import PathCollection, QuadMesh  # noqa: E402
from numpy.testing import assert_allclose  # noqa: E402

import pinlin  # noqa: E402
from pinlin import plot  # noqa: E402
from pinlin.studies.tracking import mac, track_modes  # noqa: E402


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def crossing_sweep():
    """Two uncoupled oscillators, frequencies p and 2 - p: they cross at p = 1.
    Eigenvalues given sorted by frequency at each step (what a naive plot would use)."""
    ps = np.linspace(0.5, 1.5, 11)
    lams, vecs = [], []
    for p in ps:
        lam = np.array([1j * p, 1j * (2 - p)])
        X = np.eye(2, dtype=complex)
        order = np.argsort(lam.imag)
        lams.append(lam[order])
        vecs.append(X[:, order])
    return ps, np.array(lams), np.array(vecs)


def test_tracking_follows_shapes_through_a_crossing():
    ps, lams, vecs = crossing_sweep()
    tracked = track_modes(lams, vecs)
    # column 0 starts as the mode with shape e1 (frequency p) and must stay it
    assert_allclose(tracked.eigenvalues[:, 0].imag, ps, atol=1e-15)
    assert_allclose(tracked.eigenvalues[:, 1].imag, 2 - ps, atol=1e-15)
    assert_allclose(tracked.match, 1.0)
    assert_allclose(mac(tracked.vectors[-1], tracked.vectors[0]), np.eye(2))


def test_tracking_bad_input():
    with pytest.raises(pinlin.ParameterError, match=r"expected shape \(steps, m\)"):
        track_modes(np.ones(3))
    with pytest.raises(pinlin.ParameterError, match="vectors: expected shape"):
        track_modes(np.ones((3, 2)), np.ones((3, 2, 5)))
    with pytest.raises(pinlin.ParameterError, match="non-finite"):
        track_modes(np.array([[np.nan, 1.0]]))


def test_eigenvalue_map_plain_array():
    lam = np.array([-0.1 + 2j, -0.1 - 2j, -3.0, 0.0])
    ax = plot.eigenvalue_map(lam)
    points = [c for c in ax.collections if isinstance(c, PathCollection)]
    assert sum(len(c.get_offsets()) for c in points) == 4
    assert ax.get_xlabel().startswith("Re")


def test_root_locus_and_campbell():
    ps, lams, vecs = crossing_sweep()
    ax = plot.root_locus(ps, lams, vectors=vecs, label="p")
    assert len(ax.get_lines()) == 2 + 1  # one trace per mode + the imaginary axis
    ax = plot.campbell(ps, lams, vectors=vecs, orders=(1.0, 2.0))
    lines = ax.get_lines()
    assert len(lines) == 2 + 2
    assert_allclose(lines[0].get_ydata(), ps)  # tracked, not sorted: crosses at p = 1
    with pytest.raises(pinlin.ParameterError, match="speed: expected 11 values"):
        plot.campbell(ps[:3], lams)


def test_campbell_marks_unstable_points():
    speeds = np.array([0.0, 1.0, 2.0])
    lams = np.array([[1j, -1j], [0.1 + 1j, 0.1 - 1j], [0.2 + 1j, 0.2 - 1j]])
    ax = plot.campbell(speeds, lams)
    red = [c for c in ax.collections if isinstance(c, PathCollection)]
    assert len(red) == 1 and len(red[0].get_offsets()) == 2


def test_stability_map():
    x = np.linspace(0, 1, 4)
    y = np.linspace(0, 2, 3)
    kinds = np.array([["asymptotically_stable"] * 4, ["flutter"] * 2 + ["divergence"] * 2, ["undecided"] * 4])
    ax = plot.stability_map(x, y, kinds, xlabel="P", ylabel="c")
    assert any(isinstance(c, QuadMesh) for c in ax.collections)
    assert len(ax.get_legend().get_texts()) == 4
    with pytest.raises(pinlin.ParameterError, match="unknown verdicts"):
        plot.stability_map(x, y, np.full((3, 4), "wobbly"))
    with pytest.raises(pinlin.ParameterError, match=r"expected shape \(3, 4\)"):
        plot.stability_map(x, y, kinds.T)


class _Response:
    def __init__(self):
        self.omega = np.logspace(-1, 1, 50)
        H = 1 / (1 - self.omega**2 + 0.1j * self.omega)
        self.magnitude = np.abs(H)[None, None, :]
        self.phase = np.angle(H)[None, None, :]


def test_frequency_response_axes():
    ax_mag, ax_phase = plot.frequency_response(_Response(), label="H11")
    assert len(ax_mag.get_lines()) == 1 and len(ax_phase.get_lines()) == 1
    assert ax_mag.get_xscale() == "log" and ax_mag.get_yscale() == "log"
    assert_allclose(ax_phase.get_lines()[0].get_ydata()[-1], -180, atol=5)


def test_chain_mode_shape_draws_every_joint_and_the_tip():
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(4, length=2.0))
    scene = pinlin.Scene(robot)
    ax = plot.chain_mode_shape(scene, np.zeros(4), np.array([1.0, 0.5, 0.0, -0.5]), scale=0.1)
    rest, moved = ax.get_lines()
    assert len(rest.get_xdata()) == 5  # joints 1..4 and the tip
    assert_allclose(rest.get_ydata(), [0.0, -0.5, -1.0, -1.5, -2.0], atol=1e-14)
    assert_allclose(moved.get_xdata()[1], -0.5 * np.sin(0.1), rtol=1e-12)  # joint 2 swings with joint 1
    with pytest.raises(pinlin.ParameterError, match="mode: expected 4 values"):
        plot.chain_mode_shape(scene, np.zeros(4), np.ones(3))


def test_work_precision():
    ax = plot.work_precision({"modal": ([1e-4, 2e-4], [1e-14, 1e-15]), "ode": ([1e-2, 1e-1], [1e-4, 1e-9])})
    assert len(ax.get_lines()) == 2 and ax.get_xscale() == "log"
    with pytest.raises(pinlin.ParameterError, match="differ in shape"):
        plot.work_precision({"bad": ([1.0], [1.0, 2.0])})


def test_campbell_keeps_a_whirl_branch_through_zero_frequency():
    """Rotating ring (SPEC 7.3, undamped): lam = +-i(w0 + W), +-i(w0 - W). The branch i(w0 - W)
    changes the sign of Im lam at W = w0; one member of each conjugate pair must still be drawn (a V)."""
    w0 = 2.0
    speeds = np.linspace(0.1, 4.1, 9)  # avoids W = w0, where lam = 0 is double
    lams, vecs = [], []
    for W in speeds:
        lams.append(np.array([1j * (w0 + W), -1j * (w0 + W), 1j * (w0 - W), -1j * (w0 - W)]))
        # shapes of the complex coordinates x +- i y, fixed over W
        vecs.append(np.array([[1, 1, 1, 1], [-1j, 1j, 1j, -1j]]) / np.sqrt(2))
    ax = plot.campbell(speeds, np.array(lams), vectors=np.array(vecs), orders=())
    curves = sorted((line.get_ydata() for line in ax.get_lines()), key=lambda y: y[-1])
    assert len(curves) == 2
    assert_allclose(curves[0], np.abs(w0 - speeds), atol=1e-15)
    assert_allclose(curves[1], w0 + speeds, atol=1e-15)


def test_frequency_response_of_a_load_pattern():
    """Weights over the inputs plot sum_j H[output, j] w_j (the response to a generalized force)."""

    class TwoInputs:
        omega = np.logspace(-1, 1, 30)
        response = np.stack([1 / (1 + 1j * omega), 2 / (1 + 1j * omega)])[None]  # (1 output, 2 inputs, f)
        magnitude = np.abs(response)
        phase = np.angle(response)

    ax_mag, ax_phase = plot.frequency_response(TwoInputs(), input=[1.0, 1.0])
    assert_allclose(ax_mag.get_lines()[0].get_ydata(), 3 / np.abs(1 + 1j * TwoInputs.omega), rtol=1e-14)
    resp = _Response()  # no ``response`` attribute: rebuilt from magnitude and phase
    ax_mag, _ = plot.frequency_response(resp, input=[2.0])
    assert_allclose(ax_mag.get_lines()[0].get_ydata(), 2 * resp.magnitude[0, 0], rtol=1e-14)
    with pytest.raises(pinlin.ParameterError, match="input: expected an index or 2 finite weights"):
        plot.frequency_response(TwoInputs(), input=[1.0, 2.0, 3.0])


def test_campbell_does_not_mark_rounding_as_instability():
    """An undamped spectrum has Re lam ~ 1e-16 of either sign; only Re lam beyond rtol * |lam|
    (and beyond given error bounds) is drawn as unstable."""
    speeds = np.array([0.0, 1.0, 2.0])
    lams = np.array([[1e-16 + 1j, 1e-16 - 1j], [3e-16 + 2j, 3e-16 - 2j], [1e-3 + 3j, 1e-3 - 3j]])

    def red(ax):
        points = [c for c in ax.collections if isinstance(c, PathCollection)]
        return sum(len(c.get_offsets()) for c in points)

    assert red(plot.campbell(speeds, lams)) == 1
    assert red(plot.campbell(speeds, lams, error_bounds=np.full((3, 2), 1e-2))) == 0
    assert red(plot.campbell(speeds, lams, rtol=0.0)) == 3
    with pytest.raises(pinlin.ParameterError, match="error_bounds: expected shape"):
        plot.campbell(speeds, lams, error_bounds=np.ones(3))
