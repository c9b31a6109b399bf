"""The package's shape: no import cycles, short modules, short functions, documented packages.

Walks ``src/pinlin`` with :mod:`ast` (nothing is imported):

- the graph of imports between pinlin modules, relative and absolute, must have no
  cycle; every import counts, also those inside functions and under
  ``if TYPE_CHECKING:`` (an import for a type annotation or deferred to a call is
  still a dependency of the design);
- between packages, the imports run down the data flow (:data:`LAYERS`): no package
  imports one of a later layer, and packages of one layer form no cycle;
- no module imports a ``_private`` name of another module;
- no module is longer than :data:`MAX_MODULE_LINES`;
- functions longer than :data:`FUNCTION_LINES_TARGET` lines of code are
  reported, and those longer than :data:`MAX_FUNCTION_LINES` fail;
- every package ``__init__.py`` opens with a docstring (the map of its modules).
"""

from __future__ import annotations

import ast
import io
import re
import tokenize
from pathlib import Path

#: Root of the package sources.
SRC = Path(__file__).resolve().parents[1] / "src" / "pinlin"
#: The packages (and top-level modules) of pinlin in the order of the data flow: a package may import
#: those of its own layer (without a cycle) and of earlier layers, never of a later one.
LAYERS = (
    ("errors", "version"),
    ("results", "extras"),
    ("numerics",),
    ("model",),
    ("linearization",),
    ("spectral", "adjoint", "frf", "response", "periodic", "nonlinear"),
    ("boundaries",),
    ("studies",),
    ("interop", "report", "cli", "plot", "testing"),
    ("pinlin",),
)

#: Longest module allowed [lines] (the house rule: "no module over 400 lines").
MAX_MODULE_LINES = 400
#: Function length [lines of code] above which a function is reported (the house rule: "about 80").
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


def _all_imports(tree: ast.Module):
    """Every import statement of a module: at module level, in functions, under ``if TYPE_CHECKING:``."""
    for node in ast.walk(tree):
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            yield node


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
    """Module of the package at ``root`` -> the modules of that package it imports (anywhere in it).

    ``from .pkg import name`` counts as an import of ``pkg.name`` when that is
    a module, and of the package ``pkg`` otherwise.  Importing ``a.b.c`` also
    imports the packages ``a`` and ``a.b`` (their ``__init__`` runs first).
    """
    modules = _modules(root)
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        targets: set[str] = set()
        for node in _all_imports(tree):
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


