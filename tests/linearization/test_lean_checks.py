"""The reorganized per-call checks and splits of linearize.

Configuration checks (one norm for the common case, each entry against its own
limit otherwise), the finite-entry and mass checks, the symmetric/skew split and
the few-springs path of the spring group, each against hand-derived values.
"""

import math

import numpy as np
import pytest

import pinlin
from pinlin.linearization.assembly import Assembly
from pinlin.linearization.checks import check_finite_and_mass
from pinlin.linearization.split import split_damping, split_stiffness
from pinlin.model.elements.joint_spring import SpringGroup
from pinlin.model.evaluation import Evaluation
from pinlin.model.scene import ANGLE_LIMIT
from pinlin.numerics.norms import fro


@pytest.fixture(scope="module")
def chain():
    return pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(3))


@pytest.fixture(scope="module")
def long_chain():
    """nq = 70: above the size checked with Python floats, so the numpy path runs."""
    return pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(70))


# ----------------------------------------------------------------------------- configurations


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
@pytest.mark.parametrize("which", ["chain", "long_chain"])
def test_non_finite_entries_are_named(request, which, bad):
    scene = pinlin.Scene(request.getfixturevalue(which))
    q = np.zeros(scene.robot.nq)
    q[2] = bad
    with pytest.raises(pinlin.ConfigurationError, match=r"q has non-finite entries at \[2\]"):
        scene.check_configuration(q)


def test_non_finite_entry_beside_a_quaternion_is_named():
    scene = pinlin.Scene(pinlin.load_example("solo12", free_flyer=True))
    q = scene.neutral()
    q[9] = math.nan
    with pytest.raises(pinlin.ConfigurationError, match=r"non-finite entries at \[9\]"):
        scene.check_configuration(q)


@pytest.mark.parametrize("which", ["chain", "long_chain"])
def test_angles_against_the_limit_entry_by_entry(request, which):
    """Beyond half the limit the one-norm test fails and each entry is compared with its own limit."""
    scene = pinlin.Scene(request.getfixturevalue(which))
    q = np.zeros(scene.robot.nq)
    q[1] = 0.75 * ANGLE_LIMIT  # norm above ANGLE_LIMIT / 2, the entry within ANGLE_LIMIT: accepted
    assert scene.check_configuration(q)[1] == 0.75 * ANGLE_LIMIT
    q[0] = -0.75 * ANGLE_LIMIT  # two such entries: the norm exceeds ANGLE_LIMIT, each is within
    assert scene.check_configuration(q).tolist() == q.tolist()
    q[1] = 1.01 * ANGLE_LIMIT
    with pytest.raises(pinlin.ConfigurationError, match=r"q\[1\] = .* rad on revolute joint 'joint2' is beyond"):
        scene.check_configuration(q)


def test_huge_finite_prismatic_entry_is_accepted():
    """A slider has no angle limit: 1e200 m is finite (its square overflows; the norm does not)."""
    scene = pinlin.Scene(pinlin.load_urdf_string(pinlin.turntable_urdf()))
    q = np.array([0.6, 0.8, 0.0, 1e200])  # table (cos, sin), arm angle, slider
    out = scene.check_configuration(q)
    assert out[2:].tolist() == [0.0, 1e200]
    assert math.hypot(out[0], out[1]) == pytest.approx(1.0, abs=1e-15)


@pytest.mark.parametrize("robot", ["chain", "solo"])
def test_result_is_a_fresh_array_and_the_input_is_untouched(request, robot):
    if robot == "chain":
        scene = pinlin.Scene(request.getfixturevalue("chain"))
        q = np.array([0.1, 0.2, 0.3])
    else:
        scene = pinlin.Scene(pinlin.load_example("solo12", free_flyer=True))
        q = scene.neutral()
        q[3:7] = (0.0, 0.0, 0.0, 2.0)
    before = q.copy()
    out = scene.check_configuration(q)
    assert out is not q and not np.shares_memory(out, q)
    assert q.tolist() == before.tolist()
    if robot == "solo":
        assert out[3:7].tolist() == [0.0, 0.0, 0.0, 1.0]


