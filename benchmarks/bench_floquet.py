"""Floquet analysis of periodic scenes against the leanest code a competent user writes.

The baseline: A(t) of the variational equation from bare Pinocchio at each time the integrator asks,
``scipy.integrate.solve_ivp`` (DOP853, rtol 1e-12) on the (2n)^2-dimensional matrix equation
Phi' = A(t) Phi, and ``numpy.linalg.eigvals`` of Phi(T).  pinlin: ``pinlin.floquet_analysis(scene, orbit)`` (M, C, K sampled
once per period and replaced by their trigonometric interpolant, whose measured error enters the bounds;
Gauss-Legendre collocation with step doubling on the interpolant; multipliers from the lifted block-cyclic
problem, error bounds per multiplier), and the same with ``sampling="nodes"`` (Pinocchio evaluated at every
collocation node: the alternative, in rows of its own).  All use the same exact coefficients (Pinocchio's
analytic derivatives), so the comparison is of the sampling, the integration and the eigenvalues.

Rows
----
- **rotor6**: a rigid disk with Ixx != Iyy on an anisotropic support (x, y, z translations and two tilts on
  springs) and a torsionally flexible coupling, driven at constant speed Omega: n = 6, T = 2 pi / Omega.
  Baseline A(t): ``computeRNEADerivatives`` and ``crba`` at (q(t), v(t), 0) on the free coordinates plus the
  joint springs and dampers (the drive is prescribed: forward dynamics of the whole model would not keep it).
- **chain20**: a 20-link pendulum chain hanging from a support that vibrates vertically
  (``pinlin.Harmonic``), joint dampers: n = 20.  Baseline A(t): ``computeABADerivatives`` of the chain on a
  fixed support with the effective gravity g + z_p''(t) (exact for a vertically translating support).
- **chain6**, rotor6 again: the accuracy rows against mpmath.  Both A(t) are trigonometric polynomials of
  low degree (the chain's effective gravity enters linearly; the rotor's inertia turns with the disk), fitted
  exactly from samples (the fit is checked at other times to 1e-13), so a 36-digit Taylor reference integrates
  them exactly; the 20-link chain is too large for mpmath matrices in minutes, and its errors are against
  pinlin at rtol 1e-15 with 8 stages (said in its row).
"""

from __future__ import annotations

import time

import mpmath
import numpy as np
import pinocchio as pin
import scipy.integrate

import pinlin

from .common import Report, Table, Target, interleaved_medians

G = 9.81


# ----------------------------------------------------------------------------- the scenes


def chain_urdf(n: int, length: float = 0.1, mass: float = 0.1) -> str:
    """A support on a vertical prismatic joint ``pivot`` carrying n links hanging along -z (revolute about y)."""
    inertia = f'<inertia ixx="{1e-5}" iyy="{1e-5}" izz="{1e-5}" ixy="0" ixz="0" iyz="0"/>'
    parts = ['<robot name="vibrating_chain">', '<link name="world"/>',
             f'<link name="support"><inertial><mass value="0.5"/>{inertia}</inertial></link>',
             '<joint name="pivot" type="prismatic"><parent link="world"/><child link="support"/>'
             '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1e3" velocity="1e3"/></joint>']
    parent = "support"
    for k in range(1, n + 1):
        offset = "0 0 0" if k == 1 else f"0 0 {-length}"
        parts.append(f'<link name="link{k}"><inertial><origin xyz="0 0 {-length}"/><mass value="{mass}"/>'
                     f'{inertia}</inertial></link>')
        parts.append(f'<joint name="j{k}" type="continuous"><parent link="{parent}"/><child link="link{k}"/>'
                     f'<origin xyz="{offset}"/><axis xyz="0 1 0"/></joint>')
        parent = f"link{k}"
    parts.append("</robot>")
    return "\n".join(parts)


def rotor_urdf() -> str:
    """Support translations x, y, z and tilts about x and y, a drive ``spin`` and a torsional coupling."""
    tiny = '<inertial><mass value="0.01"/><inertia ixx="1e-6" iyy="1e-6" izz="1e-6" ixy="0" ixz="0" iyz="0"/></inertial>'
    chain = [("sx", "prismatic", "1 0 0"), ("sy", "prismatic", "0 1 0"), ("sz", "prismatic", "0 0 1"),
             ("tx", "revolute", "1 0 0"), ("ty", "revolute", "0 1 0"), ("spin", "continuous", "0 0 1"),
             ("torsion", "revolute", "0 0 1")]
    parts = ['<robot name="asymmetric_rotor">', '<link name="world"/>']
    parent = "world"
    for k, (name, kind, axis) in enumerate(chain):
        child = "disk" if k == len(chain) - 1 else f"l_{name}"
        body = ('<inertial><mass value="2.0"/><inertia ixx="0.02" iyy="0.05" izz="0.06" ixy="0" ixz="0" iyz="0"/>'
                '</inertial>') if child == "disk" else tiny
        parts.append(f'<link name="{child}">{body}</link>')
        limit = '<limit lower="-1" upper="1" effort="1e3" velocity="1e3"/>' if kind != "continuous" else ""
        parts.append(f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
                     f'<axis xyz="{axis}"/>{limit}</joint>')
        parent = child
    parts.append("</robot>")
    return "\n".join(parts)


