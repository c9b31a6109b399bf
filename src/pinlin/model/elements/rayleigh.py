"""Rayleigh (proportional) damping."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ...errors import ParameterError
from ..numbers import numeric_scalar
from .base import Element

__all__ = ["RayleighDamping"]


@dataclass(frozen=True, eq=False)
class RayleighDamping(Element):
    """Rayleigh damping on the free coordinates (theory: elements).

    .. math::  Q = -(\\alpha M(q) + \\beta K_e)\\, v_{free}

    with K_e the elastic stiffness of the scene's elements (each element's
    :meth:`~pinlin.Element.add_elastic_stiffness`: a joint spring's matrix; psd by
    construction; gravity and loads are not elastic elements).  Prescribed
    joints' velocities are not damped: the damping acts on the deviation only.

    Parameters
    ----------
    alpha : float
        Mass-proportional coefficient [1/s], >= 0.
    beta : float
        Stiffness-proportional coefficient [s], >= 0.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> scene = pinlin.Scene(robot, [pinlin.JointSpring("joint1", 2.0), pinlin.RayleighDamping(beta=0.01)])
    >>> np.round(pinlin.linearize(scene, np.zeros(2)).D, 6)
    array([[0.02, 0.  ],
           [0.  , 0.  ]])
    """

    alpha: float = 0.0
    beta: float = 0.0

    kind: ClassVar[str] = "rayleigh"
    invariance: ClassVar[str] = "joint-space"
    symmetric_stiffness: ClassVar[bool] = True

    def __post_init__(self):
        for name in ("alpha", "beta"):
            value = getattr(self, name)
            value = numeric_scalar(value, f"RayleighDamping.{name}")
            if not np.isfinite(value) or value < 0:
                raise ParameterError(f"RayleighDamping.{name}", f"must be finite and >= 0, got {value!r}")
            object.__setattr__(self, name, value)

    def check(self, robot) -> None:
        """Rayleigh damping fits any robot."""

    def needs(self) -> frozenset[str]:
        return frozenset({"mass_matrix"}) if self.alpha else frozenset()

    def _matrix(self, ev) -> np.ndarray:
        D = np.zeros((ev.model.nv, ev.model.nv))
        if self.alpha:
            D += self.alpha * ev.mass_matrix()
        if self.beta:
            D += self.beta * ev.elastic_stiffness()
        return D

    def generalized_force(self, ev) -> np.ndarray:
        f = ev.free
        return -self._matrix(ev)[:, f] @ ev.v[f]

    def add_damping(self, ev, C: np.ndarray) -> None:
        f = ev.free
        C[:, f] += self._matrix(ev)[:, f]
