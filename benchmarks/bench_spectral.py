"""Modal analysis: solver paths against plain QZ, with their backward errors.

For pendulum chains of n = 50, 100, 200 links (joint stiffnesses spread
log-uniformly over 10 decades, gravity; so D = G = N = 0), in one process:

- baseline: ``scipy.linalg.eig(A, B)`` on the *unscaled* first companion pencil
  (right eigenvectors only, nothing else);
- general: ``pinlin.modal_analysis(sys, method="general")``: scaled QZ with left
  and right vectors, block recovery, eta, kappa, clusters, verdict;
- symmetric: ``pinlin.modal_analysis(sys)`` (the automatic path, eigh of size n
  with a QZ fallback when eigh's backward error exceeds ``eigh_tol``);
- the other structured paths on the same chains made to fit them: Rayleigh
  damping D = a M + b S ("proportional") and a circulatory N ("squared").

Targets: general / baseline <= 1.5; general / symmetric >= 4.  The
three timings of a ratio are interleaved in one loop (medians of the samples).
Errors: max eta of each path, and for small cases the eigenvalue error against
a 50-digit mpmath reference (the roots of det L(lam)).

Issue 14 adds, in wall-clock time (``time.perf_counter``; single calls sampled in
turn, medians of many interleaved samples, one BLAS thread; the machine is shared):

- small robots (the double pendulum, ur5, panda; springs, dampers and a
  follower force: the general path with left vectors) and a 20-link chain
  against a plain ``scipy.linalg.eig`` of the companion pencil with right
  vectors (target: at most 1.5x for n <= 20, 1.2x for n >= 50), timed three
  ways: ``modal_analysis`` alone, followed by reading ``.stability`` (the
  structural facts and the verdict, formed on first access), and followed by
  reading ``.condition``;
- the symmetric path against bare ``eigh(S, M)`` (target: at most 3x, backward
  errors at 1e-15), alone and with ``.stability`` read;
- a sweep of (linearize + modal_analysis) over the panda's joint stiffness on
  two processes against the same sweep in one (target: 1.7x), values compared
  bitwise, with the machine's load average beside it.

Why wall clock: ``time.thread_time`` and ``time.perf_counter`` agree call by
call (the same eig of the 4x4 pencil: 61 us and 62 us, never more CPU than wall
time), but a ``thread_time`` call is a system call (0.6 us against 0.07 us) and,
above all, this 2-vCPU machine has periods in which every call runs about 2.3x
slower (the other vCPU busy; the running thread is slowed, not descheduled, so
CPU time counts it too).  An eig median of 155 us by one clock against 60 us by
the other came from samples taken in different periods; interleaving the sides
of a ratio call by call makes both see the same periods.
"""

from __future__ import annotations

import functools
import os
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import scipy.linalg as sla

import pinlin
from pinlin.spectral.qep import companion_pencil

from .common import Report, Table, interleaved_medians, median_time, write_report

SIZES = (50, 100, 200)


def analyse(sys, **options) -> pinlin.Modes:
    """``modal_analysis(sys)`` after dropping the system's cached C = D + G and K = S + N.

    A timed loop analyses one system many times; without this the sums would be
    formed once and every later call would skip them, which a sweep (a new system
    per point) never does.
    """
    cache = getattr(sys, "__dict__", {})  # a tuple (M, C, K) caches nothing
    cache.pop("C", None)
    cache.pop("K", None)
    return pinlin.modal_analysis(sys, **options)


def chain_system(n: int, seed: int = 0) -> pinlin.LinearizedSystem:
    """n-link hanging chain, total length 1 m, mass 1 kg, joint stiffnesses 10^-5 .. 10^5 N m/rad."""
    rng = np.random.default_rng(seed)
    ks = 10.0 ** rng.uniform(-5, 5, n)
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n, length=1.0, mass=1.0))
    scene = pinlin.Scene(
        robot, [pinlin.JointSpring(f"joint{i + 1}", k) for i, k in enumerate(ks)], gravity=(0, 0, -9.81)
    )
    return pinlin.linearize(scene, robot.neutral())


