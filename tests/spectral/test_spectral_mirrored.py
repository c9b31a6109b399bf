"""The mirrored figures of the structured paths, tested against the full path.

``mirrored_figures`` computes the figures of one member of each +-lam (or conjugate)
pair; it also hands back the weights w(lam) it formed for the range check.  Here:

- they equal the figures of the expanded spectrum (both members stored, ordered by
  ``order_spectrum`` and given to ``pair_figures``) and the definitions: eta from
  L(lam) x with L(lam) = lam^2 M + S, w(lam) = |lam|^2 ||M|| + ||S||;
- an inverted chain (divergence pairs first in eigh's order) takes the gather.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

import pinlin
from pinlin.spectral.accuracy import pair_figures
from pinlin.spectral.ordering import mirrored_figures, order_spectrum
from pinlin.spectral.paths import choose_path, solve_path
from pinlin.spectral.problem import as_problem
from spectral_cases import chain

#: Two computations of the same figure by different summation orders (the expanded
#: spectrum stores both members and permutes them): a few eps apart.
ROUNDING = 1e-13

EPS = float(np.finfo(float).eps)


def _symmetric_raw(sys):
    problem = as_problem(sys)
    name, reason, raw = choose_path(problem, "auto", 1e-10, 1e-15)
    assert name == "symmetric"
    raw, _, _ = solve_path(problem, name, reason, raw, True, 1e-15)
    return problem, raw


def _sorted_already(raw) -> bool:
    keys = np.lexsort((-np.abs(raw.lam.imag), raw.lam.real, np.abs(raw.lam)))
    return bool(np.array_equal(keys, np.arange(keys.size)))


def _reversed(raw):
    return dataclasses.replace(
        raw, lam=raw.lam[::-1].copy(), second=raw.second[::-1].copy(), P=raw.P[..., ::-1].copy(),
        block=raw.block[::-1].copy(),
    )


def _stiff_chain(n):
    return chain(n, 10.0 ** np.linspace(-5, 5, n))


@pytest.mark.parametrize("case", ["stiff", "inverted"])
def test_mirrored_figures_equal_the_expanded_spectrum_and_the_definitions(case):
    sys = _stiff_chain(12) if case == "stiff" else chain(4, [0.5, 0.4, 0.3, 0.2], gravity=(0, 0, 9.81))
    problem, raw = _symmetric_raw(sys)
    assert _sorted_already(raw) == (case == "stiff")
    if case == "inverted":
        assert np.count_nonzero(raw.lam.real) > 0  # divergence pairs (mu < 0): +-sqrt(-mu) real
    lam, block, fig, weight = mirrored_figures(problem, raw)
    full = order_spectrum(raw.expanded())
    ref = pair_figures(problem, full.lam, full.P, full.Y, full.eta, full.norm_x, full.weight)
    assert_array_equal(lam, full.lam)
    assert_array_equal(block, full.block)
    for name in ("right", "left", "derivative", "sensitivity", "error_bound", "products", "quadratic"):
        assert_allclose(getattr(fig, name), getattr(ref, name), rtol=ROUNDING, atol=0, err_msg=name)
    assert_allclose(fig.backward_error, ref.backward_error, rtol=ROUNDING, atol=EPS * EPS)
    # the definitions: w(lam) = |lam|^2 ||M|| + ||S|| (C = 0), eta = ||L(lam) x|| / (w ||x||)
    nM, nS = np.linalg.norm(sys.M), np.linalg.norm(sys.S)
    assert_allclose(weight, np.abs(lam) ** 2 * nM + nS, rtol=4 * EPS, atol=0)
    R = (sys.M @ fig.right) * lam**2 + sys.S @ fig.right
    eta = np.linalg.norm(R, axis=0) / (weight * np.linalg.norm(fig.right, axis=0))
    assert_allclose(fig.backward_error, eta, rtol=1e-6, atol=2 * EPS)
    assert fig.backward_error.max() <= 1e-15


def test_modal_analysis_reports_the_mirrored_figures():
    sys = _stiff_chain(20)
    problem, raw = _symmetric_raw(sys)
    lam, _, fig, _ = mirrored_figures(problem, raw)
    m = pinlin.modal_analysis(sys)
    assert_array_equal(m.eigenvalues, lam)
    assert_array_equal(m.backward_error, fig.backward_error)
    assert_array_equal(m.error_bound, fig.error_bound)
    assert_array_equal(m.left, fig.left)
