"""Old import paths, kept importable for one release (0.2) after the layout of issue 10.

pinlin 0.1 had a flat layout (``pinlin.robot``, ``pinlin.scene``, ``pinlin.linearize``,
...).  Each old module path is registered in :data:`sys.modules` as an alias of its
new module, so ``from pinlin.scene import Scene`` keeps working; names that moved
between packages are served by the old package's ``__getattr__`` with a
:class:`DeprecationWarning`.  Remove in 0.3.
"""

from __future__ import annotations

import importlib
import sys
import warnings

__all__ = ["OLD_PATHS", "install", "moved_name"]

#: Old module path -> new module path.
OLD_PATHS = {
    "pinlin.robot": "pinlin.model.loading",  # Robot and the loaders, as before
    "pinlin.models": "pinlin.model.generators",
    "pinlin.scene": "pinlin.model.scene",
    "pinlin.scenefile": "pinlin.model.scenefile",
    "pinlin.elements": "pinlin.model.elements",
    "pinlin.elements.base": "pinlin.model.elements.base",
    "pinlin.elements.joint_spring": "pinlin.model.elements.joint_spring",
    "pinlin.elements.joint_damper": "pinlin.model.elements.joint_damper",
    "pinlin.elements.rayleigh": "pinlin.model.elements.rayleigh",
    "pinlin.elements.wrenches": "pinlin.model.elements.wrenches",
    "pinlin.assembly": "pinlin.linearization.assembly",
    "pinlin.equilibrium": "pinlin.linearization.equilibrium",
    "pinlin.system": "pinlin.linearization.system",
    "pinlin.sweep": "pinlin.studies.sweep",
    "pinlin.tracking": "pinlin.studies.tracking",
    "pinlin.response.simulate": "pinlin.nonlinear.simulate",
    "pinlin.response.harmonic": "pinlin.frf.harmonic",
    "pinlin.adjoint.response": "pinlin.frf.frequency",
    "pinlin.adjoint.flexibility": "pinlin.frf.flexibility",
    "pinlin.response.expansion": "pinlin.frf.expansion",
    "pinlin.adjoint.residues": "pinlin.frf.residues",
}
# ``pinlin.linearize`` is not aliased: that name is the function, and an alias module
# would shadow it as an attribute of the package.


def install() -> None:
    """Register every old path as an alias of its (already importable) new module."""
    for old, new in OLD_PATHS.items():
        if old not in sys.modules:
            sys.modules[old] = importlib.import_module(new)


def moved_name(package: str, name: str, *new_packages: str):
    """Serve a name that moved out of ``package`` (a module ``__getattr__``), with a warning.

    Raises
    ------
    AttributeError
        ``name`` is not one of the moved names either.
    """
    for new in new_packages:
        module = importlib.import_module(new)
        if name in getattr(module, "__all__", ()):
            warnings.warn(
                f"{package}.{name} moved to {new}.{name} in pinlin 0.2; the old path goes in 0.3",
                DeprecationWarning,
                stacklevel=3,
            )
            return getattr(module, name)
    raise AttributeError(f"module {package!r} has no attribute {name!r}")
