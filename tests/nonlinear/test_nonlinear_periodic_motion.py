"""simulate with periodic prescribed motions: the prescribed joints follow q_p(t),
v_p(t), a_p(t) exactly.

Closed form: a point-mass pendulum (mass m, length l) on a pivot moving horizontally, x_p = A sin(omega t),
obeys J theta'' + m g l sin theta = m l x_p'' cos theta (J = m l^2).  For small A the linear response
started on its periodic solution is theta(t) = Theta sin(omega t), Theta = -m l A omega^2 / (k - J omega^2),
k = m g l; the nonlinear terms change it by O(Theta^3) (1e-15 of Theta here).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose

import pinlin

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "periodic"))
from scene_cases import pivot_scene  # noqa: E402


def test_small_forced_swing_follows_the_linear_periodic_response():
    A, omega, m, l, g = 1e-7, 3.0, 1.3, 0.5, 9.81
    scene = pivot_scene({"pivot_x": pinlin.Harmonic(A, omega)}, length=l, mass=m, g=g)
    J, k = m * l**2, m * g * l
    Theta = -m * l * A * omega**2 / (k - J * omega**2)
    t = np.linspace(0.0, 5.0, 26)
    q0 = np.zeros(scene.model.nq)
    sim = pinlin.simulate(scene, q0, [Theta * omega], t, rtol=1e-12, atol=1e-22)  # atol far below theta
    assert_allclose(sim.q[:, 2], Theta * np.sin(omega * t), rtol=0, atol=1e-8 * abs(Theta))
    assert_allclose(sim.v[:, 2], Theta * omega * np.cos(omega * t), rtol=0, atol=1e-8 * abs(Theta) * omega)
    assert_allclose(sim.q[:, 0], A * np.sin(omega * t), rtol=1e-15, atol=0)  # the pivot, exactly
    assert_allclose(sim.v[:, 0], A * omega * np.cos(omega * t), rtol=1e-15, atol=1e-30)
    assert "q_p(t)" in sim.method


def test_vertical_pivot_parametric_resonance_grows():
    """In the first Mathieu tongue (omega = 2 omega0, eps = A / l = 0.3) the hanging pendulum's swing
    grows at least as the Floquet multiplier says over a few periods; off the tongue it does not."""
    l, g, A = 1.0, 1.0, 0.3
    scene = pivot_scene({"pivot_z": pinlin.Harmonic(A, 2.0, phase=math.pi / 2)}, length=l, g=g)
    orbit = pinlin.periodic_orbit(scene, np.zeros(scene.model.nq))
    flo = pinlin.floquet_analysis(scene, orbit)
    growth = float(np.max(np.abs(flo.multipliers)))
    assert growth > 1.2
    T = orbit.period
    t = np.array([0.0, 10 * T])
    sim = pinlin.simulate(scene, np.zeros(scene.model.nq), [1e-8], t, rtol=1e-12, atol=1e-20)
    # from a generic start the dominant Floquet mode takes over: |x(10 T)| ~ c growth^10 with c = O(1)
    assert abs(sim.v[-1, 2]) > 1e-8 * growth**10 / 100
