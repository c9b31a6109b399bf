"""Fuzzed array arguments of the public functions: shapes, dtypes, NaN and inf, 0, 1e-300, 1e300.

Each call must return a result whose headline error figure is finite (and whose
values hold no NaN while it is), or raise a PinlinError; never another
exception (a numpy error, a ZeroDivisionError, an IndexError), a numpy
ComplexWarning that drops an imaginary part, or a hang.

Bugs it found, fixed since and no longer left out: ragged nested lists and non-square
matrices in from_matrices, modal_analysis and linearize; huge points in adjugate / adjugate_eigenvectors,
arrays of strings in check_free_response, huge free responses and energy budgets.
"""

from __future__ import annotations

import warnings

import numpy as np
from fuzz_strategies import NASTY_FLOATS, arrays, check_result, outcome
from hypothesis import given
from hypothesis import strategies as st

import pinlin
from pinlin.model.scene_file import default_scene_path, load_scene

#: The fixed systems the frequency- and time-domain functions get: theory: double pendulum with a little damping.
CHECK = pinlin.LinearizedSystem.from_matrices(
    np.array([[1.04333333333, 0.2325], [0.2325, 0.075]]),
    np.array([[0.1, 0.0], [0.0, 0.1]]),
    np.array([[15.8511, 3.60725 + 1.4], [3.60725 - 1.4, 4.20725]]),
)
POLES = list(pinlin.modal_analysis(CHECK).eigenvalues)
SCENE = load_scene(default_scene_path()).scene

#: Scalars where a frequency-domain function is evaluated: nasty reals, any complex number, the poles
#: themselves and points within rounding of them.
POINTS = st.one_of(
    NASTY_FLOATS,
    st.complex_numbers(allow_nan=True, allow_infinity=True),
    st.complex_numbers(max_magnitude=100),
    st.sampled_from(POLES),
    st.sampled_from(POLES).map(lambda lam: lam * (1 + 1e-15)),
    st.sampled_from([0, 1j, -1j, 1e300j, 1e-300j]),
)


#: Beyond this magnitude an argument is "huge" for the known bugs below (half the double range's exponent).
HUGE = 1e150


def _magnitude(value) -> float:
    """The largest finite |entry| of ``value`` (0 when it has none or is not numeric)."""
    try:
        z = np.asarray(value, dtype=complex).ravel()
    except (TypeError, ValueError):
        return 0.0
    a = np.maximum(np.abs(z.real), np.abs(z.imag))  # |z| itself may overflow
    return float(np.max(a[np.isfinite(a)], initial=0.0))


def _error_on_complex_loss():
    """Turn numpy's ComplexWarning (an imaginary part dropped) into an error: no silent cast to real."""
    warnings.simplefilter("error", getattr(np, "exceptions", np).ComplexWarning)  # numpy >= 1.25 / older


@given(M=arrays([(2, 2)]), C=arrays([(2, 2)]), K=arrays([(2, 2)]), through=st.booleans())
def test_matrices_to_modal_analysis(M, C, K, through):
    with warnings.catch_warnings():
        _error_on_complex_loss()
        if through:
            sys_ = outcome(lambda: pinlin.LinearizedSystem.from_matrices(M, C, K), "from_matrices")
            if sys_ is not None:
                outcome(lambda: pinlin.modal_analysis(sys_), "modal_analysis(from_matrices)")
        else:
            outcome(lambda: pinlin.modal_analysis((M, C, K)), "modal_analysis((M, C, K))")


FREQUENCY_CALLS = {
    "flexibility": lambda a: pinlin.flexibility(CHECK, a),
    "frequency_response": lambda a: pinlin.frequency_response(CHECK, a),
    "harmonic_response": lambda a: pinlin.harmonic_response(CHECK, np.array([1.0, 0.0]), a),
    "adjugate": lambda a: pinlin.adjugate(CHECK, a),
    "residues": lambda a: pinlin.residues(CHECK, a),
    "jordan_chains": lambda a: pinlin.jordan_chains(CHECK, a),
    "adjugate_eigenvectors": lambda a: pinlin.adjugate_eigenvectors(CHECK, a),
}


