"""A scene file naming a xacro: refused unless trusted (``--trust-xacro`` or ``trust_xacro = true``)."""

import subprocess  # noqa: F401  (imported, as in the CLI's process: what the escape looks for)

import pytest

import pinlin
from pinlin.cli import EXIT_INPUT, EXIT_OK, main
from pinlin.model.scene_file import load_scene

ROBOT = """<?xml version="1.0"?>
<robot name="bar" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base"/>
  <link name="bar"><inertial><mass value="{mass}"/>
    <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="tip"><inertial><mass value="1"/>
    <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="bar"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="hinge2" type="revolute"><parent link="bar"/><child link="tip"/><origin xyz="1 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""

POPEN = ("${{[c for c in python.vars(python.type)['__subclasses__'](python.type.mro(python.int)[1]) "
         "if python.repr(c) == &quot;&lt;class 'subprocess.Popen'&gt;&quot;][0](['touch', '{target}']).wait() + 1}}")

SCENE = """[robot]
urdf = "robot.urdf.xacro"
{trust}
[[spring]]
joint = "hinge"
stiffness = 4.0

[[spring]]
joint = "hinge2"
stiffness = 1.0
"""


def _scene(tmp_path, mass, trust=""):
    (tmp_path / "robot.urdf.xacro").write_text(ROBOT.format(mass=mass))
    path = tmp_path / "scene.toml"
    path.write_text(SCENE.format(trust=trust))
    return path


def run(args, capsys):
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


def test_an_escaping_xacro_writes_no_file_through_the_cli(tmp_path, capsys):
    target = tmp_path / "written"
    path = _scene(tmp_path, POPEN.format(target=target))
    code, out, err = run(["analyze", str(path)], capsys)
    assert code == EXIT_INPUT and "Traceback" not in err
    assert "not expanded: a xacro is a program" in err and "--trust-xacro" in err
    assert not target.exists()
    code, out, err = run(["analyze", "--trust-xacro", str(path)], capsys)
    assert code == EXIT_INPUT and "(a Python escape) refused" in err
    assert not target.exists()
    with pytest.raises(pinlin.SceneFileError, match=r"\(a Python escape\) refused"):
        load_scene(_scene(tmp_path, POPEN.format(target=target), trust="trust_xacro = true"))
    assert not target.exists()


def test_a_trusted_xacro_scene_is_analysed(tmp_path, capsys):
    path = _scene(tmp_path, "2.0")
    with pytest.raises(pinlin.SceneFileError, match=r"\[robot\] .*not expanded: a xacro is a program"):
        load_scene(path)
    code, out, err = run(["analyze", "--trust-xacro", str(path)], capsys)
    assert code == EXIT_OK, err
    spec = load_scene(path, trust_xacro=True)
    assert spec.scene.robot.joint_names == ("hinge", "hinge2")
    trusted_by_file = load_scene(_scene(tmp_path, "2.0", trust="trust_xacro = true"))
    assert trusted_by_file.scene.robot.nv == 2
    with pytest.raises(pinlin.SceneFileError, match=r"trust_xacro"):
        load_scene(_scene(tmp_path, "2.0", trust='trust_xacro = "yes"'))
    with pytest.raises(pinlin.ParameterError, match="trust_xacro: expected True or False"):
        load_scene(path, trust_xacro=1)