def plain_eta(M, C, K, lam, Z):
    """eta of plain scipy eig pairs, x taken from the second block of z = [lam x; x]."""
    n = M.shape[0]
    X = Z[n:]
    R = (M @ X) * lam**2 + (C @ X) * lam + K @ X
    w = np.abs(lam) ** 2 * np.linalg.norm(M) + np.abs(lam) * np.linalg.norm(C) + np.linalg.norm(K)
    return np.linalg.norm(R, axis=0) / (w * np.linalg.norm(X, axis=0))


def _mp_roots(M, C, K, dps=50):
    """Eigenvalues of L as roots of det L(lam) in mpmath (interpolated at 2n+1 points)."""
    import mpmath as mp

    mp.mp.dps = dps
    n = M.shape[0]
    deg = 2 * n
    pts = [mp.mpf(k) / 2 - mp.mpf(deg) / 4 for k in range(deg + 1)]
    vals = []
    for x in pts:
        L = mp.matrix(n, n)
        for i in range(n):
            for j in range(n):
                L[i, j] = x * x * mp.mpf(M[i, j]) + x * mp.mpf(C[i, j]) + mp.mpf(K[i, j])
        vals.append(mp.det(L))
    # Newton interpolation -> monomial coefficients
    V = mp.matrix([[x**p for p in range(deg + 1)] for x in pts])
    coef = mp.lu_solve(V, mp.matrix(vals))
    roots = mp.polyroots([coef[p] for p in range(deg, -1, -1)], maxsteps=400, extraprec=400)
    return np.array([complex(r) for r in roots])


def _match_error(lam, ref):
    """max_k min_j |lam_k - ref_j| / |ref_j| (greedy matching)."""
    ref = list(ref)
    worst = 0.0
    for x in lam:
        j = int(np.argmin([abs(x - r) for r in ref]))
        worst = max(worst, abs(x - ref[j]) / max(abs(ref[j]), 1e-300))
        ref.pop(j)
    return worst


def _robot_system(name: str) -> pinlin.LinearizedSystem:
    """Springs (100 N m/rad at the reference pose), dampers 0.5 and a 5 N follower force at the tool."""
    robot = pinlin.load_example(name)
    q = np.asarray(robot.reference_configurations["default"], dtype=float) if name == "panda" else np.array(
        [0.3, -1.2, 1.4, -0.8, 1.1, 0.4])
    el = []
    for j, qj in zip(robot.joint_names, q):
        el += [pinlin.JointSpring(j, 100.0, rest=float(qj)), pinlin.JointDamper(j, 0.5)]
    el.append(pinlin.FollowerWrench("panda_hand" if name == "panda" else "tool0", force=(0.0, 0.0, 5.0)))
    return pinlin.linearize(pinlin.Scene(robot, el), q, balancing=True)


def _follower_chain(n: int) -> pinlin.LinearizedSystem:
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n, length=1.0, mass=1.0))
    el = [pinlin.JointSpring(f"joint{i + 1}", 10.0) for i in range(n)]
    el += [pinlin.JointDamper(f"joint{i + 1}", 0.01) for i in range(n)]
    el.append(pinlin.FollowerWrench("tip", force=(0, 0, 0.5)))
    return pinlin.linearize(pinlin.Scene(robot, el), robot.neutral())


