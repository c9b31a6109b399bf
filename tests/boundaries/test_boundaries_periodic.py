"""Stability boundaries of periodic families: Mathieu's tongues, a damped Mathieu equation,
Kapitza's critical frequency.

References: the Mathieu characteristic values a_r(q), b_r(q) (scipy.special; McLachlan, Theory and
Application of Mathieu Functions, 1947): x'' + (delta + eps cos t) x = 0 is y'' + (a - 2 q cos 2z) y = 0
with t = 2 z, a = 4 delta, q = -2 eps; at fixed q the first tongue of instability is (b_1, a_1) (regions
symmetric in q).  Kapitza (1951): the inverted pendulum on a pivot z_p = A sin(omega t) is stable where
4 delta > a_0(2 eps), delta = -g / (l omega^2), eps = A / l.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.special
from numpy.testing import assert_allclose

import pinlin
from pinlin.boundaries.periodic import periodic_critical_parameter, stability_function

EPS = 0.3
Q = 2 * EPS


def mathieu(delta: float, damping: float = 0.0):
    return pinlin.floquet_analysis_matrices(np.eye(1), 2.0 * damping * np.eye(1),
                                            lambda t: np.array([[delta + EPS * np.cos(t)]]), 2 * np.pi)


@pytest.mark.parametrize(
    ("edge", "bracket"),
    [("b1", (0.05, 0.25)), ("a1", (0.25, 0.6))],
)
def test_first_tongue_edges_equal_the_mathieu_characteristic_values(edge, bracket):
    exact = (scipy.special.mathieu_b(1, Q) if edge == "b1" else scipy.special.mathieu_a(1, Q)) / 4
    assert bracket[0] < exact < bracket[1]
    crit = periodic_critical_parameter(mathieu, bracket)
    assert_allclose(crit.value, exact, rtol=0, atol=1e-9)
    assert abs(crit.value - exact) <= crit.error_bound   # the bound contains the reference
    assert crit.error_bound < 1e-8
    assert crit.mechanism == "multiplier crossing" and crit.kind in ("flutter", "divergence")
    assert abs(abs(crit.eigenvalue) - 1.0) < 1e-7 and abs(crit.eigenvalue.real + 1.0) < 1e-3   # mu = -1: period 4 pi
    assert crit.verified and crit.evaluations == crit.function_calls <= 40


def test_conservative_stability_function_is_signed_distance_of_c_from_one():
    """On the circle c = cos(theta) in (-1, 1): sigma = |c| - 1 < 0; in the tongue c real beyond -1."""
    inside, outside = mathieu(0.25), mathieu(0.6)
    s_in, e_in, _ = stability_function(inside)
    s_out, e_out, _ = stability_function(outside)
    assert s_in > 0 > s_out
    mu = np.asarray(outside.multipliers)
    assert_allclose(s_out, np.max(np.abs(((mu + 1 / mu) / 2).real)) - 1, rtol=1e-12)
    assert 0 < e_in < 1e-8 and 0 < e_out < 1e-8


def test_damped_boundary_obeys_the_exponential_shift():
    """x'' + 2 z x' + (delta + eps cos t) x = 0 is x = exp(-z t) y with y'' + (delta - z^2 + eps cos t) y = 0,
    so at the damped boundary the undamped y-system (delta - z^2) has |mu| = exp(2 pi z) exactly."""
    zeta = 0.01
    crit = periodic_critical_parameter(lambda d: mathieu(d, zeta), (0.02, 0.25))
    shifted = mathieu(crit.value - zeta**2)
    assert_allclose(np.max(np.abs(shifted.multipliers)), math.exp(2 * math.pi * zeta), rtol=1e-9)
    assert crit.error_bound < 1e-8
    # the damped tongue is narrower: its edge lies inside the undamped one
    assert scipy.special.mathieu_b(1, Q) / 4 < crit.value


def test_kapitza_critical_frequency_from_a_scene():
    """The bundled Kapitza pendulum: stable upside down above omega_c = sqrt(-4 g / (l a_0(2 A / l)))."""
    spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    A, l, g = 0.02, 0.2, 9.81
    omega_c = math.sqrt(-4 * g / (l * scipy.special.mathieu_a(0, 2 * A / l)))

    def family(omega):
        scene = spec.scene.replace(prescribed={"pivot": pinlin.Harmonic(A, omega)})
        return pinlin.floquet_analysis(scene, pinlin.periodic_orbit(scene, spec.q0))

    crit = periodic_critical_parameter(family, (0.8 * omega_c, 1.25 * omega_c))
    assert_allclose(crit.value, omega_c, rtol=1e-9)
    assert abs(crit.value - omega_c) <= crit.error_bound
    assert crit.verdicts[0] == "divergence" and crit.verdicts[1] == "marginally_stable"


def test_bad_brackets_and_families_are_refused():
    with pytest.raises(pinlin.BracketError, match="stable at one end and unstable"):
        periodic_critical_parameter(mathieu, (0.5, 0.6))  # both between a1/4 and b2/4: stable
    with pytest.raises(pinlin.BracketError, match="two increasing numbers"):
        periodic_critical_parameter(mathieu, (0.3, 0.1))
    with pytest.raises(pinlin.errors.SystemFunctionError, match="returned LinearizedSystem"):
        periodic_critical_parameter(
            lambda d: mathieu(d) if d < 0.2 else pinlin.LinearizedSystem.from_matrices(np.eye(1)), (0.1, 0.3))
    with pytest.raises(pinlin.errors.SystemFunctionError, match="max_evaluations = 3"):
        periodic_critical_parameter(mathieu, (0.05, 0.25), max_evaluations=3)


def test_ground_resonance_range_from_floquet_equals_the_multiblade_range():
    """Coleman and Feingold's ground resonance (three lag-hinged blades on an anisotropic hub, the hand-derived
    matrices of tests/periodic/floquet_cases.py): the speed range of instability from the Floquet analysis in
    blade coordinates equals the one from the time-invariant multi-blade eigenvalues."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "periodic"))
    from floquet_cases import lag_rotor

    def blade(w):
        (M, C, K), T = lag_rotor(3, Omega=w)
        return pinlin.floquet_analysis_matrices(M, C, K, T)

    def multiblade(w):
        (M, C, K), _ = lag_rotor(3, Omega=w)
        return pinlin.multiblade_transform_matrices(M, C, K, [2, 3, 4], w)

    speeds = np.linspace(0.5, 8.0, 31)
    unstable = [w for w in speeds if np.max(pinlin.modal_analysis(multiblade(w)).eigenvalues.real) > 0]
    assert unstable, "the case has a ground-resonance range"
    step = speeds[1] - speeds[0]
    for edge in (unstable[0] - step, unstable[-1]):
        bracket = (edge, edge + step)
        mbc = pinlin.critical_parameter(multiblade, bracket)
        flo = pinlin.critical_parameter(blade, bracket)
        assert flo.mechanism == "multiplier crossing" and mbc.mechanism != "multiplier crossing"
        assert abs(flo.value - mbc.value) <= 1e-9 + flo.error_bound + mbc.error_bound
        assert flo.error_bound < 1e-8 and mbc.error_bound < 1e-8


