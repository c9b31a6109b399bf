"""Which coordinates take part in each mode: energy shares, hand-derived.

A decoupled system's modes each live on their own coordinate; for a coupled
2-DOF system with a diagonal M the share of coordinate i is m_i x_i^2 /
sum_j m_j x_j^2 with the mode shape from the characteristic equation by hand.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin import LinearizedSystem
from pinlin.spectral.participation import DOMINANT_SHARE, participation
from spectral_cases import double_pendulum


def test_decoupled_modes_live_on_their_own_coordinate():
    M = np.diag([1.0, 2.0, 0.5])
    K = np.diag([4.0, 50.0, 200.0])
    C = np.diag([0.1, 0.2, 0.3])
    sys = LinearizedSystem.from_matrices(M, C, K, dof_names=("a", "b", "c"))
    modes = pinlin.modal_analysis(sys)
    p = modes.participation
    assert p.shape == (3, 6)
    own = np.argmax(np.abs(modes.right), axis=0)
    assert_allclose(p[own, np.arange(6)], 1.0, rtol=0, atol=1e-15)
    assert_allclose(p.sum(axis=0), 1.0, rtol=1e-15)
    # omega^2 = k/m: 4, 25, 400 -> modes ordered a, b, c, each a conjugate pair
    assert [row[0][0] for row in modes.dominant()] == ["a", "a", "b", "b", "c", "c"]
    assert all(len(row) == 1 for row in modes.dominant())


def test_coupled_two_dof_by_hand():
    """M = diag(1, 2), K = [[3, -1], [-1, 1]]: det(K - w M) = 2 w^2 - 7 w + 2 = 0, w = (7 -+ sqrt 33) / 4,
    shape x = (1, 3 - w) from the first row, share of coordinate 1: 1 / (1 + 2 (3 - w)^2)."""
    M = np.diag([1.0, 2.0])
    K = np.array([[3.0, -1.0], [-1.0, 1.0]])
    modes = pinlin.modal_analysis(LinearizedSystem.from_matrices(M, None, K))
    w = (7 - np.sqrt(33)) / 4, (7 + np.sqrt(33)) / 4
    first = [1 / (1 + 2 * (3 - wk) ** 2) for wk in w]
    expected = np.array([[first[0], first[0], first[1], first[1]], [1 - first[0], 1 - first[0], 1 - first[1], 1 - first[1]]])
    assert_allclose(modes.participation, expected, rtol=1e-13)
    assert_allclose(modes.natural_frequency**2, np.repeat(w, 2), rtol=1e-14)


def test_energy_split_for_damped_and_circulatory_modes():
    """Complex modes: the shares are (|T_i| + |V_i|) / sum, T_i and V_i recomputed here from the definition."""
    sys = double_pendulum(P=4.0, c=0.05)
    modes = pinlin.modal_analysis(sys)
    X, lam = np.asarray(modes.right), modes.eigenvalues
    T = np.abs(lam) ** 2 / 4 * (np.conj(X) * (sys.M @ X)).real
    V = (np.conj(X) * (sys.S @ X)).real / 4
    assert_allclose(modes.participation, (np.abs(T) + np.abs(V)) / (np.abs(T) + np.abs(V)).sum(axis=0), rtol=1e-13)
    assert np.all(modes.participation >= 0)


def test_divergent_and_rigid_body_modes_still_sum_to_one():
    # an inverted pendulum pair (S negative: real lam, T = -V per mode) and a free mass (lam = 0, S x = 0)
    M = np.diag([1.0, 3.0])
    K = np.array([[-2.0, 0.5], [0.5, 0.0]])
    p = pinlin.modal_analysis(LinearizedSystem.from_matrices(M, None, K)).participation
    assert np.all(np.isfinite(p)) and np.all(p >= 0)
    assert_allclose(p.sum(axis=0), 1.0, rtol=1e-14)
    free = pinlin.modal_analysis(LinearizedSystem.from_matrices(np.diag([1.0, 2.0]), None, np.diag([0.0, 5.0])))
    assert_allclose(free.participation.sum(axis=0), 1.0, rtol=1e-14)
    assert np.all(free.participation[0, free.kind.index("rigid_body")] == 1.0)


def test_dominant_coordinates_in_the_table_and_to_dict():
    sys = double_pendulum(P=4.0)
    modes = pinlin.modal_analysis(sys)
    rows = modes.dominant()
    assert all(all(share >= DOMINANT_SHARE for _, share in row) for row in rows)
    assert all([s for _, s in row] == sorted((s for _, s in row), reverse=True) for row in rows)
    table = modes.table()
    assert "dominant coordinates" in table and f"{rows[0][0][0]} {rows[0][0][1]:.0%}" in table
    assert " -0 " not in table
    data = json.loads(json.dumps(modes.to_dict()))
    assert_allclose(np.array(data["participation"]), modes.participation, rtol=0)
    assert data["dominant"][0][0] == {"name": rows[0][0][0], "share": rows[0][0][1]}
    # on tuple input the coordinates are x1, x2
    tup = pinlin.modal_analysis((sys.M, sys.C, sys.K))
    assert tup.dominant()[0][0][0] in ("x1", "x2")


def test_dominant_bad_input():
    modes = pinlin.modal_analysis(double_pendulum(P=4.0))
    with pytest.raises(pinlin.ParameterError, match="share: expected a share in"):
        modes.dominant(share=0.0)
    with pytest.raises(pinlin.ParameterError, match="count: expected a positive integer"):
        modes.dominant(count=0)


def test_participation_function_matches_the_attribute():
    sys = double_pendulum(P=4.0, c=0.05)
    modes = pinlin.modal_analysis(sys)
    assert_allclose(participation(modes.eigenvalues, modes.right, sys.M, sys.S), modes.participation, rtol=0)