def test_non_native_float_arrays_take_the_conversion_path(chain):
    scene = pinlin.Scene(chain)
    q = np.array([0.1, -0.2, 0.3], dtype=">f8")  # equal to float64, not the same dtype object
    out = scene.check_configuration(q)
    assert out.dtype == np.float64 and out.tolist() == [0.1, -0.2, 0.3]


# ----------------------------------------------------------------------------- finite entries and mass


def _assembly(force_scale: float = 1.0) -> Assembly:
    return Assembly(residual=np.zeros(2), force_scale=force_scale, M=None, C=None, K=None,
                    rounding_scale_C=0.0, rounding_scale_K=0.0, coriolis_D=None, calls=[])  # fmt: skip


@pytest.mark.parametrize(
    "where, value",
    [("M", math.nan), ("M", math.inf), ("C", math.nan), ("C", -math.inf), ("M diagonal", math.inf)],
)
def test_non_finite_M_or_C_raise_computation_error(chain, where, value):
    """inf on M's diagonal passes a Cholesky (sqrt(inf) = inf): the entry check, not the mass check, must catch it."""
    scene = pinlin.Scene(chain)
    M, C = np.eye(3), np.zeros((3, 3))
    if where == "M diagonal":
        M[1, 1] = value
    elif where == "M":
        M[2, 0] = M[0, 2] = value
    else:
        C[0, 1] = value
    with pytest.raises(pinlin.ComputationError, match=r"non-finite entries in M, C, K or the residual"):
        check_finite_and_mass(scene, M, C, _assembly())


def test_non_finite_force_scale_raises_computation_error(chain):
    """force_scale = ||tau|| + ||Q_e|| + ||K||: an inf or NaN in any of them reaches it."""
    scene = pinlin.Scene(chain)
    for scale in (math.inf, math.nan):
        with pytest.raises(pinlin.ComputationError, match="non-finite entries"):
            check_finite_and_mass(scene, np.eye(3), np.zeros((3, 3)), _assembly(scale))


def test_huge_finite_entries_are_not_taken_for_overflow(chain):
    """1e200 entries overflow the product M . C and the sums of squares, yet every entry is finite."""
    scene = pinlin.Scene(chain)
    M, C = 1e200 * np.eye(3), np.full((3, 3), 1e200)
    assert not math.isfinite(float(np.vdot(M, C)))
    check_finite_and_mass(scene, M, C, _assembly(fro(np.full((6, 6), 1e200))))  # no error
    assert fro(np.full((6, 6), 1e200)) == pytest.approx(6e200, rel=1e-15)
    assert fro(np.array([3e200, 4e200])) == pytest.approx(5e200, rel=1e-15)


def test_overflowing_spring_stiffness_raises_computation_error(chain):
    """Two 1e308 springs on one joint sum to inf in K: linearize refuses it as an overflow."""
    elements = [pinlin.JointSpring("joint1", 1e308), pinlin.JointSpring("joint1", 1e308)]
    with pytest.raises(pinlin.ComputationError, match="non-finite entries in M, C, K or the residual"):
        pinlin.linearize(pinlin.Scene(chain, elements), np.zeros(3))


@pytest.mark.filterwarnings("ignore:overflow encountered", "ignore:invalid value encountered")
def test_overflowing_damping_raises_computation_error(chain):
    elements = [pinlin.JointDamper("joint2", 1e308), pinlin.JointDamper("joint2", 1e308)]
    with pytest.raises(pinlin.ComputationError, match="non-finite entries in M, C, K or the residual"):
        pinlin.linearize(pinlin.Scene(chain, elements), np.zeros(3))


def test_indefinite_mass_is_still_a_singular_mass_error(chain):
    M = np.array([[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 1.0]])  # eigenvalues 3, -1, 1
    with pytest.raises(pinlin.SingularMassError, match=r"singular or indefinite \(smallest eigenvalue -1\)"):
        check_finite_and_mass(pinlin.Scene(chain), M, np.zeros((3, 3)), _assembly())


# ----------------------------------------------------------------------------- splits


