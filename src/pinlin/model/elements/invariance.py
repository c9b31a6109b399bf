"""What an element's force may depend on, as its class declares it (``Element.invariance``).

The time-invariance proofs of the linearization stage read these declarations; the scene checks
them when it is made, so a misspelt declaration is refused at once.
"""

from __future__ import annotations

from ...errors import ParameterError

__all__ = ["INVARIANCE_KINDS", "JOINT_SPACE", "BODY_FIXED_LOAD", "DEAD_LOAD", "UNKNOWN", "invariance_kind", "declared_kind"]

#: The kinds an element class may declare as its ``invariance`` (:class:`~pinlin.Element`).
JOINT_SPACE = "joint-space"
BODY_FIXED_LOAD = "body-fixed load"
DEAD_LOAD = "dead load"
UNKNOWN = "unknown"
INVARIANCE_KINDS = (JOINT_SPACE, BODY_FIXED_LOAD, DEAD_LOAD, UNKNOWN)


def invariance_kind(element) -> str:
    """What ``element``'s force depends on: the ``invariance`` its own class declares.

    Only a declaration on ``type(element)`` itself counts, never an inherited one
    (a subclass may read more than its parent); without one the kind is
    :data:`UNKNOWN`.

    Raises
    ------
    ParameterError
        The class declares a value not in :data:`INVARIANCE_KINDS`.
    """
    return declared_kind(type(element))


def declared_kind(cls: type) -> str:
    """:func:`invariance_kind` of the elements of class ``cls``."""
    kind = cls.__dict__.get("invariance", UNKNOWN)
    if not (isinstance(kind, str) and kind in INVARIANCE_KINDS):
        raise ParameterError(
            f"{cls.__name__}.invariance", f"expected one of {INVARIANCE_KINDS}, got {kind!r}"
        )
    return kind
