"""The moving-frame term A: v = v0 + x' + A x + O(|x|^2) for q(t) = integrate(integrate(q0, t v0), x(t)).

A is checked against finite differences of exactly that definition (the velocity of q(t)
recovered with ``pin.difference`` and Richardson extrapolation, then its first-order part in
the size of x), and against a reference case: a free rigid body spinning about a principal
axis, whose nutation exponents are lambda^2 = -w^2 (Ik - Ii)(Ik - Ij) / (Ii Ij) (Euler's
equations; e.g. Goldstein, Classical Mechanics, 3rd ed., sec. 5.6; Landau-Lifshitz, Mechanics,
sec. 37).
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_allclose

from pinlin.errors import ConfigurationError, ParameterError
from pinlin.linearization.moving_frame import moving_frame_matrix


def _inertia(rng):
    return pin.Inertia(1.0 + rng.uniform(), rng.normal(size=3) * 0.1, np.diag(rng.uniform(0.5, 1.5, 3)))


def _chain(joints, seed=0):
    """A serial chain of the given joint models, each with an offset placement and a random body."""
    rng = np.random.default_rng(seed)
    model, parent = pin.Model(), 0
    for k, joint in enumerate(joints):
        placement = pin.SE3(pin.rpy.rpyToMatrix(*rng.uniform(-1, 1, 3)), rng.uniform(-0.5, 0.5, 3))
        parent = model.addJoint(parent, joint, placement, f"j{k}")
        model.appendBodyToJoint(parent, _inertia(rng), pin.SE3.Identity())
    return model


def _mixed():
    """A free flyer, a spherical joint and revolute joints (one of them continuous)."""
    return _chain([pin.JointModelFreeFlyer(), pin.JointModelRX(), pin.JointModelSpherical(),
                   pin.JointModelRevoluteUnaligned(0.6, 0.0, 0.8), pin.JointModelRUBZ()])


def _others():
    """The other joints A handles: planar (se(2)), translation, spherical ZYX, universal, prismatic, helical."""
    return _chain([pin.JointModelPlanar(), pin.JointModelTranslation(), pin.JointModelSphericalZYX(),
                   pin.JointModelUniversal(np.array([1.0, 0, 0]), np.array([0, 1.0, 0])), pin.JointModelPY(),
                   pin.JointModelHZ(0.2)])


def _velocity(model, curve, h=1e-2):
    """Pinocchio's velocity of q(t) = curve(t) at t = 0: d/dt difference(q(0), q(t)), Richardson (O(h^4)).

    Not a smaller step: Pinocchio's planar (SE(2)) difference of integrate loses up to 2e-8 relative
    for rotation increments near 1e-4 rad (1.5e-10 at 1e-3, 2e-12 at 1e-2).
    """
    q0 = curve(0.0)

    def central(step):
        return (pin.difference(model, q0, curve(step)) - pin.difference(model, q0, curve(-step))) / (2 * step)

    return (4 * central(h / 2) - central(h)) / 3


def _first_order(model, q0, v0, xi0, xi1, eps=1e-2):
    """d v / d eps at 0 for x(t) = eps (xi0 + t xi1): equals xi1 + A xi0 (Richardson in eps too)."""
    def v_at(e):
        return _velocity(model, lambda t: pin.integrate(model, pin.integrate(model, q0, t * v0), e * (xi0 + t * xi1)))

    def central(step):
        return (v_at(step) - v_at(-step)) / (2 * step)

    return (4 * central(eps / 2) - central(eps)) / 3, v_at(0.0)


@pytest.mark.parametrize("build", [_mixed, _others])
@pytest.mark.parametrize("seed", range(3))
def test_matches_the_definition(build, seed):
    model = build()
    rng = np.random.default_rng(100 + seed)
    pin.seed(100 + seed)  # randomConfiguration draws from Pinocchio's own generator
    q0 = pin.randomConfiguration(model, -np.ones(model.nq), np.ones(model.nq))
    v0 = rng.normal(size=model.nv) * 1.5
    A = moving_frame_matrix(model, v0)
    for _ in range(2):
        xi0, xi1 = rng.normal(size=model.nv), rng.normal(size=model.nv)
        slope, v_ref = _first_order(model, q0, v0, xi0, xi1)
        assert_allclose(v_ref, v0, rtol=1e-10, atol=1e-10)  # the reference moves at v0
        assert np.linalg.norm(slope - xi1 - A @ xi0) < 1e-7 * np.linalg.norm(A @ xi0)
    if build is _others:  # only the planar joint turns its deviations
        assert np.count_nonzero(A[3:]) == 0


def test_free_flyer_block_is_ad():
    """Pinocchio's (linear, angular) order: ad_(v, w) (xv, xw) = (w x xv + v x xw, w x xw)."""
    model = _chain([pin.JointModelFreeFlyer()])
    v, w = np.array([0.3, -1.0, 2.0]), np.array([0.5, 0.7, -0.2])
    xv, xw = np.array([1.0, 2.0, 3.0]), np.array([-1.0, 0.4, 0.9])
    got = moving_frame_matrix(model, np.concatenate([v, w])) @ np.concatenate([xv, xw])
    assert_allclose(got, np.concatenate([np.cross(w, xv) + np.cross(v, xw), np.cross(w, xw)]), rtol=1e-15)


