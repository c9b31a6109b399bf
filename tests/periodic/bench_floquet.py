"""Benchmark (run by hand, not collected): monodromy by pinlin.periodic against scipy's DOP853 on the m^2
matrix ODE, for smooth periodic second-order systems with m = 2 n = 12 and 40.

    OPENBLAS_NUM_THREADS=1 PYTHONPATH=src python tests/periodic/bench_floquet.py [dop853_rtol [cost_per_evaluation_s]]

Accuracy: the relative 2-norm error of Phi(T) against pinlin at s = 8, rtol = 1e-15 (checked against DOP853
at rtol = 1e-13 for m = 12), and the largest relative multiplier error.
"""

from __future__ import annotations

import sys
import time

import numpy as np
import scipy.integrate

from pinlin.periodic import floquet_analysis_matrices


def system(n: int, seed: int = 7):
    rng = np.random.default_rng(seed)
    X = rng.standard_normal((n, n)) / np.sqrt(n)
    Y, Z, W = (rng.standard_normal((n, n)) / np.sqrt(n) for _ in range(3))
    M0 = np.eye(n) + 0.1 * X @ X.T
    K0 = np.diag(np.linspace(1.0, 9.0, n)) + 0.2 * (Y + Y.T)
    C0 = 0.05 * K0 + 0.3 * (Z - Z.T)

    def M(t):
        return M0 + 0.05 * np.cos(t) * np.eye(n)

    def C(t):
        return C0 + 0.1 * np.sin(t) * (W - W.T)

    def K(t):
        return K0 + 0.3 * np.cos(t) * (Y + Y.T) + 0.2 * np.sin(2 * t) * np.eye(n)
    return M, C, K


def first_order(M, C, K, n):
    calls = [0]

    def A(t):
        calls[0] += 1
        X = np.linalg.solve(M(t), np.hstack([K(t), C(t)]))
        out = np.zeros((2 * n, 2 * n))
        out[:n, n:] = np.eye(n)
        out[n:, :n], out[n:, n:] = -X[:, :n], -X[:, n:]
        return out
    return A, calls


def dop853(A, m, T, rtol):
    sol = scipy.integrate.solve_ivp(lambda t, y: (A(t) @ y.reshape(m, m)).ravel(), (0, T), np.eye(m).ravel(),
                                    method="DOP853", rtol=rtol, atol=rtol * 1e-3)
    return sol.y[:, -1].reshape(m, m)


REPEATS = 3


def _costly(f, cost: float):
    """f with ``cost`` [s] of busy waiting added per call (a Pinocchio evaluation of that price)."""
    def g(t):
        end = time.perf_counter() + cost
        while time.perf_counter() < end:
            pass
        return f(t)
    return g if cost > 0 else f


def main(sizes=(6, 20), dop_rtol: float = 1e-12, cost: float = 0.0):
    T = 2 * np.pi
    for n in sizes:
        m = 2 * n
        M, C, K = system(n)
        M = _costly(M, cost)
        ref = floquet_analysis_matrices(M, C, K, T, stages=8, rtol=1e-15)
        t_pin, t_dop = np.inf, np.inf
        for _ in range(REPEATS):         # the best of a few: the host is shared
            t0 = time.perf_counter()
            res = floquet_analysis_matrices(M, C, K, T)
            t_pin = min(t_pin, time.perf_counter() - t0)
            A, calls = first_order(M, C, K, n)
            t0 = time.perf_counter()
            Phi = dop853(A, m, T, dop_rtol)
            t_dop = min(t_dop, time.perf_counter() - t0)
        norm = np.linalg.norm(ref.monodromy, 2)
        err_pin = np.linalg.norm(res.monodromy - ref.monodromy, 2) / norm
        err_dop = np.linalg.norm(Phi - ref.monodromy, 2) / norm
        mu_dop = np.linalg.eigvals(Phi)
        rel_mu = max(np.min(np.abs(mu_dop - x)) / abs(x) for x in ref.multipliers)
        rel_pin = np.max(np.abs(res.multipliers - ref.multipliers) / np.abs(ref.multipliers))
        print(f"m = {m} (evaluation cost + {cost * 1e6:.0f} us): pinlin {t_pin * 1e3:.1f} ms, "
              f"{res.evaluations} evaluations, {res.steps} steps, "
              f"Phi rel err {err_pin:.1e}, multiplier rel err {rel_pin:.1e} (bound {res.error:.1e}); "
              f"DOP853 rtol {dop_rtol:g} {t_dop * 1e3:.1f} ms, {calls[0]} evaluations, Phi rel err {err_dop:.1e}, "
              f"multiplier rel err {rel_mu:.1e}; speed-up {t_dop / t_pin:.1f}x")
        sys.stdout.flush()


if __name__ == "__main__":
    main(dop_rtol=float(sys.argv[1]) if len(sys.argv) > 1 else 1e-12,
         cost=float(sys.argv[2]) if len(sys.argv) > 2 else 0.0)
