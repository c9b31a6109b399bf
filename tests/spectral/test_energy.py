"""Energy distribution per mode: ``modes.energy(k, scene)`` against closed forms.

- A two-mass chain on prismatic joints (m1 = 2, m2 = 1 kg; springs k1 = 3 N/m ground-m1 and
  k2 = 1 N/m m1-m2, URDF below): omega^2 = (3 -+ sqrt 3) / 2 and the absolute amplitudes
  a2 / a1 = 4 - 2 omega^2 = 1 +- sqrt 3 by hand, so the kinetic shares are
  m1 a1^2 : m2 a2^2 = 2 : (1 +- sqrt 3)^2 and the strain shares k1 a1^2 : k2 (a2 - a1)^2 = 3 : 3.
  Joint dampers c_i = beta k_i keep these shapes (proportional damping): dissipation shares
  c1 q1^2 : c2 q2^2 = 1 : 1 too.
- The bundled four-bar (constraints, ``sys.basis``) with a crank spring under gravity: each
  link's kinetic share m_k |v_k'|^2 + I_k omega_k'^2 over M_eff, and the spring's strain share
  k / (k + V_g'') (the energy method of tests/constrained_cases.py).
- Rayleigh damping (alpha M or beta K_e) on the chain: one damper row with share 1.
- A turntable with a prescribed spin: the spun table has no kinetic share; the centrifugal
  softening is a negative share of the rest row.
- Every table sums to 1 to 1e-12; bad input raises ParameterError.
"""

from __future__ import annotations

import cmath
import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from constrained_cases import BUNDLED

M1, M2, K1, K2, BETA = 2.0, 1.0, 3.0, 1.0, 0.01


def chain_urdf() -> str:
    """Two point-like masses sliding along x: ground -> m1 (joint q1 = x1) -> m2 (joint q2 = x2 - x1)."""
    def link(name, mass):
        return (f'<link name="{name}"><inertial><origin xyz="0 0 0"/><mass value="{mass}"/>'
                f'<inertia ixx="0" iyy="0" izz="0" ixy="0" ixz="0" iyz="0"/></inertial></link>')

    def joint(name, parent, child):
        return (f'<joint name="{name}" type="prismatic"><parent link="{parent}"/><child link="{child}"/>'
                f'<axis xyz="1 0 0"/><limit lower="-10" upper="10" effort="100" velocity="10"/></joint>')

    return (f'<?xml version="1.0"?><robot name="chain"><link name="ground"/>{link("m1", M1)}{link("m2", M2)}'
            f'{joint("j1", "ground", "m1")}{joint("j2", "m1", "m2")}</robot>')


def chain(damped: bool = False):
    robot = pinlin.load_urdf_string(chain_urdf())
    elements = [pinlin.JointSpring("j1", K1), pinlin.JointSpring("j2", K2)]
    if damped:
        elements += [pinlin.JointDamper("j1", BETA * K1), pinlin.JointDamper("j2", BETA * K2)]
    scene = pinlin.Scene(robot, elements, gravity=(0, 0, 0))
    sys = pinlin.linearize(scene, np.zeros(2))
    return scene, sys, pinlin.modal_analysis(sys)


def assert_tables_sum_to_one(energy):
    for table in (energy.kinetic, energy.strain, energy.dissipation):
        if table:
            assert abs(sum(table.values()) - 1.0) <= 1e-12, table


@pytest.mark.parametrize("damped", [False, True])
def test_two_mass_chain_matches_the_closed_form(damped):
    scene, sys, modes = chain(damped)
    r3 = math.sqrt(3.0)
    for k in range(4):
        energy = modes.energy(k, scene)
        assert_tables_sum_to_one(energy)
        slow = modes.natural_frequency[k] ** 2 < 1.5
        ratio = 1 + r3 if slow else 1 - r3  # a2 / a1
        assert_allclose(modes.natural_frequency[k] ** 2, (3 - r3) / 2 if slow else (3 + r3) / 2, rtol=1e-12)
        kin = M1 + M2 * ratio**2
        assert list(energy.kinetic) == ["m1", "m2"]
        assert_allclose([energy.kinetic["m1"], energy.kinetic["m2"]], [M1 / kin, M2 * ratio**2 / kin], rtol=1e-12)
        assert list(energy.strain) == ["spring j1", "spring j2", "loads and other"]  # no gravity: no gravity row
        assert_allclose([energy.strain["spring j1"], energy.strain["spring j2"]], [0.5, 0.5], rtol=1e-12)
        assert abs(energy.strain["loads and other"]) <= 1e-12
        if damped:
            assert list(energy.dissipation) == ["damper j1", "damper j2"]
            assert_allclose(list(energy.dissipation.values()), [0.5, 0.5], rtol=1e-12)
            assert energy.dissipated_power > 0
        else:
            assert energy.dissipation == {} and energy.dissipated_power == 0
            assert any(note.startswith("no dissipation") for note in energy.notes)
        assert energy.by == "bodies" and energy.error <= 1e-15
        assert energy.dominant_body == ("m2" if energy.kinetic["m2"] > 0.5 else "m1")
        # totals: T = V for an undamped mode; T = |lam|^2 x^H M x / 4
        x = modes.right[:, k]
        assert_allclose(energy.kinetic_energy, abs(modes.eigenvalues[k]) ** 2 * np.vdot(x, sys.M @ x).real / 4,
                        rtol=1e-12)
        if not damped:
            assert_allclose(energy.kinetic_energy, energy.strain_energy, rtol=1e-12)


