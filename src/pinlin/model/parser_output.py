"""What Pinocchio's C++ parsers print on file descriptor 2, captured so that pinlin can raise or warn on it.

urdfdom and the MJCF parser print their complaints ("Error: ...") on the process's stderr and go on: capturing
them is the only way to notice that a model was built without part of its file.  File descriptor 2 belongs to
the whole process, so one thread at a time redirects it (:data:`_STDERR_LOCK`).
"""

from __future__ import annotations

import contextlib
import os
import tempfile
import threading
from collections.abc import Iterator

__all__ = ["captured_stderr"]

#: Serializes the redirections of file descriptor 2, a process-wide resource: without it a second thread saves
#: the first one's temporary file as "the" stderr and restores it last, leaving fd 2 on a deleted file.  Reentrant:
#: a capture nested in the same thread saves and restores the outer one's file, in order.
_STDERR_LOCK = threading.RLock()


@contextlib.contextmanager
def captured_stderr() -> Iterator[list[str]]:
    """Capture what the C++ parsers print on file descriptor 2 (one thread at a time).

    Examples
    --------
    >>> from pinlin.model.parser_output import captured_stderr
    >>> with captured_stderr() as messages:
    ...     _ = os.write(2, b"Error: a message from C++")
    >>> messages
    ['Error: a message from C++']
    """
    out: list[str] = []
    with _STDERR_LOCK:
        try:
            fd = os.dup(2)
        except OSError:  # no usable stderr: nothing to capture
            yield out
            return
        with tempfile.TemporaryFile(mode="w+b") as tmp:
            os.dup2(tmp.fileno(), 2)
            try:
                yield out
            finally:
                os.dup2(fd, 2)
                os.close(fd)
                tmp.seek(0)
                out.append(tmp.read().decode(errors="replace").strip())
