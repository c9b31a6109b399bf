"""What a linearization of one scene runs, decided once per scene.

A :class:`~pinlin.Scene` is immutable, so everything :func:`pinlin.linearize`
decides without looking at q is decided once, on first use, and kept by this
stage (:func:`plan_of`, a cache keyed by the scene: the description never
imports the stage that reads it): the free coordinates and their index arrays, the
Pinocchio derivative algorithm (see :mod:`.assembly`), whether the elements'
stiffness is exactly symmetric, the default structure tolerance, and which
prescribed joints are proved not to enter the equations
(:mod:`.time_invariance`) and which need the numerical check at every call,
and, when every element group's damping is constant (joint dampers), the
elements' damping matrix and its split into D and G (:class:`RestDamping`).
"""

from __future__ import annotations

import threading
import weakref

import numpy as np

from ..model.scene import Scene
from ..numerics.arrays import readonly
from .split import choose_element_parts, element_damping_parts
from .time_invariance import InvarianceProof, invariance_proofs

__all__ = ["plan_of", "LinearizationPlan", "RestDamping", "STRUCTURE_EPS_FACTOR", "default_structure_tol"]

#: Default structure_tol is STRUCTURE_EPS_FACTOR n eps: Pinocchio's recursive algorithms
#: accumulate a few rounding errors per joint, so an exactly (skew-)symmetric part that
#: should vanish comes out at a small multiple of n eps of the computed part's norm.
STRUCTURE_EPS_FACTOR = 100.0


def default_structure_tol(n: int) -> float:
    """STRUCTURE_EPS_FACTOR n eps: the default ``structure_tol`` of an n-coordinate system."""
    return STRUCTURE_EPS_FACTOR * n * float(np.finfo(float).eps)


class RestDamping:
    """The elements' damping when it is the same at every point, with its split (once per scene).

    At rest (v = 0) C is the elements' damping alone; when every element group
    adds a constant matrix (``group.constant_damping``) it is added up here, in
    the order :func:`~pinlin.linearization.assembly.assemble` adds it, so the
    values are bitwise those of a per-call assembly.  Arrays are read-only and
    handed out as views (a view of a read-only array cannot be made writable):
    the plan is shared by threads.

    Attributes
    ----------
    C : (nv, nv) ndarray
        The elements' -dQ_e/dv.
    D, G : (n, n) ndarray
        (C + C^T) / 2 and (C - C^T) / 2 on the free coordinates
        (:func:`~pinlin.linearization.split.element_damping_parts`; G is None when C is
        exactly symmetric: the zero array ``zero`` stands for it).
    size : float
        ||G|| / ||C||: 0 when C is exactly symmetric (the usual case).
    """

    __slots__ = ("C", "D", "G", "size", "zero")

    def __init__(self, scene: Scene, block):
        nv = scene.model.nv
        C = np.zeros((nv, nv))
        for group in scene.groups:
            group.add_damping(None, C)
        D, G, self.size = element_damping_parts(C[block])
        self.C = readonly(C)
        self.D = readonly(D)
        self.G = None if G is None else readonly(G)
        self.zero = readonly(np.zeros(D.shape))

    def split(self, tol: float, dropped: dict) -> tuple[np.ndarray, np.ndarray]:
        """(D, G) as read-only views, G set to zero when at rounding level (reported in ``dropped``)."""
        G = None if self.G is None else self.G.view()
        return choose_element_parts(self.D.view(), G, self.size, tol, dropped, self.zero.view())