def test_without_a_scene_the_shares_are_per_coordinate():
    _, sys, modes = chain()
    energy = modes.energy(0)
    assert energy.by == "coordinates" and energy.error == 0.0
    assert list(energy.kinetic) == ["j1", "j2"] == list(energy.strain)
    x = modes.right[:, 0]
    T = np.real(np.conj(x) * (sys.M @ x))
    assert_allclose(list(energy.kinetic.values()), T / T.sum(), rtol=1e-12)
    # strain per joint coordinate is per spring here: S = diag(k1, k2)
    assert_allclose(list(energy.strain.values()), [0.5, 0.5], rtol=1e-12)
    assert_tables_sum_to_one(energy)


def _link_energies(theta: float) -> list[float]:
    """m_k |v_k'|^2 + I_k omega_k'^2 per link of BUNDLED along the loop (per unit crank rate)."""
    a, b, c = BUNDLED.crank.length, BUNDLED.coupler.length, BUNDLED.rocker.length
    phi, chi = BUNDLED.loop(theta)
    E = [cmath.exp(1j * x) for x in (theta, phi, chi)]
    cols = np.array([[(1j * b * E[1]).real, (1j * c * E[2]).real], [(1j * b * E[1]).imag, (1j * c * E[2]).imag]])
    rhs = -1j * a * E[0]
    d1, d2 = np.linalg.solve(cols, [rhs.real, rhs.imag])
    v1 = 1j * BUNDLED.crank.com * E[0]
    v2 = 1j * a * E[0] + 1j * BUNDLED.coupler.com * d1 * E[1]
    v3 = 1j * a * E[0] + 1j * b * d1 * E[1] + 1j * BUNDLED.rocker.com * d2 * E[2]
    links = (BUNDLED.crank, BUNDLED.coupler, BUNDLED.rocker)
    return [L.mass * abs(v) ** 2 + L.inertia * w**2 for L, v, w in zip(links, (v1, v2, v3), (1.0, d1, d2))]


@pytest.fixture(scope="module")
def four_bar():
    theta0, k, g = math.radians(75.0), 50.0, 9.81
    robot = pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))
    spring = pinlin.JointSpring("crank_joint", k, rest=BUNDLED.spring_rest(theta0, k, g))
    scene = pinlin.Scene(robot, [spring], constraints=[pinlin.PointConstraint("rocker_tip", (0.7, 0.0, 0.0))])
    sys = pinlin.linearize(scene, pinlin.find_equilibrium(scene, np.zeros(3)).q)
    return scene, sys, pinlin.modal_analysis(sys), (theta0, k, g)


def test_four_bar_with_constraints_matches_the_energy_method(four_bar):
    scene, sys, modes, (theta0, k, g) = four_bar
    assert sys.basis is not None and sys.n == 1
    energy = modes.energy(0, scene)
    assert_tables_sum_to_one(energy)
    links = _link_energies(theta0)
    assert list(energy.kinetic) == ["crank", "coupler", "rocker"]
    assert_allclose(list(energy.kinetic.values()), np.array(links) / sum(links), rtol=1e-9)
    _, _, V2 = BUNDLED.energy(theta0, g)
    assert_allclose(energy.strain["spring crank_joint"], k / (k + V2), rtol=1e-9)
    # gravity's tangent Hessian and the constraint forces' curvature together are V_g''
    assert_allclose(energy.strain["gravity"] + energy.strain["loads and other"], V2 / (k + V2), rtol=1e-8)
    assert energy.dominant_element == "spring crank_joint"
    assert energy.error <= 1e-12