def package_of(module: str) -> str:
    """The first-level package (or top-level module) a pinlin module belongs to; "pinlin" for the root."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "pinlin"


def package_graph(graph: dict[str, set[str]]) -> dict[str, set[str]]:
    """First-level package -> the first-level packages its modules import."""
    out: dict[str, set[str]] = {}
    for module, targets in graph.items():
        mine = package_of(module)
        out.setdefault(mine, set()).update(package_of(t) for t in targets if package_of(t) != mine)
    return out


def layer_violations(packages: dict[str, set[str]], layers=LAYERS) -> list[str]:
    """Arrows from a package to one of a later layer, and packages not placed in any layer."""
    rank = {name: k for k, layer in enumerate(layers) for name in layer}
    out = [f"{p} is in no layer" for p in sorted(packages) if p not in rank]
    for p, targets in sorted(packages.items()):
        for t in sorted(targets):
            if p in rank and t in rank and rank[t] > rank[p]:
                out.append(f"{p} -> {t} runs up the data flow")
    return out


def private_imports(root: Path = SRC) -> list[str]:
    """``module imports _name from other`` for every import of a private name from another pinlin module."""
    modules = _modules(root)
    out = []
    for name, path in modules.items():
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for node in _all_imports(tree):
            if isinstance(node, ast.ImportFrom):
                base = _resolve(name, path.name == "__init__.py", node)
                if base.split(".")[0] != root.name or base == name:
                    continue
                for alias in node.names:
                    if alias.name.startswith("_") and not alias.name.startswith("__"):
                        out.append(f"{name} imports {alias.name} from {base}")
            else:
                for alias in node.names:
                    if any(part.startswith("_") and not part.startswith("__") for part in alias.name.split(".")):
                        out.append(f"{name} imports the private module {alias.name}")
    return out


def test_packages_follow_the_data_flow():
    packages = package_graph(import_graph())
    assert {"model", "linearization", "spectral", "numerics"} <= set(packages)
    assert not layer_violations(packages), "\n".join(layer_violations(packages))
    cycle = find_cycle(packages)
    assert cycle is None, "import cycle between pinlin packages: " + " -> ".join(cycle)


def test_no_private_name_imported_from_another_module():
    found = private_imports()
    assert not found, "\n".join(found)


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


def test_layer_and_private_checkers_on_hand_made_cases(tmp_path):
    layers = (("low",), ("mid", "side"), ("high",))
    assert layer_violations({"low": set(), "mid": {"low", "side"}, "high": {"mid"}}, layers) == []
    assert layer_violations({"low": {"mid"}, "mid": set(), "odd": set()}, layers) == [
        "odd is in no layer", "low -> mid runs up the data flow"
    ]
    assert package_of("pinlin.model.scene") == "model" and package_of("pinlin") == "pinlin"
    graph = {"pinlin.a.x": {"pinlin.b.y"}, "pinlin.b.y": {"pinlin.a.z"}, "pinlin.a.z": set()}
    assert package_graph(graph) == {"a": {"b"}, "b": {"a"}}
    pkg = tmp_path / "pinlin"
    pkg.mkdir()
    (pkg / "__init__.py").write_text('"""doc"""\n')
    (pkg / "a.py").write_text("def _helper():\n    pass\n")
    (pkg / "b.py").write_text("def f():\n    from .a import _helper\n")
    assert private_imports(pkg) == ["pinlin.b imports _helper from pinlin.a"]


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
        for n in _all_imports(tree)
        if isinstance(n, ast.ImportFrom)
    ]
    # the type checker's and the deferred import count too: they are dependencies of the design
    assert sorted(found) == [
        "__future__", "pinlin.other", "pinlin.pkg", "pinlin.pkg.hidden", "pinlin.pkg.late", "typing"
    ]
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
        "pkg.sub.tool": {"pkg.core", "pkg.late"},
        "pkg.core": {"pkg.late"},
        "pkg.late": {"pkg.sub", "pkg.sub.tool"},
    }
    # the function-level and TYPE_CHECKING imports count: each closes a cycle through pkg.late
    cycle = find_cycle(graph)
    assert cycle is not None and cycle[0] == cycle[-1] and "pkg.late" in cycle
    (pkg / "core.py").write_text("import numpy\n", encoding="utf-8")
    (pkg / "sub/tool.py").write_text("from ..core import base\n", encoding="utf-8")
    assert find_cycle(import_graph(pkg)) is None


def test_code_lines_skip_docstring_comments_and_blanks():
    source = 'def f(x):\n    """Doc.\n\n    More.\n    """\n    # a comment\n\n    y = (x +\n         1)\n    return y\n'
    node = ast.parse(source).body[0]
    assert code_lines(node, token_lines(source)) == 4  # def, the two lines of y = ..., return


def test_no_file_refers_to_the_internal_planning_document():
    """The mathematics is in the shipped theory pages (docs/theory); no code, doc or help text points users to
    the project's internal planning document, which users do not have."""
    word = re.compile(r"\b" + "S" + "PEC" + r"\b")
    root = SRC.parents[1]
    tracked = [root / p for p in ("src", "tests", "docs", "notebooks", "benchmarks", "README.md", "CHANGELOG.md")]
    offenders = []
    for base in tracked:
        for path in ([base] if base.is_file() else base.rglob("*")):
            if path.suffix in {".py", ".md", ".rst", ".ipynb", ".toml", ".txt", ".json"} and path.is_file():
                for k, line in enumerate(path.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
                    if word.search(line):
                        offenders.append(f"{path.relative_to(root)}:{k}")
    assert not offenders, "references to the internal planning document: " + ", ".join(offenders[:20])