class LinearizationPlan:
    """The q-independent decisions of :func:`pinlin.linearize` for one scene.

    Attributes
    ----------
    free : (n,) ndarray of int
        The free velocity coordinates (``scene.free_dofs``).
    n : int
    everything : bool
        True when every coordinate is free (no prescribed joint): no restriction.
    ix : tuple of ndarray or None
        ``np.ix_(free, free)``, None when ``everything``.
    block : tuple
        What restricts an (nv x nv) matrix to the free coordinates: two slices when
        they are contiguous (a view, no copy; prescribed joints usually come first
        or last), else ``ix``.
    rows : slice or ndarray
        What restricts a vector to the free coordinates: the slice, else ``free``.
    moving : bool
        True when a prescribed velocity is nonzero: the dynamics need
        ``computeRNEADerivatives`` (Coriolis and gyroscopic terms).
    symmetric_elements : bool
        True when every element group's stiffness is exactly symmetric (then the
        skew part N carries only Pinocchio's rounding, measured against its part).
    structure_tol : float
        The default ``structure_tol`` (:func:`default_structure_tol`).
    proofs : dict of str to InvarianceProof
        Prescribed joints whose position provably does not enter the equations.
    unproved : tuple of str
        Prescribed joints to check numerically at every linearization.
    proof_notes : tuple of str
        The proofs' notes, for ``sys.notes``.
    largest_departure : float
        The largest departure from exact symmetry among the proofs (0 when none):
        with a ``periodic_tol`` at least this large every proof applies.
    rest_damping : RestDamping or None
        The elements' constant damping and its split, when every group's damping
        is constant (``group.constant_damping``); None otherwise.  Used at rest,
        where C is the elements' damping alone.
    undamped : bool
        True when the elements add no damping at any point (their constant damping
        is zero): with a prescribed velocity C is Pinocchio's dtau/dv alone.
    """

    __slots__ = (
        "free",
        "n",
        "everything",
        "ix",
        "block",
        "rows",
        "moving",
        "symmetric_elements",
        "structure_tol",
        "proofs",
        "unproved",
        "proof_notes",
        "largest_departure",
        "rest_damping",
        "undamped",
    )

    def __init__(self, scene: Scene):
        self.free = scene.free_dofs
        self.n = len(self.free)
        self.everything = self.n == scene.model.nv
        self.ix = None if self.everything else np.ix_(self.free, self.free)
        contiguous = self.n > 0 and self.free[-1] - self.free[0] == self.n - 1
        span = slice(int(self.free[0]), int(self.free[-1]) + 1) if contiguous else None
        self.block = (span, span) if contiguous else self.ix
        self.rows = span if contiguous else self.free
        self.moving = bool(scene.v0.any())
        self.symmetric_elements = all(g.symmetric_stiffness for g in scene.groups) and all(
            w.symmetric_stiffness for w in scene.varying_wrenches
        )
        self.structure_tol = default_structure_tol(self.n)
        self.proofs: dict[str, InvarianceProof] = invariance_proofs(scene)
        self.unproved = tuple(name for name in scene.prescribed if name not in self.proofs)
        self.proof_notes = tuple(p.note for p in self.proofs.values())
        self.largest_departure = max((p.departure for p in self.proofs.values()), default=0.0)
        constant = all(g.constant_damping for g in scene.groups)
        self.rest_damping = RestDamping(scene, self.block) if constant else None
        self.undamped = constant and not np.count_nonzero(self.rest_damping.C)

    def __repr__(self) -> str:
        proved = ", ".join(self.proofs) or "none"
        return (
            f"LinearizationPlan(n={self.n}, moving={self.moving}, proved={proved}, "
            f"checked per call={list(self.unproved)})"
        )


#: Scene -> its plan.  Weak keys: a plan lives as long as its scene; scenes compare by identity.
_PLANS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
_PLANS_LOCK = threading.Lock()


def plan_of(scene: Scene) -> LinearizationPlan:
    """The linearization plan of ``scene``, made on the first call for it and kept while the scene lives.

    Thread-safe: two threads asking at once may both build it (a pure function of the
    immutable scene, so the two are equal); the first one stored is returned to both.
    """
    plan = _PLANS.get(scene)
    if plan is None:
        built = LinearizationPlan(scene)
        with _PLANS_LOCK:
            plan = _PLANS.setdefault(scene, built)
    return plan
