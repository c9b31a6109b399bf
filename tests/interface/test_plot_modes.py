"""pinlin.plot.mode_shape and animate_mode (headless, Agg): stick figures against Pinocchio's own kinematics.

Expected positions are computed here independently: the mode's joint displacement e (the eigenvector,
``sys.basis @ z`` with constraints) scaled so that its largest entry is 1, the configuration
q0 (+) a Re(e e^{i theta}) by ``pin.integrate``, and Pinocchio's forward kinematics in a Data of the test's own.
"""

import matplotlib

matplotlib.use("Agg")

import inspect  # noqa: E402
import pkgutil  # noqa: E402

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pinocchio as pin  # noqa: E402
import pytest  # noqa: E402
from numpy.testing import assert_allclose  # noqa: E402
from PIL import Image  # noqa: E402

import pinlin  # noqa: E402
from pinlin import plot  # noqa: E402
from pinlin.model.scene_file import load_scene  # noqa: E402

#: Positions are computed by the same Pinocchio algorithms on the same configurations: equal to rounding.
POSITION_ATOL = 1e-12  # [m]


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


@pytest.fixture(scope="module")
def pendulum():
    """The paper's double pendulum (theory: double pendulum) with a follower load and a damper on joint 1 only:
    non-proportional damping, so its modes are complex (each coordinate has its own phase)."""
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf())
    scene = pinlin.Scene(
        robot,
        [pinlin.JointSpring("joint1", 3.0), pinlin.JointSpring("joint2", 2.0), pinlin.JointDamper("joint1", 0.8),
         pinlin.FollowerWrench("tip", force=(0, 0, 2.0))],
        gravity=(0, 0, 0),
    )
    sys = pinlin.linearize(scene, np.zeros(2))
    return scene, sys, pinlin.modal_analysis(sys)


def expected_points(scene, sys, z, scale, theta, frames=("tip",)):
    """Joint origins (joints 1..) and frame origins at q0 (+) scale Re(e e^{i theta}), by Pinocchio directly."""
    model = scene.model
    data = model.createData()
    joint_disp = z if getattr(sys, "basis", None) is None else sys.basis @ z
    e = np.zeros(model.nv, dtype=complex)
    e[scene.free_dofs] = joint_disp / joint_disp[np.argmax(np.abs(joint_disp))]
    q = pin.integrate(model, sys.q, scale * np.real(e * np.exp(1j * theta)))
    pin.framesForwardKinematics(model, data, q)
    joints = np.array([data.oMi[j].translation for j in range(1, model.njoints)])
    tips = np.array([data.oMf[model.getFrameId(f)].translation for f in frames])
    return joints, tips


def by_gid(ax, gid):
    return [a for a in ax.get_children() if a.get_gid() == gid]


def xz(line):
    x, y = line.get_data()
    return np.column_stack([x, y])


def test_the_mode_is_complex(pendulum):
    """The case is meant to exercise each coordinate's own phase: the normalized shape is far from real."""
    _, _, modes = pendulum
    x = modes.right[:, 0]
    e = x / x[np.argmax(np.abs(x))]
    assert np.abs(e.imag).max() > 1e-2


def test_animation_saves_as_gif_with_positions_from_the_kinematics(pendulum, tmp_path):
    scene, sys, modes = pendulum
    n_frames, scale = 8, 0.3
    _, ax = plt.subplots(figsize=(3, 3), dpi=50)
    anim = plot.animate_mode(scene, sys, 0, ax, modes=modes, plane="xz", n_frames=n_frames, scale=scale)
    snapshots = {}

    def snapshot(k, total):
        assert total == n_frames
        links = by_gid(ax, "mode-links")
        joints, frames, wrenches = (by_gid(ax, f"mode-{name}") for name in ("joints", "frames", "wrenches"))
        assert len(links) == len(joints) == len(frames) == len(wrenches) == 1  # one moving figure
        snapshots[k] = (xz(joints[0]), xz(frames[0]), xz(wrenches[0]), np.array(links[0].get_segments()))

    path = tmp_path / "mode.gif"
    anim.save(path, writer="pillow", progress_callback=snapshot)
    with Image.open(path) as gif:
        assert gif.format == "GIF" and gif.n_frames == n_frames
    assert sorted(snapshots) == list(range(n_frames))
    # the figure: a resting and a moving stick figure (links, joints, frames, wrench frames each), the phase text
    for prefix in ("rest", "mode"):
        assert [len(by_gid(ax, f"{prefix}-{name}")) for name in ("links", "joints", "frames", "wrenches")] == [1] * 4
    assert len(by_gid(ax, "phase")) == 1
    for k in (1, 3):  # two phases, 45 and 135 degrees
        joints, tips = expected_points(scene, sys, modes.right[:, 0], scale, 2 * np.pi * k / n_frames)
        got_joints, got_frames, got_wrenches, segments = snapshots[k]
        assert_allclose(got_joints, joints[:, [0, 2]], atol=POSITION_ATOL)
        assert_allclose(got_frames, tips[:, [0, 2]], atol=POSITION_ATOL)
        assert_allclose(got_wrenches, tips[:, [0, 2]], atol=POSITION_ATOL)  # the follower load acts at the tip
        # links: world origin - joint1 - joint2, and joint2 - tip
        chain = np.vstack([[0.0, 0.0], joints[:, [0, 2]], tips[:, [0, 2]]])
        assert_allclose(segments, chain[[[0, 1], [1, 2], [2, 3]]], atol=POSITION_ATOL)
    # the phases differ: the two snapshots are not one shape scaled (a complex mode)
    assert not np.allclose(snapshots[1][0], snapshots[3][0], atol=1e-3)


