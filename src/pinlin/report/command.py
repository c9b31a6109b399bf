"""What every ``pinlin`` command prints around its report: the files written, its total time, plain help text.

- :class:`Stopwatch` -- the wall time of one command, split into its parts
  (loading, analysis, each file written), printed last as
  ``Total 7.52 s: loading 3.1 ms, analysis 15.5 ms, plot a.png 7.4 s, other 1.2 ms``;
- :func:`duration` -- seconds as ``15.5 ms`` or ``7.52 s``;
- :func:`plain_text` -- reStructuredText markup of a docstring (````x````,
  ``:func:`~pinlin.x```) as the plain text ``--help`` prints;
- :class:`CommandParser` -- a subcommand's parser that refuses a misspelt option with its own usage.
"""

from __future__ import annotations

import argparse
import difflib
import re
import time
from collections.abc import Iterator
from contextlib import contextmanager

__all__ = ["Stopwatch", "duration", "plain_text", "CommandParser"]

#: What the total of :meth:`Stopwatch.summary` does not include.
NOT_INCLUDED = "Python start-up and imports not included"


def duration(seconds: float) -> str:
    """``<0.01 ms``, ``0.42 ms``, ``15.5 ms``, ``7.52 s``, ``125 s``.

    Examples
    --------
    >>> from pinlin.report.command import duration
    >>> duration(0.0042), duration(3.5), duration(125)
    ('4.2 ms', '3.5 s', '125 s')
    """
    if seconds < 1e-5:
        return "<0.01 ms"
    if seconds < 1.0:
        return f"{seconds * 1e3:.3g} ms"
    return f"{seconds:.3g} s"


class Stopwatch:
    """Wall time of one command from its start (:func:`time.perf_counter`), by named part.

    Examples
    --------
    >>> from pinlin.report.command import Stopwatch
    >>> clock = Stopwatch()
    >>> with clock.part("analysis"):
    ...     pass
    >>> clock.summary()
    'Total ... ms: analysis <0.01 ms, other ... ms (Python start-up and imports not included)'
    """

    def __init__(self) -> None:
        self.start = time.perf_counter()
        self.parts: dict[str, float] = {}

    @contextmanager
    def part(self, name: str) -> Iterator[None]:
        """Add the wall time of the ``with`` block to part ``name`` (even when the block raises)."""
        t0 = time.perf_counter()
        try:
            yield
        finally:
            self.parts[name] = self.parts.get(name, 0.0) + time.perf_counter() - t0

    def summary(self) -> str:
        """``Total T: part t, ..., other t (what is not included)``: the parts sum to the total with "other"
        (argument parsing, printing)."""
        total = time.perf_counter() - self.start
        other = max(total - sum(self.parts.values()), 0.0)
        parts = ", ".join(f"{name} {duration(t)}" for name, t in self.parts.items())
        return f"Total {duration(total)}: {parts + ', ' if parts else ''}other {duration(other)} ({NOT_INCLUDED})"


_ROLE = re.compile(r":[a-z]+:`~?([^`]+)`")
_LITERAL = re.compile(r"``([^`]+)``")


def plain_text(text: str) -> str:
    """``text`` without reStructuredText markup: ````x```` is x, ``:func:`~pinlin.a.b``` is b (``:func:`a.b``` a.b).

    Examples
    --------
    >>> from pinlin.report.command import plain_text
    >>> plain_text("see :func:`pinlin.linearize` and :class:`~pinlin.Scene`")
    'see pinlin.linearize and Scene'
    """

    def role(match: re.Match) -> str:
        target = match.group(1)
        short = match.group(0).split("`")[1].startswith("~")
        return target.rsplit(".", 1)[-1] if short else target

    return _LITERAL.sub(r"\1", _ROLE.sub(role, text))


class CommandParser(argparse.ArgumentParser):
    """A subcommand's parser that refuses unknown arguments itself, with its own usage and the close option
    names, instead of handing them back to the top-level parser (whose usage says nothing of the options).

    Examples
    --------
    >>> import contextlib, io
    >>> from pinlin.report.command import CommandParser
    >>> parser = CommandParser(prog="pinlin analyze")
    >>> _ = parser.add_argument("--stiffness", type=float)
    >>> err = io.StringIO()
    >>> with contextlib.redirect_stderr(err):
    ...     try:
    ...         parser.parse_args(["--stifness", "3"])
    ...     except SystemExit as exc:
    ...         code = exc.code
    >>> code, err.getvalue().splitlines()[-1]
    (2, 'pinlin analyze: error: unrecognized arguments: --stifness 3 (did you mean --stiffness?)')
    """

    def parse_known_args(self, args=None, namespace=None):
        namespace, extra = super().parse_known_args(args, namespace)
        if extra:
            options = set(re.findall(r"--[a-z][a-z-]*", self.format_usage()))
            close = [m for word in extra if word.startswith("-")
                     for m in difflib.get_close_matches(word.split("=")[0], options, n=1)]
            hint = f" (did you mean {', '.join(close)}?)" if close else ""
            self.error(f"unrecognized arguments: {' '.join(extra)}{hint}")
        return namespace, extra
