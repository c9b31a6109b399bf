"""URDFs written in xacro, and ``package://`` / ``$(find pkg)`` paths.

A xacro is a program: its ``${...}`` expressions are Python, ``$(env ...)`` reads
the environment, ``load_yaml`` and ``<xacro:include>`` read files.  So, as numpy's
``load(allow_pickle=False)`` treats pickles, :func:`expand_xacro` refuses a xacro
unless the caller trusts it (``trust=True``; ``load_urdf(..., trust_xacro=True)``,
a scene file's ``trust_xacro = true``, the CLI's ``--trust-xacro``).  A trusted xacro
is expanded by the ``xacro`` package (PyPI, the optional extra ``pinlin[xacro]``) in a
child process (:mod:`.xacro_sandbox`) with a time limit (:data:`XACRO_TIME_LIMIT`), an
address-space limit (:data:`XACRO_MEMORY_LIMIT`) and no file writes, which still
refuses what ``allow`` does not list (:data:`XACRO_PERMISSIONS`): ``$(env)``,
``$(optenv)``, ``load_yaml``, Python escapes (``python.``, ``__``) and includes
outside the package search path and the file's own folder.

Packages are found through one documented search path (:func:`package_search_path`):

1. the ``package_dirs`` given, in order;
2. the entries of ``ROS_PACKAGE_PATH`` (ROS 1), where set;
3. ``<prefix>/share`` for each entry of ``AMENT_PREFIX_PATH`` (ROS 2), where set.

Package ``pkg`` is the first ``<dir>/pkg`` that is a directory, or a search-path
entry ``<dir>`` whose own name is ``pkg``.  xacro resolves ``$(find pkg)`` only
through ROS 2's ament index and does not read ``package://`` in ``<xacro:include>``;
the child process gives it this search path for both.  Meshes are never opened:
a ``package://`` URI left in a ``<mesh>`` stays as it is.
"""

from __future__ import annotations

import importlib.util
import json
import os
import subprocess
import sys
import warnings
from collections.abc import Collection, Mapping, Sequence
from pathlib import Path

from ..errors import MissingDependencyError, ParameterError, UrdfError
from .xacro_sandbox import PERMISSIONS

__all__ = [
    "expand_xacro", "package_search_path", "find_package", "is_xacro",
    "XACRO_PERMISSIONS", "XACRO_TIME_LIMIT", "XACRO_MEMORY_LIMIT",
]

#: What ``allow=`` may name, and what each lets a trusted xacro do.
XACRO_PERMISSIONS: dict[str, str] = dict(PERMISSIONS)
#: Seconds a xacro expansion may take (wall clock; CPU time is limited alike).
XACRO_TIME_LIMIT = 30.0
#: Bytes of address space the expanding process may use.
XACRO_MEMORY_LIMIT = 2 * 1024**3
_SANDBOX = Path(__file__).with_name("xacro_sandbox.py")


def is_xacro(path: str | os.PathLike) -> bool:
    """True for a ``.xacro`` file (``robot.urdf.xacro``, ``robot.xacro``).

    Examples
    --------
    >>> from pinlin.model.xacro import is_xacro
    >>> is_xacro("robot.urdf.xacro"), is_xacro("robot.urdf")
    (True, False)
    """
    return os.fspath(path).endswith(".xacro")


def _xacro_location() -> str:
    """The folder holding the ``xacro`` package this process would import (the child imports that one)."""
    spec = importlib.util.find_spec("xacro")
    if spec is None or spec.origin is None:
        raise MissingDependencyError("expanding a .xacro file needs the xacro package: pip install 'pinlin[xacro]'")
    return str(Path(spec.origin).parent.parent)