def test_animation_in_3d_and_as_html(pendulum):
    scene, sys, modes = pendulum
    ax = plt.figure(figsize=(3, 3), dpi=40).add_subplot(projection="3d")
    anim = plot.animate_mode(scene, sys, 2, ax, modes=modes, n_frames=4, scale=0.2)
    html = anim.to_jshtml()  # draws every frame, the last one last
    assert html.count("data:image/png;base64") == 4
    joints, _ = expected_points(scene, sys, modes.right[:, 2], 0.2, 2 * np.pi * 3 / 4)
    line = by_gid(ax, "mode-joints")[0]
    assert_allclose(np.column_stack(line.get_data_3d()), joints, atol=POSITION_ATOL)
    with pytest.raises(pinlin.ParameterError, match="ax: 3-D axes"):
        plot.animate_mode(scene, sys, 2, ax, modes=modes, plane="xz")


def test_animation_figure_is_not_left_open_in_pyplot(pendulum):
    scene, sys, modes = pendulum
    before = plt.get_fignums()
    anim = plot.animate_mode(scene, sys, 0, modes=modes, n_frames=2, dpi=30)
    assert plt.get_fignums() == before
    assert anim.to_jshtml().count("data:image/png;base64") == 2


def test_mode_shape_draws_the_phases_against_the_kinematics(pendulum):
    scene, sys, modes = pendulum
    phases = (0.0, 0.7, 2.0)
    ax = plot.mode_shape(scene, sys, 0, modes=modes, plane="xz", phases=phases, scale=0.25)
    joints = by_gid(ax, "mode-joints")
    assert len(joints) == len(phases) and len(by_gid(ax, "rest-joints")) == 1
    assert len(by_gid(ax, "mode-links")) == len(phases)
    for line, theta in zip(joints, phases):
        expected, _ = expected_points(scene, sys, modes.right[:, 0], 0.25, theta)
        assert_allclose(xz(line), expected[:, [0, 2]], atol=POSITION_ATOL)
    rest = xz(by_gid(ax, "rest-frames")[0])
    assert_allclose(rest, [[0.0, -1.2]], atol=1e-14)  # tip at l1 + l2 = 0.7 + 0.5 below the pivot
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["operating point", "0 deg", "40 deg", "115 deg"]


def test_a_given_vector_and_the_default_amplitude(pendulum):
    """scale=None: the fastest point moves ``fraction`` of the figure's size, to first order (tiny fraction)."""
    scene, sys, _ = pendulum
    fraction = 1e-6
    z = np.array([1.0, -0.5])  # real: its largest displacement is at phase 0
    motion = plot.mode_motion(scene, sys, z, [0.0], fraction=fraction)
    size = np.linalg.norm([0.0, 0.0, 1.2])  # the figure spans the pivot to the tip
    moved = np.linalg.norm(motion.positions[0] - motion.rest, axis=1).max()
    assert_allclose(moved, fraction * size, rtol=1e-5)
    # tip speed per unit of e = (1, -0.5): joint1 turns the whole 1.2 m, joint2 the 0.5 m link back
    assert_allclose(motion.scale, fraction * size / abs(1.2 - 0.5 * 0.5), rtol=1e-9)
    assert motion.eigenvalue is None and motion.title().startswith("mode shape")


