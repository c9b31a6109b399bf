"""The Examples sections of the spectral, adjoint, frequency-domain and boundary modules run as doctests."""

from __future__ import annotations

import doctest
import importlib
import pkgutil

import numpy as np
import pytest

import pinlin

PACKAGES = ("pinlin.spectral", "pinlin.numerics", "pinlin.adjoint", "pinlin.frf", "pinlin.boundaries")


def _modules() -> list[str]:
    names = []
    for package in PACKAGES:
        names.append(package)
        path = importlib.import_module(package).__path__
        names += [m.name for m in pkgutil.walk_packages(path, package + ".")]
    return sorted(names)


@pytest.mark.parametrize("name", _modules())
def test_examples_run(name):
    module = importlib.import_module(name)
    result = doctest.testmod(
        module, extraglobs={"np": np, "pinlin": pinlin}, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE,
        report=False,
    )
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples of {name} failed"


def test_every_public_name_of_these_packages_has_an_example():
    missing = [n for n in pinlin.__all__ if getattr(getattr(pinlin, n), "__module__", "").startswith(PACKAGES)
               and "Examples" not in (getattr(pinlin, n).__doc__ or "")]
    assert missing == []
