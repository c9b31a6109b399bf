"""Local charts of the configuration manifold, in which the nonlinear equations are integrated.

Pinocchio's configurations live on a Lie group (nq != nv for continuous,
spherical, planar and free-flyer joints).  An ODE solver needs a vector state,
so the integration runs in a chart around a base point q_b:

.. math::
    q = \\mathrm{integrate}(q_b, dq), \\qquad
    \\dot{dq} = \\left(\\partial\\, \\mathrm{integrate}(q_b, dq) / \\partial dq\\right)^{-1} v

(theory: equations: all derivatives in the tangent space).  For joints whose group
is flat (R^n, SO(2)) the chart is global and d integrate / d dq = I.  On the
curved groups the chart is good only for rotations well below pi: when the
rotation part of dq leaves a ball of radius ``chart_radius``, the base point
moves to the current configuration (a re-centring) and integration restarts.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from ..model.elements.lie_log import exp_chart_rate

__all__ = ["Chart", "chart_groups", "MAX_CHART_RADIUS"]

#: Lie groups whose ``integrate`` is a plain sum in the tangent coordinates
#: (d integrate / d v = I): a single chart covers all of them.
FLAT_GROUPS = ("R^", "SO(2)")

#: Largest chart radius [rad]: the exponential chart of SO(3) is singular at a rotation of pi,
#: and d integrate / d dq must stay well conditioned inside the chart.
MAX_CHART_RADIUS = 3.0


def chart_groups(model: pin.Model) -> list[np.ndarray]:
    """Tangent indices whose size limits a chart: the rotation part of each SO(3), SE(3), SE(2) joint.

    Joints of other curved groups contribute all their tangent indices.  Flat
    groups (R^n, SO(2)) have a global chart and contribute nothing.

    Examples
    --------
    >>> from pinlin.nonlinear.charts import chart_groups
    >>> scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
    >>> chart_groups(scene.model)  # two revolute joints: one global chart
    []
    """
    groups: list[np.ndarray] = []
    for jid in range(1, model.njoints):
        joint = model.joints[jid]
        name = joint.lieGroup().name
        if name.startswith(FLAT_GROUPS):
            continue
        start = joint.idx_v
        if name == "SE(3)":
            groups.append(np.arange(start + 3, start + 6))
        elif name == "SE(2)":
            groups.append(np.array([start + 2]))
        else:
            groups.append(np.arange(start, start + joint.nv))
    return groups


class Chart:
    """The chart q = integrate(q_b, dq) around a base point, and the rate of its coordinates.

    Parameters
    ----------
    model : pin.Model
    base : (nq,) ndarray
        The base point q_b.
    groups : list of ndarray
        :func:`chart_groups` of the model (empty: every joint is flat, the chart is global).

    Examples
    --------
    >>> from pinlin.nonlinear.charts import Chart
    >>> scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
    >>> chart = Chart(scene.model, np.zeros(2), [])
    >>> chart.configuration(np.array([0.1, 0.2])), chart.size(np.array([0.1, 0.2]))
    (array([0.1, 0.2]), 0.0)
    """

    def __init__(self, model: pin.Model, base: np.ndarray, groups: list[np.ndarray]):
        self.model = model
        self.base = base
        self.groups = groups
        self.curved = _curved(model) if groups else None

    def configuration(self, dq: np.ndarray) -> np.ndarray:
        """q = integrate(q_b, dq), (nq,)."""
        return pin.integrate(self.model, self.base, dq)

    def coordinate_rate(self, dq: np.ndarray, v: np.ndarray) -> np.ndarray:
        """d(dq)/dt for the velocity v at q = integrate(q_b, dq): (d integrate / d dq)^-1 v."""
        if not self.groups:
            return v.copy()
        if self.curved is not None:  # every curved joint SE(3), SO(3) or SE(2): block by block, accurate
            rate = v.copy()
            for block, name in self.curved:
                rate[block] = exp_chart_rate(name, dq[block], v[block])
            return rate
        J = pin.dIntegrate(self.model, self.base, dq, pin.ArgumentPosition.ARG1)
        return np.linalg.solve(J, v)

    def size(self, dq: np.ndarray) -> float:
        """The largest rotation [rad] of a curved joint in dq (0 when the chart is global)."""
        return max((float(np.linalg.norm(dq[g])) for g in self.groups), default=0.0)

    def recentred(self, dq: np.ndarray) -> Chart:
        """The chart based at integrate(q_b, dq) (where dq = 0 again)."""
        chart = Chart(self.model, self.configuration(dq), [])
        chart.groups, chart.curved = self.groups, self.curved  # the model's, unchanged
        return chart


def _curved(model: pin.Model) -> list[tuple[slice, str]] | None:
    """(tangent slice, group name) of each curved joint when all are SE(3), SO(3) or SE(2), else None.

    On those d integrate / d dq is block diagonal with the blocks of
    :func:`pinlin.model.elements.lie_log.exp_chart_rate` (solving Pinocchio 4.1's
    ``dIntegrate`` on SE(3) gives rates up to 3e-5 relative off between about 1e-4 and
    2e-3 rad); any other curved
    group keeps Pinocchio's whole-model solve.
    """
    out = []
    for jid in range(1, model.njoints):
        joint = model.joints[jid]
        name = joint.lieGroup().name
        if name.startswith(FLAT_GROUPS):
            continue
        if name not in ("SE(3)", "SO(3)", "SE(2)"):
            return None
        out.append((slice(joint.idx_v, joint.idx_v + joint.nv), name))
    return out
