"""Campbell diagrams of periodic systems : Floquet exponents against the rotor speed.

Reference: the three-bladed lag-hinged rotor on an anisotropic hub (Coleman and Feingold, NACA TR 1351, 1958;
the hand-derived matrices of tests/periodic/floquet_cases.py): in multi-blade coordinates it is time-invariant,
so at every speed each Floquet exponent of the blade coordinates equals a multi-blade eigenvalue modulo
i Omega (the Coleman transform has period 2 pi / Omega).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

import pinlin

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "periodic"))
from floquet_cases import lag_rotor  # noqa: E402

SPEEDS = np.linspace(1.0, 5.0, 6)


def blade_floquet(w):
    (M, C, K), T = lag_rotor(3, Omega=w)
    return pinlin.floquet_analysis_matrices(M, C, K, T)


def test_exponents_equal_the_multiblade_eigenvalues_modulo_the_speed_at_every_speed():
    result = pinlin.floquet_campbell(blade_floquet, SPEEDS)
    assert result.exponents.shape == (SPEEDS.size, 10) and result.error_bound.shape == result.exponents.shape
    for w, row in zip(SPEEDS, result.exponents):
        (M, C, K), _ = lag_rotor(3, Omega=w)
        lam = pinlin.modal_analysis(pinlin.multiblade_transform_matrices(M, C, K, [2, 3, 4], w)).eigenvalues
        for x in row:   # Re part and the frequency modulo Omega
            gap = min(abs(x.real - y.real) + abs(((x.imag - y.imag) / w + 0.5) % 1.0 - 0.5) * w for y in lam)
            assert gap < 1e-8
    assert np.all(result.error_bound >= 0) and result.error < 1e-8
    # ground resonance: the verdict changes across the range, and a tracked column crosses Re = 0
    assert set(result.stable) == {"asymptotically_stable", "flutter"} or "flutter" in set(result.stable)
    assert np.any(np.max(result.exponents.real, axis=0) > 0) and np.any(np.min(result.exponents.real, axis=0) < 0)
    assert result.tracked.eigenvalues.shape == result.exponents.shape
    assert "FloquetCampbell(steps=6, modes=10" in repr(result)


def test_plot_draws_the_tracked_frequencies(tmp_path):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    result = pinlin.floquet_campbell(blade_floquet, SPEEDS[:3])
    ax = pinlin.plot.campbell(result.speeds, result.exponents, error_bounds=result.error_bound)
    assert ax.get_xlabel() and ax.lines


def test_bad_input_is_refused():
    with pytest.raises(pinlin.ParameterError, match="at least two finite speeds"):
        pinlin.floquet_campbell(blade_floquet, [1.0])
    with pytest.raises(pinlin.ParameterError, match="at least two finite speeds"):
        pinlin.floquet_campbell(blade_floquet, [1.0, np.nan])
    with pytest.raises(pinlin.errors.SystemFunctionError, match="expected a FloquetAnalysis"):
        pinlin.floquet_campbell(lambda w: None, [1.0, 2.0])
    with pytest.raises(pinlin.errors.SystemFunctionError, match=r"func\(2.0\) raised ZeroDivisionError"):
        pinlin.floquet_campbell(lambda w: blade_floquet(w) if w < 2 else 1 / 0, [1.0, 2.0])


def test_error_figures_are_the_analyses_own():
    """error = the largest relative multiplier bound over the speeds; error_bound[s, j] = b / (|mu| T) of the
    multiplier tracked into column j (recomputed from fresh analyses)."""
    result = pinlin.floquet_campbell(blade_floquet, SPEEDS[:3])
    fresh = [blade_floquet(w) for w in SPEEDS[:3]]
    assert result.error == max(f.error for f in fresh)
    for s, f in enumerate(fresh):
        expected = np.asarray(f.error_bound) / np.abs(f.multipliers) / f.period
        order = np.asarray(result.tracked.order[s])
        np.testing.assert_allclose(result.error_bound[s], expected[order], rtol=1e-12)
