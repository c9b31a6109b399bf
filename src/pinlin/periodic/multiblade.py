"""Multi-blade (Coleman) coordinates of N identical, equally spaced blades (theory: Floquet).

Blade k = 1..N at azimuth psi_k = Omega t + psi0 + 2 pi (k - 1) / N carries one coordinate beta_k; the
multi-blade coordinates z (collective beta_0, cyclic beta_jc, beta_js for j = 1..(N-1)/2, and for even N the
differential beta_{N/2}) are defined by

.. math::

    \\beta_k = \\beta_0 + \\sum_j (\\beta_{jc} \\cos j\\psi_k + \\beta_{js} \\sin j\\psi_k)
               + \\beta_{N/2} (-1)^k,

i.e. x = T(psi) z with the other coordinates (hub, support) unchanged.  With T' = dT/dpsi and d/dt = Omega
d/dpsi, x' = T z' + Omega T' z and x'' = T z'' + 2 Omega T' z' + Omega^2 T'' z; projecting the equations with
T^T (virtual work, so that M_z stays symmetric positive definite and a Lagrangian system stays one):

.. math::

    M_z = T^T M T, \\quad C_z = T^T (C T + 2 \\Omega M T'), \\quad
    K_z = T^T (K T + \\Omega C T' + \\Omega^2 M T'').

(T^T T is constant, so these are the T^-1 projections up to a constant diagonal scaling.)  For an isotropic
rotor these are time-invariant whatever the support; the function checks it at several times.
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError
from ..errors.deprecated import renamed_keywords
from ..errors.periodic import MultibladeNotExactError
from .inputs import coefficient

__all__ = ["multiblade_transform_matrices", "multiblade_names", "VARIATION_TOL"]

#: Relative change of a transformed matrix over the checked times below which it counts as constant.
VARIATION_TOL = 1e-10

#: Default check times as fractions of one revolution 2 pi / Omega (irregular, so no symmetry hides a change).
_CHECK_FRACTIONS = (0.0, 0.0731, 0.1912, 0.3377, 0.4809, 0.6254, 0.7718, 0.9105)


def multiblade_names(N: int) -> list:
    """Names of the multi-blade coordinates of N blades, in the order of z.

    Examples
    --------
    >>> from pinlin.periodic.multiblade import multiblade_names
    >>> multiblade_names(4)
    ['blade_collective', 'blade_cos1', 'blade_sin1', 'blade_differential']
    """
    names = ["blade_collective"]
    for j in range(1, (N - 1) // 2 + 1):
        names += [f"blade_cos{j}", f"blade_sin{j}"]
    if N % 2 == 0:
        names.append("blade_differential")
    return names


def _transform(n: int, blades: list, psi: float, N: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """T, dT/dpsi, d2T/dpsi2 (n x n) at rotor azimuth psi; the multi-blade columns replace the blade ones."""
    T, T1, T2 = np.eye(n), np.zeros((n, n)), np.zeros((n, n))
    for k, row in enumerate(blades):
        psi_k = psi + 2 * np.pi * k / N
        T[row, :] = 0.0
        cols = list(blades)
        T[row, cols[0]] = 1.0
        for j in range(1, (N - 1) // 2 + 1):
            c, s = cols[2 * j - 1], cols[2 * j]
            T[row, c], T[row, s] = np.cos(j * psi_k), np.sin(j * psi_k)
            T1[row, c], T1[row, s] = -j * np.sin(j * psi_k), j * np.cos(j * psi_k)
            T2[row, c], T2[row, s] = -j * j * np.cos(j * psi_k), -j * j * np.sin(j * psi_k)
        if N % 2 == 0:
            T[row, cols[-1]] = (-1.0) ** (k + 1)
    return T, T1, T2


def _check_blades(blades, n: int) -> list:
    try:
        out = [int(b) for b in blades]
    except (TypeError, ValueError):
        raise ParameterError("blades", f"expected a list of coordinate indices, got {blades!r}") from None
    if len(out) < 2 or len(set(out)) != len(out) or min(out) < 0 or max(out) >= n:
        raise ParameterError("blades", f"expected N >= 2 distinct indices in 0..{n - 1} (one per blade), got {out}")
    return out


@renamed_keywords(tolerance="variation_tol")
def multiblade_transform_matrices(M, C, K, blades, omega, *, psi0: float = 0.0, check_times=None,
                                  dof_names=None, variation_tol: float = VARIATION_TOL):
    """The time-invariant system in multi-blade coordinates of a rotor given in blade coordinates.

    Parameters
    ----------
    M, C, K : callable or array_like
        t [s] -> (n, n) arrays of M(t) x'' + C(t) x' + K(t) x = 0 in blade coordinates.
    blades : sequence of int
        The coordinate index of each blade, blade k (k = 1..N, in this order) at azimuth
        psi_k = omega t + psi0 + 2 pi (k - 1) / N.
    omega : float
        Rotor speed Omega [rad/s] (nonzero).
    psi0 : float
        Azimuth of blade 1 at t = 0 [rad].
    check_times : sequence of float or None
        Times [s] at which the transformed matrices are compared (default: 8 irregular times over one
        revolution).
    dof_names : sequence of str or None
        Names of the original coordinates (default x0, x1, ...); the blade ones are replaced by
        :func:`multiblade_names`.
    variation_tol : float
        Allowed relative change of M_z, C_z, K_z between check times (``tolerance`` is its deprecated
        spelling).

    Returns
    -------
    LinearizedSystem
        ``from_matrices(M_z, C_z, K_z)`` at the first check time, coordinates z in the positions of x (the
        blade positions, in order, hold collective, cos1, sin1, ..., differential).

    Raises
    ------
    ParameterError
        Bad matrices, blades, omega or names.
    MultibladeNotExactError
        The transformed matrices change with time (N = 2, dissimilar or unequally spaced blades): use
        Floquet analysis (:func:`pinlin.periodic.floquet_analysis_matrices`) instead.

    Examples
    --------
    Three identical uncoupled blades (M = I, K = 4 I) turning at 3 rad/s: collective and cyclic coordinates,
    the cyclic ones with the gyroscopic coupling 2 Omega and the stiffness lowered by Omega^2:

    >>> sys = pinlin.multiblade_transform_matrices(np.eye(3), np.zeros((3, 3)), 4.0 * np.eye(3), [0, 1, 2], 3.0)
    >>> print(sys.dof_names, np.diag(sys.K) + 0.0, np.round(sys.G[1, 2] / sys.M[1, 1], 6))
    ('blade_collective', 'blade_cos1', 'blade_sin1') [12.  -7.5 -7.5] 6.0
    """
    from ..linearization import LinearizedSystem

    fM, shape = coefficient("M", M)
    fC, _ = coefficient("C", C, shape)
    fK, _ = coefficient("K", K, shape)
    n = shape[0]
    blades = _check_blades(blades, n)
    N = len(blades)
    if not (isinstance(omega, (int, float, np.integer, np.floating)) and np.isfinite(omega) and omega != 0):
        raise ParameterError("omega", f"expected a finite nonzero rotor speed [rad/s], got {omega!r}")
    names = [f"x{i}" for i in range(n)] if dof_names is None else [str(s) for s in dof_names]
    if len(names) != n:
        raise ParameterError("dof_names", f"expected {n} names, got {len(names)}")
    for row, name in zip(blades, multiblade_names(N)):
        names[row] = name
    times = [f * 2 * np.pi / abs(omega) for f in _CHECK_FRACTIONS] if check_times is None else list(check_times)
    mats = []
    for t in times:
        T, T1, T2 = _transform(n, blades, omega * t + psi0, N)
        Mt, Ct, Kt = fM(t), fC(t), fK(t)
        mats.append((T.T @ Mt @ T, T.T @ (Ct @ T + 2 * omega * Mt @ T1),
                     T.T @ (Kt @ T + omega * Ct @ T1 + omega ** 2 * Mt @ T2)))
    for i, label in enumerate("MCK"):
        ref = mats[0][i]
        scale = max(np.linalg.norm(ref), np.linalg.norm(mats[0][0]) * 1e-300, np.finfo(float).tiny)
        variation = max(np.linalg.norm(m[i] - ref) for m in mats) / scale
        if variation > variation_tol:
            raise MultibladeNotExactError(
                f"the multi-blade transform of {N} blades is not exact here: {label}_z changes by {variation:.2e} "
                f"(relative) over the checked times (variation_tol {variation_tol:g}); N = 2, dissimilar or unequally "
                f"spaced blades keep periodic coefficients: use Floquet analysis (floquet_analysis_matrices)",
                label, variation, variation_tol)
    return LinearizedSystem.from_matrices(*mats[0], dof_names=names)
