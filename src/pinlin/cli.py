"""The ``pinlin`` command line: ``pinlin analyze [SCENE.toml]``.

This module is the argument parsing and the exit codes; what ``analyze``
computes, its JSON document and schema, the text and the figure are the
report (:mod:`pinlin.report`).  The report: the scene, the equilibrium and its
residual, the nonzero matrices and their structure, the modes with their
errors (eta, kappa, error bound), the stability verdict with its reason, and
timings; ``--json`` writes it all in machine-readable form, ``--plot`` draws
the eigenvalue map and frequency responses.

Exit codes: 0 success, 2 bad input (scene file, URDF, parameters), 3 a
computation that failed (no convergence, lost accuracy).
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence

import numpy as np

from . import __version__
from .errors import (
    InputError,
    MissingDependencyError,
    ModelTooLargeError,
    ParameterError,
    PinlinError,
)
from .model.elements import JointDamper, JointSpring
from .model.loading import EXAMPLES, load_example
from .model.scene import Scene
from .model.scenefile import SCENE_FORMAT, SceneSpec, default_scene_path, load_scene
from .report import REPORT_SCHEMA, REPORT_VERSION, analyze, render_text, write_plot

__all__ = [
    "main",
    "example_spec",
    "EXIT_OK",
    "EXIT_INPUT",
    "EXIT_COMPUTATION",
    # the report, importable from here as in pinlin 0.1
    "analyze",
    "render_text",
    "write_plot",
    "REPORT_SCHEMA",
    "REPORT_VERSION",
]

EXIT_OK, EXIT_INPUT, EXIT_COMPUTATION = 0, 2, 3

#: Default joint stiffness of ``--example`` [N m/rad]: stiff enough that gravity only softens a 6-DOF arm a little.
DEFAULT_EXAMPLE_STIFFNESS = 1e3


def example_spec(name: str, stiffness: float, damping: float = 0.0) -> SceneSpec:
    """An example-robot-data robot with elastic joints, springs unstressed at its reference pose.

    A robot with a free-flyer joint is linearized with balancing forces (it
    has no equilibrium of its own); a fixed-base one at its equilibrium near
    the reference pose.

    Parameters
    ----------
    name : str
        One of :data:`pinlin.EXAMPLES`.
    stiffness : float
        Stiffness of every joint spring [N m/rad or N/m], > 0.
    damping : float
        Damping of every joint [N m s/rad or N s/m], >= 0 (0: no dampers).

    Raises
    ------
    ParameterError
        A stiffness that is not positive, a damping that is negative (named by
        their command-line options).
    InputError
        An unknown example name (see :func:`pinlin.load_example`).
    """
    if not (np.isfinite(stiffness) and stiffness > 0):
        raise ParameterError("--stiffness", f"must be a positive number, got {stiffness}")
    if not (np.isfinite(damping) and damping >= 0):
        raise ParameterError("--damping", f"must be a non-negative number, got {damping}")
    robot = load_example(name)
    refs = robot.reference_configurations
    q0 = next(iter(refs.values())).copy() if refs else robot.neutral()
    elements = []
    for jname in robot.joint_names:
        j = robot.joint(jname)
        if j.kind == "JointModelFreeFlyer":
            continue
        rest = q0[j.q_slice]
        elements.append(JointSpring(jname, stiffness, rest=rest if j.nq > 1 else float(rest[0])))
        if damping:
            elements.append(JointDamper(jname, damping))
    scene = Scene(robot, elements)
    floating = any(robot.joint(n).kind == "JointModelFreeFlyer" for n in robot.joint_names)
    return SceneSpec(scene, scene.check_configuration(q0), not floating, floating, f"example:{name}")


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="pinlin", description="Linearized equations of motion of multibody systems from a URDF."
    )
    parser.add_argument("--version", action="version", version=f"pinlin {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    a = sub.add_parser(
        "analyze",
        help="equilibrium, linearized matrices and their analysis for a scene",
        description=(
            "Find the equilibrium of a scene, linearize it into M, D, G, S, N and report them with "
            "their errors and timings.  Without a scene file, the bundled default scene (the paper's "
            "double pendulum with follower load) is analysed.\n\nExit codes: 0 success, 2 bad input, "
            "3 failed computation."
        ),
        epilog="Scene file format (TOML):\n" + SCENE_FORMAT,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    a.add_argument("scene", nargs="?", help="scene file (TOML); default: the bundled double pendulum")
    a.add_argument(
        "--example",
        metavar="NAME",
        help=f"analyse an example-robot-data model with elastic joints instead ({', '.join(sorted(EXAMPLES))})",
    )
    a.add_argument("--stiffness", type=float, default=DEFAULT_EXAMPLE_STIFFNESS,
                   help="joint stiffness for --example [N m/rad]")
    a.add_argument("--damping", type=float, default=0.0, help="joint damping for --example [N m s/rad]")
    a.add_argument("--json", metavar="PATH",
                   help=f"also write the machine-readable report (schema version {REPORT_VERSION}) to PATH")
    a.add_argument("--plot", metavar="PATH",
                   help="also draw the eigenvalue map and frequency response to PATH (needs matplotlib)")
    a.add_argument("--precision", type=int, default=6, help="significant digits in the text report")
    return parser


def _run(args) -> tuple[dict, int]:
    """The report of the parsed arguments, or the exit code of the failure (printed to stderr)."""
    try:
        if args.precision < 1:
            raise ParameterError("--precision", f"must be at least 1 significant digit, got {args.precision}")
        if args.example and args.scene:
            raise ParameterError("--example", "give either a scene file or --example, not both")
        if args.example:
            spec = example_spec(args.example, args.stiffness, args.damping)
        else:
            spec = load_scene(args.scene or default_scene_path())
        report, sys_, modes = analyze(spec)
        if args.plot:
            write_plot(args.plot, sys_, modes)
    except (InputError, ModelTooLargeError, MissingDependencyError) as exc:
        print(f"pinlin: error: {exc}", file=sys.stderr)
        return {}, EXIT_INPUT
    except PinlinError as exc:  # ComputationError, and any other pinlin error: a failed computation
        print(f"pinlin: computation failed: {exc}", file=sys.stderr)
        return {}, EXIT_COMPUTATION
    return report, EXIT_OK


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``pinlin`` console script.

    Parameters
    ----------
    argv : sequence of str, optional
        The arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit code: :data:`EXIT_OK`, :data:`EXIT_INPUT` (bad input, also
        an unwritable ``--json`` file) or :data:`EXIT_COMPUTATION`.  Errors are
        printed to stderr as one line, never as a traceback.

    Raises
    ------
    SystemExit
        From argparse: after ``--help`` or ``--version`` (code 0) and for
        unknown options or malformed values (code 2, like :data:`EXIT_INPUT`).
    """
    parser = _parser()
    args = parser.parse_args(argv)
    if args.command != "analyze":
        parser.print_help()
        return EXIT_INPUT
    report, code = _run(args)
    if code != EXIT_OK:
        return code
    print(render_text(report, args.precision))
    if args.json:
        try:
            with open(args.json, "w", encoding="utf-8") as f:
                json.dump(report, f, indent=2, allow_nan=False)  # to_jsonable spells non-finite floats
        except OSError as exc:
            print(f"pinlin: error: cannot write {args.json}: {exc}", file=sys.stderr)
            return EXIT_INPUT
    return EXIT_OK


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
