"""Elements between frames: the cost of spring-dampers and bushings in ``linearize``.

A 50-link pendulum chain (theory: pendulum chains) under gravity, at its equilibrium, with

- nothing but gravity (the baseline);
- joint springs (``JointSpring``, two per joint when there are more than 50);
- spring-dampers between links (``LinearSpringDamper``, link i to links i + 2 and
  i + 3, preloaded: rest length 90 % of the distance);
- bushings between links i and i + 2 (``Bushing``, deflected: unloaded at 0.1 rad
  and 1 cm from the current relative placement).

Cost per element = (linearize with E elements - baseline) / E, medians of
interleaved repeats in one process; the slope of the run time against E
(least squares over the sweep) separates the per-element cost from the fixed
cost (the frame kinematics, one ``computeJointJacobians`` + ``updateFramePlacements``).
Against central differences (``bench_linearize.fd_linearization``, 4n residual
evaluations): run time, and the error of both against Richardson extrapolation
(full run) of the same residual.  ``pinlin.testing.check_element`` gives each
element type's largest mismatch with differences on the manifold.

Run alone: ``python -m benchmarks.bench_frame_elements [--quick]``.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
import pinocchio as pin  # noqa: E402

import pinlin  # noqa: E402
from pinlin.model.evaluation import Evaluation  # noqa: E402
from pinlin.testing import check_element  # noqa: E402

from .bench_linearize import fd_linearization, matrix_error, richardson_reference  # noqa: E402
from .common import Report, Table, interleaved_medians, result_path, save_figure, write_report  # noqa: E402

#: Links of the chain.
LINKS = 50
#: Elements of the headline comparison (100 spring-dampers).
HEADLINE = 100
#: Numbers of elements in the sweep (full run, quick run).
SWEEP = (10, 30, 100, 300)
QUICK_SWEEP = (10, 100)
#: Bushings in the chain (one per link pair i, i + 2).
BUSHINGS = 20
#: Target: a spring-damper costs at most this many joint springs.
TARGET_RATIO = 3.0
#: Central-difference step [rad] of the comparison (bench_linearize's best central step).
FD_STEP = 1e-5


def chain() -> pinlin.Robot:
    return pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(LINKS, length=2.0, mass=5.0))


def _pairs(count: int) -> list[tuple[int, int]]:
    """Link pairs (i, i + s), s = 2, 3, 4, ... until ``count`` pairs."""
    out: list[tuple[int, int]] = []
    step = 2
    while len(out) < count:
        out += [(i, i + step) for i in range(1, LINKS + 1 - step)]
        step += 1
    return out[:count]


def spring_dampers(robot: pinlin.Robot, q: np.ndarray, count: int) -> list[pinlin.LinearSpringDamper]:
    ev = Evaluation(pinlin.Scene(robot), q, np.zeros(robot.nv))
    out = []
    for a, b in _pairs(count):
        fa, fb = f"link{a}", f"link{b}"
        length = np.linalg.norm(ev.frame_position(robot.frame_id(fa)) - ev.frame_position(robot.frame_id(fb)))
        out.append(pinlin.LinearSpringDamper(fa, fb, stiffness=40.0, damping=0.5, rest_length=0.9 * length))
    return out


def joint_springs(robot: pinlin.Robot, count: int) -> list[pinlin.JointSpring]:
    return [pinlin.JointSpring(f"joint{i % LINKS + 1}", 5.0) for i in range(count)]


def bushings(robot: pinlin.Robot, q: np.ndarray, count: int) -> list[pinlin.Bushing]:
    ev = Evaluation(pinlin.Scene(robot), q, np.zeros(robot.nv))
    out = []
    nudge = pin.exp6(np.array([0.01, 0.0, 0.0, 0.0, 0.1, 0.0]))
    for a, b in _pairs(count):
        fa, fb = f"link{a}", f"link{b}"
        relative = ev.frame_placement(robot.frame_id(fb)).actInv(ev.frame_placement(robot.frame_id(fa)))
        out.append(
            pinlin.Bushing(fa, fb, stiffness=[4e3, 4e3, 4e3, 50.0, 50.0, 50.0], damping=[1.0] * 6, offset=relative * nudge)
        )
    return out


def _equilibrium(scene: pinlin.Scene, q: np.ndarray) -> np.ndarray:
    return pinlin.find_equilibrium(scene, q).q


def _slope(counts, times) -> float:
    """Least-squares slope of time against the number of elements [s per element]."""
    return float(np.polyfit(np.asarray(counts, dtype=float), np.asarray(times), 1)[0])


class _Setup:
    """The chain, its start configuration and the headline scenes at their equilibria."""

    def __init__(self):
        self.robot = robot = chain()
        self.q_start = np.random.default_rng(12).uniform(-0.3, 0.3, robot.nq)
        self.bare = pinlin.Scene(robot)
        self.scenes = {
            "gravity only": self.bare,
            "joint springs": pinlin.Scene(robot, joint_springs(robot, HEADLINE)),
            "spring-dampers": pinlin.Scene(robot, spring_dampers(robot, self.q_start, HEADLINE)),
            "bushings": pinlin.Scene(robot, bushings(robot, self.q_start, BUSHINGS)),
        }
        self.counts = {"gravity only": 0, "joint springs": HEADLINE, "spring-dampers": HEADLINE, "bushings": BUSHINGS}
        self.points = {name: _equilibrium(s, self.q_start) for name, s in self.scenes.items()}


def _headline(setup: _Setup, repeats: int) -> tuple[Table, dict[str, float], dict[str, float]]:
    """Cost per element of the 100 spring-dampers, 100 joint springs and 20 bushings."""
    scenes, points, counts = setup.scenes, setup.points, setup.counts
    fns = [lambda s=s, q=points[name]: pinlin.linearize(s, q) for name, s in scenes.items()]
    times = dict(zip(scenes, interleaved_medians(fns, repeats=repeats)))
    per = {name: (times[name] - times["gravity only"]) / counts[name] for name in scenes if counts[name]}
    rows = [
        [name, counts[name], times[name] * 1e6, per.get(name, float("nan")) * 1e6,
         per.get(name, float("nan")) / per["joint springs"] if name in per else float("nan"),
         ", ".join(sorted(set(pinlin.linearize(s, points[name]).calls)))]
        for name, s in scenes.items()
    ]
    table = Table(
        f"linearize on a {LINKS}-link chain: cost per element",
        ["scene", "elements", "linearize [us]", "cost per element [us]", "per element / joint spring's", "Pinocchio calls"],
        rows,
        note=(
            "Cost per element: (linearize - gravity only) / elements, medians of interleaved repeats, each scene at "
            "its equilibrium. Joint springs are index arithmetic on q; the elements between frames also need the "
            "frame kinematics (one computeJointJacobians + updateFramePlacements for all of them) and products of "
            "their Jacobians."
        ),
    )
    return table, times, per


def _sweep(setup: _Setup, sweep, repeats: int) -> tuple[Table, dict[str, list[float]], dict[str, float]]:
    """Run time against the number of elements; least-squares slopes."""
    robot, q, bare = setup.robot, setup.q_start, setup.bare
    rows, series = [], {"spring-dampers": [], "joint springs": []}
    for count in sweep:
        made = {
            "spring-dampers": pinlin.Scene(robot, spring_dampers(robot, q, count)),
            "joint springs": pinlin.Scene(robot, joint_springs(robot, count)),
        }
        ts = interleaved_medians(
            [lambda s=s: pinlin.linearize(s, q, balancing=True) for s in made.values()]
            + [lambda: pinlin.linearize(bare, q, balancing=True)],
            repeats=repeats,
        )
        for name, t in zip(made, ts):
            series[name].append(t)
            rows.append([name, count, t * 1e6, (t - ts[-1]) / count * 1e6])
    slopes = {name: _slope(sweep, ts) for name, ts in series.items()}
    table = Table(
        "Run time against the number of elements",
        ["element", "elements", "linearize [us]", "(linearize - gravity only) / elements [us]"],
        rows,
        note=(
            "linearize(..., balancing=True) at the start configuration (many preloaded springs need not have an "
            "equilibrium there; holding it costs nothing measurable). Least-squares slopes (marginal cost of one more "
            "element): "
            + ", ".join(f"{name} {s * 1e6:.3g} us" for name, s in slopes.items())
            + f"; ratio {slopes['spring-dampers'] / slopes['joint springs']:.3g}."
        ),
    )
    return table, series, slopes


def _against_differences(setup: _Setup, quick: bool) -> tuple[Table, list[list]]:
    """Run time and error of linearize and central differences (Richardson as the reference in a full run)."""
    rows = []
    for name in ("spring-dampers", "bushings"):
        scene, q = setup.scenes[name], setup.points[name]
        sys = pinlin.linearize(scene, q)
        fd = fd_linearization(scene, q, FD_STEP, "central")
        t_lin, t_fd = interleaved_medians(
            [lambda s=scene, q=q: pinlin.linearize(s, q), lambda s=scene, q=q: fd_linearization(s, q, FD_STEP, "central")],
            repeats=3 if quick else 5,
        )
        err_lin = err_fd = float("nan")
        if not quick:
            Mr, Cr, Kr, _ = richardson_reference(scene, q)
            err_lin, err_fd = matrix_error(sys.M, sys.C, sys.K, (Mr, Cr, Kr)), matrix_error(*fd, (Mr, Cr, Kr))
        gap = matrix_error(sys.M, sys.C, sys.K, fd)
        rows.append([name, sys.n, t_lin * 1e6, t_fd * 1e6, t_fd / t_lin, gap, err_lin, err_fd])
    table = Table(
        "Analytic linearization against central differences",
        ["scene", "n", "linearize [us]", "central FD [us]", "FD / linearize", "FD vs analytic (max rel. error)",
         "analytic vs Richardson", "FD vs Richardson"],
        rows,
        note=(
            f"Central differences of the residual (h = {FD_STEP:g}, steps by pin.integrate), 4n evaluations plus crba. "
            "Errors: max relative Frobenius error of M, C, K; Richardson extrapolation (Ridders) of the same residual "
            "is the reference in the full run (quick run: not computed)."
        ),
    )
    return table, rows


def _checks(setup: _Setup, quick: bool) -> tuple[Table, list[list]]:
    """pinlin.testing.check_element on the elements of the headline scenes."""
    rows = []
    for name in ("spring-dampers", "bushings"):
        scene, q = setup.scenes[name], setup.points[name]
        elements = scene.elements[:3] if quick else scene.elements
        rows.append([name, len(elements), max(check_element(e, scene, q) for e in elements)])
    table = Table(
        "pinlin.testing.check_element at the equilibrium (largest mismatch over the elements checked)",
        ["scene", "elements checked", "largest mismatch"],
        rows,
    )
    return table, rows


def run(quick: bool = False) -> Report:
    t_start = time.perf_counter()
    repeats = 5 if quick else 9
    setup = _Setup()
    t1, times, per = _headline(setup, repeats)
    sweep = QUICK_SWEEP if quick else SWEEP
    t2, series, slopes = _sweep(setup, sweep, repeats)
    t3, fd_rows = _against_differences(setup, quick)
    t4, check_rows = _checks(setup, quick)
    ratio = per["spring-dampers"] / per["joint springs"]
    summary = {
        "cost per element": (
            f"spring-damper {per['spring-dampers'] * 1e6:.3g} us, joint spring {per['joint springs'] * 1e6:.3g} us, "
            f"bushing {per['bushings'] * 1e6:.3g} us ({HEADLINE} spring-dampers / joint springs, {BUSHINGS} bushings, "
            f"{LINKS}-link chain)"
        ),
        "spring-damper / joint spring": (
            f"{ratio:.3g}x per element (target <= {TARGET_RATIO:g}x: "
            f"{'met' if ratio <= TARGET_RATIO else 'not met'}); marginal slopes "
            f"{slopes['spring-dampers'] * 1e6:.3g} us vs {slopes['joint springs'] * 1e6:.3g} us"
        ),
        "against central differences": ", ".join(
            f"{r[0]}: linearize {r[4]:.3g}x faster, FD differs by {r[5]:.1e}" for r in fd_rows
        ),
        "check_element": ", ".join(f"{r[0]} {r[2]:.1e}" for r in check_rows),
    }
    figures = _plot(sweep, series, times["gravity only"], quick)
    text = (
        "Spring-dampers and bushings between the links of a 50-link chain: linearize's cost per element "
        "against a joint spring's, and against central differences. A joint spring adds one number to one diagonal "
        "entry of K; an element between frames adds a rank-3 (a bushing: rank-6) update over the joints supporting "
        "its two frames, at least of the order of nv^2 operations, and needs the frame kinematics once per "
        "evaluation: the target of 3x a joint spring's cost is out of reach by construction on a 50-link "
        "chain. The slope of the sweep (the marginal cost of one more element, the fixed kinematics excluded) is "
        "the fair per-element figure."
    )
    report = Report("frame_elements", [t1, t2, t3, t4], summary, figures, text=text)
    report.target(12, f"a spring-damper at most {TARGET_RATIO:g}x a joint spring's cost per element",
                  f"{ratio:.3g}x per element, marginal {slopes['spring-dampers'] / slopes['joint springs']:.3g}x",
                  bool(ratio <= TARGET_RATIO), f"joint springs on the same {LINKS}-link chain")
    report.elapsed = time.perf_counter() - t_start
    return report


def _plot(sweep, series, baseline: float, quick: bool) -> list[str]:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return []
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for marker, (name, ts) in zip("os", series.items()):
        ax.loglog(sweep, np.array(ts) * 1e6, "-" + marker, label=name)
    ax.axhline(baseline * 1e6, color="gray", ls=":", label="gravity only")
    ax.set_xlabel("elements")
    ax.set_ylabel("linearize [us]")
    ax.set_title(f"linearize of a {LINKS}-link chain against the number of elements", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return [save_figure(fig, result_path("frame_elements", quick))]


if __name__ == "__main__":
    quick = "--quick" in sys.argv[1:]
    report = run(quick=quick)
    if quick:
        report.name += "_quick"
    print(report.markdown())
    print("written to", write_report(report))
