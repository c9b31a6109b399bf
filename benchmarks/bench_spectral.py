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

Targets (issue 3): general / baseline <= 1.5; general / symmetric >= 4.  The
three timings of a ratio are interleaved in one loop (medians of the samples).
Errors: max eta of each path, and for small cases the eigenvalue error against
a 50-digit mpmath reference (the roots of det L(lam)).
"""

from __future__ import annotations

import statistics
import time

import numpy as np
import scipy.linalg as sla

import pinlin
from pinlin.spectral.qep import companion_pencil

from .common import Report, Table, median_time, write_report

SIZES = (50, 100, 200)


def chain_system(n: int, seed: int = 0) -> pinlin.LinearizedSystem:
    """n-link hanging chain, total length 1 m, mass 1 kg, joint stiffnesses 10^-5 .. 10^5 N m/rad."""
    rng = np.random.default_rng(seed)
    ks = 10.0 ** rng.uniform(-5, 5, n)
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n, length=1.0, mass=1.0))
    scene = pinlin.Scene(
        robot, [pinlin.JointSpring(f"joint{i + 1}", k) for i, k in enumerate(ks)], gravity=(0, 0, -9.81)
    )
    return pinlin.linearize(scene, robot.neutral())


def interleaved_medians(fns, repeats: int) -> list[float]:
    """Median wall time [s] of each function, timed in turn within each repeat.

    Interleaving keeps a change of machine load (this machine is shared) from
    favouring one side of a ratio; one warm-up call each first.
    """
    for f in fns:
        f()
    samples = [[] for _ in fns]
    for _ in range(repeats):
        for f, out in zip(fns, samples):
            t0 = time.perf_counter()
            f()
            out.append(time.perf_counter() - t0)
    return [statistics.median(s) for s in samples]


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
                lambda sys=sys: pinlin.modal_analysis(sys, method="general"),
                lambda sys=sys: pinlin.modal_analysis(sys),
            ],
            repeats=repeats if n > 100 else 3 * repeats,
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
                    lambda s=s: pinlin.modal_analysis(s),
                    lambda s=s: pinlin.modal_analysis(s, method="general"),
                    lambda A=A2_, B=B2_: sla.eig(A, B),
                ],
                repeats=repeats if n > 100 else 3 * repeats,
            )
            ms, mg = pinlin.modal_analysis(s), pinlin.modal_analysis(s, method="general")
            other_rows.append(
                [n, label, ms.method.name, t_s * 1e3, t_g * 1e3, t_e * 1e3, t_g / t_s, t_g / t_e,
                 ms.max_backward_error, mg.max_backward_error]
            )
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
    small = [("SPEC 4 check problem", (A2, A1, A0)), ("chain n=4, stiffness 1e-5..1e5", chain_system(4, seed=3))]
    for label, s in small:
        Mx, Cx, Kx = (s.M, s.C, s.K) if isinstance(s, pinlin.LinearizedSystem) else s
        ref = _mp_roots(Mx, Cx, Kx)
        for meth, kw in (("auto", {}), ("general", {"method": "general"}), ("unscaled", {"method": "general",
                                                                                       "scaling": False})):
            m = pinlin.modal_analysis(s, **kw)
            t = median_time(lambda s=s, kw=kw: pinlin.modal_analysis(s, **kw), repeats=repeats)
            acc_rows.append([label, meth, m.method.name, t * 1e6, _match_error(m.eigenvalues, ref),
                             float(np.max(m.error_bound / np.maximum(np.abs(m.eigenvalues), 1e-300))),
                             m.max_backward_error])
    t4 = Table(
        "Eigenvalue error against mpmath (50 digits, roots of det L) and run time",
        ["case", "request", "path", "time [us]", "max rel. error", "max rel. bound", "max eta"],
        acc_rows,
    )
    return Report("spectral", [t1, t2, t3, t4], summary)


if __name__ == "__main__":
    report = run()
    print(report.markdown())
    print("written to", write_report(report))
