"""A force given by samples, and the piecewise polynomial that represents it between them.

The exact responses (:func:`~pinlin.forced_response`) and the energy budget
(:func:`~pinlin.energy_budget`) both read a sampled force as a piecewise
polynomial of the time: a first-order hold (``"linear"``, straight lines between
samples) or a cubic spline (``"cubic"``, not-a-knot).  The response is exact
for that polynomial input; how well it represents the true force is the only
approximation.
"""

from __future__ import annotations

from dataclasses import dataclass
from math import factorial

import numpy as np
from scipy.interpolate import CubicSpline

from ..errors import ParameterError

__all__ = ["SampledForce", "INTERPOLATIONS", "check_interpolation", "sample_callable"]

#: Supported readings of a sampled force, with their polynomial degree.
INTERPOLATIONS = {"linear": 1, "cubic": 3}


def check_interpolation(value) -> int:
    """The polynomial degree of a supported reading of a sampled force.

    Raises
    ------
    ParameterError
        ``value`` is not one of :data:`INTERPOLATIONS`.

    Examples
    --------
    >>> from pinlin.response.sampled_force import check_interpolation
    >>> check_interpolation("linear"), check_interpolation("cubic")
    (1, 3)
    """
    if not isinstance(value, str) or value not in INTERPOLATIONS:
        raise ParameterError("interpolation", f"expected one of {sorted(INTERPOLATIONS)}, got {value!r}")
    return INTERPOLATIONS[value]


@dataclass(frozen=True)
class SampledForce:
    """Samples f(t_k) (K, n) of a force, read as a piecewise polynomial of degree 1 or 3.

    Parameters
    ----------
    t : (K,) ndarray
        Strictly increasing sample times [s], K >= 2.
    values : (K, n) ndarray
        Generalized forces [N, N m].
    interpolation : {"linear", "cubic"}

    Examples
    --------
    >>> from pinlin.response.sampled_force import SampledForce
    >>> t = np.linspace(0.0, 1.0, 5)
    >>> force = SampledForce(t, (t**2)[:, None], "linear")
    >>> force(np.array([0.125])), force.degree  # halfway between 0 and 0.0625
    (array([[0.03125]]), 1)
    """

    t: np.ndarray
    values: np.ndarray
    interpolation: str = "linear"

    def __post_init__(self):
        """Raises ParameterError for an unknown interpolation, or 'cubic' with fewer than 4 samples."""
        check_interpolation(self.interpolation)
        if self.interpolation == "cubic" and len(self.t) < 4:
            raise ParameterError("interpolation", f"'cubic' needs at least 4 samples, got {len(self.t)}")

    @property
    def degree(self) -> int:
        return INTERPOLATIONS[self.interpolation]

    def taylor(self) -> np.ndarray:
        """Derivatives at the left end of each interval: (K - 1, degree + 1, n), d_j = f^(j)(t_k+)."""
        f = self.values
        h = np.diff(self.t)
        if self.interpolation == "linear":
            return np.stack([f[:-1], (f[1:] - f[:-1]) / h[:, None]], axis=1)
        c = CubicSpline(self.t, f, axis=0).c  # (4, K - 1, n), highest power first
        return np.stack([c[3], c[2], 2.0 * c[1], 6.0 * c[0]], axis=1)

    def ends(self) -> tuple[np.ndarray, np.ndarray]:
        """(f, f', f'') at both ends of each interval, from that interval's polynomial.

        Returns
        -------
        left, right : (K - 1, 3, n) ndarray
            Values at t_k+ and at t_{k+1}- (derivatives may jump at the samples).
        """
        d = self.taylor()
        h = np.diff(self.t)[:, None]
        left = np.zeros((d.shape[0], 3, d.shape[2]))
        right = np.zeros_like(left)
        left[:, : min(3, d.shape[1])] = d[:, :3]
        for j in range(3):  # Taylor expansion of the j-th derivative to the right end
            for p in range(j, d.shape[1]):
                right[:, j] += d[:, p] * h ** (p - j) / factorial(p - j)
        return left, right

    def __call__(self, tt) -> np.ndarray:
        """The polynomial force at times ``tt`` inside [t_0, t_last]: (len(tt), n)."""
        tt = np.atleast_1d(np.asarray(tt, dtype=float))
        if self.interpolation == "cubic":
            return CubicSpline(self.t, self.values, axis=0)(tt)
        k = np.clip(np.searchsorted(self.t, tt, side="right") - 1, 0, len(self.t) - 2)
        w = ((tt - self.t[k]) / (self.t[k + 1] - self.t[k]))[:, None]
        return (1 - w) * self.values[k] + w * self.values[k + 1]


def sample_callable(f, times: np.ndarray, n: int, label: str = "f") -> np.ndarray:
    """``f(t) -> (n,)`` evaluated at each time: (len(times), n).

    Raises
    ------
    ParameterError
        A call that does not give n finite real numbers (the time is named).

    Examples
    --------
    >>> from pinlin.response.sampled_force import sample_callable
    >>> sample_callable(lambda t: [np.sin(t), 1.0], np.array([0.0, np.pi / 2]), 2)
    array([[0., 1.],
           [1., 1.]])
    """
    out = np.empty((len(times), n))
    for i, ti in enumerate(times):
        try:
            val = np.asarray(f(float(ti)), dtype=float)
        except (TypeError, ValueError) as exc:
            raise ParameterError(label, f"calling f({ti!r}) did not give real numbers: {exc}") from None
        if val.shape != (n,):
            raise ParameterError(label, f"f(t) must return shape ({n},), got {val.shape} at t = {ti!r}")
        if not np.all(np.isfinite(val)):
            raise ParameterError(label, f"f(t) is not finite at t = {ti!r}: {val}")
        out[i] = val
    return out
