"""pinlin's benchmark suite: run with ``python -m benchmarks`` (see benchmarks/README.md)."""
