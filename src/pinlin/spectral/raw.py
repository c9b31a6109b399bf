"""What a solver path hands to the modal analysis: :class:`RawSpectrum` (theory: spectrum).

The general path (:mod:`pinlin.spectral.qep`) and the structured paths
(:mod:`pinlin.spectral.structured`) return one; :mod:`pinlin.spectral.ordering`
orders it and :func:`pinlin.spectral.modal_analysis` attaches the figures.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["RawSpectrum"]


@dataclass(frozen=True, eq=False, kw_only=True)
class RawSpectrum:
    """What a solver path hands to the result: eigenvalues, vectors and products.

    Attributes
    ----------
    lam : (2n,) complex
        Eigenvalues; complex ones come in exactly conjugate pairs.
    P : (4, n, 2n) complex
        Right eigenvectors X (any scaling) and their products M X, C X, K X with
        the original coefficients, stacked (one array: the result permutes and
        normalizes them together).
    Y : (n, 2n) complex or None
        Left (y^T L = 0) eigenvectors, any scaling; None when L(lam) is symmetric
        (M, C, K exactly symmetric), where the left vectors are the right ones.
    block : (2n,) int
        Companion block the right vector was recovered from (1 or 2), 0 for
        structured paths.
    eta : (2n,) float or None
        Backward errors of the pairs when the path computed them (they do not
        depend on the scaling of X), else None.
    note : str
        How the spectrum was obtained when that needs saying (tropical scaling).
    second : (n,) complex or None
        A mirrored spectrum (the structured paths): ``lam``, ``P`` and ``block``
        hold one member of each pair (n of them) and ``second`` the other, which
        shares the (real) vectors and has the same modulus, backward error and
        bound (``lam`` and ``second`` are -lam or conj(lam) of each other); see
        :func:`pinlin.spectral.ordering.mirrored_figures`.  None: every pair is
        stored in full.
    norm_x, weight : (2n,) float or None
        ||x|| of the columns of ``X`` as stored and w(lam) = |lam|^2 ||M|| +
        |lam| ||C|| + ||K||, when the path formed them with ``eta`` (the figures
        reuse them); None otherwise.
    ordered : bool
        True when the path stored the spectrum in the order of
        :func:`pinlin.spectral.ordering.order_spectrum` already (conjugate pairs
        adjacent with exactly conjugate vectors, their figures equal).
    """

    lam: np.ndarray
    P: np.ndarray
    Y: np.ndarray | None
    block: np.ndarray
    eta: np.ndarray | None = None
    note: str = ""
    second: np.ndarray | None = None
    norm_x: np.ndarray | None = None
    weight: np.ndarray | None = None
    ordered: bool = False

    def expanded(self) -> RawSpectrum:
        """The same spectrum with both members of every pair stored (columns (a, b) interleaved)."""
        if self.second is None:
            return self
        k = self.lam.shape[0]
        lam = np.empty(2 * k, dtype=complex)
        lam[0::2], lam[1::2] = self.lam, self.second
        P = np.repeat(self.P.astype(complex), 2, axis=-1)
        return RawSpectrum(lam=lam, P=P, Y=None, block=np.repeat(self.block, 2), note=self.note)

    @property
    def X(self) -> np.ndarray:
        return self.P[0]

    @property
    def MX(self) -> np.ndarray:
        return self.P[1]

    @property
    def CX(self) -> np.ndarray:
        return self.P[2]

    @property
    def KX(self) -> np.ndarray:
        return self.P[3]

    @property
    def left(self) -> np.ndarray:
        """The left vectors (the right ones when L is symmetric)."""
        return self.P[0] if self.Y is None else self.Y
