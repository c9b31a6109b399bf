"""The one result convention (docs/conventions.md), checked on every result type.

``pinlin.results.result_types()`` lists every subclass of ``pinlin.results.Result``; each
must have a builder below that makes an instance through the public API on a small system
(the README's double pendulum scene, 2-DOF systems from ``LinearizedSystem.from_matrices``).
A result type without a builder fails ``test_every_result_type_has_a_builder``, so a new
result type cannot escape this test; a builder whose product is not a ``Result`` fails
``test_builder_makes_a_result`` (a type that does not follow the convention yet).

Every pinlin module is imported first, so no result type hides in a module ``import pinlin``
does not load.  The checks: ``.elapsed`` a float >= 0 [s]; ``.method`` a non-empty string; ``.error`` a finite
float, or None where the class documents that it can be None; a repr of at most
``MAX_REPR_LINES`` lines; ``to_dict()`` strict JSON (``allow_nan=False``) that survives a
round trip, led by ``type``, ``method``, ``error`` and ``elapsed``.
"""

from __future__ import annotations

import functools
import importlib
import inspect
import json
import pkgutil
import re

import numpy as np
import pinocchio as pin
import pytest

import pinlin
from pinlin.results import Result, result_types

# Import every module, so that result types defined outside what ``import pinlin`` loads are listed too.
for _module in pkgutil.walk_packages(pinlin.__path__, "pinlin."):
    importlib.import_module(_module.name)

#: A one-screen repr: at most this many lines ...
MAX_REPR_LINES = 15
#: ... and this many characters (a single line holding a whole array is not one screen).
MAX_REPR_CHARS = 2000


# ----------------------------------------------------------------------------- small systems


@functools.cache
def pendulum_scene() -> pinlin.Scene:
    """The README's double pendulum with springs and a follower load (theory: double pendulum)."""
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf())
    elements = [
        pinlin.JointSpring("joint1", stiffness=3.0),
        pinlin.JointSpring("joint2", stiffness=2.0),
        pinlin.FollowerWrench("tip", force=(0, 0, 4.0)),
    ]
    return pinlin.Scene(robot, elements, gravity=(0, 0, -9.81))


@functools.cache
def equilibrium():
    return pinlin.find_equilibrium(pendulum_scene(), np.array([0.1, -0.05]))


@functools.cache
def damped() -> pinlin.LinearizedSystem:
    """2 DOF with every matrix nonzero: simple, complex eigenvalues."""
    M = np.diag([2.0, 1.0])
    C = np.array([[0.3, -0.1 + 0.5], [-0.1 - 0.5, 0.2]])
    K = np.array([[6.0, -2.0 + 0.4], [-2.0 - 0.4, 3.0]])
    return pinlin.LinearizedSystem.from_matrices(M, C, K)


@functools.cache
def rigid() -> pinlin.LinearizedSystem:
    """A free coordinate (no stiffness, no damping) beside an oscillator: lam = 0 double, one chain of length 2."""
    return pinlin.LinearizedSystem.from_matrices(np.eye(2), np.diag([0.0, 0.4]), np.diag([0.0, 4.0]))


@functools.cache
def damped_modes():
    return pinlin.modal_analysis(damped())


TIMES = np.linspace(0.0, 2.0, 41)
X0, V0 = np.array([0.1, -0.2]), np.array([0.0, 0.3])


@functools.cache
def free():
    return pinlin.free_response(damped(), X0, V0, TIMES)


@functools.cache
def forced():
    force = np.column_stack([np.sin(2.0 * TIMES), np.zeros_like(TIMES)])
    return pinlin.forced_response(damped(), force, TIMES, X0, V0)


def lowest_eigenvalue(P: float):
    """Module level (picklable): the modes of the README pendulum under follower load P."""
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf())
    scene = pinlin.Scene(robot, [pinlin.JointSpring("joint1", 3.0), pinlin.JointSpring("joint2", 2.0),
                                 pinlin.FollowerWrench("tip", force=(0, 0, P))], gravity=(0, 0, -9.81))
    return pinlin.modal_analysis(pinlin.linearize(scene, np.zeros(2)))


def stiffened(p: float) -> pinlin.LinearizedSystem:
    """The damped 2-DOF system with p added to the first diagonal entry of K."""
    sys = damped()
    return pinlin.LinearizedSystem.from_matrices(sys.M, sys.C, sys.K + np.diag([p, 0.0]))


