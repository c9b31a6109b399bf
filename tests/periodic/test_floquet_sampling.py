"""Spectral sampling of periodic coefficients (what makes Floquet analysis of a scene fast): the trigonometric
interpolant, its measured error, the grid integrator, the bound of the interpolant's error, and the fallback to the nodes.

References: exact trigonometric polynomials, a DFT written out by hand, the scalar variation-of-constants
formula, an mpmath Taylor integration (``mpmath.odefun``, 25 digits) of coefficients that are not trigonometric
polynomials, and the nodes path (the coefficients evaluated at every collocation node)."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
from floquet_cases import mathieu
from numpy.testing import assert_allclose

import pinlin
from pinlin import ParameterError, PinlinError, SamplingError
from pinlin.periodic import floquet_analysis_matrices, floquet_from_first_order
from pinlin.periodic.bounds import coefficient_terms
from pinlin.periodic.collocation import integrate_transitions
from pinlin.periodic.gauss_step import Step, gauss_legendre
from pinlin.periodic.collocation_grid import integrate_on_grid
from pinlin.periodic.sampling import sample_periodic

TWO_PI = 2 * np.pi


def _trig3(t):
    """A 2 x 2 trigonometric polynomial of degree 3 in t (period 2 pi), as one group."""
    return np.array([[[1.0 + 0.5 * np.cos(t) - 0.2 * np.sin(3 * t), 0.3 * np.sin(2 * t)],
                      [0.7 * np.cos(3 * t), 2.0 - 0.1 * np.cos(2 * t)]]])


def test_a_trigonometric_polynomial_is_reproduced_from_eight_samples():
    calls = []
    samples = sample_periodic(lambda t: calls.append(t) or _trig3(t), TWO_PI, tol=1e-13)
    # degree 3 < 8 / 2: the first interpolant is exact, checked at the 8 midpoints, then 16 are kept
    assert samples.converged and samples.evaluations == len(calls) == 16
    assert samples.error[0] < 1e-15
    times = np.random.default_rng(3).uniform(-5.0, 12.0, 40)
    assert_allclose(samples(times), np.stack([_trig3(t) for t in times]), rtol=0, atol=1e-14)


def _dft_interpolant(values: np.ndarray, t: float) -> np.ndarray:
    """Trigonometric interpolant (period 2 pi) of equispaced samples, written out: even N splits the
    Nyquist term as a cosine."""
    N = values.shape[0]
    tj = TWO_PI * np.arange(N) / N
    out = np.zeros(values.shape[1:])
    for k in range(N // 2 + 1):
        a = 2.0 / N * np.tensordot(np.cos(k * tj), values, axes=1)
        b = 2.0 / N * np.tensordot(np.sin(k * tj), values, axes=1)
        weight = 0.5 if k == 0 or 2 * k == N else 1.0
        out += weight * (a * np.cos(k * t) + (0.0 if 2 * k == N else b * np.sin(k * t)))
    return out


def test_the_reported_error_is_the_half_grid_interpolants_error_at_the_midpoints():
    def F(t):   # exp(cos t): Fourier coefficients I_k(1), not a polynomial
        return np.array([[[np.exp(np.cos(t))]]])
    samples = sample_periodic(F, TWO_PI, tol=1e-7)
    N = samples.evaluations
    assert samples.converged and N == 32       # 16 samples miss by about I_8(1) / e = 7e-8 < 1e-7; 8 by 1e-3
    half = np.stack([F(t) for t in TWO_PI * np.arange(N // 2) / (N // 2)])
    mids = TWO_PI * (np.arange(N // 2) + 0.5) / (N // 2)
    errors = [abs(_dft_interpolant(half, t) - F(t)).max() for t in mids]
    scale = np.exp(1.0)                        # the largest |F| over the samples (at t = 0)
    assert_allclose(samples.error[0], max(errors) / scale, rtol=1e-6)
    # the reported figure over-estimates the error of the interpolant actually used (all N samples)
    fine = np.linspace(0.0, TWO_PI, 997)
    true = max(abs(samples(np.array([t]))[0] - F(t)).max() for t in fine) / scale
    assert true <= samples.error[0]


def test_a_kink_stops_the_doubling_and_auto_falls_back_to_the_nodes():
    def K(t):                                   # |sin t|: a kink at every multiple of pi
        return np.array([[2.0 + 0.3 * abs(np.sin(t))]])
    with pytest.raises(SamplingError, match="did not reach the relative error") as info:
        floquet_analysis_matrices(np.eye(1), np.array([[0.05]]), K, TWO_PI, sampling="spectral")
    err = info.value
    assert isinstance(err, PinlinError) and isinstance(err, RuntimeError)
    # algebraic decay: the error falls by about 4 per doubling, below the stagnation factor 8, from 32 samples
    assert err.samples == 64 and len(err.history) == 3 and err.history[2] > err.history[1] / 8
    auto = floquet_analysis_matrices(np.eye(1), np.array([[0.05]]), K, TWO_PI)
    nodes = floquet_analysis_matrices(np.eye(1), np.array([[0.05]]), K, TWO_PI, sampling="nodes")
    np.testing.assert_array_equal(auto.multipliers, nodes.multipliers)
    assert auto.evaluations == nodes.evaluations + 64 and "sampling did not converge: 64 samples" in auto.method


@pytest.mark.parametrize("delta, eps, damping", [(1.3, 0.4, 0.0), (0.25, 0.1, 0.0), (1.0, 0.6, 0.05)])
def test_sampled_and_nodes_paths_agree_on_mathieu(delta, eps, damping):
    spectral = floquet_analysis_matrices(*mathieu(delta, eps, damping), TWO_PI, sampling="spectral")
    nodes = floquet_analysis_matrices(*mathieu(delta, eps, damping), TWO_PI, sampling="nodes")
    assert spectral.evaluations == 16 and "16 equispaced samples" in spectral.method
    for mu, bound in zip(spectral.multipliers, spectral.error_bound):
        distance = np.min(np.abs(nodes.multipliers - mu))
        assert distance <= bound + nodes.error_bound.max()
        assert distance <= 1e-12 * abs(mu)
    assert spectral.conservative == nodes.conservative == (damping == 0.0)
    assert spectral.stability.kind == nodes.stability.kind


def test_grid_and_sequential_integrators_agree_where_the_grid_refines():
    # a narrow bump in the stiffness between two of the 64 probes (at pi and pi + 0.098): the uniform first
    # grid, made for the rate sqrt(2) seen there, is too coarse across the bump and is split
    def stiffness(t):
        return 2.0 + 30.0 * np.exp(-((np.asarray(t) - np.pi - 0.049) / 0.02) ** 2)

    def A(t):
        return np.array([[0.0, 1.0], [-stiffness(t), -0.1]])

    def A_batch(times):
        out = np.zeros((np.size(times), 2, 2))
        out[:, 0, 1], out[:, 1, 0], out[:, 1, 1] = 1.0, -stiffness(times), -0.1
        return out

    grid = integrate_on_grid(A_batch, TWO_PI, 2, second_order=True)
    sequential = integrate_transitions(A, TWO_PI, 2)
    assert grid.rejected > 0
    products = []
    for tr in (grid, sequential):
        Phi = np.eye(2)
        for factor in tr.factors:
            Phi = factor @ Phi
        products.append(Phi)
    assert_allclose(products[0], products[1], rtol=0, atol=1e-11 * np.abs(products[1]).max())
    starts = np.array([step.t0 for step in grid.steps])
    ends = starts + np.array([step.h for step in grid.steps])
    assert starts[0] == 0.0 and np.allclose(starts[1:], ends[:-1], rtol=0, atol=1e-15) and ends[-1] == pytest.approx(TWO_PI)


def test_the_coefficient_term_is_the_scalar_variation_of_constants():
    # y' = a y over one step: dP = int_0^h e^(a (h - t)) da e^(a t) dt = da h e^(a h), whatever the nodes
    a, h, da = -0.7, 0.3, 2e-9
    c, _, b = gauss_legendre(6)
    nodes = np.concatenate([c * h / 2, h / 2 + c * h / 2])
    stage = np.exp(a * nodes)[:, None, None]
    step = Step(0.0, h, np.array([[np.exp(a * h)]]), np.zeros((1, 1)), 0.0, 0.0, nodes, stage,
                np.concatenate([b, b]) * h / 2, np.array([[da]]))
    u, v = 0.6 + 0.8j, 1.5 - 0.5j
    term = coefficient_terms([step], np.array([[[u]]]), np.array([[[v]]]))
    assert_allclose(term, [da * h * np.exp(a * h) * abs(u) * abs(v)], rtol=1e-14)


@pytest.fixture(scope="module")
def analytic_reference():
    """Multipliers of x'' + 0.05 x' + (2 + 0.3 exp(cos t)) x = 0 by mpmath's Taylor integrator, 25 digits."""
    with mpmath.workdps(25):
        def F(t, y):
            k = 2 + mpmath.mpf("0.3") * mpmath.exp(mpmath.cos(t))
            return [y[1], -k * y[0] - mpmath.mpf("0.05") * y[1], y[3], -k * y[2] - mpmath.mpf("0.05") * y[3]]
        y = mpmath.odefun(F, 0, [1, 0, 0, 1])(2 * mpmath.pi)
        ev = mpmath.eig(mpmath.matrix([[y[0], y[2]], [y[1], y[3]]]), left=False, right=False)
        return np.array([complex(z) for z in ev])


def test_an_interpolation_error_that_counts_is_in_the_bound(analytic_reference, monkeypatch):
    def K(t):
        return np.array([[2.0 + 0.3 * np.exp(np.cos(t))]])
    loose = floquet_analysis_matrices(np.eye(1), np.array([[0.05]]), K, TWO_PI, rtol=1e-7, sampling="spectral")
    tight = floquet_analysis_matrices(np.eye(1), np.array([[0.05]]), K, TWO_PI, sampling="spectral")
    for result in (loose, tight):
        for mu, bound in zip(result.multipliers, result.error_bound):
            assert np.min(np.abs(analytic_reference - mu)) <= bound
    # rtol 1e-7 stops at 32 samples with a measured error of about 1e-8, far above rounding: the bound carries
    # it (the first-order effect of the stiffness error through both modes, about T 3e-9 |mu|), while the
    # rtol 1e-13 run samples until the error is rounding and its bound is the integration's alone
    assert loose.evaluations == 32 and tight.evaluations > 32
    assert loose.error > 1e3 * tight.error
    # the measured 2.3e-9 of the stiffness (times max |K| = 2 + 0.3 e) is what the loose bound is made of:
    # without the coefficient term the same run's bound is the integration's 4e-13
    import pinlin.periodic.bounds as bounds
    monkeypatch.setattr(bounds, "coefficient_terms", lambda steps, R, L: np.zeros(R.shape[2]))
    without = floquet_analysis_matrices(np.eye(1), np.array([[0.05]]), K, TWO_PI, rtol=1e-7, sampling="spectral")
    assert np.all(loose.error_bound > 1e4 * without.error_bound)
    assert "measured relative error 2.3e-09" in loose.method


def test_bad_sampling_options_are_named():
    for sampling in ("fft", None, 3):
        with pytest.raises(ParameterError, match="sampling: expected one of 'auto', 'spectral', 'nodes'"):
            floquet_analysis_matrices(*mathieu(1.3, 0.4), TWO_PI, sampling=sampling)
    for max_samples in (8, 10**6, 64.0, True):
        with pytest.raises(ParameterError, match="max_samples: expected an int in 16..65536"):
            floquet_from_first_order(np.eye(2), 1.0, max_samples=max_samples)


def _lagrangian(t, damping=0.0, circulatory=0.0):
    """M x'' + (M' + F - F^T) x' + (S + F') x = 0 from L = x'^T M x' / 2 + x'^T F x - x^T S x / 2 (period
    2 pi), plus a damping d I and a circulatory c J that break it."""
    M = np.array([[2.0 + 0.5 * np.cos(t), 0.3 * np.sin(t)], [0.3 * np.sin(t), 1.5]])
    dM = np.array([[-0.5 * np.sin(t), 0.3 * np.cos(t)], [0.3 * np.cos(t), 0.0]])
    F = np.array([[0.0, 0.4 * np.cos(t)], [0.2, 0.1 * np.sin(t)]])
    dF = np.array([[0.0, -0.4 * np.sin(t)], [0.0, 0.1 * np.cos(t)]])
    S = np.diag([3.0, 5.0]) + 0.2 * np.cos(2 * t) * np.array([[1.0, 0.5], [0.5, 0.0]])
    J = np.array([[0.0, 1.0], [-1.0, 0.0]])
    return M, dM + F - F.T + damping * np.eye(2), S + dF + circulatory * J


def _lagrangian_analysis(**options):
    damping, circulatory = options.pop("damping", 0.0), options.pop("circulatory", 0.0)
    parts = [lambda t, i=i: _lagrangian(t, damping, circulatory)[i] for i in range(3)]
    return floquet_analysis_matrices(*parts, TWO_PI, **options)


def test_a_time_varying_lagrangian_system_is_recognized_as_conservative():
    # M and G = skew(C) change with time: the constant-structure test cannot see that the monodromy is
    # symplectic; the identities sym(C) = M' and skew(K) = skew(C)' / 2 on the interpolant's derivatives can
    sampled = _lagrangian_analysis()
    asserted = _lagrangian_analysis(conservative=True, sampling="nodes")
    assert sampled.conservative and asserted.conservative
    assert sampled.stability.kind == asserted.stability.kind == "marginally_stable"
    assert_allclose(np.abs(sampled.multipliers), 1.0, rtol=0, atol=1e-12)
    # evaluated at the nodes there are no derivatives: the multipliers on the circle stay undecided
    nodes = _lagrangian_analysis(sampling="nodes")
    assert not nodes.conservative and nodes.stability.kind == "undecided"


@pytest.mark.parametrize("breaking", [{"damping": 1e-9}, {"circulatory": 1e-9}])
def test_a_broken_lagrangian_structure_is_not_taken_for_conservative(breaking):
    result = _lagrangian_analysis(**breaking)
    assert not result.conservative
    assert result.stability.kind in ("undecided", "asymptotically_stable", "flutter")


def _spinning_disk(damping: float = 0.0) -> pinlin.Scene:
    """A disk with Ixx != Iyy spun at 23 rad/s on two tilts held by springs: its inertia in the tilt
    coordinates turns with it (M(t) periodic), the variational equation of a Lagrangian system."""
    tiny = '<inertial><mass value="0.01"/><inertia ixx="1e-6" iyy="1e-6" izz="1e-6" ixy="0" ixz="0" iyz="0"/></inertial>'
    disk = '<inertial><mass value="2.0"/><inertia ixx="0.02" iyy="0.05" izz="0.06" ixy="0" ixz="0" iyz="0"/></inertial>'
    lim = '<limit lower="-1" upper="1" effort="1e3" velocity="1e3"/>'
    urdf = ('<robot name="spinning_disk"><link name="world"/>'
            f'<link name="l_tx">{tiny}</link><link name="l_ty">{tiny}</link><link name="disk">{disk}</link>'
            f'<joint name="tx" type="revolute"><parent link="world"/><child link="l_tx"/><axis xyz="1 0 0"/>{lim}</joint>'
            f'<joint name="ty" type="revolute"><parent link="l_tx"/><child link="l_ty"/><axis xyz="0 1 0"/>{lim}</joint>'
            '<joint name="spin" type="continuous"><parent link="l_ty"/><child link="disk"/><axis xyz="0 0 1"/></joint>'
            '</robot>')
    robot = pinlin.load_urdf_string(urdf)
    elements = [pinlin.JointSpring("tx", 60.0), pinlin.JointSpring("ty", 35.0)]
    if damping:
        elements.append(pinlin.JointDamper("tx", damping))
    return pinlin.Scene(robot, elements, gravity=(0.0, 0.0, 0.0), prescribed={"spin": 23.0})


def test_a_spinning_asymmetric_disk_is_decided_from_its_lagrangian_structure():
    scene = _spinning_disk()
    orbit = pinlin.periodic_orbit(scene, scene.neutral())
    co = pinlin.variational_coefficients(scene, orbit)
    assert np.abs(co.M(0.0) - co.M(0.25 * orbit.period)).max() > 1e-3       # M turns with the disk
    flo = pinlin.floquet_analysis(scene, orbit)
    asserted = pinlin.floquet_analysis(scene, orbit, conservative=True, sampling="nodes")
    assert flo.conservative and flo.stability.kind == asserted.stability.kind
    assert flo.stability.kind == "marginally_stable" and "conservative" in flo.stability.reason
    damped = _spinning_disk(1e-9)
    flo_damped = pinlin.floquet_analysis(damped, pinlin.periodic_orbit(damped, damped.neutral()))
    assert not flo_damped.conservative


# ----------------------------------------------------------------------------- thresholds at their boundaries


def test_a_measured_error_counts_only_above_64_eps():
    from pinlin.periodic.sampled import counted_errors
    # 64 eps = 64 * 2^-52 = 1.4210854715202004e-14: the samples' own rounding, not counted; the next double is
    assert_allclose(counted_errors(np.array([1.4210854715202004e-14, 1.4210854715202007e-14, 3e-9])),
                    [0.0, 1.4210854715202007e-14, 3e-9], rtol=0, atol=0)


def test_the_doubling_stalls_below_a_factor_8_from_64_samples():
    from pinlin.periodic.sampling import stalled
    assert not stalled([1e-3, 1.25e-4], 64)            # exactly 8 times lower: still converging
    assert stalled([1e-3, 1.2500001e-4], 64)
    assert not stalled([1e-3, 5e-4], 32)               # 16 against 16 fresh samples: too early to judge
    assert stalled([1e-3, 5e-4], 64) and not stalled([1e-3], 64)


def test_the_damping_scale_is_at_least_sqrt_m_k():
    from pinlin.periodic.sampled import second_order_scales
    samples = np.array([[[[4.0]], [[0.1]], [[9.0]]], [[[2.0]], [[-0.2]], [[1.0]]]])
    assert_allclose(second_order_scales(samples), [4.0, 6.0, 9.0], rtol=1e-15)      # sqrt(4 * 9) = 6 > 0.2
    samples[0, 1] = 10.0
    assert_allclose(second_order_scales(samples), [4.0, 10.0, 9.0], rtol=1e-15)


def test_block_errors_carry_the_measured_stiffness_error_through_the_mass():
    from pinlin.periodic.sampled import block_errors, second_order_scales
    from pinlin.linearization.state_form import first_order_form

    def triple(t):   # M = 2 and C = 0.05 constant (their errors are rounding), K = 2 + 0.3 exp(cos t)
        return np.array([[[2.0]], [[0.05]], [[2.0 + 0.3 * np.exp(np.cos(t))]]])
    samples = sample_periodic(triple, TWO_PI, tol=1e-7, scales=second_order_scales)
    S = samples.samples
    A = first_order_form(S[:, 0], S[:, 1], S[:, 2])[0]
    # d(M^-1 K) = M^-1 dK with dK = (measured relative error) (largest |K| = 2 + 0.3 e) and ||M^-1|| = 1 / 2
    expected = samples.error[2] * (2.0 + 0.3 * np.e) / 2.0
    assert samples.error[2] > 1e-10
    assert_allclose(block_errors(samples, A, 1), [[0.0, 0.0], [expected, 0.0]], rtol=1e-12, atol=0)


def test_the_lagrangian_defect_is_the_larger_identity_defect():
    from pinlin.periodic.second_order import lagrangian_defect
    M, dM = np.eye(2)[None], np.zeros((1, 2, 2))
    C, dC = np.array([[[0.0, 1.0], [-1.0, 0.0]]]), np.array([[[0.0, 2.0], [-2.0, 0.0]]])
    K = np.array([[[3.0, 0.5], [-0.5, 3.0]]])
    # sym(C) = M' holds; skew(K) - skew(C)' / 2 has entries 0.5 - 1: 0.5 over |K| + rate |C| = 3 + 2 * 1
    assert_allclose(lagrangian_defect(M, C, K, dM, dC, 2.0), 0.1, rtol=1e-15)
    K = np.array([[[3.0, 1.0], [-1.0, 3.0]]])
    assert lagrangian_defect(M, C, K, dM, dC, 2.0) == 0.0


@pytest.mark.parametrize("factor, conservative", [(0.99, False), (1.01, True)])
def test_the_lagrangian_structure_is_decided_at_the_structure_tolerance(factor, conservative):
    # a damping d = 1e-11 I breaks sym(C) = M' by d; over the 16 samples |C| <= 0.9 (0.7 cos t - 0.2 at t = pi)
    # and |M| <= 2.5, the rate 16 / 2: the defect is 1e-11 / (0.9 + 8 * 2.5) in units of eps
    defect = 1e-11 / (0.9 + 8 * 2.5) / np.finfo(float).eps
    result = _lagrangian_analysis(damping=1e-11, structure_tol=factor * defect)
    assert result.evaluations == 16 and result.conservative == conservative


def test_max_samples_from_16():
    with pytest.raises(ParameterError, match="max_samples: expected an int in 16..65536, got 15"):
        floquet_analysis_matrices(*mathieu(1.3, 0.4), TWO_PI, max_samples=15)
    assert floquet_analysis_matrices(*mathieu(1.3, 0.4), TWO_PI, max_samples=16).evaluations == 16


def test_the_grid_counts_the_evaluations_it_makes():
    def A_batch(times):
        out = np.zeros((np.size(times), 2, 2))
        out[:, 0, 1], out[:, 1, 0] = 1.0, -(2.0 + np.cos(np.asarray(times)))
        return out
    plain = integrate_on_grid(A_batch, TWO_PI, 2, second_order=True)
    # A(0), the 64 probes, and 3 s = 18 nodes for each step taken (accepted or rejected)
    assert plain.evaluations == 1 + 64 + 18 * (len(plain.steps) + plain.rejected)
    given = integrate_on_grid(A_batch, TWO_PI, 2, second_order=True, A0=A_batch([0.0])[0],
                              probe=A_batch(np.linspace(0, TWO_PI, 16, endpoint=False)))
    assert given.evaluations == 18 * (len(given.steps) + given.rejected)


def test_non_finite_samples_are_named():
    from pinlin.periodic.options import FloquetOptions
    from pinlin.periodic.sampled import second_order_transitions

    def triple(t):   # an unchecked coefficient function (a scene's) that breaks at t = pi / 2
        return np.array([[[1.0]], [[0.0]], [[np.nan if abs(t - np.pi / 2) < 1e-12 else 2.0]]])
    with pytest.raises(ParameterError, match="K: non-finite entries at t = 1.5708 s"):
        second_order_transitions(triple, None, TWO_PI, 1, FloquetOptions(sampling="spectral"))


def test_the_grid_refuses_non_finite_coefficients():
    from pinlin import IntegrationError

    def A_batch(times):
        out = np.zeros((np.size(times), 2, 2))
        out[:, 0, 1], out[:, 1, 0] = 1.0, np.where(np.asarray(times) > 3.0, np.nan, -2.0)
        return out
    with pytest.raises(IntegrationError, match="not finite at t = 0 or at a probed time"):
        integrate_on_grid(A_batch, TWO_PI, 2, second_order=True)
