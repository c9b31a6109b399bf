"""Frequency responses (modal against direct, and against python-control) and the characteristic polynomial.

1. Frequency response of a 100-link hanging chain (1 m, 1 kg, a 0.01 N m s/rad
   damper per joint) at 2000 frequencies (log-spaced, 0.1 ... 1e4 rad/s):
   ``pinlin.frequency_response(method="modal")`` (the spectral sum over the 2n
   Lancaster-normalized modes of :func:`pinlin.modal_analysis`) against
   ``method="direct"`` (one LU factorization of L(i omega) per frequency), for
   one input and one output (tip torque to tip angle), one input and every
   output, and the full matrix (every input and output, 200 frequencies).
   Times are medians of repeats in one process; the modal time excludes the
   eigensolution, whose time is listed apart (it is paid once per system).
   Target: modal at least 20x faster, relative difference below 1e-10
   away from resonances (|i omega - lam_k| > 1e-2 |lam_k| for every k).  The
   difference is normwise over the input's column (both methods are backward
   stable, so accurate normwise; a far entry H[0, 99] is 1e-11 of its column at
   low frequency and has no relative accuracy in either).  The full run also
   measures both against a 50-digit mpmath solve at a few frequencies.
2. The direct method against python-control: the same 100-link
   chain with springs, light dampers and a follower force at the tip (a
   non-symmetric L), 2000 frequencies, one input and one output and the full
   matrix; python-control's ``StateSpace.frequency_response`` on the first-order
   model (A = [[0, I], [-M^-1 K, -M^-1 C]]), which uses slycot's ``tb05ad``
   (Hessenberg reduction once, a Hessenberg solve per frequency; Laub 1981)
   when slycot is installed, as here; pinlin's direct method (LU per point for
   few points, one generalized Schur form and quasi-triangular solves for many)
   and the modal method (the eigensolution reused; its check exact at 32
   sampled frequencies and a bound at the others).  Interleaved medians.
3. The characteristic polynomial ``p = det L`` of chains as n grows: maximum
   relative coefficient error against det M prod (lam - lam_k) with 50-digit
   eigenvalues of the companion matrix, for pinlin's multi-circle FFT and for a
   single well-scaled circle; whether the reported bound covers the error; and
   the eigenvalue error of the roots of p against the spectral module's QEP
   solver (why the roots of p are no eigensolver).
"""

from __future__ import annotations

import mpmath as mp
import numpy as np
from numpy.polynomial import Polynomial

import pinlin
from pinlin.adjoint import characteristic_polynomial
from pinlin.testing import mp_characteristic_coefficients

from .common import Report, Table, interleaved_medians, median_time, write_report

RESONANCE_FRACTION = 1e-2
#: Upper end [rad/s] of the band reported separately (above it the stiff, overdamped joint-damper
#: modes, real eigenvalues up to 5e5 1/s with condition numbers up to 1e4, dominate the response).
BAND = 1e3


def chain(n: int, damping: float = 0.01) -> pinlin.LinearizedSystem:
    scene = pinlin.Scene(
        pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n)),
        [pinlin.JointDamper(f"joint{i + 1}", damping) for i in range(n)],
    )
    return pinlin.linearize(scene, scene.neutral())


def _away(omega: np.ndarray, eigenvalues: np.ndarray) -> np.ndarray:
    d = np.abs(1j * omega[:, None] - eigenvalues[None, :]) / np.maximum(np.abs(eigenvalues), 1e-300)[None, :]
    return d.min(axis=1) > RESONANCE_FRACTION


