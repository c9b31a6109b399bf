"""The README's tour runs as printed, from any directory.

Every ```python block of README.md is run, in order, in one fresh interpreter
whose working directory is an empty temporary directory (so a path relative to
the repository would fail).  A block preceded by a line
``<!-- readme-test: skip (why) -->`` is left out: those need an optional extra
(python-control, matplotlib) or an executor; the tour proper has no marker.
"""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
from pathlib import Path

import pinlin

README = Path(__file__).resolve().parents[2] / "README.md"
#: The marker comment that leaves the next code block out, with its reason in parentheses.
SKIP = re.compile(r"<!-- readme-test: skip \((?P<why>[^)]+)\) -->\s*$")
#: Seconds the whole tour may take (it is a few small analyses and a 2 s simulation).
TOUR_TIMEOUT = 120


def python_blocks(text: str) -> list[tuple[str, str | None]]:
    """(code, reason to skip or None) of each ```python block, in order."""
    out = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        if lines[i].strip() == "```python":
            previous = next((line for line in reversed(lines[:i]) if line.strip()), "")
            skip = SKIP.match(previous.strip())
            j = lines.index("```", i + 1)
            out.append(("\n".join(lines[i + 1 : j]), skip["why"] if skip else None))
            i = j
        i += 1
    return out


def test_the_readme_has_a_tour_and_says_why_blocks_are_skipped():
    blocks = python_blocks(README.read_text(encoding="utf-8"))
    run = [code for code, why in blocks if why is None]
    skipped = [why for _, why in blocks if why is not None]
    assert len(run) >= 5 and "pinlin.load_urdf(pinlin.data_path(" in run[0]
    assert all(re.search(r"needs", why) for why in skipped) and len(skipped) <= 2


def test_the_readme_tour_runs_from_an_empty_directory(tmp_path):
    code = "\n\n".join(block for block, why in python_blocks(README.read_text(encoding="utf-8")) if why is None)
    source = str(Path(pinlin.__file__).resolve().parents[1])
    env = {**os.environ, "PYTHONPATH": source + os.pathsep + os.environ.get("PYTHONPATH", ""), "MPLBACKEND": "Agg"}
    done = subprocess.run([sys.executable, "-c", code + "\nprint('tour done')"], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=TOUR_TIMEOUT)
    assert done.returncode == 0, done.stderr[-3000:]
    assert done.stdout.rstrip().endswith("tour done")
    assert list(tmp_path.iterdir()) == []  # the tour writes nothing where it runs


def test_the_readme_counts_the_notebooks():
    notebooks = sorted(README.parent.joinpath("notebooks").glob("*.ipynb"))
    words = {5: "five", 6: "six", 7: "seven", 8: "eight"}
    assert f"`notebooks/` holds {words[len(notebooks)]} worked examples" in README.read_text(encoding="utf-8")


#: Run before the tour: every module of an optional extra (a distribution of
#: pyproject's optional-dependencies that is not a core dependency) fails to
#: import, as after the README's own ``pip install .``.
WITHOUT_EXTRAS = """
import importlib.abc, sys
class _NotInstalled(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.partition(".")[0] in BLOCKED:
            raise ModuleNotFoundError(f"No module named {name!r} (an optional extra)", name=name)
        return None
sys.meta_path.insert(0, _NotInstalled())
"""


def _requirement_name(requirement: str) -> str:
    return re.split(r"[\s<>=!~;\[]", requirement, maxsplit=1)[0].lower().replace("_", "-")


def extra_modules() -> set[str]:
    """Top-level modules of the optional extras' distributions that no core dependency provides."""
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        import tomli as tomllib
    import importlib.metadata

    project = tomllib.loads((README.parent / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    core = {_requirement_name(r) for r in project["dependencies"]}
    extras = {_requirement_name(r) for reqs in project["optional-dependencies"].values() for r in reqs}
    extras -= core | {"pinlin"}
    modules = {m for m, dists in importlib.metadata.packages_distributions().items()
               if any(d.lower().replace("_", "-") in extras for d in dists)}
    core_modules = {m for m, dists in importlib.metadata.packages_distributions().items()
                    if any(d.lower().replace("_", "-") in core for d in dists)}
    return modules - core_modules


def test_the_readme_tour_needs_only_the_readme_install(tmp_path):
    blocked = extra_modules()
    installed = {m for m in ("matplotlib", "pandas", "control") if importlib.util.find_spec(m) is not None}
    assert installed <= blocked  # what the tour must do without
    code = "\n\n".join(block for block, why in python_blocks(README.read_text(encoding="utf-8")) if why is None)
    prelude = f"BLOCKED = {sorted(blocked)!r}\n" + WITHOUT_EXTRAS
    source = str(Path(pinlin.__file__).resolve().parents[1])
    env = {**os.environ, "PYTHONPATH": source + os.pathsep + os.environ.get("PYTHONPATH", "")}
    done = subprocess.run([sys.executable, "-c", prelude + code + "\nprint('tour done')"], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=TOUR_TIMEOUT)
    assert done.returncode == 0, done.stderr[-3000:]
    assert done.stdout.rstrip().endswith("tour done")


def test_a_readme_block_that_needs_an_extra_names_it():
    blocks = python_blocks(README.read_text(encoding="utf-8"))
    for code, why in blocks:
        if why is not None and ("to_pandas" in code or "pinlin.plot" in code or "to_control" in code):
            needed = {"pandas": "to_pandas" in code, "plot": "pinlin.plot" in code, "control": "to_control" in code}
            for extra in (name for name, used in needed.items() if used):
                assert re.search(rf"pinlin\[[a-z,]*\b{extra}\b", why), (extra, why)
    tour = "\n".join(code for code, why in blocks if why is None)
    assert "to_pandas" not in tour and "pinlin.plot" not in tour and "to_control" not in tour
