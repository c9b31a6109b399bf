"""Which coordinates take part in each mode: their share of its kinetic plus potential energy.

:func:`participation` gives the shares (columns sum to 1);
:meth:`pinlin.spectral.Modes.dominant` and the last column of
:meth:`~pinlin.spectral.Modes.table` list the coordinates above
:data:`DOMINANT_SHARE`.
"""

from __future__ import annotations

import numpy as np

__all__ = ["participation", "DOMINANT_SHARE", "DOMINANT_COUNT"]

#: A coordinate is listed among a mode's dominant coordinates when its participation is at least
#: this share: a tenth of the mode's energy is what a reader acts on (a joint worth stiffening).
DOMINANT_SHARE = 0.1

#: At most this many dominant coordinates per mode in ``table()`` (the row stays one line).
DOMINANT_COUNT = 3


def participation(lam, X, M, S) -> np.ndarray:
    """(n, k) share of each coordinate in the kinetic plus potential energy of each mode (columns sum to 1).

    For a mode (lam, x), its motion Re(x exp(lam t)) carries over a period of its
    oscillation the mean kinetic energy |lam|^2 x^H M x / 4 and potential energy
    x^H S x / 4, which split exactly over the coordinates i:

    .. math::
        T_i = \\tfrac14 |\\lambda|^2 \\operatorname{Re}(\\bar x_i (M x)_i),\\qquad
        V_i = \\tfrac14 \\operatorname{Re}(\\bar x_i (S x)_i),\\qquad
        p_i = \\frac{|T_i| + |V_i|}{\\sum_j (|T_j| + |V_j|)}.

    The magnitudes keep every share in [0, 1] also where T + V vanishes (a
    divergent mode of an undamped system has V = -T).  For an undamped system
    (S x = omega^2 M x, x real) p_i = |x_i (M x)_i| / sum_j |x_j (M x)_j|: the
    usual modal participation m_i x_i^2 / sum_j m_j x_j^2 for a diagonal M, and the
    kinetic (equally potential) energy fraction of each coordinate whenever the
    products x_i (M x)_i are nonnegative.  A mode with T = V = 0 (lam = 0 with
    S x = 0, a rigid-body mode) is shared by |Re(x_i^* (M x)_i)|, its shape's
    kinetic energy.  theory: stability (modal energies).
    """
    X = np.asarray(X)
    kinetic = np.abs((np.conj(X) * (M @ X)).real)
    potential = np.abs((np.conj(X) * (S @ X)).real)
    energy = kinetic * (np.abs(lam) ** 2)[None, :] + potential
    total = energy.sum(axis=0)
    still = ~(total > 0)
    if np.any(still):  # rigid-body modes: the shape's kinetic energy
        energy[:, still] = kinetic[:, still]
        total[still] = kinetic[:, still].sum(axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        return energy / total[None, :]
