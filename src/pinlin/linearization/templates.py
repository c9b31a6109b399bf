"""The result objects of one scene's linearizations, built from a per-scene template (issue 27 part 3).

:meth:`LinearizedSystem.trusted <pinlin.linearization.system.LinearizedSystem.trusted>`
builds a system's attribute dictionary from keywords, converting its tuples
and dictionaries each time.  Of its nineteen attributes seven are the same for
every linearization of a scene (the names, the steady velocity, the method, the
empty constraint attributes): :func:`system_template` holds them, once per
scene (kept by the scene's plan, read-only), and :func:`system_from_template`
builds a system as a copy of it with the per-point attributes filled in, the
same attributes in the same order as ``trusted``'s.
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType

import numpy as np

from .system import LinearizedSystem

__all__ = ["system_template", "system_from_template"]


def system_template(dof_names: tuple[str, ...], v: np.ndarray | None, method: str = "analytic") -> Mapping:
    """The attributes one scene's systems share, in ``trusted``'s order (a read-only mapping; per-point ones None).

    Raises
    ------
    ValueError
        ``v`` is writable: the template's arrays are shared by every system of the scene.
    """
    if v is not None and v.flags.writeable:
        raise ValueError("the template's v must be read-only: every system of the scene shares it")
    return MappingProxyType({
        "M": None, "D": None, "G": None, "S": None, "N": None, "dof_names": tuple(dof_names), "q": None, "v": v,
        "residual": None, "balancing": None, "elapsed": None, "calls": None, "dropped": None, "notes": None,
        "method": method, "basis": None, "basis_names": (), "basis_condition": None, "constraint_forces": (),
    })  # fmt: skip


def system_from_template(
    template: Mapping,
    M: np.ndarray,
    D: np.ndarray,
    G: np.ndarray,
    S: np.ndarray,
    N: np.ndarray,
    q: np.ndarray,
    residual: float,
    balancing: np.ndarray | None,
    elapsed: float,
    calls: tuple[str, ...],
    dropped: dict[str, float],
    notes: tuple[str, ...],
) -> LinearizedSystem:
    """``LinearizedSystem.trusted``'s system, the shared attributes taken from ``template`` (:func:`system_template`).

    The same promises as ``trusted`` (matrices valid by construction, taken over and
    made read-only); ``calls`` and ``notes`` must be tuples, ``dropped`` a
    dictionary handed over.
    """
    M.setflags(False)  # write=False; positional: a third of the keyword call's cost
    D.setflags(False)
    G.setflags(False)
    S.setflags(False)
    N.setflags(False)
    q.setflags(False)
    if balancing is not None:
        balancing.setflags(False)
    attributes = template.copy()
    attributes["M"], attributes["D"], attributes["G"], attributes["S"], attributes["N"] = M, D, G, S, N
    attributes["q"], attributes["residual"], attributes["balancing"] = q, residual, balancing
    attributes["elapsed"], attributes["calls"], attributes["dropped"], attributes["notes"] = (
        elapsed, calls, dropped, notes
    )  # fmt: skip
    system = object.__new__(LinearizedSystem)
    object.__setattr__(system, "__dict__", attributes)
    return system
