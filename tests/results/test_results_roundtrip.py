"""Results a user can keep: every result type reads back from its ``to_dict()``.

For each class in ``pinlin.results.result_types()`` the builder of ``tests/test_results.py`` makes
one real instance; ``to_dict`` -> ``json.dumps(allow_nan=False)`` -> ``json.loads`` ->
``pinlin.load`` (and ``Result.from_dict``, and a JSON file) gives a result of the same class whose
every kept field equals the original: arrays bitwise with their dtype and shape, tuples as tuples,
complex and non-finite numbers as they were, nested results and value types field by field.
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

import pinlin
import test_results as builders
from pinlin.results import Result, ResultArray, decode, encode, result_types

#: Fields ``to_dict`` leaves out (back-references to inputs); they read back as None.
NOT_KEPT = {"Modes": ("system", "matrices", "deferred", "verdict")}


def _canonical(a: np.ndarray) -> np.ndarray:
    """``a`` with every NaN made the positive quiet NaN (JSON's "nan" keeps no sign or payload) and -0 made 0
    (no exported number is -0); all else is bitwise."""
    if a.dtype.kind == "c":
        out = np.empty_like(a)
        out.real, out.imag = _canonical(a.real.copy()), _canonical(a.imag.copy())
        return out
    return np.where(np.isnan(a), np.abs(np.nan), a + 0.0) if a.dtype.kind == "f" else a


def assert_same(a, b, path="result"):
    """``b`` equals ``a`` in type and value; arrays bitwise (dtype, shape and bytes)."""
    if isinstance(a, np.ndarray):
        assert isinstance(b, np.ndarray), path
        a, b = np.asarray(a).view(np.ndarray), np.asarray(b).view(np.ndarray)
        assert (a.dtype, a.shape) == (b.dtype, b.shape), (path, a.dtype, a.shape, b.dtype, b.shape)
        if a.dtype.kind == "O":
            for i, (x, y) in enumerate(zip(a.ravel(), b.ravel())):
                assert_same(x, y, f"{path}[{i}]")
        else:
            assert _canonical(a).tobytes() == _canonical(b).tobytes(), path
        return
    if isinstance(a, Result):
        assert type(b) is type(a), (path, type(a), type(b))
        for name in a._field_names():
            assert_same(getattr(a, name), getattr(b, name), f"{path}.{name}")
        return
    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        assert type(b) is type(a), path
        for f in dataclasses.fields(a):
            assert_same(getattr(a, f.name), getattr(b, f.name), f"{path}.{f.name}")
        return
    if isinstance(a, BaseException):
        assert type(b) is type(a) and str(b) == str(a), path
        return
    if isinstance(a, dict) or hasattr(a, "keys"):
        assert hasattr(b, "keys") and list(a.keys()) == list(b.keys()), path
        for k in a:
            assert_same(a[k], b[k], f"{path}[{k!r}]")
        return
    if isinstance(a, (list, tuple)):
        assert type(b) is type(a) and len(b) == len(a), (path, type(a), type(b))
        for i, (x, y) in enumerate(zip(a, b)):
            assert_same(x, y, f"{path}[{i}]")
        return
    if isinstance(a, (float, complex, np.floating, np.complexfloating)) and a != a:  # NaN somewhere
        assert type(b) is type(a), path
        assert_same(np.array([a]), np.array([b]), path)  # bitwise but for the NaN's sign and payload
        return
    assert type(b) is type(a) and b == a, (path, a, b)
    if isinstance(a, str):
        assert getattr(a, "reason", None) == getattr(b, "reason", None), path  # a Method keeps its reason


def round_trip(result):
    text = json.dumps(result.to_dict(), allow_nan=False)
    return pinlin.load(json.loads(text))


@pytest.mark.parametrize("cls", result_types(), ids=lambda c: c.__name__)
def test_every_result_type_reads_back(cls):
    original = builders.build(cls.__name__)
    loaded = round_trip(original)
    assert type(loaded) is cls
    assert_same(original, loaded)
    assert loaded.to_dict() == original.to_dict()  # derived and lazily formed figures too
    assert_same(original.error, loaded.error, "error")
    assert_same(original.elapsed, loaded.elapsed, "elapsed")
    if isinstance(original, ResultArray):
        assert_same(np.asarray(original), np.asarray(loaded), "values")
        assert not loaded.flags.writeable


def test_modes_keep_their_lazy_figures_and_say_what_is_not_kept():
    modes = builders.build("Modes")
    loaded = round_trip(modes)
    for name in ("condition", "constants", "participation", "structure", "stability", "notes"):
        assert name in vars(loaded), name  # read back, not recomputed (there is no system to recompute from)
        assert_same(getattr(modes, name), getattr(loaded, name), name)
    assert loaded.stability.margin == modes.stability.margin
    assert loaded.method == modes.method and loaded.method.reason == modes.method.reason
    for name in NOT_KEPT["Modes"]:
        assert getattr(loaded, name) is None
    assert loaded.dominant() == modes.dominant()
    assert loaded.table() == modes.table()


def test_load_reads_a_json_file(tmp_path):
    sys = builders.build("LinearizedSystem")
    path = tmp_path / "sys.json"
    path.write_text(json.dumps(sys.to_dict(), allow_nan=False), encoding="utf-8")
    loaded = pinlin.load(path)
    assert_same(sys, loaded)
    assert_same(sys.K, loaded.K, "K")
    assert pinlin.load(str(path)).dof_names == sys.dof_names


def test_from_dict_on_a_class_checks_the_type():
    data = json.loads(json.dumps(builders.build("Modes").to_dict(), allow_nan=False))
    assert isinstance(pinlin.Modes.from_dict(data), pinlin.Modes)
    assert isinstance(Result.from_dict(data), pinlin.Modes)
    with pytest.raises(pinlin.ParameterError, match="holds a Modes, not a LinearizedSystem"):
        pinlin.LinearizedSystem.from_dict(data)


@pytest.mark.parametrize(
    "value",
    [np.float64(-0.0), np.array(3.5), np.array([1, 2], dtype=np.int32), np.zeros((0, 3)), np.array([[np.nan, np.inf]]),
     np.array([1 + 2j, -np.inf * 1j]), (1, "a", (2.0, float("nan"))), [complex(1, -0.0)], {"k": (np.inf,)},
     np.array([True, False]), np.zeros((2, 0), dtype=complex)],
    ids=repr,
)
def test_encoding_is_reversible(value):
    data, spec = encode(value)
    data, spec = json.loads(json.dumps([data, spec], allow_nan=False))
    assert_same(value, decode(data, spec))


def test_bad_input_to_load(tmp_path):
    with pytest.raises(pinlin.ParameterError, match="expected a path to a JSON file or a dict, got int"):
        pinlin.load(3)
    with pytest.raises(pinlin.ParameterError, match="cannot read a result from"):
        pinlin.load(tmp_path / "missing.json")
    bad = tmp_path / "bad.json"
    bad.write_text("{not json", encoding="utf-8")
    with pytest.raises(pinlin.ParameterError, match="cannot read a result from"):
        pinlin.load(bad)
    with pytest.raises(pinlin.ParameterError, match="with a 'type' key"):
        pinlin.load({"method": "x"})
    with pytest.raises(pinlin.ParameterError, match="unknown result type 'Nothing'; known: .*Modes"):
        pinlin.load({"type": "Nothing"})


def test_a_loaded_definiteness_refuses_to_decide_again():
    modes = builders.build("Modes")
    loaded = round_trip(modes)
    original = modes.structure.definiteness_M
    kept = loaded.structure.definiteness_M
    assert_same(original, kept)
    assert original.at(0.1).uncertainty == 0.1  # the original keeps its eigenvalues
    with pytest.raises(pinlin.ParameterError, match=r"read back from its data \(pinlin.load\)"):
        kept.at(0.1)


def test_a_report_section_reads_back(tmp_path, capsys):
    from pinlin.cli import main

    assert main(["analyze", "--example", "ur5", "--json", str(tmp_path / "r.json")]) == 0
    capsys.readouterr()
    report = json.loads((tmp_path / "r.json").read_text())
    modes = pinlin.load(report["modes"])  # the report-only keys (table) are ignored
    assert isinstance(modes, pinlin.Modes) and modes.dof_names[0] == "shoulder_pan_joint"
    assert modes.eigenvalues.real.tolist() == report["modes"]["eigenvalues"]["re"]
    assert modes.eigenvalues.imag.tolist() == report["modes"]["eigenvalues"]["im"]
    system = pinlin.load(report["linearization"])
    assert isinstance(system, pinlin.LinearizedSystem) and system.M.shape == (6, 6)
    assert pinlin.load(report["stability"]).kind == report["stability"]["kind"]


def test_a_user_class_of_the_same_name_does_not_shadow_pinlins():
    class Modes(Result):  # noqa: F811 -- a user's result class that happens to share the name
        _dict_fields = ()
        method, error, elapsed = "user", 0.0, 0.0

    data = json.loads(json.dumps(builders.build("Modes").to_dict(), allow_nan=False))
    assert type(pinlin.load(data)) is pinlin.Modes