def lean_tables(quick: bool) -> tuple[list[Table], dict]:
    """modal_analysis against plain eig (small general systems) and the symmetric path against eigh."""
    dp_robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf())
    dp = pinlin.linearize(pinlin.Scene(dp_robot, [
        pinlin.JointSpring("joint1", 3.0), pinlin.JointSpring("joint2", 2.0), pinlin.JointDamper("joint1", 0.1),
        pinlin.FollowerWrench("tip", force=(0, 0, 4.0))]), dp_robot.neutral())
    cases = [("double pendulum", dp), ("ur5", _robot_system("ur5")), ("panda", _robot_system("panda")),
             ("20-link follower chain", _follower_chain(20))]
    repeats = 201 if quick else 601
    rows, summary = [], {}
    for label, sys in cases:
        A, B = companion_pencil(sys.M, sys.C, sys.K)
        t_eig, t_modal, t_stab, t_cond = interleaved_medians(
            [lambda A=A, B=B: sla.eig(A, B), lambda sys=sys: analyse(sys),
             lambda sys=sys: analyse(sys).stability, lambda sys=sys: analyse(sys).condition],
            repeats if sys.n < 20 else repeats // 3,
            min_time=0.0,  # single calls, alternating
        )
        m = pinlin.modal_analysis(sys)
        rows.append([label, sys.n, m.method.name, t_eig * 1e6, t_modal * 1e6, t_modal / t_eig, t_stab * 1e6,
                     t_stab / t_eig, t_cond * 1e6, t_cond / t_eig, m.max_backward_error])
        summary[f"{label} (n = {sys.n})"] = (
            f"modal_analysis / eig {t_modal / t_eig:.2f}, with .stability read {t_stab / t_eig:.2f} (target <= 1.5)"
        )
        summary.setdefault("_targets", []).append((
            f"modal_analysis at most 1.5x eig, n <= 20: {label} (n = {sys.n})",
            f"{t_modal / t_eig:.2f}x ({t_stab / t_eig:.2f}x with the verdict read), max eta {m.max_backward_error:.1e}",
            bool(t_modal / t_eig <= 1.5), "scipy.linalg.eig(A, B), right vectors"))
    t1 = Table(
        "modal_analysis against a plain scipy.linalg.eig of the companion pencil (right vectors) [us, wall clock, "
        "medians of interleaved single calls]",
        ["case", "n", "path", "eig", "modal_analysis", "ratio", "+ .stability", "ratio", "+ .condition", "ratio",
         "max eta"],
        rows,
        note=("each timed call forms C = D + G and K = S + N afresh (a sweep's new system per point does; the "
              "system caches them, see `analyse`). "
              "modal_analysis computes the eigenvalues, right and left vectors (these L are not symmetric), eta "
              "(`.error`) and the error bound of every pair, the clusters, multiplicities and kinds, and runs every "
              "check that can raise; the structural facts (definiteness of M, D, S, det K), the verdict and the "
              "notes are formed on first access of `.structure`, `.stability` or `.notes` (the '+ .stability' "
              "columns: analysis and verdict), the condition numbers on first access of `.condition`, the verdict's "
              "margin (a bisection) on first access of its `margin`, `reason` or `error`."),
    )
    sym_rows = []
    for n in (20, 50) if quick else (20, 50, 100, 200):
        sys = chain_system(n)
        t_eigh, t_sym, t_stab = interleaved_medians(
            [lambda sys=sys: sla.eigh(sys.S, sys.M), lambda sys=sys: analyse(sys),
             lambda sys=sys: analyse(sys).stability],
            101 if n <= 50 else 21,
            min_time=0.0,  # single calls, alternating
        )
        m = pinlin.modal_analysis(sys)
        w = np.linalg.eigvalsh(sys.M)
        sym_rows.append([n, f"{w[-1] / w[0]:.1e}", t_eigh * 1e3, t_sym * 1e3, t_sym / t_eigh, t_stab / t_eigh,
                         m.max_backward_error, m.method.reason.split("; ")[-1][:70]])
        summary[f"symmetric path n={n}"] = (
            f"{t_sym / t_eigh:.1f}x eigh, with .stability read {t_stab / t_eigh:.1f}x (target <= 3), "
            f"max eta {m.max_backward_error:.1e} (target <= 1e-15)"
        )
        summary.setdefault("_targets", []).append((
            f"symmetric path at most 3x eigh with max eta <= 1e-15: chain n = {n}",
            f"{t_sym / t_eigh:.1f}x ({t_stab / t_eigh:.1f}x with the verdict read), max eta {m.max_backward_error:.1e}",
            bool(t_sym / t_eigh <= 3.0 and m.max_backward_error <= 1e-15), "scipy.linalg.eigh(S, M)"))
    t2 = Table(
        "The symmetric path against bare eigh(S, M) on hanging chains [ms, wall clock, medians of interleaved calls]",
        ["n", "cond(M)", "eigh(S, M)", "modal_analysis (symmetric)", "ratio", "ratio with .stability read",
         "max eta", "how"],
        sym_rows,
        note=("eigh's own backward error grows like eps cond(M) (1e-12 ... 1e-9 here); Newton steps on the pairs "
              "still above eigh_tol = 1e-15 bring them to rounding (a pair already below it is kept). M is factorized "
              "once: its Cholesky factor gives LAPACK's cond(M) estimate for the eigh-or-QZ prediction and the "
              "reduction of the pencil (dsygst, dsyevd, dtrsm: dsygvd's steps); the definiteness of M and S "
              "(an eigvalsh each) is the verdict's, in the '.stability' column."),
    )
    return [t1, t2], summary


