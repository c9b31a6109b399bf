"""pinlin.plot.mode_energy (headless, Agg): one bar per row of each energy table, negative shares in red."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.colors import to_hex  # noqa: E402
from numpy.testing import assert_allclose  # noqa: E402

import pinlin  # noqa: E402
from pinlin import plot  # noqa: E402


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def inverted_pendulum():
    """The README pendulum upside down: gravity's strain share is negative."""
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf())
    scene = pinlin.Scene(robot, [pinlin.JointSpring("joint1", 60.0), pinlin.JointSpring("joint2", 40.0)],
                         gravity=(0, 0, 9.81))
    return scene, pinlin.modal_analysis(pinlin.linearize(scene, np.zeros(2)))


def test_bars_are_the_shares_in_percent():
    scene, modes = inverted_pendulum()
    energy = modes.energy(0, scene)
    assert energy.strain["gravity"] < 0
    axes = plot.mode_energy(energy)
    assert len(axes) == 3 and axes[0].figure._suptitle is not None
    for ax, table in zip(axes[:2], (energy.kinetic, energy.strain)):
        widths = [bar.get_width() for bar in ax.patches]
        assert_allclose(widths, [100 * s for s in table.values()], rtol=1e-14)
        assert [t.get_text() for t in ax.get_yticklabels()] == list(table)
    gravity = list(energy.strain).index("gravity")
    assert to_hex(axes[1].patches[gravity].get_facecolor()) == plot.ENERGY_COLORS["negative"]
    assert [t.get_text() for t in axes[2].texts] == ["none"]  # undamped: no dissipation


def test_draws_into_given_axes_and_refuses_bad_input():
    scene, modes = inverted_pendulum()
    fig, given = plt.subplots(1, 3)
    assert plot.mode_energy(modes.energy(2, scene), given) == list(given)
    assert fig._suptitle is None  # the caller's figure keeps its own title
    with pytest.raises(pinlin.ParameterError, match="expected a ModeEnergy"):
        plot.mode_energy(modes)
    with pytest.raises(pinlin.ParameterError, match="expected 3 axes"):
        plot.mode_energy(modes.energy(0, scene), given[:2])
