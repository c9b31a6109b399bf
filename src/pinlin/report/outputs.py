"""The optional outputs of the command line (``--json``, ``--plot``, ``--animate``): checked before anything
is computed, written after the text report (so that a failing figure never costs the report).

Everything that can be known about an output before the analysis is checked
first: the directory exists, the file is not a directory, the suffix names a
format matplotlib (or its animation writers) can write, matplotlib and the
writer are installed.  So a typing error in an option costs nothing, and when
writing does fail afterwards (a full disk) what was computed has already been
printed and saved.
"""

from __future__ import annotations

import json
from pathlib import Path

from ..errors import MissingDependencyError, ParameterError

__all__ = [
    "check_output_path",
    "check_json_path",
    "check_figure_path",
    "check_animation_path",
    "write_json",
    "write_animation",
    "ANIMATION_WRITERS",
]

#: matplotlib's animation writer for each file suffix ``--animate`` accepts.
ANIMATION_WRITERS = {".gif": "pillow", ".webp": "pillow", ".html": "html", ".mp4": "ffmpeg", ".mkv": "ffmpeg",
                     ".mov": "ffmpeg", ".avi": "ffmpeg"}


def check_output_path(path: str, option: str) -> Path:
    """A file that can be created: a non-empty name whose directory exists and that is not a directory.

    Raises
    ------
    ParameterError
        Named ``option``: an empty name, a missing directory, a directory.

    Examples
    --------
    >>> from pinlin.report.outputs import check_output_path
    >>> import pathlib, tempfile
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> check_output_path(str(folder / "report.json"), "--json").name
    'report.json'
    >>> check_output_path(str(folder / "missing" / "report.json"), "--json")
    Traceback (most recent call last):
    ...
    pinlin.errors.base.ParameterError: --json: cannot write .../missing/report.json: the directory ... does not exist
    """
    if not path or not path.strip():
        raise ParameterError(option, "expected a file name, got an empty one")
    p = Path(path)
    if p.is_dir():
        raise ParameterError(option, f"{path} is a directory; expected a file name")
    if not p.parent.is_dir():
        raise ParameterError(option, f"cannot write {path}: the directory {p.parent} does not exist")
    return p


def check_json_path(path: str, option: str = "--json") -> Path:
    """See :func:`check_output_path`.

    Examples
    --------
    >>> from pinlin.report.outputs import check_json_path
    >>> import pathlib, tempfile
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> check_json_path(str(folder / "report.json")).suffix
    '.json'
    """
    return check_output_path(path, option)


def _matplotlib(option: str) -> None:
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        raise MissingDependencyError(f"{option} needs matplotlib: pip install 'pinlin[plot]'") from None


def check_figure_path(path: str, option: str = "--plot") -> Path:
    """A figure file matplotlib can write: its suffix names a format of ``savefig``.

    Raises
    ------
    MissingDependencyError
        matplotlib is not installed.
    ParameterError
        A path :func:`check_output_path` refuses, no suffix, or a format matplotlib cannot write.

    Examples
    --------
    >>> from pinlin.report.outputs import check_figure_path
    >>> import pathlib, tempfile
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> check_figure_path(str(folder / "modes.png")).name
    'modes.png'
    >>> check_figure_path(str(folder / "modes.xyz"))
    Traceback (most recent call last):
    ...
    pinlin.errors.base.ParameterError: --plot: cannot write a figure as 'modes.xyz': the suffix must name a format, ...
    """
    p = check_output_path(path, option)
    _matplotlib(option)
    from matplotlib.backend_bases import FigureCanvasBase

    formats = FigureCanvasBase.get_supported_filetypes()
    suffix = p.suffix.lower().lstrip(".")
    if suffix not in formats:
        raise ParameterError(option, f"cannot write a figure as {p.name!r}: the suffix must name a format, "
                             f"one of {', '.join(sorted(formats))}")
    return p


def check_animation_path(path: str, option: str = "--animate") -> Path:
    """An animation file whose matplotlib writer is available (``.gif`` through pillow, ``.mp4`` through ffmpeg, ...).

    Raises
    ------
    MissingDependencyError
        matplotlib, or the writer the suffix needs (pillow, ffmpeg), is not installed.
    ParameterError
        A path :func:`check_output_path` refuses, or a suffix not in :data:`ANIMATION_WRITERS`.

    Examples
    --------
    >>> from pinlin.report.outputs import check_animation_path
    >>> import pathlib, tempfile
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> check_animation_path(str(folder / "mode1.html")).suffix
    '.html'
    """
    p = check_output_path(path, option)
    writer = ANIMATION_WRITERS.get(p.suffix.lower())
    if writer is None:
        raise ParameterError(option, f"cannot write an animation as {p.name!r}: the suffix must be one of "
                             f"{', '.join(sorted(ANIMATION_WRITERS))}")
    _matplotlib(option)
    from matplotlib.animation import writers

    if not writers.is_available(writer):
        raise MissingDependencyError(f"{option} {p.name} needs matplotlib's {writer!r} animation writer, which is "
                                     f"not available here (pillow for .gif, ffmpeg for .mp4)")
    return p


def write_json(path: str, document: dict, option: str = "--json") -> None:
    """Write a JSON document (non-finite floats already spelled as strings by ``to_jsonable``).

    Raises
    ------
    ParameterError
        The file cannot be written (named ``option``).

    Examples
    --------
    >>> from pinlin.report.outputs import write_json
    >>> import pathlib, tempfile
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> write_json(str(folder / "doc.json"), {"error": 1.5e-16, "stable": True})
    >>> print((folder / "doc.json").read_text())
    {
      "error": 1.5e-16,
      "stable": true
    }
    """
    try:
        with open(path, "w", encoding="utf-8") as f:
            json.dump(document, f, indent=2, allow_nan=False)
    except OSError as exc:
        raise ParameterError(option, f"cannot write {path}: {exc}") from None


def write_animation(path: str, scene, sys, modes, row: int, option: str = "--animate") -> None:
    """Animate row ``row`` (1-based, as in the mode table) of ``modes`` and save it.

    Raises
    ------
    ParameterError
        ``row`` outside 1 .. 2n (named ``--mode``); the file cannot be written.
    PinlinError
        Whatever :func:`pinlin.plot.animate_mode` refuses.

    Examples
    --------
    The row is checked before anything is drawn:

    >>> from pinlin.report.outputs import write_animation
    >>> scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
    >>> sys = pinlin.linearize(scene, np.zeros(2))
    >>> write_animation("mode9.html", scene, sys, pinlin.modal_analysis(sys), 9)
    Traceback (most recent call last):
    ...
    pinlin.errors.base.ParameterError: --mode: ...
    """
    count = len(modes.eigenvalues)
    if not 1 <= row <= count:
        raise ParameterError("--mode", f"expected a row of the mode table, 1 to {count}, got {row}")
    from .. import plot

    animation = plot.animate_mode(scene, sys, row - 1, modes=modes)
    try:
        animation.save(path, writer=ANIMATION_WRITERS[Path(path).suffix.lower()])
    except OSError as exc:
        raise ParameterError(option, f"cannot write {path}: {exc}") from None
