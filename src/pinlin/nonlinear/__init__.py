"""The nonlinear reference: Pinocchio forward dynamics of a scene on its configuration manifold.

- :mod:`.simulate` -- :func:`simulate` and :func:`linear_coordinates` (the deviation
  from the operating point in the coordinates of a :class:`~pinlin.LinearizedSystem`).
"""

from .simulate import EXPLICIT_METHODS, IMPLICIT_METHODS, Simulation, linear_coordinates, simulate

__all__ = ["Simulation", "simulate", "linear_coordinates", "EXPLICIT_METHODS", "IMPLICIT_METHODS"]
