"""The ``pinlin`` command line: ``pinlin analyze``, ``pinlin sweep`` and ``pinlin campbell`` of a scene file.

This module is the argument parsing and the exit codes; what the commands
compute, their JSON documents and schemas, the text and the figures are the
report (:mod:`pinlin.report`, :mod:`pinlin.report.sweep`).  ``analyze`` reports
the scene, the equilibrium and its residual, the nonzero matrices and their
structure, the modes with their errors (eta, kappa, error bound), the
stability verdict with its reason, and timings; ``sweep`` the same analysis over
the parameter values of the scene's ``[sweep]`` table, with the modes tracked,
the verdict at each value and the exact boundaries where it changes;
``campbell`` the frequencies and damping ratios against the speed of a
prescribed joint, tracked, with the critical speeds found by
:func:`pinlin.critical_parameter` (:mod:`pinlin.report.campbell`).

Options are checked before anything is computed (an unwritable ``--json``, a
``--plot`` format matplotlib cannot write, matplotlib missing, two outputs to
one file, a ``--mode`` beyond the scene's 2n modes); then the text report is
printed and ``--json`` written before the optional figures, so a failure there
loses nothing already computed.  Each file written is named ("wrote a.gif"),
and the last line is the command's wall time split into its parts
(:class:`pinlin.report.command.Stopwatch`).

Exit codes: 0 success, 2 bad input (scene file, URDF, parameters, options,
an output that cannot be written), 3 a computation that failed (no
convergence, lost accuracy).  Errors are one line on stderr, never a traceback.
"""

from __future__ import annotations

import argparse
import dataclasses
import re
import sys
from collections.abc import Sequence
from pathlib import Path


from .errors import (
    InputError,
    MissingDependencyError,
    ModelTooLargeError,
    ParameterError,
    PinlinError,
    SceneFileError,
)
from .model.examples import ExampleNotFoundError
from .model.loading import EXAMPLES
from .model.scene_file import SCENE_FORMAT, SceneSpec, default_scene_path
from .report import REPORT_SCHEMA, REPORT_VERSION, analyze, render_text, write_plot
from .report.campbell import (
    CAMPBELL_FORMAT,
    campbell_document,
    campbell_plan,
    render_campbell_text,
    write_campbell_plot,
)
from .report.command import CommandParser, Stopwatch, plain_text
from .report.outputs import (
    check_animation_path,
    check_figure_path,
    check_json_path,
    write_animation,
    write_json,
)
from .report.scenes import (
    bundled_scenes,
    default_campbell_scene_path,
    default_sweep_scene_path,
    example_spec,
    load_scene_argument,
)
from .report.periodic import analyze_periodic, check_periodic_options, is_periodic, render_periodic_text
from .report.sweep import render_sweep_text, run_sweep, sweep_document, sweep_plan, write_sweep_plot
from .report.sweep.parameters import SWEEP_FORMAT
from .version import __version__

__all__ = [
    "main",
    "example_spec",
    "default_sweep_scene_path",
    "default_campbell_scene_path",
    "EXIT_OK",
    "EXIT_INPUT",
    "EXIT_COMPUTATION",
    "MAX_PRECISION",
    # the report, importable from here as in pinlin 0.1
    "analyze",
    "render_text",
    "write_plot",
    "REPORT_SCHEMA",
    "REPORT_VERSION",
]

EXIT_OK, EXIT_INPUT, EXIT_COMPUTATION = 0, 2, 3

#: How the SCENE argument of every command is described in its help.
SCENE_HELP = ("scene file (TOML), or the name of a bundled scene ({names}) read from any folder; "
              "default: {default}")

#: Default joint stiffness of ``--example`` [N m/rad]: stiff enough that gravity only softens a 6-DOF arm a little.
DEFAULT_EXAMPLE_STIFFNESS = 1e3
#: Most significant digits ``--precision`` allows: a double holds 17 (more would print rounding noise).
MAX_PRECISION = 17


def _command(sub, name: str, help: str, description: str, epilog: str) -> argparse.ArgumentParser:
    """A subcommand whose help texts are plain (no reStructuredText markup of the docstrings they come from)."""
    codes = "\n\nExit codes: 0 success, 2 bad input, 3 failed computation."
    return sub.add_parser(name, help=help, description=plain_text(description) + codes, epilog=plain_text(epilog),
                          formatter_class=argparse.RawDescriptionHelpFormatter)


