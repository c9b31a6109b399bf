"""Physical validity of the links' inertial data, checked when a model is loaded (issue 13).

urdfdom turns an inertia it cannot parse (``iyy="nan"``, ``"1e999"``, ``"abc"``) into
zero and a mass it cannot parse into a missing inertial, printing only to stderr; and
it accepts physically impossible data (a negative mass, an inertia tensor that is not
positive semi-definite or breaks the triangle inequality).  Either way the model would
silently be another one.  :func:`check_inertials` reads every ``<link><inertial>``
of the URDF text itself and names the first link at fault.

A rigid body's inertia tensor about its centre of mass has principal moments
I1 <= I2 <= I3 >= 0 with I1 + I2 >= I3 (each is an integral of a sum of two squared
coordinates).  Equality holds for a planar lamina, and thin rods (I1 = 0, I2 = I3)
are common in reference models, so the tests allow a relative slack of
:data:`INERTIA_TOL`.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import numpy as np

from ..errors import UrdfError

__all__ = ["check_inertials", "INERTIA_TOL"]

#: Relative slack of the positive semi-definiteness and triangle-inequality tests, against
#: the largest principal moment: URDFs exported from CAD round inertias to about six
#: significant digits, which can break an exact equality (a lamina, a rod) by 1e-6.
INERTIA_TOL = 1e-6

_COMPONENTS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


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


def _check_link(inertial: ET.Element, link: str, source: str) -> None:
    mass = inertial.find("mass")
    m = _number(None if mass is None else mass.get("value"), "mass", link, source)
    if m < 0:
        raise UrdfError(f"{source}: link {link!r} has a negative mass ({m:g} kg)", source)
    inertia = inertial.find("inertia")
    values = {k: _number(None if inertia is None else inertia.get(k, "0"), k, link, source) for k in _COMPONENTS}
    tensor = np.array(
        [
            [values["ixx"], values["ixy"], values["ixz"]],
            [values["ixy"], values["iyy"], values["iyz"]],
            [values["ixz"], values["iyz"], values["izz"]],
        ]
    )
    moments = np.linalg.eigvalsh(tensor)
    slack = INERTIA_TOL * max(abs(moments).max(), np.finfo(float).tiny)
    if moments[0] < -slack:
        raise UrdfError(
            f"{source}: the inertia tensor of link {link!r} is not positive semi-definite "
            f"(principal moments {moments.tolist()} kg m^2)",
            source,
        )
    if moments[0] + moments[1] < moments[2] - slack:
        raise UrdfError(
            f"{source}: the inertia tensor of link {link!r} breaks the triangle inequality "
            f"I1 + I2 >= I3 of a rigid body (principal moments {moments.tolist()} kg m^2)",
            source,
        )


def check_inertials(root: ET.Element, source: str) -> None:
    """Check every link's ``<inertial>``: finite mass >= 0, finite psd tensor obeying the triangle inequality.

    Raises
    ------
    UrdfError
        Naming the first link whose inertial data is not a number, not finite, or not
        physically possible.
    """
    for link in root.findall("link"):
        inertial = link.find("inertial")
        if inertial is not None:
            _check_link(inertial, link.get("name", "?"), source)
