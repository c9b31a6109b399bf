"""Numeric parameters of every element (and a contact's friction) are numbers, not text or booleans.

numpy would read ``"5"`` as 5 and ``True`` as 1; the one check
(:func:`pinlin.model.numbers.numeric_array`) refuses them, naming the element
and the parameter.
"""

import numpy as np
import pytest
from numpy.testing import assert_array_equal

import pinlin
from pinlin import (
    Bushing,
    DeadWrench,
    FollowerWrench,
    JointDamper,
    JointSpring,
    LinearSpringDamper,
    PointConstraint,
    RayleighDamping,
)
from pinlin.model.numbers import numeric_array, numeric_scalar

BAD = ["5", b"5", True, np.bool_(False), [1.0, "2"], [True, False], 1 + 2j, None]

#: (build(value), the label the error names) for each numeric parameter of each element class.
PARAMETERS = {
    "JointSpring.stiffness": (lambda v: JointSpring("j", stiffness=v), r"JointSpring\('j'\)\.stiffness"),
    "JointSpring.rest": (lambda v: JointSpring("j", 1.0, rest=v), r"JointSpring\('j'\)\.rest"),
    "JointDamper.damping": (lambda v: JointDamper("j", damping=v), r"JointDamper\('j'\)\.damping"),
    "RayleighDamping.alpha": (lambda v: RayleighDamping(alpha=v), r"RayleighDamping\.alpha"),
    "RayleighDamping.beta": (lambda v: RayleighDamping(beta=v), r"RayleighDamping\.beta"),
    "FollowerWrench.force": (lambda v: FollowerWrench("tip", force=v), r"FollowerWrench\('tip'\)\.force"),
    "FollowerWrench.torque": (lambda v: FollowerWrench("tip", torque=v), r"FollowerWrench\('tip'\)\.torque"),
    "DeadWrench.force": (lambda v: DeadWrench("tip", force=v), r"DeadWrench\('tip'\)\.force"),
    "DeadWrench.torque": (lambda v: DeadWrench("tip", torque=v), r"DeadWrench\('tip'\)\.torque"),
    "LinearSpringDamper.stiffness": (lambda v: LinearSpringDamper("tip", [0, 0, 1.0], stiffness=v),
                                     r"LinearSpringDamper\('tip'\)\.stiffness"),
    "LinearSpringDamper.damping": (lambda v: LinearSpringDamper("tip", [0, 0, 1.0], stiffness=1.0, damping=v),
                                   r"LinearSpringDamper\('tip'\)\.damping"),
    "LinearSpringDamper.rest_length": (lambda v: LinearSpringDamper("tip", [0, 0, 1.0], stiffness=1.0, rest_length=v),
                                       r"LinearSpringDamper\('tip'\)\.rest_length"),
    "LinearSpringDamper.target": (lambda v: LinearSpringDamper("tip", v, stiffness=1.0),
                                  r"LinearSpringDamper\('tip'\)\.target"),
    "Bushing.stiffness": (lambda v: Bushing("tip", np.eye(4), stiffness=v), r"Bushing\('tip'\)\.stiffness"),
    "Bushing.damping": (lambda v: Bushing("tip", np.eye(4), stiffness=np.ones(6), damping=v),
                        r"Bushing\('tip'\)\.damping"),
    "Bushing.target": (lambda v: Bushing("tip", v, stiffness=np.ones(6)), r"Bushing\('tip'\)\.target"),
    "PointConstraint.friction": (lambda v: PointConstraint("tip", [0, 0, 0.0], contact=True, friction=v),
                                 r"PointConstraint\('tip'\)\.friction"),
}


@pytest.mark.parametrize("bad", BAD, ids=repr)
@pytest.mark.parametrize("parameter", sorted(PARAMETERS))
def test_text_booleans_and_complex_numbers_are_refused_naming_element_and_parameter(parameter, bad):
    build, label = PARAMETERS[parameter]
    if parameter == "JointSpring.rest" and bad is None:
        pytest.skip("rest=None is the default: the spring's rest is the neutral configuration")
    if parameter in ("LinearSpringDamper.damping", "Bushing.damping", "PointConstraint.friction") and bad is None:
        pytest.skip("None is the documented default (no damping, friction not checked)")
    if parameter.endswith(".target") and isinstance(bad, str):
        pytest.skip("a string target is a frame name, checked against the robot by the scene")
    with pytest.raises(pinlin.ParameterError, match=rf"^{label}: expected .*, got ") as info:
        build(bad)
    assert isinstance(info.value, ValueError)


def test_the_reported_cases():
    with pytest.raises(pinlin.ParameterError, match=r"JointSpring\('j'\)\.stiffness: expected a number, a vector or a "
                       r"matrix, got str '5'"):
        JointSpring("j", stiffness="5")
    with pytest.raises(pinlin.ParameterError, match=r"JointSpring\('j'\)\.stiffness: .* got bool True"):
        JointSpring("j", stiffness=True)


def test_numbers_of_every_numpy_kind_still_work():
    assert_array_equal(JointSpring("j", np.int64(3)).stiffness, 3.0)
    assert_array_equal(JointSpring("j", [np.float32(1.0), 2]).stiffness, [1.0, 2.0])
    assert RayleighDamping(alpha=np.uint8(2)).alpha == 2.0
    assert_array_equal(numeric_array(np.array([[1, 2], [3, 4]], dtype=object), "a"), [[1.0, 2.0], [3.0, 4.0]])
    assert numeric_scalar(np.float64(0.5), "a") == 0.5


def test_the_helper_names_the_parameter():
    with pytest.raises(pinlin.ParameterError, match=r"^p: expected a number, got list \[1.0, 2.0\]"):
        numeric_scalar([1.0, 2.0], "p")
    with pytest.raises(pinlin.ParameterError, match=r"^p: expected a number or an array of numbers, got ndarray"):
        numeric_array(np.array(["a"]), "p")
    with pytest.raises(pinlin.ParameterError, match=r"^p: expected .* got list \[\[1.0\], \[1.0, 2.0\]\]"):
        numeric_array([[1.0], [1.0, 2.0]], "p")  # ragged
