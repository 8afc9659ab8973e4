"""nullpath: physically based rendering in curved spacetime, from Python.

Scenes are the same TOML files the ``nullpath`` program renders; images come back as NumPy arrays.
"""

from ._nullpath import __version__

# Scene API and rendering (issue 42, pyscene).
from ._nullpath import RenderResult, Scene, SceneError, SceneTable, read_exr

__all__ = [
    "__version__",
    # Scene API and rendering (issue 42, pyscene).
    "RenderResult",
    "Scene",
    "SceneError",
    "SceneTable",
    "read_exr",
]
