"""Floquet bounds that hold where the coefficients jump, where the orbit is only as good as its shooting, and
at the Jordan block of an autonomous conservative orbit.

Sources: Meissner's equation x'' + c x' + k(t) x = 0 with a square-wave k (E. Meissner, Schweiz. Bauzeitung
78, 1921): the monodromy is exactly the product of three matrix exponentials (scipy.linalg.expm); the forced
saddle against the same analysis along a reference orbit shot to 1e-14; the pendulum's large swing has the
exact multipliers 1, 1 in a Jordan block (the period varies along the family of swings).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
import scipy.linalg

import pinlin
from pinlin.periodic.jumps import find_jumps
from scene_cases import pivot_scene

K_LOW, K_HIGH = -25.95, 124.05          # k jumps at T / 4 and 3 T / 4


def square_k(T):
    def K(t):
        return np.array([[K_HIGH if 0.25 <= (t % T) / T < 0.75 else K_LOW]])
    return K


def meissner_exact(T, c):
    def expm(k, tau):
        return scipy.linalg.expm(np.array([[0.0, 1.0], [-k, -c]]) * tau)
    return np.linalg.eigvals(expm(K_LOW, T / 4) @ expm(K_HIGH, T / 2) @ expm(K_LOW, T / 4))


@pytest.mark.parametrize("T", [0.25, 0.5, 0.75])
@pytest.mark.parametrize("c", [0.0, 0.002])
def test_meissner_bounds_contain_the_exact_error(T, c):
    with pytest.warns(pinlin.AccuracyWarning, match=r"jumps of the coefficients located at t = .*"
                                                    r"with a step boundary at each jump"):
        flo = pinlin.floquet_analysis_matrices(np.eye(1), None if c == 0 else np.array([[c]]), square_k(T), T)
    exact = meissner_exact(T, c)
    for mu, bound in zip(flo.multipliers, flo.error_bound):
        error = np.min(np.abs(exact - mu))
        assert error <= bound
        assert bound <= 1e-10 * max(1.0, abs(mu))    # the jumps found: the bound is the smooth case's
    steps = flo.step_times
    assert T / 4 in steps and 3 * T / 4 in steps            # the integration steps to the jumps exactly
    assert f"{T / 4!r}" in flo.method or f"{T / 4:.17g}" in flo.method


@pytest.mark.parametrize("T", [0.25, 0.5, 0.75])
@pytest.mark.parametrize("c", [0.0, 0.002])
def test_meissner_on_the_nodes_path(T, c):
    """sampling="nodes" takes no samples: the jumps are found in the gaps between the steps' outer nodes
    (as filed, a step from 0.18696 to 0.23855 had all its nodes after the jump at 0.1875: off by 5.7e-3)."""
    flo = pinlin.floquet_analysis_matrices(np.eye(1), None if c == 0 else np.array([[c]]), square_k(T), T,
                                           sampling="nodes")
    exact = meissner_exact(T, c)
    for mu, bound in zip(flo.multipliers, flo.error_bound):
        assert np.min(np.abs(exact - mu)) <= bound <= 1e-10 * max(1.0, abs(mu))
    for jump in (T / 4, 3 * T / 4):                  # a step boundary within a few ulps of each jump
        assert np.min(np.abs(flo.step_times - jump)) <= 4 * np.spacing(jump)


def test_spectral_sampling_refuses_naming_the_jumps():
    with pytest.raises(pinlin.SamplingError, match=r"jumps of the coefficients located at t = 0\.0625, 0\.1875 s"):
        pinlin.floquet_analysis_matrices(np.eye(1), None, square_k(0.25), 0.25, sampling="spectral")


def test_find_jumps_thresholds_at_their_boundaries():
    # a step of relative size 1e-9 at t = 0.3 of a constant 1: found above the floor, ignored at it
    F = lambda t: np.array([[[1.0 + (1e-9 if 0.3 <= t % 1.0 < 0.8 else 0.0)]]])
    samples = np.stack([F(t) for t in np.arange(32) / 32])
    jumps, breaks, _ = find_jumps(F, 1.0, samples, np.array([1.0]), 0.5e-9)
    assert jumps == pytest.approx([0.3, 0.8], abs=1e-15)
    assert find_jumps(F, 1.0, samples, np.array([1.0]), 2e-9)[0] == []
    # a smooth F: neighbouring differences agree to O(h); a ramp over one spacing is no jump either
    G = lambda t: np.array([[[np.sin(2 * np.pi * t)]]])
    smooth = np.stack([G(t) for t in np.arange(32) / 32])
    assert find_jumps(G, 1.0, smooth, np.array([1.0]), 1e-13)[0] == []
    # a steep continuous ramp of width 1e-6 at 0.51: two step boundaries around it, no jump
    H = lambda t: np.array([[[np.clip((t % 1.0 - 0.51) / 1e-6, 0.0, 1.0)]]])
    steep = np.stack([H(t) for t in np.arange(32) / 32])
    jumps, breaks, _ = find_jumps(H, 1.0, steep, np.array([1.0]), 1e-13)
    assert jumps == [] and len(breaks) == 2 and 0.51 - 1e-6 <= breaks[0] < breaks[1] <= 0.51 + 3e-6


@pytest.mark.parametrize("jump", [0.4, 0.123456789])
def test_a_step_boundary_at_the_jump_gives_the_exact_transition(jump):
    """y' = a(t) y with a = -1 then +2 from t = jump: Phi(1) = exp(-jump + 2 (1 - jump)) exactly, whether the
    jump is given as a break or found in a gap between steps."""
    from pinlin.periodic.collocation import integrate_transitions
    A = lambda t: np.array([[-1.0 if t < jump else 2.0]])
    exact = math.exp(-jump + 2 * (1 - jump))
    for tr in (integrate_transitions(A, 1.0, 1, breaks=[jump]), integrate_transitions(A, 1.0, 1)):
        assert abs(np.prod([f[0, 0] for f in tr.factors]) - exact) <= 1e-13 * exact
        assert min(abs(s.t0 - jump) for s in tr.steps) <= 4 * np.spacing(jump)


def forced_saddle():
    scene = pivot_scene({"pivot_x": pinlin.Harmonic(0.02, 8.0)}, length=0.5, mass=1.3)
    q0 = np.zeros(scene.model.nq)
    q0[2] = np.pi
    return scene, q0


def test_forced_saddle_bound_contains_the_orbit_error():
    """The inverted pendulum driven horizontally (0.02 sin 8 t): a saddle orbit, multipliers 32.5 and 0.031.
    At the default residual_tol the orbit is off by 2.3e-11 and the larger multiplier by 1.3e-11, twice the
    integration and eigensolver parts of the bound (5.6e-12): the orbit's part must cover it."""
    scene, q0 = forced_saddle()
    orbit = pinlin.periodic_orbit(scene, q0)
    reference = pinlin.periodic_orbit(scene, q0, residual_tol=1e-14)
    flo = pinlin.floquet_analysis(scene, orbit)
    ref = pinlin.floquet_analysis(scene, reference)
    error = np.abs(flo.multipliers - ref.multipliers)
    assert error[0] > flo.integration_bound[0] + flo.eigensolver_bound[0]    # the case: not covered before
    assert np.all(error <= flo.error_bound - ref.error_bound)
    assert flo.error_bound[0] <= 10 * error[0]                                  # and not decades above it
    assert np.all(ref.orbit_bound < flo.orbit_bound)
    np.testing.assert_allclose(flo.error_bound, flo.integration_bound + flo.eigensolver_bound + flo.orbit_bound)


