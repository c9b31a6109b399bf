"""Physical validity of inertial data, checked where the dynamics lives.

Two levels:

1. The URDF text (:func:`check_inertials`, before parsing).  urdfdom turns an inertia
   it cannot parse (``iyy="nan"``, ``"1e999"``, ``"abc"``) into zero and a mass it
   cannot parse into a missing inertial, printing only to stderr, so numbers that
   are not finite, and negative masses, are refused naming the link.  A link whose
   tensor is not physically possible is only *noted* here: many real URDFs carry
   dummy links (``base`` of go1: principal moments [-2e-22, 8.5e-23, 3e-6]) that
   Pinocchio merges through their fixed joint into a valid body.
2. The bodies of the Pinocchio model (:func:`check_bodies`, after parsing): the
   inertia ``model.inertias[j]`` of each joint ``j``, which is the sum of every link
   fixed to it.  These are what the equations of motion use.  A body that is not
   physically possible is refused (``inertia="check"``) or replaced by the nearest
   valid tensor (``inertia="repair"``, :func:`nearest_valid_moments`), with an
   :class:`InertiaWarning` naming the body and the change.  A link that failed on
   its own but whose body is valid, or that is fixed to the world (it never
   moves), gives an :class:`InertiaWarning` naming it: never a silent pass.

A rigid body's inertia tensor about its centre of mass has principal moments
I1 <= I2 <= I3 with I_i <= I_j + I_k for every permutation (each moment is an
integral of a sum of two squared coordinates); these triangle inequalities imply
I_i >= 0.  Equality holds for a lamina, and thin rods (I1 = 0, I2 = I3) are common
in reference models, so the tests allow a slack of :data:`INERTIA_TOL` relative to
the body's own largest principal moment (rounding in printed digits is not physics).
"""

from __future__ import annotations

import math
import warnings
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin
from scipy.optimize import nnls

from ..errors import MjcfError, ParameterError, UrdfError

__all__ = [
    "check_inertials",
    "check_bodies",
    "check_inertia_option",
    "inertia_fault",
    "nearest_valid_moments",
    "InertiaWarning",
    "INERTIA_TOL",
    "INERTIA_OPTIONS",
]

#: Relative slack of the positive semi-definiteness and triangle-inequality tests, against
#: the body's largest principal moment: URDFs exported from CAD round inertias to about six
#: significant digits, which can break an exact equality (a lamina, a rod) by 1e-6.
INERTIA_TOL = 1e-6

#: Values of ``load_urdf(..., inertia=...)``.
INERTIA_OPTIONS = ("check", "repair")

_COMPONENTS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")

#: Generators of the cone of valid principal moments {e : e_i <= e_j + e_k}: a simplicial cone.
_RAYS = np.array([[0.0, 1.0, 1.0], [1.0, 0.0, 1.0], [1.0, 1.0, 0.0]])


class InertiaWarning(UserWarning):
    """Inertial data that is not physically possible was found and did not stop the load.

    Either a link whose own tensor is impossible but which Pinocchio merges into a
    valid body (or which is fixed to the world), or a body replaced by its nearest
    valid tensor under ``inertia="repair"``.  The message names the link or body.

    Examples
    --------
    >>> issubclass(pinlin.InertiaWarning, UserWarning)
    True
    """


def check_inertia_option(inertia) -> str:
    """``inertia`` if it is one of :data:`INERTIA_OPTIONS`.

    Raises
    ------
    ParameterError
        Any other value.
    """
    if not isinstance(inertia, str) or inertia not in INERTIA_OPTIONS:
        raise ParameterError("inertia", f"expected one of {list(INERTIA_OPTIONS)}, got {inertia!r}")
    return inertia


def inertia_fault(moments: np.ndarray, tol: float = INERTIA_TOL) -> str | None:
    """What is physically impossible about sorted principal moments [kg m^2], or None.

    The slack is ``tol`` times the largest absolute moment: the body's own scale.
    """
    slack = tol * max(float(np.abs(moments).max()), np.finfo(float).tiny)
    if moments[0] < -slack:
        return "is not positive semi-definite"
    if moments[0] + moments[1] < moments[2] - slack:
        return "breaks the triangle inequality I1 + I2 >= I3 of a rigid body"
    return None