def _column_difference(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Per input and frequency: ||a[:, i, f] - b[:, i, f]|| / ||b[:, i, f]||."""
    return np.linalg.norm(a - b, axis=0) / np.linalg.norm(b, axis=0)


def _mp_column(sys, s: complex, col: int, dps: int = 50) -> np.ndarray:
    n = sys.n
    with mp.workdps(dps):
        z = mp.mpc(s.real, s.imag)
        L = mp.matrix(
            [[z * z * mp.mpf(sys.M[i, j]) + z * mp.mpf(sys.C[i, j]) + mp.mpf(sys.K[i, j]) for j in range(n)] for i in range(n)]
        )
        e = mp.matrix(n, 1)
        e[col] = 1
        x = mp.lu_solve(L, e)
        return np.array([complex(x[i]) for i in range(n)])


def frequency_response_table(quick: bool) -> tuple[Table, Table | None, dict]:
    n = 40 if quick else 100
    n_freq = 400 if quick else 2000
    sys = chain(n)
    modes = pinlin.modal_analysis(sys)
    t_modes = median_time(lambda: pinlin.modal_analysis(sys), repeats=3)
    omega = np.logspace(-1, 4, n_freq)
    away = _away(omega, modes.eigenvalues)
    tip = n - 1
    configs = [
        ("tip torque -> tip angle (SISO)", [tip], [tip], omega),
        ("tip torque -> all angles (SIMO)", [tip], None, omega),
        ("all -> all (full H)", None, None, omega[:: max(1, n_freq // 200)]),
    ]
    repeats = 3 if quick else 5
    rows = []
    summary = {}
    for label, inputs, outputs, w in configs:
        mask = _away(w, modes.eigenvalues)

        def direct(w=w, inputs=inputs, outputs=outputs, check=False):
            return pinlin.frequency_response(sys, w, inputs, outputs, check=check)

        def modal(w=w, inputs=inputs, outputs=outputs, check=False):
            return pinlin.frequency_response(sys, w, inputs, outputs, method="modal", modes=modes, check=check)

        t_direct = median_time(direct, repeats=repeats)
        t_modal = median_time(modal, repeats=repeats)
        t_modal_checked = median_time(lambda: modal(check=True), repeats=repeats)
        # differences on full columns (all outputs) of the same inputs
        d_full = pinlin.frequency_response(sys, w, inputs, None, check=True)
        m_full = pinlin.frequency_response(sys, w, inputs, None, method="modal", modes=modes, check=True)
        diff = _column_difference(m_full.response, d_full.response)
        diff_away = float(np.max(diff[:, mask])) if np.any(mask) else float("nan")
        band = mask & (w <= BAND)
        diff_band = float(np.max(diff[:, band])) if np.any(band) else float("nan")
        ins = d_full.inputs
        driving_d = d_full.response[ins, np.arange(len(ins))]  # H[i, i] for each input i: (m, F)
        driving_m = m_full.response[ins, np.arange(len(ins))]
        driving = np.abs(driving_m - driving_d) / np.abs(driving_d)
        rows.append(
            [
                label,
                len(w),
                t_direct * 1e3,
                t_modal * 1e3,
                t_direct / t_modal,
                t_direct / (t_modal + t_modes),
                t_modal_checked * 1e3,
                diff_away,
                diff_band,
                float(np.max(diff)),
                float(np.max(driving[:, mask])) if np.any(mask) else float("nan"),
                d_full.error,
                m_full.error,
            ]
        )
        summary[label] = (
            f"modal {t_direct / t_modal:.0f}x faster than direct "
            f"({t_direct / (t_modal + t_modes):.1f}x including the eigensolution); "
            f"max column difference away from resonances {diff_away:.1e}"
        )
    table = Table(
        f"frequency response of the {n}-link chain ({n_freq} frequencies 0.1 ... 1e4 rad/s): modal vs direct",
        [
            "inputs -> outputs",
            "frequencies",
            "direct [ms]",
            "modal [ms]",
            "direct / modal",
            "direct / (modal + eigensolution)",
            "modal with residual check [ms]",
            "max column rel. diff (away from resonances)",
            f"same, omega <= {BAND:g} rad/s",
            "max column rel. diff (all)",
            "max rel. diff of driving-point entries H[i, i] (away)",
            "direct residual",
            "modal residual",
        ],
        rows,
        note=(
            f"Eigensolution (pinlin.modal_analysis, {modes.method.name} path) took {t_modes * 1e3:.1f} ms, once. "
            f"{int(np.sum(~away))} of {n_freq} frequencies are within {RESONANCE_FRACTION:g} |lam_k| of an "
            f"eigenvalue (excluded from 'away'). Timed calls skip the residual check (check=False) unless stated. "
            f"Column difference: ||H_modal[:, i] - H_direct[:, i]|| / ||H_direct[:, i]||; entries many orders "
            f"below their column (H[0, tip] at low frequency) have no relative accuracy in either method, "
            f"so the entrywise column shows the driving-point entries H[i, i] of the inputs i only. "
            f"Residual: max over frequencies of ||L H_c - I_c|| / (||L|| ||H_c||)."
        ),
    )
    summary["eigensolution [ms]"] = f"{t_modes * 1e3:.1f}"
    ref_table = None
    if not quick:
        ref_rows = []
        probe = omega[np.linspace(0, n_freq - 1, 4).astype(int)]
        resp_d = pinlin.frequency_response(sys, probe, [tip], None)
        resp_m = pinlin.frequency_response(sys, probe, [tip], None, method="modal", modes=modes)
        for k, w in enumerate(probe):
            ref = _mp_column(sys, 1j * w, tip)
            nr = np.linalg.norm(ref)
            ref_rows.append(
                [
                    w,
                    float(np.linalg.norm(resp_d.response[:, 0, k] - ref) / nr),
                    float(np.linalg.norm(resp_m.response[:, 0, k] - ref) / nr),
                    float(abs(resp_d.response[tip, 0, k] - ref[tip]) / abs(ref[tip])),
                    float(abs(resp_m.response[tip, 0, k] - ref[tip]) / abs(ref[tip])),
                ]
            )
        ref_table = Table(
            f"errors against a 50-digit mpmath solve ({n}-link chain, tip torque column)",
            ["omega [rad/s]", "direct, column", "modal, column", "direct, tip entry", "modal, tip entry"],
            ref_rows,
            note="Relative errors: column normwise, and of the driving-point entry H[tip, tip].",
        )
    return table, ref_table, summary


def follower_chain(n: int) -> pinlin.LinearizedSystem:
    """n links, joint springs 10 N m/rad, dampers 0.01 N m s/rad, a 0.5 N follower force at the tip."""
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n, length=1.0, mass=1.0))
    el = [pinlin.JointSpring(f"joint{i + 1}", 10.0) for i in range(n)]
    el += [pinlin.JointDamper(f"joint{i + 1}", 0.01) for i in range(n)]
    el.append(pinlin.FollowerWrench("tip", force=(0, 0, 0.5)))
    return pinlin.linearize(pinlin.Scene(robot, el), robot.neutral())


def w_count(quick: bool) -> int:
    """Frequencies of the python-control comparison."""
    return 400 if quick else 2000


def python_control_table(quick: bool) -> tuple[Table, dict]:
    """pinlin's direct and modal frequency responses against python-control (with slycot when installed)."""
    import warnings

    import control

    try:
        import slycot  # noqa: F401

        engine = "slycot tb05ad (Hessenberg, Laub 1981)"
    except ImportError:
        engine = "python-control without slycot (its fallback solver)"
    n = 40 if quick else 100
    sys = follower_chain(n)
    w = np.linspace(0.1, 50.0, w_count(quick))
    Minv = np.linalg.inv(sys.M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ sys.K, -Minv @ sys.C]])
    modes = pinlin.modal_analysis(sys)
    rows, summary = [], {}
    for label, ins, outs in (("SISO: joint1 torque -> tip angle", [0], [n - 1]), ("full H", None, None)):
        m = 1 if ins else n
        B = np.vstack([np.zeros((n, m)), Minv[:, :m] if ins else Minv])
        Cm = np.hstack([np.eye(n)[[n - 1]] if outs else np.eye(n), np.zeros((1 if outs else n, n))])
        ss = control.ss(A, B, Cm, 0)
        calls = {
            "python-control": lambda ss=ss: ss.frequency_response(w),
            "direct, checked": lambda ins=ins, outs=outs: pinlin.frequency_response(sys, w, ins, outs),
            "direct, unchecked": lambda ins=ins, outs=outs: pinlin.frequency_response(sys, w, ins, outs, check=False),
            "modal, sampled check": lambda ins=ins, outs=outs: pinlin.frequency_response(
                sys, w, ins, outs, method="modal", modes=modes),
            "modal, unchecked": lambda ins=ins, outs=outs: pinlin.frequency_response(
                sys, w, ins, outs, method="modal", modes=modes, check=False),
        }
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # (a modal bound above tol warns; the figures are in the table)
            times = dict(zip(calls, interleaved_medians(list(calls.values()), repeats=3 if quick else 5,
                                                        min_time=0.0)))
            direct = pinlin.frequency_response(sys, w, ins, outs)
            modal = pinlin.frequency_response(sys, w, ins, outs, method="modal", modes=modes)
        ref = ss.frequency_response(w).complex.reshape(direct.response.shape)
        diff = float(np.max(np.abs(ref - direct.response)) / np.max(np.abs(direct.response)))
        rows.append([label, w.size, *(times[k] * 1e3 for k in calls), times["python-control"] / times["direct, checked"],
                     direct.error, modal.error, diff])
        summary[f"_ratio {label}"] = times["python-control"] / times["direct, checked"]
        if ins is None and outs is None:  # full H = L(s)^-1: the exact defect at every point against the figure
            summary["_modal defect bound"] = (_max_defect(sys, w, modal.response), modal.error)
        summary[label] = (
            f"direct (checked) {times['python-control'] / times['direct, checked']:.2f}x the speed of python-control "
            f"({engine}); unchecked {times['python-control'] / times['direct, unchecked']:.2f}x; modal unchecked "
            f"{times['python-control'] / times['modal, unchecked']:.1f}x"
        )
    table = Table(
        f"frequency response of the {n}-link follower chain ({w.size} frequencies): pinlin against python-control [ms]",
        ["case", "frequencies", "python-control", "direct, checked", "direct, unchecked", "modal, sampled check",
         "modal, unchecked", "python-control / direct (checked)", "direct error (max defect)",
         "modal error (bound)", "max abs(H_control - H_direct) / max abs(H)"],
        rows,
        note=(
            f"python-control {control.__version__} on the first-order model, through {engine}; it needs M^-1 "
            f"(the difference to pinlin, 1e-7 here, is that of forming M^-1 K with cond(M) = "
            f"{np.linalg.cond(sys.M):.1e}). pinlin's modal method reuses one modal analysis "
            f"({modes.elapsed * 1e3:.1f} ms, not included). Interleaved medians in one process, one BLAS thread."
        ),
    )
    return table, summary


