"""Nonlinear configurations as the coordinates x of a linearized system (theory: equations)."""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from ..errors import ConfigurationError
from ..model.elements.lie_log import curved_joints
from ..model.scene import Scene

__all__ = ["linear_coordinates"]


def _configurations(q, nq: int) -> tuple[np.ndarray, bool]:
    """(len(t), nq) finite configurations, and whether a single one was given."""
    try:
        qs = np.array(q, dtype=float)
    except (TypeError, ValueError):
        raise ConfigurationError(f"q must be an array of numbers, got {q!r:.80}") from None
    single = qs.ndim == 1
    qs = np.atleast_2d(qs)
    if qs.ndim != 2 or qs.shape[1] != nq:
        raise ConfigurationError(f"q has shape {np.shape(q)}; expected (nq,) or (len(t), nq) with nq = {nq}")
    if not np.all(np.isfinite(qs)):
        raise ConfigurationError("q has non-finite entries")
    return qs, single


def _velocities(v, rows: int, nv: int) -> np.ndarray:
    """(rows, nv) finite velocities."""
    try:
        vs = np.atleast_2d(np.array(v, dtype=float))
    except (TypeError, ValueError):
        raise ConfigurationError(f"v must be an array of numbers, got {v!r:.80}") from None
    if vs.shape != (rows, nv):
        raise ConfigurationError(f"v has shape {np.shape(v)}; expected ({rows}, {nv}) like q")
    if not np.all(np.isfinite(vs)):
        raise ConfigurationError("v has non-finite entries")
    return vs


def linear_coordinates(scene: Scene, q_op, q, v=None) -> tuple[np.ndarray, np.ndarray]:
    """Nonlinear configurations as coordinates x of the linearized system at ``q_op``.

    .. math::
        x = \\mathrm{difference}(q_{op}, q)_f, \\qquad
        \\dot x = \\left(\\partial\\, \\mathrm{difference}(q_{op}, q) / \\partial q\\; v\\right)_f

    restricted to the free coordinates f (the tangent-space coordinates in
    which :func:`pinlin.linearize` differentiates, theory: equations).  Pinocchio's
    ``difference`` acts joint by joint, so the advancing angle of a prescribed
    joint does not enter: for a steady motion x is the deviation from it.
    xdot is the exact time derivative of x (not just v_f, which differs from
    it at second order on curved joints).  On free-flyer, spherical and planar
    joints both come from :mod:`pinlin.model.elements.lie_log` (Pinocchio 4.1's
    ``dDifference`` loses up to 3e-5 relative between about 1e-4 and 2e-3 rad).

    Parameters
    ----------
    scene : Scene
    q_op : (nq,) array
        The operating point (the configuration ``linearize`` was given).
    q : (nq,) or (len(t), nq) array
        Configurations.
    v : (nv,) or (len(t), nv) array, optional
        Velocities; without them xdot is None.

    Returns
    -------
    x, xdot : ndarray
        (n,) or (len(t), n) each; xdot is None when v is not given.

    Raises
    ------
    ConfigurationError
        Wrong sizes or non-finite values.

    Examples
    --------
    >>> scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
    >>> x, xdot = pinlin.linear_coordinates(scene, [0.0, 0.0], [0.1, -0.2], [1.0, 0.0])
    >>> x, xdot
    (array([ 0.1, -0.2]), array([1., 0.]))
    """
    q_op = scene.check_configuration(q_op, "q_op")
    model = scene.model
    qs, single = _configurations(q, model.nq)
    vs = None if v is None else _velocities(v, qs.shape[0], model.nv)
    f = scene.free_dofs
    x = np.empty((qs.shape[0], len(f)))
    xdot = None if vs is None else np.empty_like(x)
    curved = curved_joints(model, q_op)  # free-flyer, spherical, planar: logs accurate at every angle
    for i, qi in enumerate(qs):
        dq = pin.difference(model, q_op, qi)
        J = None if vs is None else pin.dDifference(model, q_op, qi, pin.ArgumentPosition.ARG1)
        for q_block, v_block, log in curved:
            if J is None:
                dq[v_block] = log.difference(qi[q_block])
            else:  # e and its Jacobian from one evaluation of the log
                dq[v_block], J[v_block, v_block] = log.evaluate(qi[q_block])
        x[i] = dq[f]
        if J is not None:
            xdot[i] = (J @ vs[i])[f]
    if single:
        return x[0], (None if xdot is None else xdot[0])
    return x, xdot
