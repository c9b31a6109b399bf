"""Bad MJCF files, each with the MjcfError it must give; run as a script it loads each in turn.

Used in process by test_mjcf_validation.py and, as ``python mjcf_bad_cases.py DIR``, in fresh processes:
Pinocchio 4.1 read these with uninitialized memory, so a wrong answer could differ from run to run.
"""

from __future__ import annotations

import sys
from pathlib import Path

MODEL = """<mujoco model="two_links">
  <compiler angle="radian"/>
  <worldbody>
    <body name="a" pos="0 0 0">
      <joint name="j1" type="hinge" axis="0 1 0"/>
      <inertial pos="0 0 -0.5" mass="1" diaginertia="0.1 0.1 0.01"/>
      <site name="sa" pos="0 0 -1"/>
      <body name="b" pos="0 0 -1">
        <joint name="j2" type="hinge" axis="0 1 0"/>
        <inertial pos="0 0 -0.5" mass="1" diaginertia="0.1 0.1 0.01"/>
        <site name="sb" pos="0 0 -1"/>
        <body name="c" pos="0 0 -1"><inertial pos="0 0 0" mass="0.1" diaginertia="0.001 0.001 0.001"/></body>
      </body>
    </body>
  </worldbody>
  <equality>{equality}</equality>
</mujoco>
"""

REPEATED = MODEL.replace(
    '<body name="c" pos="0 0 -1"><inertial pos="0 0 0" mass="0.1" diaginertia="0.001 0.001 0.001"/></body>',
    '<body name="c" pos="0 0 -1"><inertial pos="0 0 0" mass="0.1" diaginertia="0.001 0.001 0.001"/></body>' * 2,
)