def test_the_orbit_correction_is_the_next_newton_step():
    """ds = -(Phi - I)^-1 r against the reference orbit's start: a figure at half or twice fails."""
    from pinlin.periodic.orbit_error import orbit_start_error
    scene, q0 = forced_saddle()
    orbit = pinlin.periodic_orbit(scene, q0)
    reference = pinlin.periodic_orbit(scene, q0, residual_tol=1e-14)
    flo = pinlin.floquet_analysis(scene, orbit)
    ds, unknown = orbit_start_error(scene, orbit, flo.monodromy, 0)
    true = np.array([reference.q0[2] - orbit.q0[2], reference.v0[2] - orbit.v0[2]])
    np.testing.assert_allclose(ds, true, rtol=1e-3, atol=1e-3 * np.linalg.norm(true))
    assert 0 < unknown < 0.2 * np.linalg.norm(ds)


def test_constant_orbit_has_no_orbit_part():
    spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    flo = pinlin.floquet_analysis(spec.scene, pinlin.periodic_orbit(spec.scene, spec.q0))
    assert np.all(flo.orbit_bound == 0.0)


def test_trivial_pair_bound_covers_its_jordan_block():
    """The large swing at 2 rad: exact multipliers 1, 1; the computed pair splits as the square root of the
    monodromy's perturbation."""
    scene = pivot_scene({}, length=0.5, mass=1.3)
    q0 = np.zeros(scene.model.nq)
    q0[2] = 2.0
    orbit = pinlin.periodic_orbit(scene, q0, period=1.3 * 2 * math.pi / math.sqrt(9.81 / 0.5))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pinlin.AccuracyWarning)
        flo = pinlin.floquet_analysis(scene, orbit)
    error = np.abs(flo.multipliers - 1.0)
    assert flo.trivial.all()
    assert np.all(error <= flo.error_bound)
    first_order = flo.integration_bound + flo.eigensolver_bound + flo.orbit_bound
    assert np.all(flo.error_bound >= first_order)


