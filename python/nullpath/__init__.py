"""nullpath: physically based rendering in curved spacetime, from Python.

Scenes are the same TOML files the ``nullpath`` program renders; images come back as NumPy arrays.
Spacetimes are the program's built-in metrics (or metrics written as expressions), and photons are
traced through them one at a time with their trajectories, or in bulk.
"""

from ._nullpath import __version__

__all__ = ["__version__"]

# --- spacetimes and geodesics (pygeo) ---
from ._nullpath import FATES, Spacetime, SpacetimeError, deflections, geodesic, geodesics, spacetimes

__all__ += ["FATES", "Spacetime", "SpacetimeError", "deflections", "geodesic", "geodesics", "spacetimes"]
# --- end spacetimes and geodesics ---
