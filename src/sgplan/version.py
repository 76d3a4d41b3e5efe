"""sgplan's version, in a module of its own so that any layer may read it without loading the package's
public API (``sgplan/__init__.py``, which names the top layers)."""

__version__ = "0.1.0"
