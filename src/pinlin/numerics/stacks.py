"""Evaluating L(s) on many points in chunks of bounded memory (theory: equations: never an OOM kill)."""

from __future__ import annotations

from collections.abc import Iterator

__all__ = ["CHUNK_BYTES", "chunks"]

#: Bytes of complex (n, n) stacks evaluated at once: large enough for vectorized
#: LAPACK calls to pay off, small against the memory of any machine pinlin runs on.
CHUNK_BYTES = 32 * 2**20

#: Bytes of one complex double.
_COMPLEX_BYTES = 16


def chunks(N: int, n: int, budget: int = CHUNK_BYTES) -> Iterator[slice]:
    """Slices of ``range(N)`` holding about ``budget`` bytes of (n, n) complex matrices each."""
    size = max(1, budget // max(_COMPLEX_BYTES * n * n, 1))
    for start in range(0, N, size):
        yield slice(start, min(N, start + size))
