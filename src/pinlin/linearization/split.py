"""The symmetric and skew parts of C and K, rounding-level parts set to exactly zero (theory: equations).

:func:`split_stiffness` (S, N) and :func:`split_damping` (D, G) for
:func:`~pinlin.linearization.linearize`; what was set to zero and its relative
size go to ``sys.dropped``.  The halving of a skew part is skipped when it is
dropped: its size is half the difference's norm, exactly (a power-of-two scaling).
"""

from __future__ import annotations

import numpy as np

from ..numerics.norms import fro

__all__ = ["split_stiffness", "split_damping", "element_damping_parts", "choose_element_parts"]

_TINY = float(np.finfo(float).tiny)


def _halves(A: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """((A^T + A) / 2, A - A^T and ||A - A^T||_F): the arithmetic of the symmetric/skew split.

    ``A`` may be a block view of a larger matrix; both halves are new arrays.
    """
    difference = A - A.T
    return (A + A.T) / 2, difference, fro(difference)


def split_stiffness(K: np.ndarray, rounding: float, tol: float, dropped: dict) -> tuple[np.ndarray, np.ndarray]:
    """S = (K + K^T) / 2 and N = (K - K^T) / 2, N set to zero when it is at rounding level.

    The reference of N's size is ``rounding``: the norm of the parts of K that
    carry rounding breaking their exact symmetry (Pinocchio's, and the elements'
    whose stiffness is not exactly symmetric).
    """
    S, difference, norm = _halves(K)
    return S, _skew_part(difference, norm, rounding, tol, dropped, "N")


def _skew_part(difference: np.ndarray, norm: float, scale: float, tol: float, dropped: dict, name: str) -> np.ndarray:
    """(A - A^T) / 2 from ``difference`` = A - A^T (halved in place), or zeros when it is at rounding level.

    Its size ||(A - A^T) / 2|| / scale is half the difference's norm, exactly (a
    power-of-two scaling); a nonzero size at or below ``tol`` goes to ``dropped[name]``.
    """
    size = 0.5 * norm / max(scale, _TINY)
    if size <= tol:
        if size:
            dropped[name] = size
        return np.zeros(difference.shape)
    difference *= 0.5
    return difference


def element_damping_parts(C: np.ndarray) -> tuple[np.ndarray, np.ndarray | None, float]:
    """(D, G, ||G|| / ||C||) of the elements' damping C; G None (size 0) when C is exactly symmetric, D then C."""
    D, difference, norm = _halves(C)
    if not norm and not np.count_nonzero(difference):
        return C, None, 0.0
    difference *= 0.5
    return D, difference, 0.5 * norm / max(fro(C), _TINY)


def choose_element_parts(D, G, size: float, tol: float, dropped: dict, zero: np.ndarray):
    """(D, G) of the elements' damping, G replaced by ``zero`` when absent or at rounding level (reported)."""
    if G is None:
        return D, zero
    if size <= tol:
        dropped["G (element rounding)"] = size
        return D, zero
    return D, G


def split_damping(
    C: np.ndarray, base, plan, tol: float, dropped: dict
) -> tuple[np.ndarray, np.ndarray]:
    """D = (C + C^T) / 2 and G = (C - C^T) / 2 with the rounding-level parts set to zero.

    At rest C is the elements' damping: G is their rounding (products that are
    not symmetric in floating point) unless it exceeds ``tol`` of ||C||.  With a
    prescribed velocity, Pinocchio's dtau/dv is skew in exact arithmetic: its
    symmetric part (``coriolis_D``) is dropped from D when at rounding level, and
    G when it is, both against the norm of Pinocchio's part.  Sizes of G are
    half the difference's norm, exactly (a power-of-two scaling).
    """
    if base.coriolis_D is None and not plan.moving and plan.rest_damping is not None:
        return plan.rest_damping.split(tol, dropped)  # constant: split once per scene
    if base.coriolis_D is None:  # C from the elements alone
        return choose_element_parts(*element_damping_parts(C), tol, dropped, np.zeros(C.shape))
    D, difference, norm = _halves(C)
    if plan.undamped:  # C is Pinocchio's alone (coriolis_D is C): D is its symmetric part
        size = fro(D) / max(base.rounding_scale_C, _TINY)
        if size <= tol:
            D = np.zeros(C.shape)  # D - D: exactly zero, D being finite (checked before the split)
    else:
        D_rnea = base.coriolis_D if plan.everything else base.coriolis_D[plan.block]
        size = fro(D_rnea) / max(base.rounding_scale_C, _TINY)
        if size <= tol:  # the Coriolis part of C is skew in exact arithmetic
            D -= D_rnea  # D is a fresh array
    if size <= tol and size:
        dropped["D (Coriolis rounding)"] = size
    return D, _skew_part(difference, norm, base.rounding_scale_C, tol, dropped, "G")
