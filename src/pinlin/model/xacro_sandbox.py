"""The child process that expands one xacro file (run by :func:`pinlin.model.xacro.expand_xacro`).

A xacro is a program: its ``${...}`` expressions are Python, its ``$(env ...)``
reads the environment, ``load_yaml`` and ``<xacro:include>`` read files.  This
script is run as a file (``python -I -B xacro_sandbox.py``), imports only the standard
library and xacro, and reads one JSON request on stdin::

    {"path": ..., "mappings": {...}, "packages": {name: folder}, "roots": [...],
     "allow": [...], "memory_limit": bytes, "time_limit": seconds, "xacro_location": folder}

It lowers its own limits first (address space, CPU time, size of any file written:
zero), then refuses what ``allow`` does not list (:data:`PERMISSIONS`), expands, and
writes one JSON answer on stdout: ``{"urdf": text}``, ``{"missing_package": name}`` or
``{"error": message, "explained": bool}`` (explained: a refusal, said as is).  Any
failure inside xacro (``ExpatError``, ``RecursionError``, xacro's own) becomes such an
answer, so the parent raises one pinlin error.
"""

from __future__ import annotations

import json
import os
import re
import resource
import sys

__all__ = ["PERMISSIONS"]

#: What a trusted xacro may be allowed beyond plain expansion, and what each permits.
PERMISSIONS = {
    "env": "$(env NAME): read an environment variable",
    "optenv": "$(optenv NAME): read an environment variable",
    "load_yaml": "xacro.load_yaml(file): read a YAML file",
    "python": "Python escapes ('python.' builtins, '__' attributes) in ${...} and $(eval ...)",
    "include": "<xacro:include> of files outside the package search path and the file's own folder",
}

_PYTHON_ESCAPE = re.compile(r"__|\bpython\s*\.")


class _Refused(Exception):
    """A construct the caller did not allow (its message is the answer)."""


def _refuse(what: str, permission: str) -> _Refused:
    return _Refused(f"{what} refused: a xacro is a program, and even a trusted one may not do this unless "
                   f"allowed; pass allow={{{permission!r}}} to expand_xacro (xacro_allow= to load_urdf) to permit it")


def _limit(memory_limit: int, time_limit: float) -> None:
    resource.setrlimit(resource.RLIMIT_AS, (memory_limit, memory_limit))
    cpu = int(time_limit) + 1
    resource.setrlimit(resource.RLIMIT_CPU, (cpu, cpu + 1))
    resource.setrlimit(resource.RLIMIT_FSIZE, (0, 0))  # the expansion writes no file


def _check_text(text: str, allow: set[str]) -> None:
    if "python" not in allow and _PYTHON_ESCAPE.search(text):
        raise _refuse(f"the expression {text.strip()[:80]!r} (a Python escape)", "python")
    if "load_yaml" not in allow and "load_yaml" in text:
        raise _refuse(f"the expression {text.strip()[:80]!r} (load_yaml reads files)", "load_yaml")


def _inside(path: str, roots: list[str]) -> bool:
    real = os.path.realpath(path)
    return any(os.path.commonpath([real, root]) == root for root in roots)


class _MissingPackage(Exception):
    """A package not in the request's ``packages`` (the parent names the directories searched)."""


def _install(xacro, substitution_args, request: dict) -> None:
    """Point xacro's package lookup at the search path and put the refusals in place."""
    allow, packages = set(request["allow"]), request["packages"]
    roots = [os.path.realpath(r) for r in request["roots"]]

    def find(pkg):
        if pkg not in packages:
            raise _MissingPackage(pkg)
        return packages[pkg]

    def resolve(spec):
        if spec.startswith("package://"):
            package, _, rest = spec[len("package://"):].partition("/")
            spec = os.path.join(find(package), rest)
        return abs_spec(spec)

    abs_spec, get_include_files, safe_eval, sub_eval = (
        xacro.abs_filename_spec, xacro.get_include_files, xacro.safe_eval, substitution_args._eval)
    substitution_args._eval_find = find
    substitution_args._eval_dict["find"] = find
    xacro.abs_filename_spec = resolve
    for name in ("env", "optenv"):
        if name not in allow:
            def refused(variable, default="", _name=name):
                raise _refuse(f"$({_name} {variable})", _name)
            setattr(substitution_args, f"_eval_{name}", refused)
            substitution_args._eval_dict[name] = refused
    if "load_yaml" not in allow:
        xacro._global_symbols.pop("load_yaml", None)
        xacro._global_symbols["xacro"].pop("load_yaml", None)
    if "python" not in allow:
        xacro._global_symbols.pop("python", None)
        # $(eval ...) evaluates with the interpreter's builtins (open, __import__): give it the few xacro names
        builtins = dict(substitution_args._eval_dict["__builtins__"])
        substitution_args.eval = lambda text, _globals, names: eval(text, {"__builtins__": builtins}, names)

    def checked_eval(expr, globals, locals=None):
        _check_text(expr, allow)
        return safe_eval(expr, globals, locals)

    def checked_sub_eval(s, context):
        _check_text(s, allow)
        return sub_eval(s, context)

    def checked_includes(filename_spec, symbols):
        for filename in get_include_files(filename_spec, symbols):
            if "include" not in allow and not _inside(filename, roots):
                raise _refuse(f"<xacro:include filename={filename!r}> (outside {roots})", "include")
            yield filename

    xacro.safe_eval, substitution_args._eval, xacro.get_include_files = checked_eval, checked_sub_eval, checked_includes


def _cause(exc: BaseException, kinds: tuple[type, ...]) -> BaseException | None:
    """The first exception of ``kinds`` behind ``exc``, which xacro may have wrapped (its ``exc``, the chain)."""
    seen = set()
    while exc is not None and id(exc) not in seen:
        if isinstance(exc, kinds):
            return exc
        seen.add(id(exc))
        exc = getattr(exc, "exc", None) or exc.__cause__ or exc.__context__
    return None


def _main() -> None:
    request = json.loads(sys.stdin.read())
    _limit(request["memory_limit"], request["time_limit"])
    sys.path.insert(0, request["xacro_location"])  # the xacro the caller would import, not a file beside this one
    try:
        import xacro
        from xacro import substitution_args

        _install(xacro, substitution_args, request)
        answer = {"urdf": xacro.process_file(request["path"], mappings=request["mappings"]).toxml()}
    except Exception as exc:  # the process boundary: every failure becomes one answer (module docstring)
        explained, missing = _cause(exc, (_Refused,)), _cause(exc, (_MissingPackage,))
        if missing is not None:
            answer = {"missing_package": missing.args[0]}
        elif explained is not None:
            answer = {"error": str(explained), "explained": True}
        elif _cause(exc, (MemoryError,)) is not None:
            answer = {"error": f"ran out of memory (limit {request['memory_limit']} bytes)", "explained": False}
        else:
            answer = {"error": f"{type(exc).__name__}: {exc}", "explained": False}
    sys.stdout.write(json.dumps(answer))


if __name__ == "__main__":
    _main()
