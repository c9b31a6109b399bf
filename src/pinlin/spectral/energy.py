"""Where a mode keeps its energy: the share of each body, element and damper.

:func:`mode_energy` (also :meth:`pinlin.Modes.energy`) splits the period-mean energies
of mode k, the motion Re(x exp(lam t)) of its eigenvector x at its eigenvalue lam,

.. math::
    T = \\tfrac14 |\\lambda|^2 x^H M x,\\qquad
    V = \\tfrac14 x^H S x,\\qquad
    P = \\tfrac12 |\\lambda|^2 x^H D x,

into three tables of shares (:class:`ModeEnergy`), each summing to 1:

- ``kinetic``: with a scene, each body's T_b = 1/4 |lam|^2 u_b^H I_b u_b, u_b = J_b T x its
  spatial velocity per unit lam (J_b the joint Jacobian in the body's axes, I_b its spatial
  inertia, T the map from the system's coordinates to the robot's joint velocities: the
  free coordinates, and ``sys.basis`` with constraints); without a scene, each coordinate's
  1/4 |lam|^2 Re(conj(x_i) (M x)_i);
- ``strain``: each element's elastic stiffness K_e (:meth:`~pinlin.Element.add_elastic_stiffness`:
  joint springs, spring-dampers, bushings), 1/4 (T x)^H K_e (T x); then ``"gravity"``
  (the symmetric part of dg/dq) and ``"loads and other"``: the rest of V (loads, preloads,
  constraint forces, inertial terms of prescribed motions), V minus the rows before;
- ``dissipation``: each damper's D_e (the symmetric part of what
  :meth:`~pinlin.Element.add_damping` adds), 1/2 |lam|^2 (T x)^H D_e (T x), and
  ``"other damping"`` for the rest of P when it is above rounding.

**Signs.** A share is its row's energy over the table's signed total, so the shares of a
table sum to 1 (to rounding, 1e-12) whatever their signs.  A negative share (gravity on an
inverted pendulum, a compressive load) is energy the row gives back: the stiffening rows
then exceed 1 together.  When the total itself is negative (a divergent mode), every share
keeps that sign convention: a positive share then means a negative energy.  A table whose
total is zero within rounding (the strain of a rigid-body mode, the dissipation of an
undamped system) is empty, and ``notes`` says so.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, fields
from types import MappingProxyType

import numpy as np
import pinocchio as pin

from ..errors import ParameterError
from ..model.evaluation import Evaluation
from ..model.scene import Scene
from ..numerics.floating import EPS
from ..results import Result

__all__ = ["ModeEnergy", "mode_energy", "ENERGY_ROUNDING", "SCENE_MATCH_TOL"]

#: A table's total counts as zero at or below this many eps times its scale (|lam|^2 ||M||, ||S||, ...).
ENERGY_ROUNDING = 1e3
#: ``scene`` matches the system when T^T M(q) T reproduces ``sys.M`` to this relative Frobenius distance.
SCENE_MATCH_TOL = 1e-8


@dataclass(frozen=True, repr=False, eq=False, kw_only=True)
class ModeEnergy(Result):
    """The energy distribution of one mode (see :mod:`pinlin.spectral.energy`).

    Attributes
    ----------
    index : int
        The mode's position k in its :class:`~pinlin.Modes`.
    eigenvalue : complex
        lam_k [1/s].
    kinetic, strain, dissipation : mapping of str to float
        Shares per body (or coordinate), per element and per damper, each summing to 1
        (signed, see the module docstring); empty when the table's total is zero.
    kinetic_energy, strain_energy, dissipated_power : float
        The totals T [J], V [J] and P [W] for the unit eigenvector (period means).
    by : str
        ``"bodies"`` (with a scene) or ``"coordinates"``: what the kinetic rows are.
    method : str
        What was split and how.
    error : float
        With a scene: ||T^T M(q) T - sys.M||_F / ||sys.M||_F, how well the scene's bodies
        reproduce the analysed mass matrix (the kinetic shares' accuracy); 0 without a scene
        (the coordinate split is exact).
    elapsed : float
        Seconds.
    notes : tuple of str

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> scene = pinlin.Scene(robot, [pinlin.JointSpring(j, 10.0) for j in robot.joint_names])
    >>> modes = pinlin.modal_analysis(pinlin.linearize(scene, robot.neutral()))
    >>> energy = modes.energy(0, scene)
    >>> {body: round(share, 6) for body, share in energy.kinetic.items()}
    {'link1': 0.18182, 'link2': 0.81818}
    >>> energy.by, round(sum(energy.strain.values()), 6)
    ('bodies', 1.0)
    """

    index: int
    eigenvalue: complex
    kinetic: dict[str, float]
    strain: dict[str, float]
    dissipation: dict[str, float]
    kinetic_energy: float
    strain_energy: float
    dissipated_power: float
    by: str
    method: str
    error: float
    elapsed: float
    notes: tuple[str, ...] = field(default=())

    def __post_init__(self):
        for name in ("kinetic", "strain", "dissipation"):  # an immutable value: read-only tables
            object.__setattr__(self, name, MappingProxyType(dict(getattr(self, name))))

    @classmethod
    def _from_values(cls, values: dict) -> ModeEnergy:
        return cls(**{f.name: values[f.name] for f in fields(cls)})

    @property
    def dominant_body(self) -> str | None:
        """The body (or coordinate) with the largest kinetic share; None if the table is empty."""
        return max(self.kinetic, key=self.kinetic.get) if self.kinetic else None

    @property
    def dominant_element(self) -> str | None:
        """The element row with the largest strain share (gravity and the rest excluded); None if none."""
        rows = {k: v for k, v in self.strain.items() if k not in _REST_ROWS}
        return max(rows, key=rows.get) if rows else None

    def table(self) -> str:
        """The three tables as text: one row per body, element and damper with its share [%].

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> scene = pinlin.Scene(robot, [pinlin.JointSpring(j, 10.0) for j in robot.joint_names])
        >>> print(pinlin.modal_analysis(pinlin.linearize(scene, robot.neutral())).energy(0, scene).table())
        Energy of mode 1: lam = ... (0.7333 Hz)
          kinetic (bodies): total ... J
            link1     18.18 %
            link2     81.82 %
          strain (elements): total ... J
            spring joint1       40.33 %
            spring joint2        2.67 %
            gravity             57.00 %
        ...
        """
        lam = self.eigenvalue
        parts = ("elements", "dampers") if self.by == "bodies" else ("coordinates", "coordinates")
        lines = [f"Energy of mode {self.index + 1}: lam = {lam.real + 0.0:.6g} {lam.imag + 0.0:+.6g}j"
                 f" ({abs(lam) / (2 * np.pi):.4g} Hz)"]
        for title, rows, total, unit in (
            (f"kinetic ({self.by})", self.kinetic, self.kinetic_energy, "J"),
            (f"strain ({parts[0]})", self.strain, self.strain_energy, "J"),
            (f"dissipation ({parts[1]})", self.dissipation, self.dissipated_power, "W"),
        ):
            lines.append(f"  {title}: total {total + 0.0:.4g} {unit}")
            width = max((len(name) for name in rows), default=0)
            for name, share in rows.items():
                lines.append(f"    {name:<{width}}  {_percent(share)} %")
            if not rows:
                lines.append("    (none)")
        lines.extend(f"  note: {note}" for note in self.notes)
        return "\n".join(lines)

    def __repr__(self) -> str:
        return (
            f"ModeEnergy(mode={self.index}, lam={complex(self.eigenvalue):.4g}, by={self.by!r}, "
            f"body={self.dominant_body!r}, element={self.dominant_element!r}, error={self.error:.1e})"
        )


def _percent(share: float) -> str:
    """``100 share`` to two decimals, never "-0.00" (a rounding-size negative share)."""
    text = f"{100 * share:8.2f}"
    return f"{0.0:8.2f}" if float(text) == 0 else text


#: The strain rows that are no element.
_REST_ROWS = ("gravity", "loads and other")


def mode_energy(modes, k: int, scene: Scene | None = None) -> ModeEnergy:
    """The kinetic, strain and dissipated energy shares of mode ``k`` (see :mod:`pinlin.spectral.energy`).

    Parameters
    ----------
    modes : Modes
        A modal analysis.
    k : int
        The mode's position in ``modes`` (0 <= k < 2n).
    scene : Scene or None
        The scene the analysed system was linearized from: kinetic shares per body and
        strain and dissipation per element.  None: shares per coordinate.

    Returns
    -------
    ModeEnergy

    Raises
    ------
    ParameterError
        ``k`` not an integer in [0, 2n); ``scene`` not a Scene, or not the scene of the
        analysed system (other coordinates, or a mass matrix that differs by more than
        :data:`SCENE_MATCH_TOL`), or given for modes of bare matrices; ``modes`` read back
        by :func:`pinlin.load` (they keep no matrices).
    """
    t0 = time.perf_counter()
    if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or not 0 <= k < len(modes):
        raise ParameterError("k", f"expected a mode index, an integer in [0, {len(modes)}), got {k!r}")
    k = int(k)
    lam = complex(modes.eigenvalues[k])
    x = np.asarray(modes.right[:, k])
    M, D, S = _system_matrices(modes)
    w = abs(lam) ** 2
    if scene is None:
        tables = _coordinate_tables(x, modes.dof_names, M, D, S, w)
        method, by, error = "per coordinate: Re(conj(x_i) (A x)_i) for A = M, S, D", "coordinates", 0.0
    else:
        tables, error = _scene_tables(modes, scene, x, M, D, S, w)
        method, by = "per body (joint Jacobians, spatial inertias) and per element (K_e, D_e)", "bodies"
    shares, notes = [], []
    for (rows, total, scale), what in zip(tables, ("kinetic energy", "strain energy", "dissipation")):
        if abs(total) <= ENERGY_ROUNDING * EPS * scale:
            shares.append({})
            notes.append(f"no {what}: its total {total + 0.0:.3g} is zero within rounding")
        else:
            shares.append({name: float(value / total) + 0.0 for name, value in rows.items()})
    return ModeEnergy(
        index=k, eigenvalue=lam, kinetic=shares[0], strain=shares[1], dissipation=shares[2],
        kinetic_energy=float(tables[0][1]), strain_energy=float(tables[1][1]), dissipated_power=float(tables[2][1]),
        by=by, method=method, error=float(error), elapsed=time.perf_counter() - t0, notes=tuple(notes),
    )  # fmt: skip


def _system_matrices(modes) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    sys = modes.system
    if sys is not None:
        return np.asarray(sys.M), np.asarray(sys.D), np.asarray(sys.S)
    if modes.matrices is None:
        raise ParameterError("modes", "were read back by pinlin.load, which keeps no system or matrices: "
                             "analyse the system again to split the energy")
    M, C, K = modes.matrices
    return 0.5 * (M + M.T), 0.5 * (C + C.T), 0.5 * (K + K.T)


def _form(x: np.ndarray, A: np.ndarray) -> float:
    """Re x^H A x."""
    return float(np.real(np.vdot(x, A @ x)))


def _coordinate_tables(x, names, M, D, S, w):
    out = []
    for A, factor in ((M, w / 4), (S, 0.25), (D, w / 2)):
        parts = factor * np.real(np.conj(x) * (A @ x))
        out.append(({name: float(p) for name, p in zip(names, parts)}, _form(x, A) * factor,
                    factor * np.linalg.norm(A) * np.vdot(x, x).real))
    return out


def _coordinate_map(modes, scene: Scene) -> np.ndarray:
    """T (nv, n): joint velocities of the robot per unit coordinate of the analysed system."""
    sys = modes.system
    if not isinstance(scene, Scene):
        raise ParameterError("scene", f"expected a pinlin.Scene, got {type(scene).__name__}")
    if sys is None:
        raise ParameterError("scene", "these modes are of bare matrices: there is no system to match the scene to")
    names = sys.basis_names if sys.basis is not None else sys.dof_names
    if tuple(names) != tuple(scene.dof_names) or sys.q is None or len(sys.q) != scene.robot.nq:
        raise ParameterError(
            "scene", f"does not match the analysed system: its coordinates are {list(scene.dof_names)}, "
            f"the system's {list(names)}"
        )
    T = np.zeros((scene.robot.nv, sys.n))
    T[scene.free_dofs] = sys.basis if sys.basis is not None else np.eye(sys.n)
    return T


def _scene_tables(modes, scene, x, M, D, S, w):
    T = _coordinate_map(modes, scene)
    sys = modes.system
    q = np.asarray(sys.q)
    ev = Evaluation(scene, q, np.asarray(sys.v if sys.v is not None else scene.v0))
    M_full = ev.mass_matrix()
    scale = np.abs(M).max()  # M positive definite: scale > 0; dividing first keeps tiny masses from underflowing
    error = float(np.linalg.norm((T.T @ M_full @ T - M) / scale) / np.linalg.norm(M / scale))
    if not error <= SCENE_MATCH_TOL:
        raise ParameterError(
            "scene", f"does not match the analysed system: its mass matrix at sys.q differs from sys.M by "
            f"{error:.2e} (relative), above {SCENE_MATCH_TOL:g}"
        )
    u = T @ x
    size = np.vdot(x, x).real
    kinetic = _body_energies(scene, ev, u, w)
    strain, damping = _element_energies(scene, ev, u, w)
    V = _form(x, S) / 4
    if scene.has_gravity:
        dg = np.array(ev.call("computeGeneralizedGravityDerivatives", pin.computeGeneralizedGravityDerivatives,
                              scene.model, ev.data, q))
        strain["gravity"] = _form(u, 0.5 * (dg + dg.T)) / 4
    strain["loads and other"] = V - sum(strain.values())
    P = w * _form(x, D) / 2
    rest = P - sum(damping.values())
    d_scale = w / 2 * (np.linalg.norm(D) + sum(abs(v) for v in damping.values()) / max(size, EPS)) * size
    if abs(rest) > ENERGY_ROUNDING * EPS * d_scale:
        damping["other damping"] = rest
    return [
        (kinetic, sum(kinetic.values()), w / 4 * np.linalg.norm(M) * size),
        (strain, V, 0.25 * (np.linalg.norm(S) + np.linalg.norm(T.T @ ev.elastic_stiffness() @ T)) * size),
        (damping, P, d_scale),
    ], error


def _body_energies(scene: Scene, ev: Evaluation, u: np.ndarray, w: float) -> dict[str, float]:
    """T_b = 1/4 |lam|^2 u_b^H I_b u_b per body with inertia, u_b = J_b u (joint Jacobian, body axes)."""
    model = scene.model
    ev.world_jacobian()  # the joint Jacobians (computeJointJacobians), once
    out: dict[str, float] = {}
    for j in range(1, model.njoints):
        inertia = model.inertias[j]
        if inertia.mass == 0 and not np.any(inertia.inertia):
            continue
        # (6, nv): the binding returns a (6,) vector when nv = 1
        J = np.reshape(pin.getJointJacobian(model, ev.data, j, pin.ReferenceFrame.LOCAL), (6, model.nv))
        out[_body_name(model, j)] = w / 4 * _form(J @ u, inertia.matrix())
    return out


def _body_name(model: pin.Model, j: int) -> str:
    """The first body frame (link) carried by joint j, else the joint's name."""
    for frame in model.frames:
        if frame.parentJoint == j and frame.type == pin.FrameType.BODY:
            return frame.name
    return model.names[j]


def _element_energies(scene: Scene, ev: Evaluation, u: np.ndarray, w: float):
    """Strain 1/4 u^H K_e u and dissipation 1/2 |lam|^2 u^H D_e u per element (those with a nonzero matrix)."""
    nv = scene.robot.nv
    strain: dict[str, float] = {}
    damping: dict[str, float] = {}
    for element in scene.elements:
        name = _unique(_label(element), strain, damping)
        K = np.zeros((nv, nv))
        element.add_elastic_stiffness(ev, K)
        if np.any(K):
            strain[name] = _form(u, 0.5 * (K + K.T)) / 4
        C = np.zeros((nv, nv))
        element.add_damping(ev, C)
        if np.any(C + C.T):
            damping[name] = w * _form(u, 0.5 * (C + C.T)) / 2
    return strain, damping


def _label(element) -> str:
    where = getattr(element, "joint", None) or getattr(element, "frame", None)
    target = getattr(element, "target", None)
    if isinstance(target, str):
        where = f"{where}-{target}"
    return f"{element.kind} {where}" if where else element.kind


def _unique(name: str, *tables: dict) -> str:
    out, i = name, 2
    while any(out in t for t in tables):
        out, i = f"{name} #{i}", i + 1
    return out
