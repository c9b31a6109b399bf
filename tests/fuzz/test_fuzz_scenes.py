"""Fuzzed TOML scene files through ``load_scene``, the analysis, and ``pinlin analyze``.

Valid scene documents (the ``--help`` example with every table, the bundled
scenes) are mutated: a value replaced by another type or a nasty number, a key
deleted or added, a value nested in arrays up to 600 deep, a table renamed.
``load_scene`` and the analysis must give a PinlinError or a report whose
results have finite error figures, valid against the report's schema; the
command line must exit 0, 2 or 3 with one line on stderr, never raise (a
traceback, exit code 1) or hang.
"""

from __future__ import annotations

import contextlib
import copy
import io
import json
import os
import sys
import tempfile
import textwrap
from pathlib import Path

import jsonschema
from fuzz_strategies import check_result, hard_deadline, outcome, toml_dumps, toml_values
from hypothesis import event, given
from hypothesis import strategies as st

import pinlin
from pinlin.cli import EXIT_COMPUTATION, EXIT_INPUT, EXIT_OK, main
from pinlin.model.scene_file import SCENE_FORMAT, load_scene
from pinlin.report import REPORT_SCHEMA, analyze

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


def _bases() -> dict[str, dict]:
    example = tomllib.loads(textwrap.dedent(SCENE_FORMAT))
    example["sweep"]["values"] = [1.0, 2.0]
    bases = {"help example": example}
    for name in ("double_pendulum", "turntable", "rotating_ring", "four_bar"):
        doc = tomllib.loads(pinlin.data_path(f"scenes/{name}.toml").read_text())
        doc["robot"]["urdf"] = Path(doc["robot"]["urdf"]).name  # a bundled URDF by name, from any directory
        bases[name] = doc
    return bases


BASES = _bases()
#: Keys the mutations add: the format's own (in the wrong places too) and unknown ones.
KEYS = ["urdf", "joint", "frame", "stiffness", "damping", "force", "q", "joints", "equilibrium", "balancing",
        "gravity", "table", "alpha", "parameter", "values", "second", "colour", "type", "target", "locked"]


def _paths(node, prefix=()):
    yield prefix
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _paths(v, (*prefix, k))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _paths(v, (*prefix, i))


@st.composite
def mutated_scenes(draw) -> dict:
    doc = copy.deepcopy(BASES[draw(st.sampled_from(sorted(BASES)))])
    for _ in range(draw(st.sampled_from([1, 1, 2, 3]))):
        paths = [p for p in _paths(doc) if p]
        path = draw(st.sampled_from(paths))
        parent = doc
        for key in path[:-1]:
            parent = parent[key]
        last = path[-1]
        op = draw(st.sampled_from(["replace", "replace", "perturb", "perturb", "delete", "add", "nest", "wrap"]))
        value = parent[last]
        if op == "perturb" and isinstance(value, (int, float)) and not isinstance(value, bool):
            parent[last] = draw(st.floats(-100, 100))  # plausible numbers: the scene often still loads
        elif op == "perturb" and isinstance(value, list) and all(isinstance(x, float) for x in value):
            parent[last] = draw(st.lists(st.floats(-100, 100), min_size=len(value), max_size=len(value)))
        elif op == "replace":
            parent[last] = draw(toml_values())
        elif op == "delete":
            del parent[last]
        elif op == "add" and isinstance(parent[last], dict):
            parent[last][draw(st.sampled_from(KEYS))] = draw(toml_values())
        elif op == "nest":
            for _ in range(draw(st.sampled_from([1, 2, 50, 200]))):  # 500 deep: test_cli_robustness
                parent[last] = [parent[last]]
        elif op == "wrap":
            parent[last] = {"a": parent[last]}
    return doc


@contextlib.contextmanager
def _written(doc: dict):
    """The document as a scene file in a temporary directory, removed afterwards."""
    with tempfile.TemporaryDirectory(prefix="pinlin-fuzz-") as directory:
        path = Path(directory) / "scene.toml"
        path.write_text(toml_dumps(doc), encoding="utf-8")
        yield path


@given(doc=mutated_scenes())
def test_fuzzed_scene_file_loads_and_analyses_or_says_why(doc):
    with _written(doc) as path:  # kept while analysing: errors name the file when it exists
        spec = outcome(lambda: load_scene(path), "load_scene")
        analysed = None if spec is None else outcome(lambda: analyze(spec), "analyze")
    if spec is None:
        event("refused by load_scene")
        return
    if analysed is None:
        event("refused by analyze")
        return
    report, sys_, modes = analysed
    for result in (sys_, modes, modes.stability):
        check_result(result, type(result).__name__)
    jsonschema.validate(json.loads(json.dumps(report, allow_nan=False)), REPORT_SCHEMA)
    event("analysed")


@contextlib.contextmanager
def _inside(directory: str):
    """Run in ``directory`` (relative output names land there), then come back."""
    here = os.getcwd()
    os.chdir(directory)
    try:
        yield
    finally:
        os.chdir(here)


def _cli(args: list[str]) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with hard_deadline(), contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(args)
        except SystemExit as exc:  # argparse: --help (0) or a malformed option (2)
            code = exc.code
    return code, out.getvalue(), err.getvalue()


@given(doc=mutated_scenes())
def test_pinlin_analyze_never_exits_with_a_traceback(doc):
    with _written(doc) as path:
        code, out, err = _cli(["analyze", str(path), "--json", str(path.with_suffix(".json"))])
        report = json.loads(path.with_suffix(".json").read_text()) if code == EXIT_OK else None
    assert code in (EXIT_OK, EXIT_INPUT, EXIT_COMPUTATION), (code, err)
    assert "Traceback" not in err
    if code == EXIT_OK:
        assert err == "" and "Stability:" in out
        jsonschema.validate(report, REPORT_SCHEMA)
    else:
        assert err.startswith("pinlin: ") and err.count("\n") == 1, err
    event(f"exit {code}")


OPTION_VALUES = ["-5", "0", "1", "17", "18", "abc", "", "1e3", "nan", "inf", "-1", "out.xyz", "out.png", "x/y.png",
                 "mode.gif", "mode.mp4", "ur5", "r2d2", "double_pendulum.toml", "--", "0:1:3", "1,2"]


@given(args=st.lists(st.one_of(
    st.sampled_from(["--precision", "--plot", "--json", "--example", "--stiffness", "--damping", "--animate",
                     "--mode", "--parameter", "--values", "--no-boundaries"]),
    st.sampled_from(OPTION_VALUES)), max_size=5), command=st.sampled_from(["analyze", "sweep"]))
def test_command_line_options_never_give_a_traceback(args, command):
    with tempfile.TemporaryDirectory() as directory, _inside(directory):
        code, out, err = _cli([command, *args, "--no-boundaries"] if command == "sweep" else [command, *args])
    assert code in (EXIT_OK, EXIT_INPUT, EXIT_COMPUTATION), (code, err)
    assert "Traceback" not in err