def test_the_error_bound_is_its_documented_formula():
    """error_bound = (b - a) + max(e_a, e_b) / |slope| over the final bracket (a, b), widened by powers of 10
    until the verdicts at value -+ bound are decided and differ; recomputed here from fresh analyses."""
    crit = periodic_critical_parameter(mathieu, (0.0, 0.25))
    a, b = crit.bracket
    (sa, ea, _), (sb, eb, _) = stability_function(mathieu(a)), stability_function(mathieu(b))
    assert (sa < 0) != (sb < 0)
    formula = (b - a) + max(ea, eb) / abs((sb - sa) / (b - a))
    k = math.log10(crit.error_bound / formula)
    assert k > -1e-9 and abs(k - round(k)) < 1e-9   # a power of ten times the formula: half of it fails
    from pinlin.boundaries.evaluation import VERDICT_CLASS

    def kind(p):
        return VERDICT_CLASS[mathieu(p).stability.kind]

    below, above = kind(crit.value - crit.error_bound), kind(crit.value + crit.error_bound)
    assert "undecided" not in (below, above) and (below == "stable") != (above == "stable")
    if round(k) > 0:   # widened: one step less did not decide
        w = crit.error_bound / 10
        assert "undecided" in (kind(crit.value - w), kind(crit.value + w)) or \
            (kind(crit.value - w) == "stable") == (kind(crit.value + w) == "stable")

