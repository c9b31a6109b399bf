"""Tables of a modal analysis: one record per eigenvalue, as plain data or a pandas DataFrame.

- :func:`mode_records`: the rows of :meth:`pinlin.Modes.to_pandas` as a list of dicts (no pandas needed);
- :func:`modes_frame`: the same as a :class:`pandas.DataFrame` (``pip install 'pinlin[pandas]'``).
"""

from __future__ import annotations

from ..extras import import_pandas

__all__ = ["MODE_COLUMNS", "mode_records", "modes_frame"]

#: The columns of :func:`mode_records`, in order (units in :func:`mode_records`).
MODE_COLUMNS = (
    "eigenvalue_re", "eigenvalue_im", "natural_frequency", "frequency_hz", "damping_ratio", "backward_error",
    "condition", "error_bound", "multiplicity", "kind", "dominant",
)


def mode_records(modes) -> list[dict]:
    """One dict per eigenvalue k of ``modes`` (in its order), with the keys of :data:`MODE_COLUMNS`.

    ``eigenvalue_re`` [1/s] and ``eigenvalue_im`` [rad/s] are the parts of lam_k;
    ``natural_frequency`` |lam_k| [rad/s] and ``frequency_hz`` |lam_k| / (2 pi) [Hz];
    ``damping_ratio`` -Re lam_k / |lam_k| (NaN for lam_k = 0); ``backward_error``,
    ``condition`` and ``error_bound`` the figures of :class:`~pinlin.Modes`; ``kind`` the
    mode kind; ``dominant`` the coordinates of :meth:`~pinlin.Modes.dominant` with their
    shares, as text ("joint1 62%, joint2 38%").  Negative zeros are written as 0.
    """
    dominant = modes.dominant()
    out = []
    for k, lam in enumerate(modes.eigenvalues):
        out.append({
            "eigenvalue_re": float(lam.real) + 0.0,
            "eigenvalue_im": float(lam.imag) + 0.0,
            "natural_frequency": float(modes.natural_frequency[k]),
            "frequency_hz": float(modes.frequency_hz[k]),
            "damping_ratio": float(modes.damping_ratio[k]) + 0.0,
            "backward_error": float(modes.backward_error[k]),
            "condition": float(modes.condition[k]),
            "error_bound": float(modes.error_bound[k]),
            "multiplicity": int(modes.multiplicity[k]),
            "kind": modes.kind[k],
            "dominant": ", ".join(f"{name} {share:.0%}" for name, share in dominant[k]),
        })
    return out


def modes_frame(modes):
    """:func:`mode_records` as a :class:`pandas.DataFrame` indexed by the eigenvalue's position ``k``.

    Raises
    ------
    MissingDependencyError
        pandas is not installed (``pip install 'pinlin[pandas]'``).
    """
    pd = import_pandas()
    frame = pd.DataFrame.from_records(mode_records(modes), columns=list(MODE_COLUMNS))
    frame.index = pd.RangeIndex(len(frame), name="k")
    return frame
