"""The Examples sections of the errors, responses, nonlinear, studies, interop and report modules and the
command line run as doctests (numpy as ``np`` and ``pinlin`` given, ELLIPSIS and NORMALIZE_WHITESPACE)."""

import doctest
import importlib
import pkgutil

import numpy as np
import pytest

import pinlin

PACKAGES = ["errors", "response", "nonlinear", "studies", "interop", "report"]
MODULES = sorted((
    {f"pinlin.{package}" for package in PACKAGES}
    | {info.name for package in PACKAGES
       for info in pkgutil.walk_packages(importlib.import_module(f"pinlin.{package}").__path__, f"pinlin.{package}.")}
    | {"pinlin.cli", "pinlin.extras"}
) - {"pinlin.studies.floquet_campbell"})  # the Floquet Campbell study has its own owner and examples
#: Modules whose examples draw with matplotlib (an optional dependency).
DRAWING = {"pinlin.report.figure", "pinlin.report.campbell", "pinlin.report.sweep.figure"}


@pytest.mark.parametrize("name", MODULES)
def test_examples_run(name):
    if name in DRAWING:
        pytest.importorskip("matplotlib")
    module = importlib.import_module(name)
    result = doctest.testmod(module, extraglobs={"np": np, "pinlin": pinlin},
                             optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.failed == 0


def test_every_public_name_of_these_modules_has_an_example():
    missing = []
    for name in MODULES:
        module = importlib.import_module(name)
        for public in getattr(module, "__all__", ()):
            obj = getattr(module, public)
            if callable(obj) and getattr(obj, "__module__", None) == name and ">>>" not in (obj.__doc__ or ""):
                missing.append(f"{name}.{public}")
    assert missing == []
