"""nullpath: physically based rendering in curved spacetime, from Python.

Scenes are the same TOML files the ``nullpath`` program renders; images come back as NumPy arrays.
"""

from ._nullpath import __version__

__all__ = ["__version__"]