def test_bad_input_is_refused(four_bar):
    scene, sys, modes, _ = four_bar
    chain_scene, _, chain_modes = chain()
    with pytest.raises(pinlin.ParameterError, match=r"expected a mode index, an integer in \[0, 2\), got 2"):
        modes.energy(2, scene)
    with pytest.raises(pinlin.ParameterError, match=r"an integer in \[0, 2\), got -1"):
        modes.energy(-1)
    with pytest.raises(pinlin.ParameterError, match=r"got True"):
        modes.energy(True)
    with pytest.raises(pinlin.ParameterError, match=r"got 0.0"):
        modes.energy(0.0)
    with pytest.raises(pinlin.ParameterError, match="expected a pinlin.Scene, got str"):
        modes.energy(0, "scene")
    with pytest.raises(pinlin.ParameterError, match=r"does not match the analysed system: its coordinates are \['j1', 'j2'\]"):
        modes.energy(0, chain_scene)
    heavier = pinlin.Scene(pinlin.load_urdf_string(chain_urdf().replace('mass value="2.0"', 'mass value="2.5"')),
                           chain_scene.elements, gravity=(0, 0, 0))
    with pytest.raises(pinlin.ParameterError, match="its mass matrix at sys.q differs from sys.M by"):
        chain_modes.energy(0, heavier)
    loaded = pinlin.load(chain_modes.to_dict())
    with pytest.raises(pinlin.ParameterError, match="read back by pinlin.load, which keeps no system or matrices"):
        loaded.energy(0)
    bare = pinlin.modal_analysis((np.eye(2), np.zeros((2, 2)), np.diag([1.0, 4.0])))
    with pytest.raises(pinlin.ParameterError, match="modes of bare matrices|bare matrices: there is no system"):
        bare.energy(0, chain_scene)


def test_mode_energy_reads_back_and_prints():
    scene, _, modes = chain(damped=True)
    energy = modes.energy(0, scene)
    loaded = pinlin.load(energy.to_dict())
    assert loaded.kinetic == energy.kinetic and loaded.strain == energy.strain
    assert loaded.eigenvalue == energy.eigenvalue and loaded.notes == energy.notes
    text = energy.table()
    assert "kinetic (bodies)" in text and "damper j2" in text
    assert "loads and other      0.00 %" in text and "-0.00 %" not in text  # a rounding-size share prints as 0
    assert "\n" not in repr(energy)


@pytest.mark.parametrize("alpha, beta", [(0.0, 0.01), (0.05, 0.0)])
def test_rayleigh_damping_is_one_damper(alpha, beta):
    """C = alpha M + beta K_e keeps the chain's shapes; the Rayleigh element dissipates everything."""
    robot = pinlin.load_urdf_string(chain_urdf())
    scene = pinlin.Scene(robot, [pinlin.JointSpring("j1", K1), pinlin.JointSpring("j2", K2),
                                 pinlin.RayleighDamping(alpha=alpha, beta=beta)], gravity=(0, 0, 0))
    modes = pinlin.modal_analysis(pinlin.linearize(scene, np.zeros(2)))
    energy = modes.energy(0, scene)
    assert list(energy.dissipation) == ["rayleigh"]
    assert_allclose(energy.dissipation["rayleigh"], 1.0, rtol=1e-12)
    assert_allclose([energy.strain["spring j1"], energy.strain["spring j2"]], [0.5, 0.5], rtol=1e-10)


def test_prescribed_rotation_softens_through_the_rest_row():
    """A turntable spun at 2 rad/s: the spun table takes no kinetic share of a mode (its speed is
    prescribed), and the centrifugal softening of the slider is a negative share of the rest row."""
    robot = pinlin.load_urdf_string(pinlin.turntable_urdf())
    scene = pinlin.Scene(robot, [pinlin.JointSpring("arm", 5.0), pinlin.JointSpring("slider", 50.0),
                                 pinlin.JointDamper("slider", 0.2)], prescribed={"table": 2.0})
    sys = pinlin.linearize(scene, pinlin.find_equilibrium(scene, scene.neutral()).q)
    modes = pinlin.modal_analysis(sys)
    energy = modes.energy(0, scene)
    assert_tables_sum_to_one(energy)
    assert energy.kinetic["table"] == 0.0
    assert energy.strain["loads and other"] < 0 and energy.strain["spring slider"] > 1
    assert energy.dissipation == {"damper slider": pytest.approx(1.0, abs=1e-12)}


def test_tables_are_read_only():
    scene, _, modes = chain()
    energy = modes.energy(0, scene)
    with pytest.raises(TypeError):
        energy.kinetic["m1"] = 0.0
    loaded = pinlin.load(energy.to_dict())
    with pytest.raises(TypeError):
        loaded.strain["spring j1"] = 0.0