def _max_defect(sys, w: np.ndarray, H: np.ndarray) -> float:
    """max over omega of ||L(i w) H - I||_F / (||L(i w)||_F ||H||_F + ||I||_F), the defect of a full H."""
    n = sys.n
    worst = 0.0
    for k, wk in enumerate(w):
        s = 1j * wk
        L = s * s * sys.M + s * sys.C + sys.K
        Hk = H[k] if H.shape[0] == w.size else H[:, :, k]
        r = np.linalg.norm(L @ Hk - np.eye(n)) / (np.linalg.norm(L) * np.linalg.norm(Hk) + np.sqrt(n))
        worst = max(worst, float(r))
    return worst


def _eig_error(approx: np.ndarray, ref: np.ndarray) -> float:
    """Largest relative distance from a reference eigenvalue to the nearest approximation."""
    d = np.abs(ref[:, None] - approx[None, :]).min(axis=1)
    return float(np.max(d / np.maximum(np.abs(ref), 1e-300)))


def polynomial_table(quick: bool) -> tuple[Table, dict]:
    sizes = (1, 2, 4, 6, 8) if quick else (1, 2, 4, 6, 8, 10, 12, 15, 20)
    rows = []
    worst = {}
    for n in sizes:
        sys = chain(n)
        ref, ref_ev = mp_characteristic_coefficients(sys)
        p = characteristic_polynomial(sys)
        t_p = median_time(lambda sys=sys: characteristic_polynomial(sys), repeats=3)
        rel = np.abs(p.coef - ref) / np.abs(ref)
        covered = bool(np.all(np.abs(p.coef - ref) <= p.coef_error))
        rho = abs(np.linalg.det(sys.K) / np.linalg.det(sys.M)) ** (1 / (2 * n))
        single = characteristic_polynomial(sys, radii=[rho])
        rel_single = np.abs(single.coef - ref) / np.abs(ref)
        modes = pinlin.modal_analysis(sys)
        rows.append(
            [
                n,
                float(np.max(rel)),
                float(np.max(p.relative_coef_error)),
                "yes" if covered else "NO",
                float(np.max(rel_single)),
                float(np.abs(ref).max() / np.abs(ref).min()),
                t_p * 1e3,
                p.evaluations,
                _eig_error(Polynomial(p.coef).roots(), ref_ev),
                _eig_error(modes.eigenvalues, ref_ev),
            ]
        )
        worst[n] = float(np.max(rel))
    table = Table(
        "characteristic polynomial of pendulum chains: accuracy as n grows",
        [
            "n",
            "max rel. coefficient error (multi-circle FFT)",
            "reported max rel. bound",
            "bound covers error",
            "max rel. coefficient error (one circle)",
            "coefficient range max/min",
            "time [ms]",
            "determinants",
            "roots of p: max rel. eigenvalue error",
            "modal_analysis: max rel. eigenvalue error",
        ],
        rows,
        note=(
            "Reference: det M prod(lam - lam_k) with 50-digit eigenvalues of the companion matrix (mpmath). "
            "One circle: radius |det K / det M|^(1/2n), the geometric mean of the eigenvalue moduli. The "
            "coefficients stay accurate relative to themselves, yet their roots lose accuracy fast "
            "(the roots of a polynomial are ill-conditioned functions of its coefficients). A 100-link chain's "
            "coefficients are not representable in double precision at all (det M is about 1e-620 in SI units)."
        ),
    )
    return table, {f"p(lam) max rel. coefficient error, n = {n}": f"{e:.1e}" for n, e in worst.items()}