ROTOR_SPRINGS = {"sx": 4.0e3, "sy": 9.0e3, "sz": 6.0e3, "tx": 60.0, "ty": 35.0, "torsion": 25.0}
ROTOR_DAMPING = 0.02  # [N s/m, N m s/rad] on every free joint
ROTOR_SPEED = 23.0    # [rad/s]
CHAIN_DAMPING = 2e-3  # [N m s/rad]: light, the timing rows
HEAVY_DAMPING = 0.02  # [N m s/rad]: the accuracy row, whose multipliers span about 25 decades
SUPPORT = (0.01, 30.0)  # amplitude [m], omega [rad/s] of the support's motion


def rotor_scene(speed: float = ROTOR_SPEED):
    """The rotor driven at ``speed`` [rad/s] (a Campbell diagram varies it)."""
    robot = pinlin.load_urdf_string(rotor_urdf())
    elements = [pinlin.JointSpring(j, k) for j, k in ROTOR_SPRINGS.items()]
    elements += [pinlin.JointDamper(j, ROTOR_DAMPING) for j in ROTOR_SPRINGS]
    return pinlin.Scene(robot, elements, gravity=(0.0, 0.0, 0.0), prescribed={"spin": speed})


def chain_scene(n: int, damping: float = CHAIN_DAMPING):
    robot = pinlin.load_urdf_string(chain_urdf(n))
    elements = [pinlin.JointDamper(f"j{k}", damping) for k in range(1, n + 1)]
    amplitude, omega = SUPPORT
    return pinlin.Scene(robot, elements, gravity=(0.0, 0.0, -G),
                        prescribed={"pivot": pinlin.Harmonic(amplitude, omega)})


# ----------------------------------------------------------------------------- the baselines


def rotor_baseline_A():
    """A(t) from bare Pinocchio for the rotor: RNEA derivatives and crba on the free coordinates."""
    model = pin.buildModelFromXML(rotor_urdf())
    model.gravity = pin.Motion.Zero()
    data = model.createData()
    spin = model.joints[model.getJointId("spin")]
    free = np.array([i for i in range(model.nv) if i != spin.idx_v])
    ix = np.ix_(free, free)
    Ks = np.zeros((model.nv, model.nv))
    for name, k in ROTOR_SPRINGS.items():
        j = model.joints[model.getJointId(name)].idx_v
        Ks[j, j] = k
    Ks, Cs = Ks[ix], ROTOR_DAMPING * np.eye(free.size)
    q, v, a = pin.neutral(model), np.zeros(model.nv), np.zeros(model.nv)
    iq = model.joints[model.getJointId("spin")].idx_q
    v[spin.idx_v] = ROTOR_SPEED
    n = free.size
    top = np.hstack([np.zeros((n, n)), np.eye(n)])

    def A(t):
        q[iq], q[iq + 1] = np.cos(ROTOR_SPEED * t), np.sin(ROTOR_SPEED * t)
        dq, dv, _ = pin.computeRNEADerivatives(model, data, q, v, a)
        M = pin.crba(model, data, q)
        M = np.triu(M) + np.triu(M, 1).T
        X = np.linalg.solve(M[ix], np.hstack([dq[ix] + Ks, dv[ix] + Cs]))
        return np.vstack([top, -X])

    return A, 2 * np.pi / ROTOR_SPEED


def chain_baseline_A(n: int, damping: float = CHAIN_DAMPING):
    """A(t) from bare Pinocchio for the chain: ABA derivatives on a fixed support under g + z_p''(t)."""
    model = pin.buildModelFromXML(chain_urdf(n))
    model = pin.buildReducedModel(model, [model.getJointId("pivot")], pin.neutral(model))
    data = model.createData()
    q, v, tau = pin.neutral(model), np.zeros(model.nv), np.zeros(model.nv)
    amplitude, omega = SUPPORT
    top = np.hstack([np.zeros((n, n)), np.eye(n)])

    def A(t):
        accel = -amplitude * omega**2 * np.sin(omega * t)   # z_p'' of Harmonic(amplitude, omega)
        model.gravity = pin.Motion(np.array([0.0, 0.0, -(G + accel)]), np.zeros(3))
        dq, dv, Minv = pin.computeABADerivatives(model, data, q, v, tau)
        Minv = np.triu(Minv) + np.triu(Minv, 1).T
        return np.vstack([top, np.hstack([dq, dv - damping * Minv])])

    return A, 2 * np.pi / omega


