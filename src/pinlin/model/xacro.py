"""URDFs written in xacro, and ``package://`` / ``$(find pkg)`` paths.

:func:`expand_xacro` runs the ``xacro`` package (PyPI, the optional extra
``pinlin[xacro]``) on a file with the given arguments and returns the URDF text.
Packages are found through one documented search path (:func:`package_search_path`):

1. the ``package_dirs`` given, in order;
2. the entries of ``ROS_PACKAGE_PATH`` (ROS 1), where set;
3. ``<prefix>/share`` for each entry of ``AMENT_PREFIX_PATH`` (ROS 2), where set.

Package ``pkg`` is the first ``<dir>/pkg`` that is a directory, or a search-path
entry ``<dir>`` whose own name is ``pkg``.  xacro resolves ``$(find pkg)`` only
through ROS 2's ament index and does not read ``package://`` in ``<xacro:include>``;
while it expands, pinlin gives it this search path for both (xacro keeps its state in
module globals, so expansions are serialized by a lock).  Meshes are never opened:
a ``package://`` URI left in a ``<mesh>`` stays as it is.
"""

from __future__ import annotations

import contextlib
import os
import threading
from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path

from ..errors import MissingDependencyError, ParameterError, UrdfError

__all__ = ["expand_xacro", "package_search_path", "find_package", "is_xacro"]

_LOCK = threading.Lock()


def is_xacro(path: str | os.PathLike) -> bool:
    """True for a ``.xacro`` file (``robot.urdf.xacro``, ``robot.xacro``)."""
    return os.fspath(path).endswith(".xacro")


def _import_xacro():
    try:
        import xacro
        from xacro import substitution_args
    except ImportError as exc:
        raise MissingDependencyError(
            "expanding a .xacro file needs the xacro package: pip install 'pinlin[xacro]'"
        ) from exc
    return xacro, substitution_args


def package_search_path(package_dirs: Sequence[str | os.PathLike] | None = None) -> list[Path]:
    """The directories searched for ROS packages, in order (module docstring).

    Raises
    ------
    ParameterError
        ``package_dirs`` is a single string or not a sequence of paths.
    """
    if package_dirs is None:
        package_dirs = []
    if isinstance(package_dirs, (str, os.PathLike)) or not isinstance(package_dirs, Sequence):
        raise ParameterError("package_dirs", f"expected a list of directories, got {package_dirs!r}")
    out = [Path(os.fspath(d)) for d in package_dirs]
    out += [Path(p) for p in os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep) if p]
    out += [Path(p) / "share" for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
    return out


def find_package(name: str, search_path: Sequence[Path]) -> Path:
    """The directory of package ``name`` on ``search_path``.

    Raises
    ------
    UrdfError
        No such package; the message lists the directories searched.
    """
    for d in search_path:
        if (d / name).is_dir():
            return d / name
        if d.name == name and d.is_dir():
            return d
    shown = [str(d) for d in search_path] or "nothing: pass package_dirs=[...] or set ROS_PACKAGE_PATH"
    raise UrdfError(f"package {name!r} not found; searched {shown}", name)


def _resolve_uri(spec: str, search_path: Sequence[Path]) -> str:
    if not spec.startswith("package://"):
        return spec
    package, _, rest = spec[len("package://"):].partition("/")
    return str(find_package(package, search_path) / rest)


@contextlib.contextmanager
def _search_path_for_xacro(xacro, substitution_args, search_path) -> Iterator[None]:
    eval_find, abs_spec = substitution_args._eval_find, xacro.abs_filename_spec
    substitution_args._eval_find = lambda pkg: str(find_package(pkg, search_path))
    xacro.abs_filename_spec = lambda spec: abs_spec(_resolve_uri(spec, search_path))
    try:
        yield
    finally:
        substitution_args._eval_find, xacro.abs_filename_spec = eval_find, abs_spec


def expand_xacro(
    path: str | os.PathLike,
    xacro_args: Mapping[str, object] | None = None,
    package_dirs: Sequence[str | os.PathLike] | None = None,
) -> str:
    """The URDF text of a xacro file.

    Parameters
    ----------
    path : path-like
        The ``.xacro`` file.
    xacro_args : mapping, optional
        Values of its ``<xacro:arg>`` (``$(arg name)``), converted with ``str``.
    package_dirs : sequence of path-like, optional
        Directories searched first for ``$(find pkg)`` and ``package://pkg/...``.

    Raises
    ------
    MissingDependencyError
        The ``xacro`` package is not installed (``pip install 'pinlin[xacro]'``).
    UrdfError
        A file, package or argument xacro needs is missing, or xacro fails; the
        message is xacro's.
    ParameterError
        ``xacro_args`` is not a mapping of names to values.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "tagged.urdf.xacro"
    >>> _ = path.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
    ...                     '<xacro:arg name="tag" default="a"/><link name="link_$(arg tag)"/></robot>')
    >>> 'name="link_b"' in pinlin.expand_xacro(path, {"tag": "b"})
    True
    """
    xacro, substitution_args = _import_xacro()
    source = os.fspath(path)
    if xacro_args is not None and not isinstance(xacro_args, Mapping):
        raise ParameterError("xacro_args", f"expected a mapping of argument names to values, got {xacro_args!r}")
    mappings = {str(k): str(v) for k, v in (xacro_args or {}).items()}
    search_path = package_search_path(package_dirs)
    if not Path(source).is_file():
        raise UrdfError(f"xacro file not found: {source}", source)
    with _LOCK, _search_path_for_xacro(xacro, substitution_args, search_path):
        try:
            doc = xacro.process_file(source, mappings=mappings)
        except UrdfError as exc:
            raise UrdfError(f"{source}: {exc}", source) from None
        except (xacro.XacroException, substitution_args.SubstitutionException, OSError, ValueError, KeyError,
                NameError, TypeError) as exc:
            raise UrdfError(f"{source}: xacro could not expand the file ({type(exc).__name__}: {exc})", source) from None
    return doc.toxml()
