"""pinlin.plot (headless, Agg): the figures carry the expected artists.  Tracking: tests/studies/test_tracking.py."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.collections import PathCollection, QuadMesh  # noqa: E402
from numpy.testing import assert_allclose  # noqa: E402

import pinlin  # noqa: E402
from pinlin import plot  # noqa: E402
from pinlin.spectral import MODE_KINDS  # noqa: E402
from studies.cases import crossing_sweep  # noqa: E402


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


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
    """Rotating ring (theory: rotating ring, undamped): lam = +-i(w0 + W), +-i(w0 - W). The branch i(w0 - W)
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


def test_kind_styles_are_exactly_the_mode_kinds():
    """Every kind modal_analysis produces has a style, and no style for a kind it never produces."""
    assert set(plot.KIND_STYLE) == set(MODE_KINDS)
    assert "critically_damped" not in plot.KIND_STYLE


def test_eigenvalue_map_of_modes_marks_kinds_and_error_bars():
    """A free coordinate (rigid body: lam = 0 twice), an oscillator, and a coordinate with negative stiffness."""
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(3), np.diag([0.0, 0.2, 0.0]), np.diag([0.0, 4.0, -1.0]))
    modes = pinlin.modal_analysis(sys)
    assert set(modes.kind) == {"rigid_body", "underdamped", "overdamped", "unstable"}
    ax = plot.eigenvalue_map(modes)
    labels = {t.get_text() for t in ax.get_legend().get_texts()}
    assert labels == {"rigid body", "underdamped", "overdamped", "unstable"}
    points = [c for c in ax.collections if isinstance(c, PathCollection)]
    assert sum(len(c.get_offsets()) for c in points) == 6
    assert ax.get_title() == modes.stability.kind.replace("_", " ")
    left, right = ax.get_xlim()
    assert left <= -plot.AXIS_MARGIN * 1.0 + 1e-12 and right >= plot.AXIS_MARGIN * 1.0 - 1e-12  # lam = -1, +1
    with pytest.raises(pinlin.ParameterError, match="eigenvalues: has non-finite"):
        plot.eigenvalue_map(np.array([np.nan, 1.0]))


def test_chain_mode_shape_uses_the_threads_workspace(monkeypatch):
    """plot never calls createData itself: the only Data comes through Robot.create_data (the memory
    guard) when the calling thread's workspace for the scene is made, and is reused after."""
    import inspect
    import pkgutil

    from pinlin.model.robot import Robot

    for info in pkgutil.iter_modules(plot.__path__, "pinlin.plot."):  # every module of the package
        assert "createData" not in inspect.getsource(__import__(info.name, fromlist=["_"])), info.name
    calls = []
    original = Robot.create_data

    def counting(self, *args, **kwargs):
        calls.append(self.name)
        return original(self, *args, **kwargs)

    monkeypatch.setattr(Robot, "create_data", counting)
    scene = pinlin.Scene(pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(3)))
    for _ in range(2):
        plot.chain_mode_shape(scene, np.zeros(3), np.array([1.0, 0.0, 0.0]))
    assert len(calls) == 1
    with pytest.raises(pinlin.ParameterError, match="plane: expected two of x, y, z"):
        plot.chain_mode_shape(scene, np.zeros(3), np.ones(3), plane="xq")