def run(quick: bool = False) -> Report:
    fr_table, ref_table, summary = frequency_response_table(quick)
    pc_table, pc_summary = python_control_table(quick)
    ratios = {k[len("_ratio "):]: pc_summary.pop(k) for k in list(pc_summary) if k.startswith("_ratio ")}
    defect, bound = pc_summary.pop("_modal defect bound")
    summary.update(pc_summary)
    p_table, p_summary = polynomial_table(quick)
    summary.update(p_summary)
    tables = [fr_table] + ([ref_table] if ref_table is not None else []) + [pc_table, p_table]
    report = Report("adjoint", tables, summary)
    n = 40 if quick else 100
    for label, ratio in ratios.items():
        report.target(14, f"direct frequency response at least as fast as python-control ({label}, n = {n})",
                      f"{ratio:.2f}x its speed", bool(ratio >= 1.0), "python-control + slycot tb05ad")
    report.target(14, f"modal method: its check sampled, its error figure (max relative defect) still a bound "
                  f"(full H, n = {n}, {w_count(quick)} frequencies)",
                  f"figure {bound:.1e} >= actual max defect {defect:.1e}", bool(defect <= bound),
                  "the defect computed at every frequency")
    return report


if __name__ == "__main__":
    report = run()
    print(report.markdown())
    print("written to", write_report(report))