MOMENTS = (1.0, 1.7, 2.9)  # I1 < I2 < I3, no two nutation rates equal to the spin


def _spinning_body(axis, w):
    """A free rigid body without gravity, principal moments MOMENTS, spinning at w about body axis ``axis``."""
    model = pin.Model()
    joint = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "body")
    model.appendBodyToJoint(joint, pin.Inertia(3.0, np.zeros(3), np.diag(MOMENTS)), pin.SE3.Identity())
    model.gravity = pin.Motion.Zero()
    v0 = np.zeros(6)
    v0[3 + axis] = w
    q0 = pin.integrate(model, pin.neutral(model), np.array([0.2, -0.1, 0.4, 0.3, -0.5, 0.8]))
    return model, q0, v0


def _steady_motion_eigenvalues(model, q0, v0):
    """Eigenvalues of M x'' + (C + M A) x' + (K + C A) x = 0 (C, K: RNEA derivatives at (q0, v0, 0))."""
    data = model.createData()
    a0 = np.zeros(model.nv)
    assert np.linalg.norm(pin.aba(model, data, q0, v0, np.zeros(model.nv))) < 1e-14  # steady: a = 0
    K, C, _ = pin.computeRNEADerivatives(model, data, q0, v0, a0)
    M = pin.crba(model, data, q0)
    M = np.triu(M) + np.triu(M, 1).T
    A = moving_frame_matrix(model, v0)
    n = model.nv
    Minv = np.linalg.inv(M)
    companion = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ (K + C @ A), -Minv @ (C + M @ A)]])
    return np.linalg.eigvals(companion)


@pytest.mark.parametrize("axis", [0, 1, 2])
def test_free_body_nutation_exponents(axis):
    """lambda^2 = -w^2 (Ik - Ii)(Ik - Ij) / (Ii Ij): marginal about the minor and major axes, a real
    positive pair about the intermediate one (the tennis-racket instability)."""
    w = 1.5
    model, q0, v0 = _spinning_body(axis, w)
    eig = _steady_motion_eigenvalues(model, q0, v0)
    Ik, Ii, Ij = MOMENTS[axis], *(MOMENTS[i] for i in range(3) if i != axis)
    lam2 = -(w**2) * (Ik - Ii) * (Ik - Ij) / (Ii * Ij)
    expected = math.sqrt(lam2) if lam2 > 0 else 1j * math.sqrt(-lam2)
    for target in (expected, -expected):
        nearest = eig[np.argmin(abs(eig - target))]
        assert abs(nearest - target) < 1e-12 * abs(target)
    growth = max(eig.real)
    if axis == 1:
        assert growth == pytest.approx(math.sqrt(lam2), rel=1e-12)
    else:
        assert growth < 1e-7  # marginal (the rest: zeros and the rotating frame's +-i w, defective pairs)


def test_bad_input_is_refused():
    model = _chain([pin.JointModelFreeFlyer()])
    with pytest.raises(ConfigurationError, match="v0 must be 6 finite numbers"):
        moving_frame_matrix(model, np.zeros(5))
    with pytest.raises(ConfigurationError, match="v0 must be 6 finite numbers"):
        moving_frame_matrix(model, [0, 0, 0, 0, 0, math.nan])
    composite = pin.JointModelComposite(2)
    composite.addJoint(pin.JointModelRX())
    composite.addJoint(pin.JointModelRY())
    model = _chain([composite])
    with pytest.raises(ParameterError, match=r"model: joint 'j0' \(JointModelComposite\)"):
        moving_frame_matrix(model, np.zeros(2))


def test_examples_run():
    """The Examples sections of the module's docstrings, as the doctest runner sees them."""
    import doctest

    import pinlin
    import pinlin.linearization.moving_frame as module

    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    result = doctest.testmod(module, extraglobs={"np": np, "pinlin": pinlin}, optionflags=flags)
    assert result.failed == 0 and result.attempted >= 5