def package_search_path(package_dirs: Sequence[str | os.PathLike] | None = None) -> list[Path]:
    """The directories searched for ROS packages, in order (module docstring).

    Raises
    ------
    ParameterError
        ``package_dirs`` is a single string or not a sequence of paths.

    Examples
    --------
    >>> from pinlin.model.xacro import package_search_path
    >>> package_search_path(["/ws/src"])[0].as_posix()
    '/ws/src'
    """
    if package_dirs is None:
        package_dirs = []
    if isinstance(package_dirs, (str, os.PathLike)) or not isinstance(package_dirs, Sequence):
        raise ParameterError("package_dirs", f"expected a list of directories, got {package_dirs!r}")
    out = [Path(os.fspath(d)) for d in package_dirs]
    out += [Path(p) for p in os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep) if p]
    out += [Path(p) / "share" for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
    return out


def _package_directories(search_path: Sequence[Path]) -> dict[str, Path]:
    """Package name -> its directory: the first ``<dir>/pkg`` or entry named ``pkg`` (module docstring)."""
    out: dict[str, Path] = {}
    for d in search_path:
        try:
            children = sorted(c for c in d.iterdir() if c.is_dir())
        except OSError:  # missing or unreadable: nothing found there, as for a missing folder
            continue
        for child in children:
            out.setdefault(child.name, child)
        out.setdefault(d.name, d)
    return out


def find_package(name: str, search_path: Sequence[Path]) -> Path:
    """The directory of package ``name`` on ``search_path``.

    Raises
    ------
    UrdfError
        No such package; the message lists the directories searched.

    Examples
    --------
    >>> from pinlin.model.xacro import find_package
    >>> data = pinlin.data_path("urdf/double_pendulum.urdf").parent.parent
    >>> find_package("urdf", [data]) == data / "urdf"
    True
    """
    found = _package_directories(search_path).get(name)
    if found is None:
        shown = [str(d) for d in search_path] or "nothing: pass package_dirs=[...] or set ROS_PACKAGE_PATH"
        raise UrdfError(f"package {name!r} not found; searched {shown}", name)
    return found


def _check_allow(allow: Collection[str]) -> frozenset[str]:
    if isinstance(allow, str) or not isinstance(allow, Collection) or not set(allow) <= set(XACRO_PERMISSIONS):
        raise ParameterError("allow", f"expected a set of {sorted(XACRO_PERMISSIONS)}, got {allow!r}")
    return frozenset(allow)


def _check_limit(name: str, value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not 0 < value < float("inf"):
        raise ParameterError(name, f"expected a finite positive number, got {value!r}")
    return value


def _untrusted(source: str) -> UrdfError:
    return UrdfError(
        f"{source}: not expanded: a xacro is a program (its ${{...}} expressions run Python, $(env ...) and "
        f"<xacro:include> read this machine), so pinlin expands only xacro files you trust: "
        f"load_urdf(path, trust_xacro=True), expand_xacro(path, trust=True), trust_xacro = true in a scene "
        f"file's [robot] table, or the CLI's --trust-xacro; or expand it yourself and load the URDF",
        source,
    )


def _run_sandbox(request: dict, search_path: list[Path], source: str) -> str:
    try:
        done = subprocess.run(
            [sys.executable, "-I", "-B", str(_SANDBOX)], input=json.dumps(request), capture_output=True, text=True,
            timeout=request["time_limit"], check=False,
        )
    except subprocess.TimeoutExpired:
        raise UrdfError(f"{source}: xacro did not finish within the time limit of {request['time_limit']} s "
                        f"(a xacro is a program: this one runs too long)", source) from None
    try:
        answer = json.loads(done.stdout)
    except json.JSONDecodeError:
        raise UrdfError(f"{source}: xacro's process ended without an answer (exit status {done.returncode}, "
                        f"time limit {request['time_limit']} s, memory limit {request['memory_limit']} bytes): "
                        f"{' '.join(done.stderr.split())[-300:]}", source) from None
    if "missing_package" in answer:
        find_package(answer["missing_package"], search_path)  # raises, naming the directories searched
    if "error" in answer:
        said = " ".join(answer["error"].split())
        raise UrdfError(f"{source}: {said}" if answer["explained"] else
                        f"{source}: xacro could not expand the file ({said})", source)
    said = " ".join(done.stderr.split())
    if said:
        warnings.warn(f"{source}: xacro says: {said}", UserWarning, stacklevel=3)
    return answer["urdf"]


def expand_xacro(
    path: str | os.PathLike,
    xacro_args: Mapping[str, object] | None = None,
    package_dirs: Sequence[str | os.PathLike] | None = None,
    *,
    trust: bool = False,
    allow: Collection[str] = (),
    time_limit: float = XACRO_TIME_LIMIT,
    memory_limit: int = XACRO_MEMORY_LIMIT,
) -> str:
    """The URDF text of a xacro file, expanded only if ``trust`` (module docstring).

    Parameters
    ----------
    path : path-like
        The ``.xacro`` file.
    xacro_args : mapping, optional
        Values of its ``<xacro:arg>`` (``$(arg name)``), converted with ``str``.
    package_dirs : sequence of path-like, optional
        Directories searched first for ``$(find pkg)`` and ``package://pkg/...``.
    trust : bool
        Expand the file: a xacro is a program, so only a file you trust (default: refused).
    allow : collection of str
        What a trusted file may also do, from :data:`XACRO_PERMISSIONS` (``"env"``,
        ``"optenv"``, ``"load_yaml"``, ``"python"``, ``"include"``); default nothing.
    time_limit : float
        Seconds the expansion may take [s].
    memory_limit : int
        Bytes of address space the expanding process may use.

    Raises
    ------
    UrdfError
        Not trusted; a construct ``allow`` does not list; over a limit; a file, package
        or argument xacro needs is missing, or xacro fails (its message).
    MissingDependencyError
        The ``xacro`` package is not installed (``pip install 'pinlin[xacro]'``).
    ParameterError
        ``xacro_args`` is not a mapping, ``allow`` names something else, a limit is not positive.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "tagged.urdf.xacro"
    >>> _ = path.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
    ...                     '<xacro:arg name="tag" default="a"/><link name="link_$(arg tag)"/></robot>')
    >>> 'name="link_b"' in pinlin.expand_xacro(path, {"tag": "b"}, trust=True)
    True
    >>> try:
    ...     pinlin.expand_xacro(path)
    ... except pinlin.UrdfError as exc:
    ...     print("a xacro is a program" in str(exc))
    True
    """
    source = os.fspath(path)
    if xacro_args is not None and not isinstance(xacro_args, Mapping):
        raise ParameterError("xacro_args", f"expected a mapping of argument names to values, got {xacro_args!r}")
    allow = _check_allow(allow)
    time_limit = _check_limit("time_limit", time_limit)
    memory_limit = int(_check_limit("memory_limit", memory_limit))
    search_path = package_search_path(package_dirs)
    if not Path(source).is_file():
        raise UrdfError(f"xacro file not found: {source}", source)
    if trust is not True:
        if not isinstance(trust, bool):
            raise ParameterError("trust", f"expected True or False, got {trust!r}")
        raise _untrusted(source)
    packages = _package_directories(search_path)
    request = {
        "xacro_location": _xacro_location(),
        "path": os.path.abspath(source),
        "mappings": {str(k): str(v) for k, v in (xacro_args or {}).items()},
        "packages": {name: str(d) for name, d in packages.items()},
        # the file's folder, the search path and every package on it (a package may be a link to elsewhere)
        "roots": [str(Path(source).resolve().parent), *(str(d) for d in [*search_path, *packages.values()])],
        "allow": sorted(allow),
        "time_limit": time_limit,
        "memory_limit": memory_limit,
    }
    return _run_sandbox(request, search_path, source)
