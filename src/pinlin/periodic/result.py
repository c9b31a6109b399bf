"""The result of a Floquet analysis: :class:`FloquetAnalysis` (theory: Floquet)."""

from __future__ import annotations

import functools
from dataclasses import dataclass, field

import numpy as np

from ..extras import import_pandas
from ..results import Result
from ..spectral.stability.verdict import Stability

__all__ = ["FloquetAnalysis"]


@dataclass(frozen=True, repr=False, eq=False, kw_only=True)
class FloquetAnalysis(Result):
    """Floquet multipliers of y' = A(t) y, A T-periodic, with error bounds, exponents, frequencies, verdict.

    Attributes
    ----------
    multipliers : ndarray, complex (m,)
        mu_k, eigenvalues of the monodromy Phi(T), largest modulus first; computed from the segment
        transitions (periodic eigenproblem), never from ``monodromy``.
    error_bound : ndarray (m,)
        Bound on |mu_k computed - mu_k exact| (absolute): ``integration_bound + eigensolver_bound +
        orbit_bound``, each a first-order figure (:mod:`pinlin.periodic.bounds`); for the trivial pair of a
        conservative family's orbit (a Jordan block at 1) at least the square-root bound of
        :func:`~pinlin.periodic.bounds.jordan_bound`.
    integration_bound, eigensolver_bound : ndarray (m,)
        Its parts: the integration's estimated error and the eigensolver's backward error, each through
        the multiplier's condition in the periodic eigenproblem.
    orbit_bound : ndarray (m,) or None
        The part from the reference orbit's own error (:mod:`pinlin.periodic.orbit_error`; zeros for
        coefficients given by the caller).
    exponents : ndarray, complex (m,)
        log(mu_k) / T (principal branch) [1/s]; real parts unambiguous, imaginary parts modulo 2 pi / T.
    frequencies : ndarray (m,)
        Im(exponent) + j* 2 pi / T [rad/s] with j* the harmonic carrying most of the mode's energy.
    harmonic_content : ndarray (m, 2 J + 1)
        Energy fraction of harmonic j = -J..J (column j + J) in the periodic part of each mode.
    dominant_harmonic : ndarray of int (m,)
        j* per mode.  These three are formed on first access (from the step data the result keeps, by
        :func:`~pinlin.periodic.harmonics.harmonic_content`): read them, or the table, when you need them.
    trivial : ndarray of bool (m,)
        Multipliers set apart as an autonomous orbit's 1 (and its Jordan partner); excluded from the verdict
        and from ``error``.
    conservative : bool
        The monodromy is known symplectic (the verdict used it).
    stability : Stability
        The verdict (:mod:`pinlin.periodic.floquet_verdict` documents the mapping to the kinds).
    monodromy : ndarray (m, m)
        Phi(T), the formed product of the step transitions (for users; its own eigenvalues lose the small
        multipliers' relative accuracy).
    period : float
        T [s].
    segments : int
        K, the number of segment transitions in the periodic eigenproblem.
    steps : int
        Accepted integration steps.
    evaluations : int
        Calls of the coefficient function(s) (each: one A(t), or one M, C, K triple).
    step_times : ndarray (steps + 1,)
        Step boundaries [s].
    step_errors : ndarray (steps,)
        Estimated 2-norm error of each step transition (absolute; rounding floor included).
    integration_error : float
        max over steps of step_errors / ||P_step||_2: the largest relative local error estimate (what
        ``rtol`` controls).
    elapsed : float
        Wall time [s].
    method : str
    error : float
        max over non-trivial k of error_bound_k / |mu_k|: the largest relative error bound of a multiplier
        (each multiplier's own relative accuracy, whatever its size).

    Examples
    --------
    >>> flo = pinlin.floquet_analysis_matrices([[1.0]], None, lambda t: [[1.3 + 0.4 * np.cos(t)]], 2 * np.pi)
    >>> print(flo.multipliers.shape, flo.steps > 0, flo.error < 1e-10, np.round(flo.exponents.real + 0.0, 6))
    (2,) True True [0. 0.]
    """

    multipliers: np.ndarray
    error_bound: np.ndarray
    integration_bound: np.ndarray
    eigensolver_bound: np.ndarray
    exponents: np.ndarray
    trivial: np.ndarray
    conservative: bool
    stability: Stability
    monodromy: np.ndarray
    period: float
    segments: int
    steps: int
    evaluations: int
    step_times: np.ndarray
    step_errors: np.ndarray
    integration_error: float
    elapsed: float
    method: str
    orbit_bound: np.ndarray | None = None
    deferred: object = field(default=None, repr=False)

    _dict_exclude = ("deferred",)
    _dict_fields = ("multipliers", "error_bound", "integration_bound", "eigensolver_bound", "orbit_bound",
                    "exponents", "frequencies", "harmonic_content", "dominant_harmonic", "trivial", "conservative",
                    "stability", "monodromy", "period", "segments", "steps", "evaluations", "step_times", "step_errors",
                    "integration_error", "elapsed", "method")

    @functools.cached_property
    def _harmonics(self) -> tuple:
        return self.deferred()

    @functools.cached_property
    def frequencies(self) -> np.ndarray:
        return self._harmonics[0]

    @functools.cached_property
    def harmonic_content(self) -> np.ndarray:
        return self._harmonics[1]

    @functools.cached_property
    def dominant_harmonic(self) -> np.ndarray:
        return self._harmonics[2]

    @property
    def error(self) -> float:
        keep = ~self.trivial
        if not keep.any():
            return 0.0
        return float(np.max(self.error_bound[keep] / np.abs(self.multipliers[keep])))

    @property
    def harmonics(self) -> np.ndarray:
        """The harmonic numbers j = -J..J of the columns of ``harmonic_content``."""
        J = (self.harmonic_content.shape[1] - 1) // 2
        return np.arange(-J, J + 1)

    def __repr__(self) -> str:
        r = np.abs(self.multipliers)
        return (f"FloquetAnalysis(m={r.size}, period={self.period:.6g} s, |mu| in [{r.min():.3g}, {r.max():.3g}], "
                f"stability={self.stability.kind!r}, error={self.error:.2e}, steps={self.steps}, "
                f"segments={self.segments}, evaluations={self.evaluations}, elapsed={self.elapsed * 1e3:.3g} ms)")

    def to_pandas(self):
        """One row per multiplier: ``mu_re``, ``mu_im``, ``abs_mu``, ``error_bound``, ``exponent_re`` [1/s],
        ``frequency`` [rad/s] and ``frequency_hz`` [Hz] (the representative chosen by harmonic content),
        ``harmonic`` (its j) and ``share`` (the energy share of that harmonic), ``trivial``.

        Raises
        ------
        MissingDependencyError
            pandas is not installed (``pip install 'pinlin[pandas]'``).

        Examples
        --------
        >>> flo = pinlin.floquet_analysis_matrices([[1.0]], None, lambda t: [[1.3 + 0.4 * np.cos(t)]], 2 * np.pi)
        >>> df = flo.to_pandas()
        >>> df.shape, list(df.columns[:4]), df["harmonic"].tolist()
        ((2, 10), ['mu_re', 'mu_im', 'abs_mu', 'error_bound'], [-1, 1])
        """
        pd = import_pandas()
        J = (self.harmonic_content.shape[1] - 1) // 2
        mu = np.asarray(self.multipliers)
        dominant = np.asarray(self.dominant_harmonic)
        return pd.DataFrame({
            "mu_re": mu.real + 0.0, "mu_im": mu.imag + 0.0, "abs_mu": np.abs(mu), "error_bound": self.error_bound,
            "exponent_re": np.asarray(self.exponents).real + 0.0, "frequency": np.asarray(self.frequencies) + 0.0,
            "frequency_hz": np.asarray(self.frequencies) / (2 * np.pi) + 0.0, "harmonic": dominant,
            "share": self.harmonic_content[np.arange(mu.size), dominant + J], "trivial": np.asarray(self.trivial),
        })

    def table(self) -> str:
        """One line per multiplier: mu, |mu|, its bound, the exponent's real part (0 where it is within its own
        error, bound / (|mu| T)), the chosen frequency in rad/s and Hz, and the share of its harmonic.

        Examples
        --------
        >>> flo = pinlin.floquet_analysis_matrices([[1.0]], None, lambda t: [[1.3 + 0.4 * np.cos(t)]], 2 * np.pi)
        >>> print(flo.table())
          k   multiplier   |mu|   bound   Re exponent   frequency      j*  share
                                          [1/s]         [rad/s]  [Hz]
          0   0.679569...-0.733610...j  1.0000e+00 ... -1.13108  -0.18  -1  0.967
          1   0.679569...+0.733610...j  1.0000e+00 ...  1.13108   0.18   1  0.967
        stability: marginally stable: ...
        """
        lines = [f"{'k':>3} {'multiplier':>34} {'|mu|':>11} {'bound':>9} {'Re exponent':>12} "
                 f"{'frequency':>12} {'':>10} {'j*':>4} {'share':>6}",
                 f"{'':>3} {'':>34} {'':>11} {'':>9} {'[1/s]':>12} {'[rad/s]':>12} {'[Hz]':>10}"]
        J = (self.harmonic_content.shape[1] - 1) // 2
        floor = self.error_bound / np.maximum(np.abs(self.multipliers), np.finfo(float).tiny) / self.period
        for k, mu in enumerate(self.multipliers):
            share = self.harmonic_content[k, self.dominant_harmonic[k] + J]
            note = "  trivial" if self.trivial[k] else ""
            rate = self.exponents[k].real if abs(self.exponents[k].real) > floor[k] else 0.0
            f = self.frequencies[k] + 0.0
            lines.append(f"{k:>3} {complex(mu) + 0.0:>34.10g} {abs(mu):>11.4e} {self.error_bound[k]:>9.2e} "
                         f"{rate + 0.0:>12.5e} {f:>12.6g} {f / (2 * np.pi) + 0.0:>10.4g} "
                         f"{self.dominant_harmonic[k]:>4d} {share:>6.3f}{note}")
        lines.append(f"stability: {self.stability}")
        return "\n".join(lines)
