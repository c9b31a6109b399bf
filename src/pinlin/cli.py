"""The ``pinlin`` command line: ``pinlin analyze [SCENE.toml]``.

The report: the scene, the equilibrium and its residual, the nonzero matrices
and their structure, the modes with their errors (eta, kappa, error bound), the
stability verdict with its reason, and timings; ``--json`` writes it all in
machine-readable form, ``--plot`` draws the eigenvalue map and frequency
responses.

Exit codes: 0 success, 2 bad input (scene file, URDF, parameters), 3 a
computation that failed (no convergence, lost accuracy).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections.abc import Sequence

import numpy as np

from . import __version__
from .model.elements import JointDamper, JointSpring
from .linearization.equilibrium import find_equilibrium
from .errors import (
    ComputationError,
    InputError,
    MissingDependencyError,
    ModelTooLargeError,
    ParameterError,
    PinlinError,
)
from .linearization.linearize import linearize
from .model.loading import EXAMPLES, load_example
from .model.scene import Scene
from .model.scenefile import SCENE_FORMAT, SceneSpec, default_scene_path, load_scene
from .spectral import modal_analysis
from .linearization.system import MATRIX_NAMES, LinearizedSystem

__all__ = ["main", "analyze", "render_text", "REPORT_SCHEMA"]

EXIT_OK, EXIT_INPUT, EXIT_COMPUTATION = 0, 2, 3

_NUMBERS = {"type": "array", "items": {"type": "number"}}
_OPTIONAL_NUMBERS = {"type": "array", "items": {"type": ["number", "null"]}}
_MATRIX = {"type": "array", "items": _NUMBERS}

#: JSON Schema (draft 2020-12) of the ``--json`` report; ``null`` marks values
#: that do not exist for a mode (the damping ratio of lam = 0, the condition
#: number of a defective eigenvalue).
REPORT_SCHEMA = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "type": "object",
    "required": ["pinlin_version", "scene", "linearization", "modes", "stability", "elapsed"],
    "properties": {
        "pinlin_version": {"type": "string"},
        "elapsed": {"type": "number", "minimum": 0},
        "scene": {
            "type": "object",
            "required": ["source", "robot", "urdf", "nq", "nv", "n", "dof_names", "gravity", "prescribed", "elements"],
            "properties": {
                "nq": {"type": "integer", "minimum": 1},
                "nv": {"type": "integer", "minimum": 1},
                "n": {"type": "integer", "minimum": 1},
                "dof_names": {"type": "array", "items": {"type": "string"}},
                "gravity": {**_NUMBERS, "minItems": 3, "maxItems": 3},
                "prescribed": {"type": "object", "additionalProperties": {"type": "number"}},
                "elements": {"type": "array", "items": {"type": "object", "required": ["kind"]}},
            },
        },
        "equilibrium": {
            "type": "object",
            "required": ["q", "residual", "relative_residual", "iterations", "elapsed"],
            "properties": {"q": _NUMBERS, "iterations": {"type": "integer", "minimum": 0}},
        },
        "linearization": {
            "type": "object",
            "required": ["q", "relative_residual", "balancing", "nonzero", "calls", "dropped", "notes", "elapsed",
                         "structure", "matrices"],
            "properties": {
                "nonzero": {"type": "array", "items": {"enum": list(MATRIX_NAMES)}},
                "calls": {"type": "array", "items": {"type": "string"}},
                "balancing": {"oneOf": [{"type": "null"}, _NUMBERS]},
                "matrices": {
                    "type": "object",
                    "required": list(MATRIX_NAMES),
                    "additionalProperties": _MATRIX,
                },
            },
        },
        "modes": {
            "type": "object",
            "required": ["method", "method_reason", "elapsed", "is_simple", "max_backward_error", "eigenvalues_real",
                         "eigenvalues_imag", "natural_frequency", "damping_ratio", "backward_error", "condition",
                         "error_bound", "multiplicity", "kind", "table"],
            "properties": {
                "eigenvalues_real": _NUMBERS,
                "eigenvalues_imag": _NUMBERS,
                "natural_frequency": _NUMBERS,
                "backward_error": _NUMBERS,
                "damping_ratio": _OPTIONAL_NUMBERS,
                "condition": _OPTIONAL_NUMBERS,
                "error_bound": _OPTIONAL_NUMBERS,
                "kind": {"type": "array", "items": {"type": "string"}},
                "is_simple": {"type": "boolean"},
            },
        },
        "stability": {
            "type": "object",
            "required": ["kind", "reason"],
            "properties": {
                "kind": {"enum": ["asymptotically_stable", "marginally_stable", "divergence", "flutter", "undecided"]},
                "reason": {"type": "string"},
            },
        },
    },
}


def _example_spec(name: str, stiffness: float, damping: float) -> SceneSpec:
    """An example robot with elastic joints, springs unstressed at its reference pose."""
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


def _definiteness(a: np.ndarray) -> dict:
    if not np.any(a):
        return {"zero": True, "negative": 0, "zero_eigenvalues": a.shape[0], "positive": 0}
    w = np.linalg.eigvalsh(a)
    tol = a.shape[0] * np.finfo(float).eps * np.abs(w).max()
    return {
        "zero": False,
        "negative": int(np.sum(w < -tol)),
        "zero_eigenvalues": int(np.sum(np.abs(w) <= tol)),
        "positive": int(np.sum(w > tol)),
    }


def analyze(spec: SceneSpec):
    """Run equilibrium, linearization and modal analysis on a scene spec.

    Returns the machine-readable report (a JSON-compatible dict), the
    :class:`~pinlin.LinearizedSystem` and the :class:`~pinlin.Modes`.
    """
    t0 = time.perf_counter()
    scene = spec.scene
    robot = scene.robot
    report: dict = {
        "pinlin_version": __version__,
        "scene": {
            "source": spec.path,
            "robot": robot.name,
            "urdf": robot.source,
            "nq": robot.nq,
            "nv": robot.nv,
            "n": scene.n,
            "dof_names": list(scene.dof_names),
            "gravity": scene.gravity.tolist(),
            "prescribed": dict(scene.prescribed),
            "elements": [_describe(e) for e in scene.elements],
        },
    }
    q = spec.q0
    if spec.equilibrium:
        eq = find_equilibrium(scene, q)
        q = eq.q
        report["equilibrium"] = {
            "q": eq.q.tolist(),
            "residual": eq.residual,
            "relative_residual": eq.relative_residual,
            "iterations": eq.iterations,
            "elapsed": eq.elapsed,
        }
    sys_ = linearize(scene, q, balancing=spec.balancing)
    report["linearization"] = {
        "q": sys_.q.tolist(),
        "relative_residual": sys_.residual,
        "balancing": None if sys_.balancing is None else sys_.balancing.tolist(),
        "nonzero": list(sys_.nonzero),
        "calls": list(sys_.calls),
        "dropped": sys_.dropped,
        "notes": list(sys_.notes),
        "elapsed": sys_.elapsed,
        "structure": {name: _definiteness(getattr(sys_, name)) for name in ("M", "D", "S")},
        "matrices": {name: getattr(sys_, name).tolist() for name in MATRIX_NAMES},
    }
    modes = modal_analysis(sys_)
    report["modes"] = {
        "method": modes.method.name,
        "method_reason": modes.method.reason,
        "elapsed": modes.elapsed,
        "is_simple": bool(modes.is_simple),
        "max_backward_error": float(modes.max_backward_error),
        "eigenvalues_real": modes.eigenvalues.real.tolist(),
        "eigenvalues_imag": modes.eigenvalues.imag.tolist(),
        "natural_frequency": modes.natural_frequency.tolist(),
        "damping_ratio": [None if not np.isfinite(z) else float(z) for z in modes.damping_ratio],
        "backward_error": modes.backward_error.tolist(),
        "condition": [None if not np.isfinite(k) else float(k) for k in modes.condition],
        "error_bound": [None if not np.isfinite(b) else float(b) for b in modes.error_bound],
        "multiplicity": np.asarray(modes.multiplicity).tolist(),
        "kind": list(modes.kind),
        "table": modes.table(max_rows=None),
    }
    report["stability"] = {"kind": modes.stability.kind, "reason": modes.stability.reason}
    report["elapsed"] = time.perf_counter() - t0
    return report, sys_, modes


def _describe(element) -> dict:
    out = {"kind": element.kind}
    for key in ("joint", "frame", "stiffness", "rest", "damping", "force", "torque", "alpha", "beta"):
        if hasattr(element, key):
            value = getattr(element, key)
            out[key] = value.tolist() if isinstance(value, np.ndarray) else value
    return out


def _matrix_text(name: str, a: np.ndarray, names: Sequence[str], precision: int) -> str:
    if a.shape[0] > 12:
        return f"  {name}: {a.shape[0]}x{a.shape[0]}, ||{name}||_F = {np.linalg.norm(a):.6g}"
    width = max(len(n) for n in names)
    rows = [f"  {name} ="]
    for label, row in zip(names, a):
        cells = " ".join(f"{x: .{precision}g}".rjust(precision + 7) for x in row)
        rows.append(f"    {label.rjust(width)}  {cells}")
    return "\n".join(rows)


def render_text(report: dict, precision: int = 6) -> str:
    """The human-readable report."""
    s, lin = report["scene"], report["linearization"]
    out = [
        f"pinlin {report['pinlin_version']}: {s['robot']} from {s['urdf']}",
        f"  scene file: {s['source']}",
        f"  nq = {s['nq']}, nv = {s['nv']}, free coordinates n = {s['n']}: {', '.join(s['dof_names'])}",
        f"  gravity = {s['gravity']} m/s^2"
        + (f", prescribed velocities {s['prescribed']}" if s["prescribed"] else ""),
        "  elements: "
        + (", ".join(f"{e['kind']}({e.get('joint', e.get('frame', ''))})" for e in s["elements"]) or "none"),
        "",
    ]
    if "equilibrium" in report:
        eq = report["equilibrium"]
        out += [
            "Equilibrium (Newton on the configuration manifold)",
            f"  q = {np.array2string(np.array(eq['q']), precision=precision)}",
            f"  residual = {eq['residual']:.3e} (relative {eq['relative_residual']:.2e}), "
            f"{eq['iterations']} iterations, {eq['elapsed'] * 1e3:.2f} ms",
            "",
        ]
    if lin["balancing"] is not None:
        out += [
            "Operating point held by constant actuator forces (balancing, asked for explicitly)",
            f"  balancing forces = {np.array2string(np.array(lin['balancing']), precision=4)}",
            "",
        ]
    out.append("Linearized equations  M x'' + (D + G) x' + (S + N) x = f")
    out.append(f"  nonzero: {', '.join(lin['nonzero'])}; zero: "
               f"{', '.join(n for n in MATRIX_NAMES if n not in lin['nonzero']) or 'none'}")
    for name in lin["nonzero"]:
        out.append(_matrix_text(name, np.array(lin["matrices"][name]), s["dof_names"], precision))
    out.append("  structure (eigenvalue signs -/0/+): " + "; ".join(
        f"{k}: " + ("zero" if v["zero"] else f"{v['negative']}/{v['zero_eigenvalues']}/{v['positive']}")
        for k, v in lin["structure"].items()
    ))
    out.append(f"  Pinocchio calls: {', '.join(lin['calls']) or 'none'}")
    if lin["dropped"]:
        out.append(
            "  set to zero as rounding: "
            + ", ".join(f"{k} ({v:.1e} relative)" for k, v in lin["dropped"].items())
        )
    for note in lin["notes"]:
        out.append(f"  note: {note}")
    out.append(f"  equilibrium residual (relative) = {lin['relative_residual']:.2e}; "
               f"linearize {lin['elapsed'] * 1e3:.2f} ms")
    out.append("")
    modes = report["modes"]
    out.append(modes["table"])
    out.append(f"  modal analysis {modes['elapsed'] * 1e3:.2f} ms")
    out.append("")
    st = report["stability"]
    out.append(f"Stability: {st['kind'].replace('_', ' ').upper()}")
    out.append(f"  {st['reason']}")
    out.append("")
    out.append(f"Total {report['elapsed'] * 1e3:.1f} ms")
    return "\n".join(out)


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
    a.add_argument("--stiffness", type=float, default=1e3, help="joint stiffness for --example [N m/rad]")
    a.add_argument("--damping", type=float, default=0.0, help="joint damping for --example [N m s/rad]")
    a.add_argument("--json", metavar="PATH", help="also write the machine-readable report to PATH")
    a.add_argument("--plot", metavar="PATH", help="also draw the eigenvalue map and frequency response to PATH (needs matplotlib)")
    a.add_argument("--precision", type=int, default=6, help="significant digits in the text report")
    return parser


def write_plot(path: str, sys_: LinearizedSystem, modes) -> None:
    """Eigenvalue map and driving-point frequency responses (up to four coordinates) into one figure."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise MissingDependencyError("--plot needs matplotlib: pip install 'pinlin[plot]'") from None
    from . import plot
    from .frf import frequency_response

    fig = plt.figure(figsize=(11, 4.5))
    grid = fig.add_gridspec(2, 2, width_ratios=(1, 1.2))
    plot.eigenvalue_map(modes, fig.add_subplot(grid[:, 0]))
    mags = np.abs(modes.eigenvalues)
    mags = mags[mags > 1e-9 * max(mags.max(), 1.0)]
    lo, hi = (0.1 * mags.min(), 10 * mags.max()) if mags.size else (0.1, 10.0)
    omega = np.logspace(np.log10(lo), np.log10(hi), 600)
    dofs = list(range(min(sys_.n, 4)))
    resp = frequency_response(sys_, omega, inputs=dofs, outputs=dofs)
    axes = (fig.add_subplot(grid[0, 1]), fig.add_subplot(grid[1, 1]))
    for k, name in enumerate(sys_.dof_names[: len(dofs)]):
        plot.frequency_response(resp, axes, output=k, input=k, label=f"H[{name}, {name}]")
    fig.suptitle(f"{sys_.n} coordinates: {modes.stability.kind.replace('_', ' ')}")
    fig.tight_layout()
    try:
        fig.savefig(path)
    except OSError as exc:
        raise ParameterError("--plot", f"cannot write {path}: {exc}") from None
    finally:
        plt.close(fig)


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``pinlin`` console script; returns the exit code."""
    parser = _parser()
    args = parser.parse_args(argv)
    if args.command != "analyze":
        parser.print_help()
        return EXIT_INPUT
    try:
        if args.example and args.scene:
            raise ParameterError("--example", "give either a scene file or --example, not both")
        if args.example:
            spec = _example_spec(args.example, args.stiffness, args.damping)
        else:
            spec = load_scene(args.scene or default_scene_path())
        report, sys_, modes = analyze(spec)
        if args.plot:
            write_plot(args.plot, sys_, modes)
    except (InputError, ModelTooLargeError, MissingDependencyError) as exc:
        print(f"pinlin: error: {exc}", file=sys.stderr)
        return EXIT_INPUT
    except ComputationError as exc:
        print(f"pinlin: computation failed: {exc}", file=sys.stderr)
        return EXIT_COMPUTATION
    except PinlinError as exc:  # any other pinlin error is a failed computation
        print(f"pinlin: computation failed: {exc}", file=sys.stderr)
        return EXIT_COMPUTATION
    print(render_text(report, args.precision))
    if args.json:
        try:
            with open(args.json, "w", encoding="utf-8") as f:
                json.dump(report, f, indent=2)
        except OSError as exc:
            print(f"pinlin: error: cannot write {args.json}: {exc}", file=sys.stderr)
            return EXIT_INPUT
    return EXIT_OK


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
