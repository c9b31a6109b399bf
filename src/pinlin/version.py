"""The package version (one place: the report, the CLI and ``pinlin.__version__`` read it)."""

__all__ = ["__version__"]

__version__ = "0.3.0"