def test_constrained_four_bar_maps_the_mode_through_the_basis():
    """One coordinate drives three joints: the drawing follows sys.basis @ z (theory: constraints)."""
    spec = load_scene(pinlin.data_path("scenes/four_bar.toml"))
    scene = spec.scene
    sys = pinlin.linearize(scene, pinlin.find_equilibrium(scene, spec.q0).q)
    assert sys.basis is not None and sys.basis.shape == (3, 1)
    modes = pinlin.modal_analysis(sys)
    ax = plot.mode_shape(scene, sys, 0, modes=modes, plane="xz", phases=(0.3,), scale=0.05)
    tips = plot.Skeleton(scene).frame_names
    joints, frames = expected_points(scene, sys, modes.right[:, 0], 0.05, 0.3, frames=tips)
    assert_allclose(xz(by_gid(ax, "mode-joints")[0]), joints[:, [0, 2]], atol=POSITION_ATOL)
    assert_allclose(xz(by_gid(ax, "mode-frames")[0]), frames[:, [0, 2]], atol=POSITION_ATOL)
    assert "rocker_tip" in tips  # the constraint's frame is drawn


def test_bad_arguments(pendulum):
    scene, sys, modes = pendulum
    with pytest.raises(pinlin.ParameterError, match="plane: expected two of x, y, z"):
        plot.mode_shape(scene, sys, 0, plane="xq")
    with pytest.raises(pinlin.ParameterError, match=r"mode: expected an index into modes.eigenvalues, 0 to 3 \(or -4 to -1"):
        plot.mode_shape(scene, sys, 4, modes=modes)
    with pytest.raises(pinlin.ParameterError, match="mode: expected an index or 2 finite values"):
        plot.mode_shape(scene, sys, np.ones(3))
    with pytest.raises(pinlin.ParameterError, match="mode: is zero"):
        plot.mode_shape(scene, sys, np.zeros(2))
    with pytest.raises(pinlin.ParameterError, match="scale: must be positive"):
        plot.mode_shape(scene, sys, 0, modes=modes, scale=-1.0)
    with pytest.raises(pinlin.ParameterError, match="phases: expected finite phases"):
        plot.mode_shape(scene, sys, 0, modes=modes, phases=[np.nan])
    with pytest.raises(pinlin.ParameterError, match="n_frames: expected an integer >= 2"):
        plot.animate_mode(scene, sys, 0, modes=modes, n_frames=1)
    with pytest.raises(pinlin.ParameterError, match="duration: must be positive"):
        plot.animate_mode(scene, sys, 0, modes=modes, duration=0.0)
    _, flat = plt.subplots()
    with pytest.raises(pinlin.ParameterError, match="ax: 3-D axes"):
        plot.mode_shape(scene, sys, 0, flat, modes=modes)
    bare = pinlin.LinearizedSystem.from_matrices(sys.M, sys.D, sys.S)
    with pytest.raises(pinlin.ParameterError, match="q: the system has no operating point"):
        plot.mode_shape(scene, bare, np.ones(2))
    other = pinlin.Scene(pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(3)))
    with pytest.raises(pinlin.ParameterError, match="sys: has coordinates"):
        plot.mode_shape(other, sys, np.ones(2), q=np.zeros(3))
    with pytest.raises(pinlin.FrameNotFoundError, match="nowhere"):
        plot.mode_shape(scene, sys, 0, modes=modes, frames=["nowhere"])
    chain = pinlin.Scene(pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(1)))
    chain_sys = pinlin.linearize(chain, np.zeros(1))
    with pytest.raises(pinlin.ParameterError, match="scale: the mode moves none of the drawn points"):
        plot.mode_shape(chain, chain_sys, np.ones(1), frames=[])


def test_no_plot_module_creates_pinocchio_data(monkeypatch):
    """Kinematics run in the calling thread's workspace: one Data per thread and scene, made through the
    robot's memory guard (Robot.create_data), reused by every later drawing."""
    from pinlin.model.robot import Robot

    for info in pkgutil.iter_modules(plot.__path__, "pinlin.plot."):
        module = __import__(info.name, fromlist=["_"])
        assert "createData" not in inspect.getsource(module), info.name
    calls = []
    original = Robot.create_data

    def counting(self, *args, **kwargs):
        calls.append(self.name)
        return original(self, *args, **kwargs)

    monkeypatch.setattr(Robot, "create_data", counting)
    scene = pinlin.Scene(pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(3)), [pinlin.JointSpring("joint1", 1.0)])
    sys = pinlin.linearize(scene, np.zeros(3))
    calls.clear()  # linearize made this thread's workspace already
    for _ in range(2):
        plot.mode_shape(scene, sys, np.array([1.0, 0.0, 0.0]), plane="xz")
        plot.animate_mode(scene, sys, np.array([1.0, 0.0, 0.0]), n_frames=2, dpi=20).to_jshtml()
    assert calls == []