def test_split_stiffness_by_hand():
    K = np.array([[2.0, 3.0], [1.0, 5.0]])
    dropped = {}
    S, N = split_stiffness(K, 1.0, 1e-12, dropped)
    assert S.tolist() == [[2.0, 2.0], [2.0, 5.0]]
    assert N.tolist() == [[0.0, 1.0], [-1.0, 0.0]]
    assert dropped == {}
    # a skew part at rounding level: N is zero and its relative size ||(K - K^T)/2|| / rounding is reported
    K = np.array([[2.0, 3.0 + 2**-40], [3.0, 5.0]])
    S, N = split_stiffness(K, 4.0, 1e-9, dropped)
    assert not N.any() and S[0, 1] == S[1, 0] == 3.0 + 2**-41
    assert dropped == {"N": 0.5 * math.sqrt(2) * 2**-40 / 4.0}


def test_split_damping_of_elements_by_hand():
    class Plan:  # what split_damping reads of a plan whose damping is not constant
        moving, rest_damping, everything = False, None, True

    C = np.array([[4.0, 1.0], [3.0, 2.0]])
    dropped = {}
    D, G = split_damping(C, _assembly(), Plan, 1e-12, dropped)
    assert D.tolist() == [[4.0, 2.0], [2.0, 2.0]] and G.tolist() == [[0.0, -1.0], [1.0, 0.0]]
    sym = np.array([[4.0, 1.0], [1.0, 2.0]])
    D, G = split_damping(sym, _assembly(), Plan, 1e-12, dropped)
    assert D is sym and not G.any() and G.shape == (2, 2) and dropped == {}
    tiny = np.array([[4.0, 1.0 + 2**-50], [1.0, 2.0]])
    D, G = split_damping(tiny, _assembly(), Plan, 1e-12, dropped)
    assert not G.any()
    assert dropped == {"G (element rounding)": 0.5 * math.sqrt(2) * 2**-50 / fro(tiny)}


# ----------------------------------------------------------------------------- few springs


@pytest.mark.parametrize("count", [1, 2, 3, 4])
def test_simple_springs_match_hand_values(chain, count):
    """Q = -k (q - rest) and K_ii = k added in element order (repeated joint included)."""
    joints = ["joint1", "joint2", "joint3", "joint2"][:count] + ["joint1"] * max(0, count - 4)
    ks = [3.0, 2.5, 7.0, 0.3, 1.1][:count]
    rests = [0.1, -0.2, 0.05, 0.3, -0.4][:count]
    springs = tuple(pinlin.JointSpring(j, k, rest=r) for j, k, r in zip(joints, ks, rests))
    scene = pinlin.Scene(chain, springs)
    q = scene.check_configuration([0.3, -0.1, 0.7])
    group = SpringGroup(springs, chain)
    ev = Evaluation(scene, q, np.zeros(3))
    Q, K = np.zeros(3), np.zeros((3, 3))
    group.add_force(ev, Q)
    group.add_stiffness(ev, K)
    Q_hand, K_hand = [0.0] * 3, np.zeros((3, 3))
    for j, k, r in zip(joints, ks, rests):
        i = int(j[-1]) - 1
        Q_hand[i] = Q_hand[i] - k * (q[i] - r)
        K_hand[i, i] += k
    assert Q.tolist() == Q_hand and K.tolist() == K_hand.tolist()


def test_structure_checks_hold_for_entries_near_the_top_of_double_range():
    """Huge entries (1e300): the symmetry check's norms are rescaled, not overflowed to inf (which made the
    check vacuous: an asymmetric M passed) and no spurious overflow warning reaches the user."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sys = pinlin.LinearizedSystem.from_matrices(1e300 * np.eye(3), None, 1e-300 * np.eye(3))
    assert sys.n == 3
    bad = 1e300 * np.array([[1.0, 0.5], [0.4, 1.0]])
    zero = np.zeros((2, 2))
    with pytest.raises(pinlin.ParameterError, match="M.*symmetric"):
        pinlin.LinearizedSystem(bad, zero, zero, np.eye(2), zero)