def baseline(A, T, rtol: float = 1e-12):
    m = A(0.0).shape[0]
    sol = scipy.integrate.solve_ivp(lambda t, y: (A(t) @ y.reshape(m, m)).ravel(), (0.0, T), np.eye(m).ravel(),
                                    method="DOP853", rtol=rtol, atol=rtol * 1e-6)
    return np.linalg.eigvals(sol.y[:, -1].reshape(m, m)), sol.nfev


# ----------------------------------------------------------------------------- references


def trig_fit(A, T: float, max_degree: int = 8):
    """A(t) = sum_h C_h cos(h w t) + S_h sin(h w t), w = 2 pi / T, h <= H: the least degree H whose fit (from
    2 H + 1 equally spaced samples, exact for such a polynomial) matches A at two other times to 1e-13
    relative.  Returns (C, S, residual) with C, S of shape (H + 1, m, m)."""
    w = 2 * np.pi / T
    checks = [0.1234 * T, 0.777 * T]
    for H in range(1, max_degree + 1):
        N = 2 * H + 1
        ts = np.arange(N) * T / N
        vals = np.array([A(t) for t in ts])
        C = np.array([2.0 / N * np.tensordot(np.cos(h * w * ts), vals, axes=1) for h in range(H + 1)])
        S = np.array([2.0 / N * np.tensordot(np.sin(h * w * ts), vals, axes=1) for h in range(H + 1)])
        C[0] /= 2.0
        residual = 0.0
        for t in checks:
            fit = sum(C[h] * np.cos(h * w * t) + S[h] * np.sin(h * w * t) for h in range(H + 1))
            exact = A(t)
            residual = max(residual, float(np.linalg.norm(fit - exact) / np.linalg.norm(exact)))
        if residual < 1e-13:
            break
    return C, S, residual


def mp_multipliers(C, S, T: float, *, steps: int, dps: int = 36, product_dps: int = 80) -> np.ndarray:
    """Multipliers over T of y' = A(t) y for the trigonometric polynomial A of :func:`trig_fit`, at ``dps``
    digits: each step's transition summed from its Taylor series ((k + 1) Phi_{k+1} = sum_i A_i Phi_{k-i},
    the A_i from the exact derivatives of cos and sin), the product and its eigenvalues at ``product_dps``
    digits (every multiplier keeps its relative accuracy)."""
    H, m = C.shape[0] - 1, C.shape[1]

    def mp(a):
        return mpmath.matrix([[mpmath.mpf(float(x)) for x in row] for row in a])

    with mpmath.workdps(dps):
        Cm, Sm = [mp(c) for c in C], [mp(s) for s in S]
        w = 2 * mpmath.pi / mpmath.mpf(T)
        h = mpmath.mpf(T) / steps
        tol = mpmath.mpf(10) ** (-dps - 5)
        factors = []
        for j in range(steps):
            t0 = j * h
            coeffs, terms, total, k = [], [mpmath.eye(m)], mpmath.eye(m), 0
            while True:
                Ak = mpmath.zeros(m, m)
                for q in range(H + 1):
                    scale = (q * w) ** k / mpmath.factorial(k)
                    phase = q * w * t0 + k * mpmath.pi / 2
                    Ak += (Cm[q] * mpmath.cos(phase) + Sm[q] * mpmath.sin(phase)) * scale if (q or k == 0) else 0 * Ak
                coeffs.append(Ak)
                nxt = mpmath.zeros(m, m)
                for i in range(k + 1):
                    nxt += coeffs[i] * terms[k - i]
                nxt /= k + 1
                terms.append(nxt)
                k += 1
                contribution = nxt * h**k
                total += contribution
                if k > 4 and mpmath.mnorm(contribution, 1) < tol * mpmath.mnorm(total, 1):
                    break
            factors.append(total)
    with mpmath.workdps(product_dps):
        Phi = mpmath.eye(m)
        for F in factors:
            Phi = F * Phi
        ev = mpmath.eig(Phi, left=False, right=False)
    return np.array(sorted((complex(z) for z in ev), key=lambda z: -abs(z)))


def mp_reference(A, T: float, steps: int):
    """Multipliers over T (mpmath, 36 digits) of the coefficients A fitted exactly by a trigonometric
    polynomial (:func:`trig_fit`), and the fit's residual."""
    C, S, residual = trig_fit(A, T)
    return mp_multipliers(C, S, T, steps=steps), residual


