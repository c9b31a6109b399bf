"""What the command line says when it is asked something it cannot do: a misspelt option, an unknown
example, a Campbell diagram of a periodic scene, a scene named by its bundled name; and the example table
indexed by name."""

from __future__ import annotations

import pytest

import pinlin
from pinlin.cli import EXIT_INPUT, EXIT_OK, main
from pinlin.model.examples import ExampleInfo, ExampleTable


def run(args, capsys):
    code = main([str(a) for a in args])
    out = capsys.readouterr()
    return code, out.out, out.err


def test_a_misspelt_option_shows_the_subcommand_usage_and_the_close_option(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["analyze", "--stifness", "3"])
    err = capsys.readouterr().err
    assert exit_.value.code == EXIT_INPUT
    assert err.startswith("usage: pinlin analyze [-h]") and "--stiffness STIFFNESS" in err
    assert err.rstrip().endswith("pinlin analyze: error: unrecognized arguments: --stifness "
                                 "(did you mean --stiffness?)")


@pytest.mark.parametrize(("argv", "usage", "close"), [
    (["sweep", "--valeus", "0:1:3"], "usage: pinlin sweep", "--values"),
    (["campbell", "--sped=0:1:3"], "usage: pinlin campbell", "--speeds"),
    (["campbell", "--no-such-thing"], "usage: pinlin campbell", None),
])
def test_every_subcommand_refuses_unknown_options_with_its_own_usage(argv, usage, close, capsys):
    with pytest.raises(SystemExit) as exit_:
        main(argv)
    err = capsys.readouterr().err
    assert exit_.value.code == EXIT_INPUT and err.startswith(usage)
    assert ("did you mean" in err) == (close is not None) and (close is None or f"did you mean {close}?" in err)


def test_an_unknown_example_is_refused_naming_the_option(capsys):
    code, out, err = run(["analyze", "--example", "nosuchbot"], capsys)
    assert code == EXIT_INPUT and out == ""
    assert err.startswith("pinlin: error: --example: unknown example 'nosuchbot'; known examples: ['a1', ")
    assert "name:" not in err
    code, _, err = run(["analyze", "--example", "ur55"], capsys)
    assert code == EXIT_INPUT and err.startswith("pinlin: error: --example: unknown example 'ur55'; did you mean 'ur5'")


def test_the_unknown_example_message_starts_with_what_is_wrong():
    with pytest.raises(pinlin.ExampleNotFoundError, match=r"^unknown example 'nosuchbot'; known examples") as info:
        pinlin.load_example("nosuchbot")
    assert info.value.parameter == "name" and info.value.name == "nosuchbot"


def test_a_campbell_diagram_of_a_periodic_scene_points_to_the_floquet_analysis(capsys):
    kapitza = pinlin.data_path("scenes/kapitza.toml")
    code, out, err = run(["campbell", kapitza], capsys)
    assert code == EXIT_INPUT and out == ""
    assert "[campbell.joint] the scene prescribes no constant speed: 'pivot' follows a periodic motion" in err
    assert f"analyse it with 'pinlin analyze {kapitza}' (the Floquet multipliers)" in err
    assert "pinlin.floquet_campbell" in err and "prescribes no joint" not in err
    code, out, err = run(["campbell", kapitza, "--joint", "pivot", "--speeds", "0:1:3"], capsys)
    assert code == EXIT_INPUT and "--joint: the scene prescribes no constant speed: 'pivot'" in err
    code, out, err = run(["analyze", kapitza], capsys)  # where the message points: it works
    assert code == EXIT_OK and "Floquet" in out, err


def test_a_scene_without_any_prescribed_joint_still_says_so(capsys):
    code, _, err = run(["campbell", "double_pendulum.toml", "--speeds", "0:1:3"], capsys)
    assert code == EXIT_INPUT and "the scene prescribes no joint: add a [prescribed] table" in err


@pytest.mark.parametrize("name", ["turntable.toml", "turntable"])
def test_a_bundled_scene_is_read_by_name_from_any_folder(name, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    code, out, err = run(["campbell", name, "--joint", "table", "--speeds", "0:3:4"], capsys)
    assert code == EXIT_OK, err
    assert "Campbell" in out and list(tmp_path.iterdir()) == []
    spec = pinlin.report.scenes.load_scene_argument(name, None)
    assert spec.path == str(pinlin.data_path("scenes/turntable.toml"))


def test_a_file_of_the_working_folder_comes_before_the_bundled_scene_of_its_name(tmp_path, monkeypatch, capsys):
    own = tmp_path / "double_pendulum.toml"
    own.write_text(pinlin.data_path("scenes/double_pendulum.toml").read_text().replace(
        '"../urdf/double_pendulum.urdf"', '"double_pendulum.urdf"'))
    monkeypatch.chdir(tmp_path)
    assert pinlin.report.scenes.scene_path("double_pendulum.toml") == own.relative_to(tmp_path)
    code, out, err = run(["analyze", "double_pendulum.toml"], capsys)
    assert code == EXIT_OK, err


def test_a_missing_scene_lists_the_bundled_names(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    code, out, err = run(["analyze", "turntabel.toml"], capsys)
    assert code == EXIT_INPUT and out == ""
    assert err.startswith("pinlin: error: turntabel.toml: scene file not found (bundled scenes, read by name "
                          "from any folder: double_pendulum.toml, ")
    assert "turntable.toml" in err
    code, _, err = run(["analyze", "scenes/turntable.toml"], capsys)  # a path is a path: not looked up
    assert code == EXIT_INPUT and "scenes/turntable.toml: scene file not found" in err


def test_the_example_table_is_indexed_by_name():
    table = pinlin.examples()
    panda = table["panda"]
    assert isinstance(panda, ExampleInfo)
    assert (panda.name, panda.nv, panda.free_flyer) == ("panda", 9, False)
    assert "panda" in table and "nosuchbot" not in table and panda in table
    assert table[0] is table[table[0].name] and isinstance(table[:3], ExampleTable) and len(table[:3]) == 3
    with pytest.raises(pinlin.ExampleNotFoundError, match=r"unknown example 'pandaa'; did you mean 'panda'"):
        table["pandaa"]
    robot = pinlin.load_example(panda.name)
    assert robot.model.nv == panda.nv