def _outputs(p: argparse.ArgumentParser, what: str) -> None:
    p.add_argument("--json", metavar="PATH", help=f"also write the machine-readable {what} to PATH")
    p.add_argument("--plot", metavar="PATH", help="also draw the figure to PATH, format from its suffix (matplotlib)")
    p.add_argument("--precision", type=int, default=6, help=f"significant digits in the text (1 to {MAX_PRECISION})")


def _trust_xacro(p: argparse.ArgumentParser) -> None:
    p.add_argument("--trust-xacro", action="store_true",
                   help="expand the scene's .xacro robot file: a xacro is a program, use only files you trust")


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="pinlin", description="Linearized equations of motion of multibody systems from a URDF."
    )
    parser.add_argument("--version", action="version", version=f"pinlin {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=CommandParser)
    a = _command(
        sub, "analyze", "equilibrium, linearized matrices and their analysis for a scene",
        "Find the equilibrium of a scene, linearize it into M, D, G, S, N and report them with their errors and "
        "timings.  Without a scene file, the bundled default scene (the double pendulum with follower load of "
        "Example 6.2 of the paper pinlin grew from, on the linearized equations of multibody dynamics) is "
        "analysed.",
        "Scene file format (TOML):\n" + SCENE_FORMAT,
    )
    a.add_argument("scene", nargs="?", help=SCENE_HELP.format(names=", ".join(bundled_scenes()),
                                                               default="the bundled double pendulum"))
    _trust_xacro(a)
    a.add_argument("--example", metavar="NAME",
                   help=f"analyse an example-robot-data model with elastic joints instead ({', '.join(sorted(EXAMPLES))})")
    a.add_argument("--stiffness", type=float, default=DEFAULT_EXAMPLE_STIFFNESS,
                   help="joint stiffness for --example [N m/rad; N/m on prismatic joints]")
    a.add_argument("--damping", type=float, default=0.0,
                   help="joint damping for --example [N m s/rad; N s/m on prismatic joints]")
    _outputs(a, f"report (schema version {REPORT_VERSION})")
    a.add_argument("--animate", metavar="PATH", help="also animate a mode to PATH (.gif, .html, .mp4, ...)")
    a.add_argument("--mode", type=int, default=None, help="row of the mode table to animate (default 1)")
    s = _command(
        sub, "sweep", "a scene over the parameter values of its [sweep] table: root locus, verdicts, boundaries",
        "Analyse a scene at every value of the parameter(s) of its [sweep] table (or of --parameter and "
        "--values): the modes tracked by shape, the stability verdict at each value and the exact parameter "
        "values where it changes.  Without a scene file, the bundled double pendulum over its follower load.",
        "The [sweep] table of a scene file (TOML):\n" + SWEEP_FORMAT,
    )
    s.add_argument("scene", nargs="?", help=SCENE_HELP.format(names="as for analyze",
                                                               default="the bundled double pendulum sweep"))
    _trust_xacro(s)
    s.add_argument("--parameter", metavar="PATH", help="the parameter to sweep instead of the file's [sweep] table")
    s.add_argument("--values", metavar="VALUES", help="its values: START:STOP:NUM or a comma-separated list")
    s.add_argument("--no-boundaries", action="store_true", help="skip the exact boundaries between the points")
    _outputs(s, "sweep document")
    c = _command(
        sub, "campbell", "frequencies, damping and critical speeds against the speed of a prescribed joint",
        "Analyse a scene at every speed of one of its prescribed joints (--joint, --speeds, or the scene file's "
        "[campbell] table): the damped frequencies |Im lam| and damping ratios of the modes, tracked by shape, "
        "and the critical speeds where the stability verdict changes, each found to rounding by "
        "critical_parameter on the speed.  Without a scene file, the bundled rotating ring (theory: rotating ring), whose "
        "critical speed is sqrt(k/m).",
        "The [campbell] table of a scene file (TOML):\n" + CAMPBELL_FORMAT,
    )
    c.add_argument("scene", nargs="?", help=SCENE_HELP.format(names="as for analyze",
                                                               default="the bundled rotating ring"))
    _trust_xacro(c)
    c.add_argument("--joint", metavar="NAME", help="the prescribed joint whose speed varies (default: the only one)")
    c.add_argument("--speeds", metavar="SPEEDS", help="START:STOP:NUM or a comma-separated list [rad/s or m/s]")
    _outputs(c, "Campbell document (the sweep document with a campbell section)")
    return parser


def _check_outputs(args) -> None:
    """Everything about the options that can be checked before computing."""
    if not 1 <= args.precision <= MAX_PRECISION:
        raise ParameterError("--precision", f"must be 1 to {MAX_PRECISION} significant digits, got {args.precision}")
    if args.json is not None:
        check_json_path(args.json)
    if args.plot is not None:
        check_figure_path(args.plot)
    given = {option: getattr(args, option.lstrip("-"), None) for option in ("--json", "--plot", "--animate")}
    seen: dict[Path, str] = {}
    for option, path in given.items():
        if path is not None:
            other = seen.setdefault(Path(path).resolve(), option)
            if other != option:
                raise ParameterError(option, f"{path} is also the file of {other}: give each output its own file")


def _check_mode(row: int, spec: SceneSpec) -> None:
    """``--mode`` against the scene's size, before anything is computed: 2n modes for n coordinates
    (with constraints fewer, n - rank J_c, known after the linearization, which checks again)."""
    n = spec.scene.n
    bound = "at most " if spec.scene.constraints else ""
    if row > 2 * n:
        raise ParameterError("--mode", f"expected a row of the mode table, 1 to {bound}{2 * n} (2n for the "
                             f"scene's n = {n} coordinates), got {row}")


def _write(args, option: str, path: str, write) -> None:
    """Write one output file, timed as part ``option PATH``, and say so."""
    with args.clock.part(f"{option.lstrip('-')} {path}"):
        write()
    print(f"wrote {path}")


def _analyze(args) -> int:
    with args.clock.part("checking options"):
        _check_outputs(args)
        if args.animate is not None:
            check_animation_path(args.animate)
    if args.mode is not None and args.animate is None:
        raise ParameterError("--mode", "chooses the mode of --animate; give --animate PATH too")
    row = 1 if args.mode is None else args.mode
    if row < 1:
        raise ParameterError("--mode", f"expected a row of the mode table (1, 2, ...), got {row}")
    if args.example and args.scene:
        raise ParameterError("--example", "give either a scene file or --example, not both")
    with args.clock.part("loading"):
        spec = example_spec(args.example, args.stiffness, args.damping) if args.example else (
            load_scene_argument(args.scene, default_scene_path(), trust_xacro=args.trust_xacro))
    args.source = spec.path
    if spec.sweep is not None:
        sweep_plan(spec, spec.sweep)  # a [sweep] table is checked here too, not only by `pinlin sweep`
    if spec.campbell is not None:
        campbell_plan(spec)  # and a [campbell] table
    if is_periodic(spec):  # periodic coefficients: the orbit and its Floquet multipliers
        check_periodic_options(args.plot, args.animate)
        with args.clock.part("analysis"):
            report, orbit, flo = analyze_periodic(spec)
        print(render_periodic_text(report, orbit, flo, args.precision))
    else:
        if args.animate is not None:
            _check_mode(row, spec)
        with args.clock.part("analysis"):
            report, sys_, modes = analyze(spec)
        print(render_text(report, args.precision))
    if args.json is not None:
        _write(args, "--json", args.json, lambda: write_json(args.json, report))
    if args.plot is not None:
        _write(args, "--plot", args.plot, lambda: write_plot(args.plot, sys_, modes))
    if args.animate is not None:
        _write(args, "--animate", args.animate, lambda: write_animation(args.animate, spec.scene, sys_, modes, row))
    print(args.clock.summary())
    return EXIT_OK


def _values(text: str, option: str = "--values") -> object:
    """``--values``: START:STOP:NUM as a { start, stop, num } table, or a comma-separated list."""
    try:
        if ":" in text:
            start, stop, num = text.split(":")
            return {"start": float(start), "stop": float(stop), "num": int(num)}
        return [float(v) for v in text.split(",")]
    except ValueError:
        raise ParameterError(option, f"expected START:STOP:NUM or a comma-separated list of numbers, "
                             f"got {text!r}") from None


def _sweep(args) -> int:
    with args.clock.part("checking options"):
        _check_outputs(args)
    if (args.parameter is None) != (args.values is None):
        raise ParameterError("--parameter", "--parameter and --values go together")
    values = None if args.values is None else _values(args.values)
    with args.clock.part("loading"):
        spec = load_scene_argument(args.scene, default_sweep_scene_path(), trust_xacro=args.trust_xacro)
    args.source = spec.path
    options = args.parameter is not None
    table = {"parameter": args.parameter, "values": values} if options else spec.sweep
    plan = sweep_plan(spec, table, options=options)
    if args.no_boundaries:
        plan = dataclasses.replace(plan, boundaries=False)
    with args.clock.part("sweep"):
        outcome = run_sweep(plan)
    document = sweep_document(outcome)
    print(render_sweep_text(document, args.precision))
    return _finish(args, document, lambda: write_sweep_plot(args.plot, outcome))


def _campbell(args) -> int:
    with args.clock.part("checking options"):
        _check_outputs(args)
    speeds = None if args.speeds is None else _values(args.speeds, "--speeds")
    with args.clock.part("loading"):
        spec = load_scene_argument(args.scene, default_campbell_scene_path(), trust_xacro=args.trust_xacro)
    args.source = spec.path
    plan = campbell_plan(spec, args.joint, speeds)
    with args.clock.part("campbell"):
        outcome = run_sweep(plan)
    document = campbell_document(outcome)
    print(render_campbell_text(document, args.precision))
    return _finish(args, document, lambda: write_campbell_plot(args.plot, outcome))


def _finish(args, document: dict, write_plot) -> int:
    """Write the ``--json`` document and the ``--plot`` figure (each named as written), print the total."""
    if args.json is not None:
        _write(args, "--json", args.json, lambda: write_json(args.json, document))
    if args.plot is not None:
        _write(args, "--plot", args.plot, write_plot)
    print(args.clock.summary())
    return EXIT_OK


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``pinlin`` console script.

    Parameters
    ----------
    argv : sequence of str, optional
        The arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit code: :data:`EXIT_OK`, :data:`EXIT_INPUT` (bad input or
        options, also an output that cannot be written) or
        :data:`EXIT_COMPUTATION`.  Errors are printed to stderr as one line,
        never as a traceback; a computation that fails names the scene file.

    Raises
    ------
    SystemExit
        From argparse: after ``--help`` or ``--version`` (code 0) and for
        unknown options or malformed values (code 2, like :data:`EXIT_INPUT`).

    Examples
    --------
    ``pinlin analyze`` on the bundled double pendulum, its text report captured:

    >>> import contextlib, io
    >>> out = io.StringIO()
    >>> with contextlib.redirect_stdout(out):
    ...     code = pinlin.cli.main(["analyze", str(pinlin.data_path("scenes/double_pendulum.toml"))])
    >>> code == pinlin.cli.EXIT_OK, "Stability: MARGINALLY STABLE" in out.getvalue()
    (True, True)
    """
    clock = Stopwatch()
    parser = _parser()
    args = parser.parse_args(argv)
    args.clock = clock
    commands = {"analyze": _analyze, "sweep": _sweep, "campbell": _campbell}
    if args.command not in commands:
        parser.print_help()
        return EXIT_INPUT
    args.source = None
    try:
        return commands[args.command](args)
    except (InputError, ModelTooLargeError, MissingDependencyError) as exc:
        option = "--example: " if isinstance(exc, ExampleNotFoundError) else ""  # the only option naming one
        print(f"pinlin: error: {option}{_one_line(exc)}", file=sys.stderr)
        return EXIT_INPUT
    except PinlinError as exc:  # ComputationError, and any other pinlin error: a failed computation
        where = "" if args.source is None or isinstance(exc, SceneFileError) else f"{args.source}: "
        print(f"pinlin: computation failed: {where}{_one_line(exc)}", file=sys.stderr)
        return EXIT_COMPUTATION


def _one_line(exc: Exception) -> str:
    """The message on one line (numpy wraps long arrays in a message over several)."""
    return re.sub(r"\s*\n\s*", " ", str(exc)).strip()


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
