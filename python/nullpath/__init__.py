"""nullpath: physically based rendering in curved spacetime, from Python.

Scenes are the same TOML files the ``nullpath`` program renders; images come back as NumPy arrays.
Spacetimes are the program's built-in metrics (or metrics written as expressions), and photons are
traced through them one at a time with their trajectories, or in bulk.
"""

from ._nullpath import (
    FATES,
    RenderResult,
    Scene,
    SceneError,
    SceneTable,
    Spacetime,
    SpacetimeError,
    __version__,
    deflections,
    geodesic,
    geodesics,
    read_exr,
    spacetimes,
)

__all__ = [
    "__version__",
    # Scenes and their renders.
    "RenderResult",
    "Scene",
    "SceneError",
    "SceneTable",
    "read_exr",
    # Spacetimes and photons.
    "FATES",
    "Spacetime",
    "SpacetimeError",
    "deflections",
    "geodesic",
    "geodesics",
    "spacetimes",
]