def softening(p: float) -> pinlin.LinearizedSystem:
    """Damped, with the first stiffness 1 - p: asymptotically stable below p = 1, divergence above."""
    return pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), np.diag([1.0 - p, 2.0]))


def softening2(p1: float, p2: float) -> pinlin.LinearizedSystem:
    """The first stiffness p1 - p2: the stability boundary is p2* = p1."""
    return softening(1.0 - p1 + p2)


@functools.cache
def closed_pendulum_scene() -> pinlin.Scene:
    """The README pendulum with its tip held at the point it reaches at q = (0.4, -0.7) (theory: constraints)."""
    robot = pendulum_scene().robot
    data = robot.model.createData()
    pin.framesForwardKinematics(robot.model, data, np.array([0.4, -0.7]))
    tip = data.oMf[robot.model.getFrameId("tip")].translation.copy()
    return pinlin.Scene(robot, pendulum_scene().elements, constraints=[pinlin.PointConstraint("tip", tip)])


@functools.cache
def kapitza_orbit() -> pinlin.PeriodicOrbit:
    """The bundled Kapitza scene's (constant) periodic orbit (theory: Floquet)."""
    from pinlin.model.scene_file import load_scene

    spec = load_scene(pinlin.data_path("scenes/kapitza.toml"))
    return pinlin.periodic_orbit(spec.scene, spec.q0)


def refuse_negative(P: float):
    if P < 0:
        raise pinlin.ParameterError("P", "must be >= 0")
    return P


# ----------------------------------------------------------------------------- builders


BUILDERS = {
    # linearization
    "EquilibriumResult": equilibrium,
    "LinearizedSystem": lambda: pinlin.linearize(pendulum_scene(), equilibrium().q),
    "ClosureResult": lambda: pinlin.close_loops(closed_pendulum_scene(), np.array([0.3, -0.5])),
    # spectral
    "Modes": damped_modes,
    "Stability": lambda: damped_modes().stability,
    # Ziegler's column at P = 1.8 in joint angles: a marginal verdict with its dissipation table
    "DissipationRow": lambda: pinlin.modal_analysis(pinlin.LinearizedSystem.from_matrices(
        [[6.0, 2.0], [2.0, 1.0]], None, [[1.0, 1.8], [0.0, 1.0]])).stability.dissipation[1],
    "JordanChains": lambda: pinlin.jordan_chains(rigid(), 0.0),
    "Cluster": lambda: pinlin.modal_analysis(rigid()).clusters[0],
    "ModeEnergy": lambda: pinlin.modal_analysis(pinlin.linearize(pendulum_scene(), equilibrium().q)).energy(
        0, pendulum_scene()),
    # adjoint
    "CharacteristicPolynomial": lambda: pinlin.characteristic_polynomial(damped()),
    "AdjugateMatrix": lambda: pinlin.adjugate(damped(), 1.0 + 2.0j),
    "AdjugatePolynomial": lambda: pinlin.adjoint.adjugate_polynomial(damped()),
    "AdjugateTaylor": lambda: pinlin.adjoint.adjugate_taylor(damped(), 0.5j, 2),
    "AdjugateEigenvectors": lambda: pinlin.adjugate_eigenvectors(damped(), damped_modes().eigenvalues[0]),
    "AdjugateChain": lambda: pinlin.adjoint.adjugate_chain(rigid(), 0.0, 2),
    "CharacteristicDifferentialEquation": lambda: pinlin.adjoint.characteristic_differential_equation(damped()),
    "CDECheck": lambda: pinlin.check_free_response(damped(), TIMES, np.asarray(free())),
    # frequency domain
    "FlexibilityArray": lambda: pinlin.flexibility(damped(), 1j * np.array([0.5, 1.5])),
    "FrequencyResponse": lambda: pinlin.frequency_response(damped(), np.array([0.5, 1.0, 2.0])),
    "HarmonicResponse": lambda: pinlin.harmonic_response(damped(), np.array([1.0, 0.0]), 1.3),
    "Residues": lambda: pinlin.residues(damped(), damped_modes().eigenvalues[0]),
    "ModalExpansion": lambda: pinlin.frf.modal_expansion(damped()),
    # time domain
    "FreeResponse": free,
    "ForcedResponse": forced,
    "EnergyBudget": lambda: pinlin.energy_budget(damped(), forced().t, forced().x, forced().xdot, forced().f),
    "Simulation": lambda: pinlin.simulate(pendulum_scene(), equilibrium().q + np.array([0.01, 0.0]), None,
                                          np.linspace(0.0, 0.05, 6)),
    "StateSpaceModel": lambda: pinlin.state_space(damped()),
    # time-periodic motions
    "PeriodicOrbit": kapitza_orbit,
    "FloquetAnalysis": lambda: pinlin.floquet_analysis(kapitza_orbit().scene, kapitza_orbit()),
    "FloquetCampbell": lambda: pinlin.floquet_campbell(
        lambda w: pinlin.floquet_analysis_matrices(np.eye(1), None, lambda t: np.array([[w + 0.1 * np.cos(t)]]),
                                                   2 * np.pi), [2.0, 3.0]),
    # parameter studies
    "CriticalParameter": lambda: pinlin.critical_parameter(softening, (0.0, 2.0)),
    "StabilityBoundary": lambda: pinlin.stability_boundary(softening2, [1.0, 1.5], (0.0, 3.0)),
    "EigenvalueSensitivity": lambda: pinlin.eigenvalue_sensitivity(stiffened, 0.5),
    "SweepResult": lambda: pinlin.sweep(lowest_eigenvalue, {"P": [0.0, 2.0]}),
    "SweepFailure": lambda: pinlin.sweep(refuse_negative, {"P": [1.0, -1.0]}, on_error="record").values[1],
    "TrackedModes": lambda: pinlin.studies.track_modes(
        [damped_modes().eigenvalues, damped_modes().eigenvalues], [damped_modes().right, damped_modes().right]
    ),
}


