"""How a sweep reports its progress: in completion order, as a text bar, a tqdm bar or a callback.

Points are reported as they finish, not in grid order, so one slow early point
never holds the bar (or the callback) behind it.  The text bar needs nothing;
tqdm is used when installed and asked for (``progress=True`` prefers it).
"""

from __future__ import annotations

import sys
import time
from typing import TextIO

from ..errors import MissingDependencyError, ParameterError

__all__ = ["TextBar", "progress_bar", "PROGRESS_MIN_POINTS", "PROGRESS_WIDTH", "PROGRESS_KINDS"]

#: A progress bar is shown by default only above this many points: shorter sweeps finish before one helps.
PROGRESS_MIN_POINTS = 20
#: Characters of the text bar: fits an 80-column terminal with the counts and times beside it.
PROGRESS_WIDTH = 30
#: Values of ``sweep(progress=...)`` besides None and booleans.
PROGRESS_KINDS = ("text", "tqdm")


class TextBar:
    """A dependency-free text progress bar on a stream (stderr by default).

    Parameters
    ----------
    total : int
        Number of points.
    stream : text stream, optional
        Where the bar is written; default stderr.
   

    Examples
    --------
    >>> import io
    >>> from pinlin.studies.progress import TextBar
    >>> stream = io.StringIO()
    >>> bar = TextBar(3, stream)
    >>> bar.update(); bar.update(2); bar.close()
    >>> stream.getvalue().split(chr(13))[-1][:42]  # the last redraw
    'sweep [##############################] 3/3'
    """

    def __init__(self, total: int, stream: TextIO | None = None):
        self.total, self.stream = total, stream or sys.stderr
        self.done = 0
        self.t0 = time.perf_counter()

    def update(self, count: int = 1) -> None:
        """``count`` more points finished: redraw the bar with the elapsed and estimated remaining time [s]."""
        self.done += count
        filled = int(PROGRESS_WIDTH * self.done / self.total)
        elapsed = time.perf_counter() - self.t0
        eta = elapsed / self.done * (self.total - self.done)
        self.stream.write(
            f"\rsweep [{'#' * filled}{'.' * (PROGRESS_WIDTH - filled)}] {self.done}/{self.total} "
            f"{elapsed:.1f} s elapsed, ~{eta:.1f} s left"
        )
        if self.done == self.total:
            self.stream.write("\n")
        self.stream.flush()

    def close(self) -> None:
        """Nothing to release: the last update ended the line."""


def _tqdm():
    try:
        from tqdm import tqdm
    except ImportError:
        return None
    return tqdm


def progress_bar(total: int, progress, stream: TextIO | None = None):
    """The bar a sweep of ``total`` points updates, or None for no bar.

    Parameters
    ----------
    total : int
        Number of points.
    progress : bool, "text", "tqdm" or None
        None: a bar only above :data:`PROGRESS_MIN_POINTS` points; True: tqdm when
        installed, else the text bar; ``"text"`` or ``"tqdm"``: that bar; False: none.
    stream : text stream, optional
        Where the bar is written; default stderr.

    Returns
    -------
    TextBar, tqdm.tqdm or None
        An object with ``update(1)`` and ``close()``.

    Raises
    ------
    ParameterError
        An unknown ``progress``.
    MissingDependencyError
        ``progress="tqdm"`` without tqdm installed.

    Examples
    --------
    >>> import io
    >>> from pinlin.studies.progress import progress_bar
    >>> progress_bar(3, None) is None, type(progress_bar(3, "text", io.StringIO())).__name__
    (True, 'TextBar')
    """
    if progress is None:
        progress = total > PROGRESS_MIN_POINTS
    if progress is False:
        return None
    if progress is not True and progress not in PROGRESS_KINDS:
        raise ParameterError("progress", f"expected None, True, False or one of {list(PROGRESS_KINDS)}, got {progress!r}")
    tqdm = _tqdm() if progress in (True, "tqdm") else None
    if tqdm is None and progress == "tqdm":
        raise MissingDependencyError("sweep(progress='tqdm') needs tqdm: pip install tqdm")
    if tqdm is None:
        return TextBar(total, stream)
    return tqdm(total=total, file=stream or sys.stderr, desc="sweep", unit="point")