def nearest_valid_moments(moments) -> np.ndarray:
    """The valid principal moments nearest to ``moments`` [kg m^2] in the Euclidean norm.

    The valid moments form the convex cone {e : e_i <= e_j + e_k for all i}, generated
    by (0, 1, 1), (1, 0, 1) and (1, 1, 0); the nearest point is ``G c`` with ``c >= 0``
    minimizing ``||G c - e||`` (non-negative least squares, exact).  Keeping the
    principal axes, the tensor so repaired is the valid tensor nearest to the
    original in the Frobenius norm (the set is spectral and convex: Lewis, "Convex
    analysis on the Hermitian matrices", SIAM J. Optim. 6, 1996).  MuJoCo's
    ``balanceinertia`` is the precedent for repairing rather than refusing.
    """
    e = np.asarray(moments, dtype=float)
    c, _ = nnls(_RAYS.T, e)
    return _RAYS.T @ c


def _number(text: str | None, what: str, link: str, source: str) -> float:
    try:
        value = float(text) if text is not None else math.nan
    except ValueError:
        value = math.nan
    if not math.isfinite(value):
        raise UrdfError(
            f"{source}: link {link!r} has {what} = {text!r}, not a finite number; urdfdom would "
            f"silently read it as zero or drop the link's inertia",
            source,
        )
    return value


def _link_fault(inertial: ET.Element, link: str, source: str) -> str | None:
    mass = inertial.find("mass")
    m = _number(None if mass is None else mass.get("value"), "mass", link, source)
    if m < 0:
        raise UrdfError(f"{source}: link {link!r} has a negative mass ({m:g} kg)", source)
    inertia = inertial.find("inertia")
    v = {k: _number(None if inertia is None else inertia.get(k, "0"), k, link, source) for k in _COMPONENTS}
    tensor = np.array(
        [[v["ixx"], v["ixy"], v["ixz"]], [v["ixy"], v["iyy"], v["iyz"]], [v["ixz"], v["iyz"], v["izz"]]]
    )
    moments = np.linalg.eigvalsh(tensor)
    fault = inertia_fault(moments)
    return None if fault is None else f"{fault} (principal moments {moments.tolist()} kg m^2)"


def check_inertials(root: ET.Element, source: str) -> dict[str, str]:
    """Read every link's ``<inertial>``: refuse what is not a number, note what is not physical.

    Returns
    -------
    dict of str to (str or None)
        Every link with an ``<inertial>`` -> what is physically impossible about its
        own tensor, or None (for :func:`check_bodies`, which decides once the links
        are merged into bodies).

    Raises
    ------
    UrdfError
        Naming the first link whose mass or inertia is not a finite number, or whose
        mass is negative.
    """
    faults: dict[str, str | None] = {}
    for link in root.findall("link"):
        inertial = link.find("inertial")
        if inertial is not None:
            name = link.get("name", "?")
            faults[name] = _link_fault(inertial, name, source)
    return faults


def _links_of_joints(model: pin.Model, inertial_links) -> dict[int, list[str]]:
    """Joint -> the links (body frames) with an ``<inertial>`` that make up its body."""
    out: dict[int, list[str]] = {}
    for frame in model.frames:
        if frame.type == pin.FrameType.BODY:
            out.setdefault(frame.parentJoint, [])
            if frame.name in inertial_links:
                out[frame.parentJoint].append(frame.name)
    return out


def _body_name(links: list[str]) -> str:
    return "link " + (" + ".join(repr(n) for n in links) if links else "(none)")


def _where(model: pin.Model, jid: int, links: list[str]) -> str:
    merged = "the links merged by fixed joints into " if len(links) > 1 else ""
    return f"{merged}the body moved by joint {model.names[jid]!r}"