def sweep_point(k: float):
    """One sweep point (module level: picklable): the panda with joint stiffness k, linearized and analysed."""
    robot = _panda()
    q = np.asarray(robot.reference_configurations["default"], dtype=float)
    el = []
    for j, qj in zip(robot.joint_names, q):
        el += [pinlin.JointSpring(j, k, rest=float(qj)), pinlin.JointDamper(j, 0.5)]
    el.append(pinlin.FollowerWrench("panda_hand", force=(0.0, 0.0, 5.0)))
    modes = pinlin.modal_analysis(pinlin.linearize(pinlin.Scene(robot, el), q, balancing=True))
    return modes.eigenvalues, modes.stability.kind


@functools.cache
def _panda():
    return pinlin.load_example("panda")


def sweep_table(quick: bool) -> tuple[Table, dict]:
    """A sweep on two processes (chunked, and one point per task) against the same sweep in one process."""
    ks = list(np.linspace(50.0, 500.0, 100 if quick else 400))
    rows = []
    t0 = time.perf_counter()
    serial = pinlin.sweep(sweep_point, {"k": ks}, progress=False)
    t_serial = time.perf_counter() - t0
    with ProcessPoolExecutor(2) as pool:
        pinlin.sweep(sweep_point, {"k": ks[:4]}, executor=pool, progress=False)  # start the workers
        for label, size in (("chunked (automatic)", None), ("one point per task", 1)):
            load = os.getloadavg()[0]
            t0 = time.perf_counter()
            par = pinlin.sweep(sweep_point, {"k": ks}, executor=pool, progress=False, chunk_size=size)
            t_par = time.perf_counter() - t0
            same = all(np.array_equal(a[0], b[0]) and a[1] == b[1] for a, b in zip(serial.values, par.values))
            # the points' own run times where they ran: slower than in the serial run when the workers had
            # to share their processors with other jobs; the ratio estimates the speedup on a free machine
            slowdown = sum(par.point_elapsed) / sum(serial.point_elapsed)
            rows.append([label, len(ks), t_serial, t_par, t_serial / t_par, slowdown, t_serial / t_par * slowdown,
                         same, f"{load:.1f}"])
    table = Table(
        "sweep of (linearize + modal_analysis) over the panda's joint stiffness: 2 processes against 1 [s, wall]",
        ["submission", "points", "one process", "two processes", "speedup", "point time, 2 processes / 1",
         "speedup corrected for contention", "values identical", "load average"],
        rows,
        note=(f"{os.cpu_count()} processors; the load average (1 min, before the run) counts other jobs on the "
              "machine: with a load near 2 two processes cannot run at full speed. The points' own run times, "
              "taken where they ran, show the contention (their ratio to the serial run's); the corrected "
              "speedup multiplies the measured one by it: an estimate for a machine without other jobs."),
    )
    summary_targets = [(
        "sweep of (linearize + modal_analysis) on panda: at least 1.7x on two processes (chunked)",
        f"{rows[0][4]:.2f}x measured (load {rows[0][8]}), {rows[0][6]:.2f}x corrected for contention",
        bool(rows[0][4] >= 1.7), "the same sweep in one process")]
    return table, {"_targets": summary_targets, "sweep speedup on 2 processes": f"{rows[0][4]:.2f} measured, {rows[0][6]:.2f} corrected for "
                   f"contention (chunked); {rows[1][4]:.2f} / {rows[1][6]:.2f} one point per task; target 1.7; "
                   f"identical to serial: {rows[0][7] and rows[1][7]}"}