@functools.cache
def build(name: str):
    return BUILDERS[name]()


def _documents_none(cls: type) -> bool:
    """The class (or its ``error`` property) says that ``error`` may be None."""
    prop = inspect.getattr_static(cls, "error", None)
    texts = [(prop.__doc__ or "") if isinstance(prop, property) else ""]
    doc = inspect.getdoc(cls) or ""
    entry = re.search(r"^error\b.*?(?=^\S|\Z)", doc, flags=re.M | re.S)
    texts.append(entry.group(0) if entry else "")
    return any("None" in text for text in texts)


# ----------------------------------------------------------------------------- tests


@pytest.mark.parametrize("cls", result_types(), ids=lambda c: c.__name__)
def test_every_result_type_has_a_builder(cls):
    assert cls.__name__ in BUILDERS, (
        f"{cls.__module__}.{cls.__name__} is a pinlin result type without a builder in tests/test_results.py"
    )


@pytest.mark.parametrize("name", sorted(BUILDERS))
def test_builder_makes_a_result(name):
    result = build(name)
    assert type(result).__name__ == name
    assert isinstance(result, Result), f"{name} does not follow the result convention (pinlin.results.Result)"


@pytest.mark.parametrize("name", sorted(BUILDERS))
def test_result_convention(name):
    result = build(name)
    cls = type(result)
    assert isinstance(result.elapsed, float) and np.isfinite(result.elapsed) and result.elapsed >= 0, result.elapsed
    assert isinstance(result.method, str) and result.method.strip(), result.method
    if result.error is None:
        assert _documents_none(cls), f"{name}.error is None but its docstring does not say when"
    else:
        assert isinstance(result.error, float) and np.isfinite(result.error), result.error
    text = repr(result)
    assert len(text.splitlines()) <= MAX_REPR_LINES and len(text) <= MAX_REPR_CHARS, text[:MAX_REPR_CHARS]
    data = result.to_dict()
    assert list(data)[:4] == ["type", "method", "error", "elapsed"]
    assert data["type"] == name and data["elapsed"] == result.elapsed
    assert json.loads(json.dumps(data, allow_nan=False)) == data


def test_sweep_error_is_the_largest_error_of_its_results():
    sweep = build("SweepResult")
    errors = [modes.error for modes in sweep.values]
    assert sweep.point_errors == tuple(errors)
    assert sweep.error == max(errors)
    assert build("SweepFailure").error is None