def matched_errors(computed: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """Relative error of each reference multiplier against the nearest computed one."""
    computed = np.asarray(computed)
    return np.array([np.min(np.abs(computed - r)) / abs(r) for r in reference])


# ----------------------------------------------------------------------------- the benchmark


def floquet_call(scene, **options):
    orbit = pinlin.periodic_orbit(scene, pin.neutral(scene.model))
    return orbit, (lambda: pinlin.floquet_analysis(scene, orbit, **options))


def _row(name, scene, A, T, reference, ref_label, repeats, **options):
    orbit, analyse = floquet_call(scene, **options)
    flo = analyse()
    mu_base, nfev = baseline(A, T)
    t_pin, t_base = interleaved_medians([analyse, lambda: baseline(A, T)], repeats=repeats, clock=time.thread_time)
    err_pin = matched_errors(flo.multipliers, reference)
    err_base = matched_errors(mu_base, reference)
    smallest = int(np.argmin(np.abs(reference)))
    contained = bool(np.all(np.array([np.min(np.abs(flo.multipliers - r) - flo.error_bound) <= 0
                                      for r in reference])))
    return [name, scene.n, t_pin * 1e3, t_base * 1e3, t_base / t_pin, float(np.max(err_pin)), float(np.max(err_base)),
            f"{abs(reference[smallest]):.1e}", float(err_pin[smallest]), float(err_base[smallest]),
            flo.evaluations, nfev, "yes" if contained else "NO", ref_label]


def run(quick: bool = False) -> Report:
    repeats = 3 if quick else 5
    rows = []
    rotor = rotor_scene()
    A_rotor, T_rotor = rotor_baseline_A()
    ref_rotor, fit_rotor = mp_reference(A_rotor, T_rotor, steps=24)
    label = f"mpmath 36 digits (trig fit residual {fit_rotor:.0e})"
    rows.append(_row("rotor6", rotor, A_rotor, T_rotor, ref_rotor, label, repeats))
    rows.append(_row("rotor6, sampling='nodes'", rotor, A_rotor, T_rotor, ref_rotor, label, repeats, sampling="nodes"))
    chain6 = chain_scene(6, HEAVY_DAMPING)
    A6, T6 = chain_baseline_A(6, HEAVY_DAMPING)
    ref6, fit6 = mp_reference(A6, T6, steps=24)
    label = f"mpmath 36 digits (trig fit residual {fit6:.0e})"
    rows.append(_row("chain6 (heavily damped)", chain6, A6, T6, ref6, label, repeats))
    rows.append(_row("chain6 (heavily damped), sampling='nodes'", chain6, A6, T6, ref6, label, repeats,
                     sampling="nodes"))
    if not quick:
        chain20 = chain_scene(20)
        A20, T20 = chain_baseline_A(20)
        _, analyse = floquet_call(chain20)
        tight = pinlin.floquet_analysis(chain20, pinlin.periodic_orbit(chain20, pin.neutral(chain20.model)),
                                        rtol=1e-15, stages=8)
        rows.append(_row("chain20", chain20, A20, T20, np.asarray(tight.multipliers),
                         "pinlin rtol 1e-15, 8 stages (mpmath too slow at n = 20)", 3))
    table = Table(
        "Floquet analysis: pinlin against DOP853 (rtol 1e-12) on the matrix equation + eig of the product",
        ["scene", "n", "pinlin [ms]", "baseline [ms]", "speed-up", "max rel err pinlin", "max rel err baseline",
         "smallest |mu|", "its rel err pinlin", "its rel err baseline", "A(t) evals pinlin", "A(t) evals baseline",
         "bounds contain ref", "reference"],
        rows,
        note="Thread CPU medians of interleaved repeats in one process; OPENBLAS_NUM_THREADS=1. Errors: relative "
             "to each reference multiplier, against the nearest computed one.",
    )
    speedups = {r[0]: r[4] for r in rows if "nodes" not in r[0]}
    targets = [Target(23, f"Floquet analysis at least 10x faster than DOP853 + eig on {name}", f"{s:.1f}x",
                      s >= 10.0, "solve_ivp DOP853 rtol 1e-12 on the matrix ODE, bare-Pinocchio A(t), numpy eig")
               for name, s in speedups.items() if not name.startswith("chain6")]
    targets += [Target(23, f"smallest multiplier of {r[0]} accurate where the baseline's is not",
                       f"{r[8]:.1e} against {r[9]:.1e} (|mu| = {r[7]})", r[8] < 1e-6 <= r[9] or r[8] < r[9],
                       "the same") for r in rows if not r[0].startswith("chain20") and "nodes" not in r[0]]
    return Report("floquet", [table], targets=targets)