@given(name=st.sampled_from(sorted(FREQUENCY_CALLS)),
       arg=st.one_of(POINTS, arrays([(3,)]), st.lists(POINTS, min_size=1, max_size=3).map(np.array)))
def test_frequency_domain_arguments(name, arg):
    with warnings.catch_warnings():
        _error_on_complex_loss()
        outcome(lambda: FREQUENCY_CALLS[name](arg), name)


@given(F=arrays([(2,)]), omega=st.one_of(NASTY_FLOATS, arrays([(3,)])))
def test_harmonic_force_amplitudes(F, omega):
    outcome(lambda: pinlin.harmonic_response(CHECK, F, omega), "harmonic_response(F)")


def _linspace(stop: float, num: int) -> np.ndarray:
    with np.errstate(all="ignore"):  # a grid up to 1e308 or inf: pinlin judges it, numpy need not warn
        return np.linspace(0.0, stop, num)


def _times():
    spans = st.one_of(NASTY_FLOATS, st.floats(0.01, 10))
    return st.one_of(
        st.tuples(spans, st.integers(1, 6)).map(lambda a: _linspace(a[0], a[1])),
        arrays([(4,)]),
    )


@given(x0=arrays([(2,)]), v0=arrays([(2,)]), x=arrays([(4, 2), (1, 2), (6, 2)]), t=_times(),
       which=st.sampled_from(["free", "check", "forced", "energy"]))
def test_time_domain_arguments(x0, v0, x, t, which):
    calls = {
        "free": lambda: pinlin.free_response(CHECK, x0, v0, t),
        "check": lambda: pinlin.check_free_response(CHECK, t, x),
        "forced": lambda: pinlin.forced_response(CHECK, x, t, x0, v0),
        "energy": lambda: pinlin.energy_budget(CHECK, t, x, x),
    }
    with warnings.catch_warnings():
        _error_on_complex_loss()
        outcome(calls[which], which)


@given(q=arrays([(2,)]), v=arrays([(2,)]), t=_times(),
       which=st.sampled_from(["linearize", "equilibrium", "coordinates", "simulate"]))
def test_scene_functions_arguments(q, v, t, which):
    with warnings.catch_warnings():
        _error_on_complex_loss()
        if which == "linearize":
            outcome(lambda: pinlin.linearize(SCENE, q, balancing=True), "linearize")
        elif which == "equilibrium":
            outcome(lambda: pinlin.find_equilibrium(SCENE, q), "find_equilibrium")
        elif which == "coordinates":
            outcome(lambda: pinlin.linear_coordinates(SCENE, np.zeros(2), q, v), "linear_coordinates")
        else:
            # a small budget keeps a far end time cheap: the run stops with IntegrationBudgetError
            outcome(lambda: pinlin.simulate(SCENE, q, v, t, max_steps=100), "simulate")


@given(qs=arrays([(1, 2), (3, 2), (7, 2)]))
def test_linearize_many_is_linearize_row_by_row(qs):
    """Whatever the rows (nasty values, wrong shapes and types included): linearize_many raises a
    PinlinError, or returns for every row what linearize returns for it, bitwise."""
    with warnings.catch_warnings():
        _error_on_complex_loss()
        systems = outcome(lambda: pinlin.linearize_many(SCENE, qs, balancing=True), "linearize_many")
    if systems is None:
        return
    rows = np.asarray(qs, dtype=float)
    assert len(systems) == len(rows)
    for row, system in zip(rows, systems):
        check_result(system, "linearize_many")
        single = pinlin.linearize(SCENE, row, balancing=True)
        for name in ("M", "D", "G", "S", "N", "q"):
            assert np.array_equal(getattr(system, name), getattr(single, name)), name
