"""A xacro is a program: expanded only when trusted, in a limited child process, with its escapes refused."""

import time

import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.model.xacro import XACRO_PERMISSIONS

ROBOT = """<?xml version="1.0"?>
<robot name="two_links" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="m" value="{mass}"/>
  {extra}
  <link name="base"/>
  <link name="bar"><inertial><mass value="${{m}}"/>
    <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="bar"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""

# Ran ``touch`` through load_urdf before xacro needed trust (its process had imported subprocess).
POPEN = ("[c for c in python.vars(python.type)['__subclasses__'](python.type.mro(python.int)[1]) "
         "if python.repr(c) == &quot;&lt;class 'subprocess.Popen'&gt;&quot;][0](['touch', '{target}']).wait() + 1")


def _xacro(tmp_path, mass="2.5", extra="", name="robot.urdf.xacro"):
    path = tmp_path / name
    path.write_text(ROBOT.format(mass=mass, extra=extra))
    return path


def test_a_benign_xacro_loads_when_trusted(tmp_path):
    robot = pinlin.load_urdf(_xacro(tmp_path), trust_xacro=True)
    assert robot.joint_names == ("hinge",)
    assert_allclose(robot.model.inertias[1].mass, 2.5, rtol=1e-15)
    assert_allclose(robot.model.inertias[1].inertia, [[1, 0, 0], [0, 1, 0], [0, 0, 1]], rtol=1e-15)


def test_an_untrusted_xacro_is_refused_with_how_to_allow_it(tmp_path):
    path = _xacro(tmp_path)
    with pytest.raises(pinlin.UrdfError, match=r"robot.urdf.xacro: not expanded: a xacro is a program .*"
                                               r"load_urdf\(path, trust_xacro=True\).*--trust-xacro"):
        pinlin.load_urdf(path)
    with pytest.raises(pinlin.UrdfError, match="a xacro is a program"):
        pinlin.expand_xacro(path)
    with pytest.raises(pinlin.ParameterError, match="trust: expected True or False, got 'yes'"):
        pinlin.expand_xacro(path, trust="yes")


def test_a_python_escape_writes_no_file(tmp_path):
    import subprocess  # noqa: F401  (imported, as in any process that loaded pinlin: the escape's target)

    target = tmp_path / "written"
    path = _xacro(tmp_path, mass="${" + POPEN.format(target=target) + "}")
    with pytest.raises(pinlin.UrdfError, match="a xacro is a program"):
        pinlin.load_urdf(path)
    assert not target.exists()
    with pytest.raises(pinlin.UrdfError, match=r"\(a Python escape\) refused: .*allow=\{'python'\}"):
        pinlin.load_urdf(path, trust_xacro=True)
    assert not target.exists()


@pytest.mark.parametrize(
    ("mass", "permission", "match"),
    [
        ("${xacro.load_yaml('/etc/passwd')}", "load_yaml", r"load_yaml reads files\) refused"),
        ("${load_yaml('/etc/passwd')}", "load_yaml", r"load_yaml reads files\) refused"),
        ("$(optenv HOME)", "optenv", r"\$\(optenv HOME\) refused: .*allow=\{'optenv'\}"),
        ("$(env HOME)", "env", r"\$\(env HOME\) refused: .*allow=\{'env'\}"),
        ("$(eval open('/etc/passwd').read())", "python", r"could not expand"),
        ("$(eval open)", "python", r"could not expand the file .*name 'open' is not defined"),
        ("${python.open}", "python", r"a Python escape\) refused"),
    ],
)
def test_reading_the_machine_is_refused_even_when_trusted(tmp_path, mass, permission, match):
    path = _xacro(tmp_path, mass=mass)
    with pytest.raises(pinlin.UrdfError, match=match) as caught:
        pinlin.load_urdf(path, trust_xacro=True)
    assert "root:" not in str(caught.value)  # nothing of /etc/passwd reaches the message
    assert permission in XACRO_PERMISSIONS


def test_eval_keeps_its_arithmetic(tmp_path):
    robot = pinlin.load_urdf(_xacro(tmp_path, mass="$(eval 3.0 / 2)"), trust_xacro=True)
    assert_allclose(robot.model.inertias[1].mass, 1.5, rtol=1e-15)


def test_an_allowed_environment_read_expands(tmp_path, monkeypatch):
    monkeypatch.setenv("PINLIN_TEST_MASS", "4.0")
    path = _xacro(tmp_path, mass="$(optenv PINLIN_TEST_MASS 1.0)")
    robot = pinlin.load_urdf(path, trust_xacro=True, xacro_allow={"optenv"})
    assert_allclose(robot.model.inertias[1].mass, 4.0, rtol=1e-15)


def test_a_runaway_expression_ends_at_the_time_limit(tmp_path):
    path = _xacro(tmp_path, mass="${9**9**9}")
    start = time.perf_counter()
    with pytest.raises(pinlin.UrdfError, match=r"did not finish within the time limit of 2.0 s"):
        pinlin.expand_xacro(path, trust=True, time_limit=2.0)
    assert time.perf_counter() - start < 10.0


def test_a_runaway_allocation_ends_at_the_memory_limit(tmp_path):
    path = _xacro(tmp_path, mass="${len('x' * 10**10)}")
    with pytest.raises(pinlin.UrdfError, match=r"ran out of memory \(limit 1073741824 bytes\)"):
        pinlin.expand_xacro(path, trust=True, memory_limit=2**30)


def test_an_include_outside_the_allowed_folders_is_refused(tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "part.xacro").write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>')
    inside = tmp_path / "robot"
    inside.mkdir()
    (inside / "part.xacro").write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>')
    for spec in ("/etc/passwd", str(outside / "part.xacro"), "../outside/part.xacro"):
        path = _xacro(inside, extra=f'<xacro:include filename="{spec}"/>')
        with pytest.raises(pinlin.UrdfError, match=r"<xacro:include filename=.*refused: .*allow=\{'include'\}"):
            pinlin.load_urdf(path, trust_xacro=True)
    path = _xacro(inside, extra='<xacro:include filename="part.xacro"/>')  # its own folder
    assert pinlin.load_urdf(path, trust_xacro=True).nv == 1
    path = _xacro(inside, extra=f'<xacro:include filename="{outside / "part.xacro"}"/>')
    assert pinlin.load_urdf(path, package_dirs=[outside], trust_xacro=True).nv == 1  # a package folder
    assert pinlin.load_urdf(path, trust_xacro=True, xacro_allow={"include"}).nv == 1


def test_malformed_and_deep_xacros_are_pinlin_errors(tmp_path):
    broken = tmp_path / "broken.urdf.xacro"
    broken.write_text("<robot><link name='a'></robot>")
    with pytest.raises(pinlin.UrdfError, match=r"xacro could not expand the file \(.*mismatched tag"):
        pinlin.load_urdf(broken, trust_xacro=True)
    deep = tmp_path / "deep.urdf.xacro"
    deep.write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="f" params="">'
                    '<xacro:f/></xacro:macro><xacro:f/></robot>')
    with pytest.raises(pinlin.UrdfError, match=r"xacro could not expand the file"):
        pinlin.load_urdf(deep, trust_xacro=True)


def test_bad_limits_and_permissions(tmp_path):
    path = _xacro(tmp_path)
    with pytest.raises(pinlin.ParameterError, match=r"allow: expected a set of \['env', 'include'"):
        pinlin.expand_xacro(path, trust=True, allow={"network"})
    with pytest.raises(pinlin.ParameterError, match="allow: expected a set"):
        pinlin.expand_xacro(path, trust=True, allow="env")
    with pytest.raises(pinlin.ParameterError, match="time_limit: expected a finite positive number"):
        pinlin.expand_xacro(path, trust=True, time_limit=float("nan"))
    with pytest.raises(pinlin.ParameterError, match="memory_limit: expected a finite positive number"):
        pinlin.expand_xacro(path, trust=True, memory_limit=-1)