def run(quick: bool = False) -> Report:
    sizes = SIZES[:2] if quick else SIZES
    repeats = 3 if quick else 5
    rows, eta_rows, other_rows = [], [], []
    summary: dict[str, object] = {}
    for n in sizes:
        sys = chain_system(n)
        M, C, K = sys.M, sys.C, sys.K
        A, B = companion_pencil(M, C, K)
        t_base, t_gen, t_sym = interleaved_medians(
            [
                lambda A=A, B=B: sla.eig(A, B),
                lambda sys=sys: analyse(sys, method="general"),
                lambda sys=sys: analyse(sys),
            ],
            repeats=repeats if n > 100 else 3 * repeats,
            min_time=0.0,  # single calls, alternating
        )
        t_eigh = median_time(lambda sys=sys: sla.eigh(sys.S, sys.M), repeats=repeats)
        gen = pinlin.modal_analysis(sys, method="general")
        uns = pinlin.modal_analysis(sys, method="general", scaling=False)
        sym = pinlin.modal_analysis(sys)
        lam, Z = sla.eig(A, B)
        eta_plain = float(np.max(plain_eta(M, C, K, lam, Z)))
        rows.append([n, t_base * 1e3, t_gen * 1e3, t_sym * 1e3, t_eigh * 1e3, t_gen / t_base, t_gen / t_sym])
        eta_rows.append(
            [n, eta_plain, uns.max_backward_error, gen.max_backward_error, sym.max_backward_error, sym.method.reason[:60]]
        )
        # the other structured paths on the same chain
        rng = np.random.default_rng(n)
        a_, b_ = 0.05, 1e-4
        prop = pinlin.LinearizedSystem(M, a_ * M + b_ * sys.S, np.zeros_like(M), sys.S, np.zeros_like(M))
        Nsk = rng.standard_normal((n, n))
        Nsk = 1e-3 * np.linalg.norm(sys.S) / n * (Nsk - Nsk.T)
        circ = pinlin.LinearizedSystem(M, np.zeros_like(M), np.zeros_like(M), sys.S, Nsk)
        for label, s in (("proportional", prop), ("squared", circ)):
            A2_, B2_ = companion_pencil(s.M, s.C, s.K)
            t_s, t_g, t_e = interleaved_medians(
                [
                    lambda s=s: analyse(s),
                    lambda s=s: analyse(s, method="general"),
                    lambda A=A2_, B=B2_: sla.eig(A, B),
                ],
                repeats=repeats if n > 100 else 3 * repeats,
                min_time=0.0,  # single calls, alternating
            )
            ms, mg = pinlin.modal_analysis(s), pinlin.modal_analysis(s, method="general")
            other_rows.append(
                [n, label, ms.method.name, t_s * 1e3, t_g * 1e3, t_e * 1e3, t_g / t_s, t_g / t_e,
                 ms.max_backward_error, mg.max_backward_error]
            )
        if n >= 50:
            summary.setdefault("_targets", []).append((
                f"general path at most 1.2x eig for n >= 50: chain n = {n}", f"{t_gen / t_base:.2f}x",
                bool(t_gen / t_base <= 1.2), "scipy.linalg.eig(A, B), right vectors"))
        summary[f"n={n}"] = (
            f"general/eig {t_gen / t_base:.2f} (target <= 1.5), general/symmetric {t_gen / t_sym:.1f} (target >= 4); "
            f"max eta: plain eig {eta_plain:.1e}, unscaled QZ {uns.max_backward_error:.1e}, general "
            f"{gen.max_backward_error:.1e}, symmetric {sym.max_backward_error:.1e}"
        )
    t1 = Table(
        "Time per modal analysis of a hanging chain [ms]",
        ["n", "scipy eig (unscaled companion)", "general", "symmetric (auto)", "bare eigh(S, M)", "general / eig",
         "general / symmetric"],
        rows,
        note="Medians in one process.  'general' and 'symmetric' include eta, kappa, clusters and the verdict.",
    )
    t2 = Table(
        "Max backward error eta per path (same chains)",
        ["n", "plain scipy eig", "unscaled QZ (pinlin)", "general (scaled)", "symmetric (auto)", "symmetric path note"],
        eta_rows,
    )
    t3 = Table(
        "Other structured paths against the general path (chain matrices, Rayleigh D or skew N added) [ms]",
        ["n", "case", "path", "structured", "general", "scipy eig (unscaled companion)", "general / structured",
         "general / eig", "max eta structured", "max eta general"],
        other_rows,
        note=(
            "The chain's L is symmetric (and so is the Rayleigh-damped one), so QZ computes right vectors only; with "
            "a skew N ('squared' case) L is not symmetric and the general path also gets left vectors from QZ."
        ),
    )
    # accuracy against a 50-digit reference on small cases
    acc_rows = []
    A2 = np.array([[1, 2, 2], [3, 1, 1], [3, 2, 1.0]])
    A1 = np.array([[3, 2, 1], [2, 1, 3], [1, 3, 2.0]])
    A0 = np.array([[1, 1, 2], [2, 3, 1], [3, 1, 2.0]])
    small = [("theory: spectrum check problem", (A2, A1, A0)), ("chain n=4, stiffness 1e-5..1e5", chain_system(4, seed=3))]
    for label, s in small:
        Mx, Cx, Kx = (s.M, s.C, s.K) if isinstance(s, pinlin.LinearizedSystem) else s
        ref = _mp_roots(Mx, Cx, Kx)
        for meth, kw in (("auto", {}), ("general", {"method": "general"}), ("unscaled", {"method": "general",
                                                                                       "scaling": False})):
            m = pinlin.modal_analysis(s, **kw)
            t = median_time(lambda s=s, kw=kw: analyse(s, **kw), repeats=repeats)
            acc_rows.append([label, meth, m.method.name, t * 1e6, _match_error(m.eigenvalues, ref),
                             float(np.max(m.error_bound / np.maximum(np.abs(m.eigenvalues), 1e-300))),
                             m.max_backward_error])
    t4 = Table(
        "Eigenvalue error against mpmath (50 digits, roots of det L) and run time",
        ["case", "request", "path", "time [us]", "max rel. error", "max rel. bound", "max eta"],
        acc_rows,
    )
    lean, lean_summary = lean_tables(quick)
    sweep_t, sweep_summary = sweep_table(quick)
    targets = lean_summary.pop("_targets", []) + summary.pop("_targets", []) + sweep_summary.pop("_targets", [])
    summary.update(lean_summary)
    summary.update(sweep_summary)
    report = Report("spectral", [*lean, t1, t2, t3, t4, sweep_t], summary)
    for what, measured, met, baseline in targets:
        report.target(14, what, measured, met, baseline)
    return report


if __name__ == "__main__":
    report = run()
    print(report.markdown())
    print("written to", write_report(report))
