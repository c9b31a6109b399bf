"""Stress tests: stiffness and mass ratios, near-massless links, units (theory: error figures).

Each asserts backward errors recomputed from the returned vectors, eigenvalues
within their reported error bounds of an mpmath reference, and the verdict the
theorems of theory: stability imply.
"""

from __future__ import annotations

import re
import subprocess
import sys

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from stress_cases import chain, check_modes, mp_eigenvalues

METHODS = ("auto", "general")


@pytest.mark.parametrize("gravity", [(0, 0, 0), (0, 0, -9.81)])
@pytest.mark.parametrize("method", METHODS)
def test_stiffness_ratio_1e12_between_joints(gravity, method):
    sys = chain(6, np.logspace(-6, 6, 6), gravity=gravity)
    s = np.linalg.eigvalsh(sys.S)
    assert s[-1] / s[0] > (1e11 if not any(gravity) else 1e6)  # gravity stiffens the soft joints
    m = pinlin.modal_analysis(sys, method=method)
    check_modes(m, sys, mp_eigenvalues(sys))
    # D = G = N = 0 and S positive definite: Lagrange-Dirichlet, eigenvalues on the axis
    assert m.stability.kind == "marginally_stable"
    assert np.all(m.eigenvalues.real == 0) or m.method == "general"
    assert set(m.kind) == {"undamped"}  # D = 0: on the axis, hence undamped


@pytest.mark.parametrize("method", METHODS)
def test_stiffness_ratio_1e12_damped_with_follower(method):
    sys = chain(6, np.logspace(-6, 6, 6), dampers=[0.01] * 6, P=0.5)
    assert sys.nonzero == ("M", "D", "S", "N")
    m = pinlin.modal_analysis(sys, method=method)
    ref = mp_eigenvalues(sys)
    check_modes(m, sys, ref)
    assert m.stability.kind == "asymptotically_stable"
    assert np.max(ref.real) < 0  # the reference agrees


@pytest.mark.parametrize("order", ["heavy_top", "heavy_tip"])
def test_mass_ratio_1e8(order):
    masses = np.logspace(0, -8, 6) if order == "heavy_top" else np.logspace(-8, 0, 6)
    sys = chain(6, [10.0] * 6, masses=masses, lengths=np.full(6, 1 / 6), dampers=[0.01] * 6)
    w = np.linalg.eigvalsh(sys.M)
    assert w[-1] / w[0] > 1e8
    for method in METHODS:
        m = pinlin.modal_analysis(sys, method=method)
        check_modes(m, sys, mp_eigenvalues(sys))
        # N = 0, D > 0, S > 0: Thomson-Tait-Chetaev
        assert m.stability.kind == "asymptotically_stable"
        assert m.stability.theorem == "Thomson-Tait-Chetaev"


@pytest.mark.parametrize("tiny", [1e-10, 1e-14])
def test_near_massless_link(tiny):
    """An ill-conditioned M (cond ~ 1/tiny): still backward stable, eigenvalues within their bounds."""
    masses = [1.0, 1.0, 1.0, tiny]  # the last joint moves only the near-massless link
    sys = chain(4, [10.0] * 4, masses=masses, lengths=np.full(4, 0.25))
    assert np.linalg.cond(sys.M) > 0.1 / tiny
    ref = mp_eigenvalues(sys)
    m = pinlin.modal_analysis(sys)  # symmetric path: eigh, or QZ of size n when eigh loses accuracy
    check_modes(m, sys, ref)
    assert m.stability.kind == "marginally_stable"
    cond = np.linalg.cond(sys.M)
    if cond < 0.01 / np.finfo(float).eps:
        m = pinlin.modal_analysis(sys, method="general")
        check_modes(m, sys, ref)
        assert m.stability.kind == "marginally_stable"
    else:  # M singular to working precision: QZ of the 2n companion pencil may find an infinite
        # eigenvalue (a backward-stable answer); then it must say so, not return garbage
        try:
            m = pinlin.modal_analysis(sys, method="general")
        except pinlin.ComputationError as exc:
            assert "numerically singular" in str(exc)
        else:
            check_modes(m, sys, ref)
    # the massless link's mode is the fast one: |lam|^2 ~ k / (tiny l^2 / 3)
    assert np.max(np.abs(ref)) > 1e3 / np.sqrt(tiny) * 1e-3


def test_massless_link_is_a_clear_error():
    """A link with exactly no mass and no inertia at the end of the chain: M is singular, said clearly."""
    text = pinlin.pendulum_chain_urdf(2, 1.0, 2.0)
    text = re.sub(r'(<link name="link2">\s*<inertial>.*?<mass value=")[^"]*(".*?<inertia )[^/]*/>',
                  r'\g<1>0.0\g<2>ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>', text, flags=re.S)
    robot = pinlin.load_urdf_string(text)
    scene = pinlin.Scene(robot, [pinlin.JointSpring("joint2", 1.0)], gravity=(0, 0, -9.81))
    with pytest.raises(pinlin.SingularMassError, match="joint2"):
        pinlin.linearize(scene, robot.neutral())


