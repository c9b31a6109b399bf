"""pinlin.studies.tracking: modes followed through a sweep by their shapes, with a matching defect."""

import json

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.studies.tracking import mac, one_per_conjugate_pair, track_modes
from studies.cases import crossing_sweep


def test_tracking_follows_shapes_through_a_crossing():
    ps, lams, vecs = crossing_sweep()
    tracked = track_modes(lams, vecs)
    # column 0 starts as the mode with shape e1 (frequency p) and must stay it
    assert_allclose(tracked.eigenvalues[:, 0].imag, ps, atol=1e-15)
    assert_allclose(tracked.eigenvalues[:, 1].imag, 2 - ps, atol=1e-15)
    assert_allclose(tracked.match, 1.0)
    assert_allclose(mac(tracked.vectors[-1], tracked.vectors[0]), np.eye(2))
    assert tracked.error == 0.0  # every match has MAC exactly 1


def test_error_with_shapes_is_one_minus_the_worst_mac():
    """Shapes turned by theta between two steps: MAC = cos^2 theta, so error = sin^2 theta."""
    theta = 0.2
    c, s = np.cos(theta), np.sin(theta)
    lam = np.array([[1j, 3j], [1.1j, 3.2j], [1.2j, 3.1j]])
    shapes = np.array([np.eye(2), [[c, -s], [s, c]], [[c, -s], [s, c]]], dtype=complex)
    tracked = track_modes(lam, shapes)
    assert_allclose(tracked.match, [1.0, c**2, 1.0], rtol=1e-14)
    assert_allclose(tracked.error, s**2, rtol=1e-12)
    assert "MAC" in tracked.method and "0.5" in tracked.method
    # the eigenvalue jumps are kept too: |1.1i - 1i| / 2.1 and |3.2i - 3i| / 6.2 at step 1
    assert_allclose(tracked.jump, [0.0, max(0.1 / 2.1, 0.2 / 6.2), max(0.1 / 2.3, 0.1 / 6.3)], rtol=1e-12)


def test_error_without_shapes_is_the_largest_relative_jump():
    lam = np.array([[-1 + 2j, -3.0], [-1 + 2.5j, -2.0]])
    tracked = track_modes(lam)
    jumps = [abs(0.5j) / (abs(-1 + 2j) + abs(-1 + 2.5j)), 1.0 / 5.0]
    assert_allclose(tracked.error, max(jumps), rtol=1e-14)
    assert np.all(np.isnan(tracked.match)) and tracked.vectors is None
    assert "eigenvalue distance" in tracked.method and "no shapes" in tracked.method


def test_result_convention():
    ps, lams, vecs = crossing_sweep()
    tracked = track_modes(lams, vecs)
    assert tracked.elapsed >= 0
    assert repr(tracked).startswith("TrackedModes(11 steps x 2 modes, with shapes, error=0.00e+00")
    data = json.loads(json.dumps(tracked.to_dict(), allow_nan=False))
    assert data["type"] == "TrackedModes" and data["error"] == 0.0
    assert data["order"][0] == [0, 1] and data["eigenvalues"]["im"][0] == [0.5, 1.5]
    with pytest.raises(ValueError, match="read-only"):
        tracked.eigenvalues[0, 0] = 0.0


def test_tracking_bad_input():
    with pytest.raises(pinlin.ParameterError, match=r"expected shape \(steps, m\)"):
        track_modes(np.ones(3))
    with pytest.raises(pinlin.ParameterError, match="vectors: expected shape"):
        track_modes(np.ones((3, 2)), np.ones((3, 2, 5)))
    with pytest.raises(pinlin.ParameterError, match="non-finite"):
        track_modes(np.array([[np.nan, 1.0]]))
    with pytest.raises(pinlin.ParameterError, match="vectors: has non-finite"):
        track_modes(np.ones((1, 2)), np.full((1, 2, 2), np.nan))
    with pytest.raises(pinlin.ParameterError, match="eigenvalue_weight: must be >= 0"):
        track_modes(np.ones((1, 2)), eigenvalue_weight=-1.0)
    with pytest.raises(pinlin.ParameterError, match=r"lam: expected shape \(steps, m\)"):
        one_per_conjugate_pair(np.ones(3))


def test_one_per_conjugate_pair():
    """Of the pair +-i(2 - W) (its sign of Im flips), the column with the larger sum of Im is kept;
    a real column and a column with Im > 0 throughout are kept; a lone Im < 0 column is not."""
    W = np.array([0.0, 1.0, 3.0])
    lam = np.column_stack([1j * (2 - W), -1j * (2 - W), -np.ones(3), 1j * np.ones(3) + 5, -2j * np.ones(3) - 7])
    assert one_per_conjugate_pair(lam) == [0, 2, 3]


def test_one_per_conjugate_pair_rtol_is_conjugate_tol_with_a_warning():
    lam = np.array([[2.0, 2.0 + 2e-6]])  # two real roots 1e-6 apart (relative): a "pair" only above that
    assert one_per_conjugate_pair(lam) == [0, 1]
    assert one_per_conjugate_pair(lam, conjugate_tol=1e-5) == [0]
    with pytest.warns(DeprecationWarning, match=r"one_per_conjugate_pair\(rtol=...\) is deprecated .* conjugate_tol"):
        assert one_per_conjugate_pair(lam, rtol=1e-5) == [0]
    with pytest.warns(DeprecationWarning, match="CONJUGATE_TOL"):
        from pinlin.studies.tracking import CONJUGATE_RTOL
    assert CONJUGATE_RTOL == 1e-8
