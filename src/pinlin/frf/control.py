"""pinlin's frequency responses as python-control data.

python-control is an optional extra (``pip install 'pinlin[control]'``), imported
only when a conversion is asked for (:func:`pinlin.extras.import_control`).
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError
from ..extras import import_control

__all__ = ["frequency_response_data"]


def frequency_response_data(resp, name: str | None = None):
    """A :class:`~pinlin.FrequencyResponse` as a python-control ``FrequencyResponseData``.

    The data ``resp.response[output, input, frequency]`` (python-control's own
    order) at ``resp.omega`` [rad/s]; the inputs are named ``"force:" + name``
    and the outputs by the coordinate names, as in :func:`pinlin.state_space`,
    so the data and the state-space model of the same system share signal names.

    ``FrequencyResponse.to_control`` is this function as a method.

    Parameters
    ----------
    resp : FrequencyResponse
    name : str, optional
        The system's name in python-control.

    Returns
    -------
    control.FrequencyResponseData

    Raises
    ------
    ParameterError
        ``resp`` is not a frequency response with data of shape
        (outputs, inputs, frequencies), or its frequencies are negative or not
        increasing (python-control's frequency data are on omega >= 0, in order).
    MissingDependencyError
        python-control is not installed.
    """
    data = np.asarray(getattr(resp, "response", None))
    omega = np.asarray(getattr(resp, "omega", None))
    outs, ins = getattr(resp, "output_names", None), getattr(resp, "input_names", None)
    if outs is None or ins is None or data.ndim != 3 or omega.ndim != 1:
        raise ParameterError("resp", f"expected a pinlin.FrequencyResponse, got {type(resp).__name__}")
    if data.shape != (len(outs), len(ins), len(omega)):
        raise ParameterError(
            "resp",
            f"response has shape {data.shape}; expected (outputs, inputs, frequencies) = "
            f"({len(outs)}, {len(ins)}, {len(omega)})",
        )
    if np.any(omega < 0) or np.any(np.diff(omega) <= 0):
        raise ParameterError(
            "resp.omega",
            "python-control needs frequencies >= 0 in increasing order; compute the response on such a grid "
            "(H(-i w) = conj H(i w))",
        )
    control = import_control()
    kwargs = {} if name is None else {"name": str(name)}
    return control.FrequencyResponseData(
        np.array(data, dtype=complex),
        np.array(omega, dtype=float),
        inputs=[f"force:{n}" for n in ins],
        outputs=list(outs),
        **kwargs,
    )