def check_bodies(model: pin.Model, link_faults: dict[str, str | None], source: str, inertia: str = "check",
                 error: type[UrdfError] | type[MjcfError] = UrdfError) -> None:
    """Check (or repair, in place) the inertia of every body the dynamics uses.

    Parameters
    ----------
    model : pinocchio.Model
        Built from the URDF; ``model.inertias[j]`` for ``j >= 1`` are the bodies.
    link_faults : dict
        From :func:`check_inertials`: every link with an ``<inertial>`` -> what is
        impossible about its own tensor, or None.
    source : str
        The file, for messages.
    inertia : {"check", "repair"}
        Refuse an impossible body, or replace its tensor by the nearest valid one
        (:func:`nearest_valid_moments`, principal axes kept) with an
        :class:`InertiaWarning` giving the old and new principal moments.
    error : exception class
        Raised for an impossible body: :class:`~pinlin.UrdfError` (URDF) or
        :class:`~pinlin.MjcfError` (MJCF, whose bodies the messages call links).

    Raises
    ------
    UrdfError or MjcfError
        ``inertia="check"`` and a body has a negative or non-finite mass, or an
        impossible tensor; the message names its links and joint.
    """
    inertia = check_inertia_option(inertia)
    links = _links_of_joints(model, link_faults)
    faulty: set[int] = set()
    for jid in range(1, model.njoints):
        body = model.inertias[jid]
        name, where = _body_name(links.get(jid, [])), _where(model, jid, links.get(jid, []))
        tensor = np.asarray(body.inertia, dtype=float)
        if not (math.isfinite(body.mass) and body.mass >= 0 and np.all(np.isfinite(tensor))):
            raise error(f"{source}: {name} ({where}) has mass {body.mass!r} kg and tensor "
                            f"{tensor.tolist()}; expected finite numbers and a mass >= 0", source)
        moments, axes = np.linalg.eigh(tensor)
        fault = inertia_fault(moments)
        if fault is None:
            continue
        faulty.add(jid)
        if inertia == "check":
            raise error(
                f"{source}: the inertia tensor of {name} {fault} ({where}; principal moments "
                f"{moments.tolist()} kg m^2); "
                f"load with inertia='repair' for the nearest valid tensor",
                source,
            )
        fixed = nearest_valid_moments(moments)
        model.inertias[jid] = pin.Inertia(body.mass, body.lever, axes @ np.diag(fixed) @ axes.T)
        warnings.warn(
            f"{source}: the inertia tensor of {name} ({where}) {fault}; repaired to the nearest valid tensor: principal "
            f"moments {moments.tolist()} -> {fixed.tolist()} kg m^2 (change {np.linalg.norm(fixed - moments):.3g} "
            f"kg m^2 in the Frobenius norm, principal axes kept)",
            InertiaWarning,
            stacklevel=4,
        )
    _warn_merged_links(model, link_faults, links, faulty, source)


def _warn_merged_links(model: pin.Model, link_faults: dict[str, str | None], links: dict[int, list[str]],
                       faulty: set[int], source: str) -> None:
    joint_of = {link: jid for jid, names in links.items() for link in names}
    for link, fault in link_faults.items():
        jid = joint_of.get(link)
        if fault is None or jid is None or jid in faulty:  # not in the model, or its body was already reported
            continue  # not in the model (Pinocchio reported it); nothing of it reaches the dynamics
        if jid == 0:
            why = "it is fixed to the world, so its inertia does not enter the equations of motion"
        else:
            others = [n for n in links[jid] if n != link]
            shown = ", ".join(repr(n) for n in others[:4]) + (f" and {len(others) - 4} more" if len(others) > 4 else "")
            why = (f"Pinocchio merges it by fixed joints with {shown or 'no other link'} into the body moved by "
                   f"joint {model.names[jid]!r}, which is valid")
        warnings.warn(f"{source}: the inertia tensor of link {link!r} {fault}; {why}", InertiaWarning, stacklevel=5)
