"""Package version (single source: kept in step with pyproject.toml by a test)."""

__version__ = "0.3.0"
