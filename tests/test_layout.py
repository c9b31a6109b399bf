"""The package's shape (issue 10): no import cycles, short modules, short functions, documented packages.

Walks ``src/pinlin`` with :mod:`ast` (nothing is imported):

- the graph of module-level imports between pinlin modules, relative and
  absolute, must have no cycle (imports inside functions and under
  ``if TYPE_CHECKING:`` are deferred and do not count);
- no module is longer than :data:`MAX_MODULE_LINES`;
- functions longer than :data:`FUNCTION_LINES_TARGET` lines of code are
  reported, and those longer than :data:`MAX_FUNCTION_LINES` fail;
- every package ``__init__.py`` opens with a docstring (the map of its modules).
"""

from __future__ import annotations

import ast
import io
import tokenize
from pathlib import Path

#: Root of the package sources.
SRC = Path(__file__).resolve().parents[1] / "src" / "pinlin"
#: Longest module allowed [lines] (issue 10: "no module over 400 lines").
MAX_MODULE_LINES = 400
#: Function length [lines of code] above which a function is reported (issue 10: "about 80").
FUNCTION_LINES_TARGET = 80
#: Function length [lines of code] that fails: "about 80" leaves room, 1.5 times that does not.
MAX_FUNCTION_LINES = 120


def _modules(root: Path = SRC) -> dict[str, Path]:
    """Dotted module name -> file, for every module of the package at ``root``."""
    out = {}
    for path in sorted(root.rglob("*.py")):
        parts = list(path.relative_to(root.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = path
    return out


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _module_level_imports(tree: ast.Module):
    """Import statements executed when the module is imported (not in functions, not for type checkers)."""
    stack = list(tree.body)
    while stack:
        node = stack.pop()
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            yield node
        elif isinstance(node, ast.If):
            if not _is_type_checking(node.test):
                stack.extend(node.body)
            stack.extend(node.orelse)
        elif isinstance(node, ast.Try):
            for block in (node.body, node.orelse, node.finalbody, *(h.body for h in node.handlers)):
                stack.extend(block)
        elif isinstance(node, (ast.With, ast.ClassDef)):
            stack.extend(node.body)


def _resolve(module: str, is_package: bool, node: ast.ImportFrom) -> str:
    """The absolute module name an ``ImportFrom`` refers to."""
    if not node.level:
        return node.module or ""
    base = module.split(".")
    if not is_package:
        base = base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def import_graph(root: Path = SRC) -> dict[str, set[str]]:
    """Module of the package at ``root`` -> the modules of that package it imports at module level.

    ``from .pkg import name`` counts as an import of ``pkg.name`` when that is
    a module, and of the package ``pkg`` otherwise.  Importing ``a.b.c`` also
    imports the packages ``a`` and ``a.b`` (their ``__init__`` runs first).
    """
    modules = _modules(root)
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        targets: set[str] = set()
        for node in _module_level_imports(tree):
            if isinstance(node, ast.Import):
                targets.update(alias.name for alias in node.names)
            else:
                base = _resolve(name, path.name == "__init__.py", node)
                for alias in node.names:
                    sub = f"{base}.{alias.name}"
                    targets.add(sub if sub in modules else base)
        edges = set()
        for target in targets:
            parts = target.split(".")
            for k in range(1, len(parts) + 1):
                prefix = ".".join(parts[:k])
                if prefix in modules and prefix != name and not name.startswith(prefix + "."):
                    edges.add(prefix)
        graph[name] = edges
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle of the graph as [a, b, ..., a], or None (iterative depth-first search)."""
    state: dict[str, int] = {}  # 1: on the current path, 2: finished
    for root in sorted(graph):
        if state.get(root):
            continue
        path = [root]
        iters = [iter(sorted(graph[root]))]
        state[root] = 1
        while iters:
            nxt = next(iters[-1], None)
            if nxt is None:
                state[path.pop()] = 2
                iters.pop()
            elif state.get(nxt) == 1:
                return path[path.index(nxt) :] + [nxt]
            elif not state.get(nxt):
                state[nxt] = 1
                path.append(nxt)
                iters.append(iter(sorted(graph.get(nxt, ()))))
    return None


def token_lines(source: str) -> set[int]:
    """Numbers of the lines of a module that hold a token other than a comment (blank lines hold none)."""
    skip = {
        tokenize.COMMENT,
        tokenize.NL,
        tokenize.NEWLINE,
        tokenize.INDENT,
        tokenize.DEDENT,
        tokenize.ENDMARKER,
    }
    out: set[int] = set()
    for tok in tokenize.generate_tokens(io.StringIO(source).readline):
        if tok.type not in skip:
            out.update(range(tok.start[0], tok.end[0] + 1))
    return out


def code_lines(node: ast.AST, lines_with_code: set[int]) -> int:
    """Lines of code of a function: its lines with a token, less its docstring."""
    span = set(range(node.lineno, node.end_lineno + 1))
    body = node.body
    if (
        body
        and isinstance(body[0], ast.Expr)
        and isinstance(body[0].value, ast.Constant)
        and isinstance(body[0].value.value, str)
    ):
        span -= set(range(body[0].lineno, body[0].end_lineno + 1))
    return len(span & lines_with_code)


def long_functions(threshold: int) -> list[tuple[int, str]]:
    """(lines of code, "module:qualified name") of every function longer than ``threshold``."""
    out = []
    for name, path in _modules().items():
        source = path.read_text(encoding="utf-8")
        tree = ast.parse(source, filename=str(path))
        lines_with_code = token_lines(source)
        stack = [(node, "") for node in tree.body]
        while stack:
            node, prefix = stack.pop()
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                qual = f"{prefix}{node.name}"
                stack.extend((child, qual + ".") for child in node.body)
                if not isinstance(node, ast.ClassDef):
                    n = code_lines(node, lines_with_code)
                    if n > threshold:
                        out.append((n, f"{name}:{qual}"))
    return sorted(out, reverse=True)


# ----------------------------------------------------------------------------- the checks


def test_no_import_cycle():
    graph = import_graph()
    assert "pinlin" in graph and len(graph) > 20  # the walk found the package
    cycle = find_cycle(graph)
    assert cycle is None, "import cycle between pinlin modules: " + " -> ".join(cycle)


def test_no_module_over_limit():
    sizes = {name: len(path.read_text(encoding="utf-8").splitlines()) for name, path in _modules().items()}
    too_long = sorted((n, name) for name, n in sizes.items() if n > MAX_MODULE_LINES)
    assert not too_long, f"modules over {MAX_MODULE_LINES} lines: " + ", ".join(
        f"{m} ({n})" for n, m in too_long
    )


def test_function_lengths(capsys):
    over_target = long_functions(FUNCTION_LINES_TARGET)
    with capsys.disabled():
        if over_target:
            print(
                f"\nfunctions over {FUNCTION_LINES_TARGET} lines of code (target: about {FUNCTION_LINES_TARGET}):"
            )
            for n, where in over_target:
                print(f"  {n:4d}  {where}")
    too_long = [(n, w) for n, w in over_target if n > MAX_FUNCTION_LINES]
    assert not too_long, f"functions over {MAX_FUNCTION_LINES} lines of code: " + ", ".join(
        f"{w} ({n})" for n, w in too_long
    )


def test_every_package_has_a_module_map():
    packages = [path for path in SRC.rglob("__init__.py")]
    assert len(packages) >= 8
    missing = [
        str(p.relative_to(SRC.parent))
        for p in packages
        if not ast.get_docstring(ast.parse(p.read_text(encoding="utf-8")))
    ]
    assert not missing, f"package __init__.py without a docstring (the map of its modules): {missing}"


# ----------------------------------------------------------------------------- the checkers themselves


def test_cycle_finder_on_hand_made_graphs():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": set()}) is None
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b", "d"}, "b": set(), "d": {"d2"}, "d2": {"d"}}) == ["d", "d2", "d"]


def test_import_resolution_and_deferred_imports(tmp_path):
    source = (
        "from __future__ import annotations\n"
        "from typing import TYPE_CHECKING\n"
        "from . import sibling\n"
        "from ..other import thing\n"
        "if TYPE_CHECKING:\n"
        "    from .hidden import X\n"
        "def f():\n"
        "    from .late import y\n"
    )
    tree = ast.parse(source)
    found = [
        _resolve("pinlin.pkg.mod", False, n)
        for n in _module_level_imports(tree)
        if isinstance(n, ast.ImportFrom)
    ]
    assert sorted(found) == ["__future__", "pinlin.other", "pinlin.pkg", "typing"]
    # from a package's __init__, "." is the package itself
    node = ast.parse("from .sub import a").body[0]
    assert _resolve("pinlin.pkg", True, node) == "pinlin.pkg.sub"


def test_import_graph_of_a_small_package(tmp_path):
    pkg = tmp_path / "pkg"
    (pkg / "sub").mkdir(parents=True)
    files = {
        "__init__.py": '"""Map."""\nfrom .sub import tool\n',
        "sub/__init__.py": '"""Map."""\nfrom .tool import run\n',
        "sub/tool.py": "from typing import TYPE_CHECKING\nfrom ..core import base\nif TYPE_CHECKING:\n    from ..late import L\n",
        "core.py": "import numpy\ndef base():\n    from .late import x\n",
        "late.py": "from .sub import tool\n",
    }
    for name, text in files.items():
        (pkg / name).write_text(text, encoding="utf-8")
    graph = import_graph(pkg)
    assert graph == {
        "pkg": {"pkg.sub", "pkg.sub.tool"},
        "pkg.sub": {"pkg.sub.tool"},
        "pkg.sub.tool": {"pkg.core"},
        "pkg.core": set(),
        "pkg.late": {"pkg.sub", "pkg.sub.tool"},
    }
    assert find_cycle(graph) is None  # the function-level and TYPE_CHECKING imports close no cycle
    (pkg / "core.py").write_text("from .late import x\n", encoding="utf-8")
    cycle = find_cycle(import_graph(pkg))
    assert cycle is not None and cycle[0] == cycle[-1] and "pkg.core" in cycle and "pkg.late" in cycle


def test_code_lines_skip_docstring_comments_and_blanks():
    source = 'def f(x):\n    """Doc.\n\n    More.\n    """\n    # a comment\n\n    y = (x +\n         1)\n    return y\n'
    node = ast.parse(source).body[0]
    assert code_lines(node, token_lines(source)) == 4  # def, the two lines of y = ..., return
