"""The numerical time-invariance check of one linearization (where no proof of
:mod:`.time_invariance` applies).

The equations are assembled again with each unproved prescribed joint moved by
:data:`PERIODIC_TEST_ANGLES` and compared against one system-wide scale, so an exactly
zero matrix (an undamped system's C) does not turn rounding into a huge relative
change.  A change beyond the tolerance means the equations are time-periodic.
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin

from ..errors import TimePeriodicError
from ..model.scene import Scene
from ..numerics.norms import fro
from .assembly import Assembly, assemble

__all__ = ["numeric_change", "refuse_motions", "PERIODIC_TEST_ANGLES", "FLOQUET_HINT"]

#: How a time-periodic scene is analysed instead (theory: Floquet), named in every :class:`TimePeriodicError`.
FLOQUET_HINT = (
    "; analyse it with pinlin.periodic_orbit(scene, q0) (the periodic reference motion) and "
    "pinlin.floquet_analysis(scene, orbit) (Floquet multipliers)"
)


def refuse_motions(scene: Scene) -> None:
    """Refuse a scene with periodic prescribed motions (:class:`~pinlin.Harmonic` etc.).

    Raises
    ------
    TimePeriodicError
        Always, naming the first such joint and its period.
    """
    name, motion = next(iter(scene.motions.items()))
    raise TimePeriodicError(
        f"prescribed joint {name!r} follows a periodic motion {motion!r} (period {motion.period:.6g} s): the "
        f"linearized equations are time-periodic, not constant-coefficient, and cannot be analysed as "
        f"M x'' + C x' + K x = f" + FLOQUET_HINT,
        joint=name,
        variation=float("inf"),
    )

#: Offsets [rad or m] of a prescribed joint at which the equations are evaluated again
#: (when no proof applies) to check that they do not depend on its position; two offsets
#: not commensurate with a turn, so that no periodic dependence hides at both.
PERIODIC_TEST_ANGLES = (1.0, 2.5)


def _offset_unit(kind: str) -> str:
    """The unit of a 1-DOF joint's coordinate: m for a prismatic joint, rad for a revolute one."""
    return "m" if kind.startswith(("JointModelP", "JointModelTranslation")) else "rad"


def _scales(base: Assembly, free: np.ndarray, omega: float) -> dict[str, float]:
    """System-wide scales of M, C, K and the residual: L(w) at one frequency w of the whole system.

    .. math::  w^2 = \\|K\\| / \\|M\\| + (\\|C\\| / \\|M\\|)^2 + \\Omega^2

    so that C is measured against ``||C|| + w ||M||`` and K against ``||K|| + w^2 ||M||``
    (an undamped system's exactly zero C against the inertia forces, not against zero).
    """
    ix = np.ix_(free, free)
    nM, nC, nK = fro(base.M[ix]), fro(base.C[ix]), fro(base.K[ix])
    w2 = nK / nM + (nC / nM) ** 2 + omega**2
    return {"M": nM, "C": nC + math.sqrt(w2) * nM, "K": nK + w2 * nM, "r": base.force_scale + w2 * nM}


def numeric_change(
    scene: Scene, q: np.ndarray, base: Assembly, joints, tol: float
) -> tuple[float, list[str]]:
    """Largest relative change of M, C, K and the residual when a prescribed joint moves.

    Each joint of ``joints`` is moved by :data:`PERIODIC_TEST_ANGLES` and the scene
    assembled again; the changes are measured against the system-wide scales of
    :func:`_scales`.  Returns the change and the Pinocchio calls made.

    Raises
    ------
    TimePeriodicError
        A change exceeds ``tol``.
    """
    free = scene.free_dofs
    ix = np.ix_(free, free)
    omega = max(abs(w) for w in scene.prescribed.values())
    scale = _scales(base, free, omega)
    worst = 0.0
    calls: list[str] = []
    for name in joints:
        j = scene.robot.joint(name)
        for offset in PERIODIC_TEST_ANGLES:
            dq = np.zeros(scene.model.nv)
            dq[j.idx_v] = offset
            other = assemble(scene, pin.integrate(scene.model, q, dq), stiffness=True, damping=True, mass=True)
            calls.extend(other.calls)
            diffs = {key: fro(getattr(other, key)[ix] - getattr(base, key)[ix]) for key in ("M", "C", "K")}
            diffs["r"] = fro(other.residual[free] - base.residual[free])
            change = max(d / scale[key] if d else 0.0 for key, d in diffs.items())
            worst = max(worst, change)
            if not change <= tol:
                raise TimePeriodicError(
                    f"the linearized equations depend on the position of prescribed joint {name!r} "
                    f"(relative change {change:.2e} after {offset} {_offset_unit(j.kind)}, against the system's "
                    f"scales): with its "
                    f"prescribed velocity they are time-periodic, not constant-coefficient, and cannot be "
                    f"analysed as M x'' + C x' + K x = f" + FLOQUET_HINT,
                    joint=name,
                    variation=change,
                )
    return worst, calls