UNITS = {
    "mm-g-ms": (1e-3, 1e-3, 1e-3),
    "m-t-s": (1.0, 1e3, 1.0),
    "um-mg-us": (1e-6, 1e-6, 1e-6),
    "km-Gt-h": (1e3, 1e12, 3600.0),
}


@pytest.mark.parametrize("units", list(UNITS))
def test_units_transform_eigenvalues_by_the_time_unit(units):
    """The same scene in other units: lam [1/Tu] = lam [1/s] Tu, within the error bounds of both."""
    Lu, Mu, Tu = UNITS[units]
    kw = dict(masses=[1.0, 2.0, 0.5, 1.5], lengths=[0.3, 0.5, 0.2, 0.4], radius=0.02, dampers=[0.1, 0.2, 0.05, 0.1],
              P=3.0)
    si = chain(4, [50.0, 30.0, 20.0, 10.0], **kw)
    other = chain(4, [50.0, 30.0, 20.0, 10.0], units=(Lu, Mu, Tu), **kw)
    assert_allclose(other.M, si.M / (Mu * Lu**2), rtol=1e-12)
    ms = pinlin.modal_analysis(si)
    mo = pinlin.modal_analysis(other)
    check_modes(mo, other)
    lam = mo.eigenvalues / Tu
    assert np.all(np.abs(lam - ms.eigenvalues) <= ms.tolerances["safety"] * (mo.error_bound / Tu + ms.error_bound))
    assert mo.stability.kind == ms.stability.kind == "asymptotically_stable"
    assert mo.method == ms.method


@pytest.mark.parametrize("tau", [1e2, 1e4, 1e6, 1e8])
@pytest.mark.parametrize("mixed", [False, True])
def test_heavily_damped_backward_error(tau, mixed):
    """||C|| >> sqrt(||M|| ||K||): the Fan-Lin-Van Dooren scaling alone left eta = 4.5e-11 at tau = 1e6 and
    1e-8 at tau = 1e8 (this test exposed it); tropical scaling restores eta ~ eps (Hammarling, Munro, Tisseur 2013).
    ``mixed``: dampers on some joints only, so eigenvalues of three sizes (gamma+, FLVD gamma, gamma-)."""
    rng = np.random.default_rng(int(np.log10(tau)) + 10 * mixed)
    n = 5
    A = rng.standard_normal((n, n))
    M = A @ A.T + n * np.eye(n)
    B = rng.standard_normal((n, n))
    K = B @ B.T + n * np.eye(n)
    if mixed:
        C = np.diag([1.0, 0.0, 1.0, 0.0, 0.0]) * tau * np.sqrt(np.linalg.norm(M) * np.linalg.norm(K))
    else:
        W = rng.standard_normal((n, n))
        C = W @ W.T / np.linalg.norm(W @ W.T) * tau * np.sqrt(np.linalg.norm(M) * np.linalg.norm(K))
    sys = pinlin.LinearizedSystem(M, C, np.zeros((n, n)), K, np.zeros((n, n)))
    m = pinlin.modal_analysis(sys, method="general")
    e = check_modes(m, sys)
    assert np.max(e) < 1e-13
    assert ("tropical" in m.method.reason) == (tau > 10)
    if mixed:  # D only semidefinite: bounded (Lagrange-Dirichlet); the slowest decay may be within rounding
        assert m.stability.kind in ("asymptotically_stable", "undecided") and m.stability.bounded
    else:
        assert m.stability.kind == "asymptotically_stable"  # Thomson-Tait-Chetaev
    if tau <= 1e4:  # the eigenvalues against mpmath (beyond, 40 digits resolve the tiny ones too, but slowly)
        check_modes(m, sys, mp_eigenvalues(sys))


_HWM_SCRIPT = """
import sys, pinlin
from pinlin.model.evaluation import Workspace
def hwm():
    for line in open("/proc/self/status"):
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) * 1024
n = int(sys.argv[1])
robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n))
scene = pinlin.Scene(robot, [])
before = hwm()
Workspace(scene)
print(hwm() - before)
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc/self/status")
def test_memory_guard_covers_the_peak_of_createData():
    n = 150
    out = subprocess.run([sys.executable, "-c", _HWM_SCRIPT, str(n)], capture_output=True, text=True, check=True)
    peak_growth = int(out.stdout.strip())
    assert peak_growth <= pinlin.model.memory.pinocchio_data_bytes(n)
