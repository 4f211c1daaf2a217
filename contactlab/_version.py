"""The package version: a leaf module (imports nothing), so any layer may read it without
importing the package face (``contactlab/__init__.py``) and closing an import circle."""

__all__ = ["__version__"]

__version__ = "0.1.0"