def test_jordan_bound_is_the_square_root_law():
    """[[1, c], [e, 1]] has the eigenvalues 1 +- sqrt(c e): the bound sqrt(c e) + e, neither half nor twice."""
    from pinlin.periodic.bounds import jordan_bound
    for c, e in [(1.0, 1e-10), (30.0, 1e-14)]:
        Phi = np.array([[1.0, c], [e, 1.0]])
        mu = np.linalg.eigvals(Phi)
        true = float(np.max(np.abs(mu - 1)))
        bound = jordan_bound(Phi, mu, np.array([True, True]), e)
        assert true <= bound <= 1.01 * true + e


@pytest.mark.parametrize("jump, found", [(7.2, True), (6.8, False)])
def test_a_jump_is_a_candidate_from_eight_times_its_neighbours_difference(jump, found):
    """A jump J on a ramp of slope 1, 32 samples (spacing h = 1/32): the difference across it is J + h, its
    neighbours' h, so the ratio 8 is crossed at J = 7 h (8.2 at 7.2 h, 7.8 at 6.8 h)."""
    h = 1 / 32
    F = lambda t: np.array([[[(t % 1.0) + (jump * h if t % 1.0 >= 0.4 else 0.0)]]])
    samples = np.stack([F(t) for t in np.arange(32) * h])
    jumps = find_jumps(F, 1.0, samples, np.array([2.0]), 1e-13)[0]    # the ramp's reset at T: no step needed
    assert jumps == ([pytest.approx(0.4, abs=1e-15)] if found else [])


def test_the_fallback_to_the_nodes_warns_and_says_why():
    """|sin t| has a kink, no jump: the interpolant's error falls by 2 per doubling (1.7e-2, 9.1e-3, 4.6e-3)."""
    K = lambda t: np.array([[2.0 + 0.3 * abs(np.sin(t))]])
    with pytest.warns(pinlin.AccuracyWarning, match=r"did not reach the relative error 1e-13 with 64 samples "
                                                    r"\(measured errors after each doubling: 1\.7e-02, 9\.1e-03, "
                                                    r"4\.6e-03\): evaluating them at every collocation node"):
        flo = pinlin.floquet_analysis_matrices(np.eye(1), np.array([[0.05]]), K, 2 * np.pi)
    assert "sampling did not converge: 64 samples" in flo.method