#: (label, file text, regex of the MjcfError, or None when the file is valid)
CASES = [
    ("connect on missing sites", MODEL.format(equality='<connect site1="nope" site2="sb"/>'),
     r"<connect> attribute site1='nope': no such site; sites: \['sa', 'sb'\]"),
    ("connect on a missing second site", MODEL.format(equality='<connect site1="sa" site2="nope"/>'),
     r"<connect> attribute site2='nope': no such site"),
    ("anchor nan", MODEL.format(equality='<connect body1="b" anchor="nan 0 0"/>'),
     r"<connect> attribute anchor='nan 0 0': expected 3 finite number\(s\)"),
    ("anchor letters", MODEL.format(equality='<connect body1="b" anchor="a b c"/>'),
     r"<connect> attribute anchor='a b c': expected 3 finite number\(s\)"),
    ("anchor of two numbers", MODEL.format(equality='<connect body1="b" anchor="0 0"/>'),
     r"<connect> attribute anchor='0 0': expected 3 finite number\(s\)"),
    ("weld relpose of three numbers", MODEL.format(equality='<weld name="w" body1="b" relpose="0 0 1"/>'),
     r"<weld name='w'> attribute relpose='0 0 1': expected 7 finite number\(s\)"),
    ("repeated body subtree", REPEATED.format(equality=""), r"two <body> elements are named 'c'.*repeated"),
    ("body constrained to itself", MODEL.format(equality='<connect body1="b" body2="b" anchor="0 0 0"/>'),
     r"<connect> constrains body 'b' to itself"),
    ("sites on one body", MODEL.format(equality='<connect site1="sb" site2="sb"/>'),
     r"<connect> constrains body 'b' to itself"),
    ("bodies that move together", MODEL.format(equality='<connect name="glued" body1="b" body2="c" anchor="0 0 -1"/>'),
     r"<connect name='glued'> joins bodies 'b' and 'c', which move together"),
    ("unknown body", MODEL.format(equality='<connect body1="zz" anchor="0 0 0"/>'),
     r"<connect> attribute body1='zz': no such body; bodies: \['a', 'b', 'c'\]"),
    ("unknown body2", MODEL.format(equality='<weld body1="b" body2="zz"/>'), r"<weld> attribute body2='zz': no such body"),
    ("connect without anchor", MODEL.format(equality='<connect body1="b"/>'), r"<connect> has no attribute anchor"),
    ("bodies and sites", MODEL.format(equality='<connect body1="b" site1="sa" site2="sb" anchor="0 0 0"/>'),
     r"gives both bodies and sites"),
    ("body pos of two numbers", MODEL.format(equality="").replace('name="b" pos="0 0 -1"', 'name="b" pos="0 -1"'),
     r"<body name='b'> attribute pos='0 -1': expected 3 finite number\(s\)"),
    ("infinite mass", MODEL.format(equality="").replace('mass="1"', 'mass="inf"', 1),
     r"<inertial> attribute mass='inf': expected 1 finite number\(s\)"),
    ("negative inertia", MODEL.format(equality="").replace('diaginertia="0.1 0.1 0.01"', 'diaginertia="0.1 -0.1 0.01"', 1),
     r"<inertial> attribute diaginertia='0.1 -0.1 0.01': expected numbers >= 0"),
    ("zero axis", MODEL.format(equality="").replace('axis="0 1 0"', 'axis="0 0 0"', 1),
     r"<joint name='j1'> attribute axis='0 0 0': expected a non-zero vector"),
    ("zero quaternion", MODEL.format(equality="").replace('name="b" pos="0 0 -1"', 'name="b" pos="0 0 -1" quat="0 0 0 0"'),
     r"<body name='b'> attribute quat='0 0 0 0': expected a non-zero vector"),
    ("unknown joint type", MODEL.format(equality="").replace('type="hinge"', 'type="hing"', 1),
     r"<joint name='j1'> attribute type='hing': expected one of \['hinge', 'slide', 'ball', 'free'\]"),
    ("joint range of one number", MODEL.format(equality="").replace('axis="0 1 0"/>', 'axis="0 1 0" range="1"/>', 1),
     r"<joint name='j1'> attribute range='1': expected 2 finite number\(s\)"),
    ("unknown default class", MODEL.format(equality="").replace('name="j1" type="hinge"', 'name="j1" class="nope" type="hinge"'),
     r"<joint name='j1'> attribute class='nope': no such default class; classes: \['main'\]"),
    ("unknown child class", MODEL.format(equality="").replace('<body name="a" pos="0 0 0">', '<body name="a" childclass="x">'),
     r"<body name='a'> attribute childclass='x': no such default class"),
    ("unknown geom type", MODEL.format(equality="").replace('<site name="sa"', '<geom type="blob" size="1"/><site name="sa"'),
     r"<geom> attribute type='blob': expected one of \['plane'"),
    ("parallel xyaxes", MODEL.format(equality="").replace('name="b" pos="0 0 -1"', 'name="b" pos="0 0 -1" xyaxes="1 0 0 2 0 0"'),
     r"<body name='b'> attribute xyaxes='1 0 0 2 0 0': expected a non-zero axis \(axisangle\) or two non-parallel"),
    ("zero axisangle", MODEL.format(equality="").replace('name="b" pos="0 0 -1"', 'name="b" pos="0 0 -1" axisangle="0 0 0 1"'),
     r"attribute axisangle='0 0 0 1'"),
    ("impossible inertia", MODEL.format(equality="").replace('diaginertia="0.1 0.1 0.01"', 'diaginertia="0.1 0.1 0.5"', 1),
     r"the inertia tensor of link 'a' breaks the triangle inequality .*moved by joint 'j1'.*inertia='repair'"),
    ("site connect (valid)", MODEL.format(equality='<connect name="loop" site1="sb" site2="sa"/>'), None),
    ("weld to the world (valid)", MODEL.format(equality='<weld name="w" body1="b" relpose="0 0 1 1 0 0 0"/>'), None),
]


def load(text: str, directory: Path, k: int):
    import pinlin

    path = directory / f"case{k}.xml"
    path.write_text(text)
    return pinlin.load_mjcf(path)


def main(directory: str) -> None:
    import pinlin

    for k, (label, text, _) in enumerate(CASES):
        try:
            robot = load(text, Path(directory), k)
            scene = pinlin.Scene(robot)
            print(f"{label}: loaded, constraints {[type(c).__name__ for c in scene.constraints]}")
        except pinlin.MjcfError as exc:
            print(f"{label}: MjcfError: {str(exc).split(': ', 1)[1]}")


if __name__ == "__main__":
    main(sys.argv[1])
