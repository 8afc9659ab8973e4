"""Type stubs of the Rust extension module ``nullpath._nullpath``."""

__version__: str

# --- spacetimes and geodesics (pygeo) ---
from typing import Any, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

_Vectors = Union[npt.ArrayLike, Sequence[float], Sequence[Sequence[float]]]

FATES: tuple[str, str, str, str]
"""The fates' names, indexed by the codes ``geodesics`` returns: escaped, captured, traversed,
failed."""

class SpacetimeError(ValueError):
    """A spacetime's parameter, or a photon's start, is outside what it may be. ``parameter``
    names the parameter at fault (``None`` when the fault is no one parameter's)."""

    parameter: Optional[str]

class Spacetime:
    """A spacetime: one of the built-in metrics with its parameters, or a metric written as
    expressions.

    ``Spacetime("kerr", mass=1.0, spin=0.9)`` builds the built-in metric of that scene-file
    ``type`` (``nullpath.spacetimes()`` lists them). A parameter left out takes the value
    ``nullpath geodesic`` takes (mass and throat radius 1, spin and charge 0), else the scene
    files' default; every value is checked by the metric's constructor, and a bad one raises
    ``SpacetimeError`` (a ``ValueError``) naming it. A spinning hole's axis is z.
    """

    def __init__(self, name: str, **parameters: float) -> None: ...
    @staticmethod
    def from_toml(text: str) -> Spacetime:
        """The spacetime of a scene file's ``[spacetime]`` table, read by the scene reader: a
        built-in ``type`` with its keys, or ``type = "metric"`` with its components written as
        expressions (docs/scene-format.md). Raises ``SpacetimeError`` with the reader's message.
        An ``axis`` key is read and checked but not applied: spins here are about z."""
    @staticmethod
    def from_dict(table: dict[str, Any]) -> Spacetime:
        """The spacetime of a ``[spacetime]`` table given as a dict (``{"type": "metric", ...}``),
        read as ``from_toml`` reads it."""
    @property
    def name(self) -> str:
        """The scene-file ``type``: a built-in metric's name, or ``"metric"`` for a written one."""
    @property
    def parameters(self) -> dict[str, float]:
        """The parameters and their values (empty for a written metric)."""
    @property
    def length_scale(self) -> float:
        """The curvature length scale: the mass, or a wormhole's throat radius (1 for flat space)."""
    def __eq__(self, other: object) -> bool: ...

def spacetimes() -> list[dict[str, Any]]:
    """The built-in spacetimes, each a dict: ``name``, ``description``, ``constraint`` (between
    parameters, or ``None``) and ``parameters``, a list of dicts with ``name``, ``meaning``,
    ``unit``, ``range`` (``"≥ 0"``, ``"> 0"`` or ``"of either sign"``) and ``default`` (the
    value ``Spacetime`` takes when it is left out; ``None``: required)."""

def geodesic(
    spacetime: Spacetime,
    position: _Vectors,
    direction: _Vectors,
    *,
    rtol: float = 1e-10,
    escape_radius: Optional[float] = None,
    max_steps: int = 1_000_000,
    observer: str = "static",
    region: str = "upper",
) -> dict[str, Any]:
    """The trajectory of one photon that leaves ``position`` (world coordinates, the hole at the
    origin, a spin along z) in the ``direction`` its local static observer measures (the
    chart's normal observer where none can stay at rest), with unit energy as that observer
    measures it, followed forwards in time by integrating Hamilton's equations in 4-D.

    Returns a dict: ``lambda``, ``t``, ``x``, ``y``, ``z`` (arrays (N,): the affine parameter
    and the position at the start and at every accepted step), ``p`` (N, 4) the covariant
    momenta ``p_μ``, ``hamiltonian`` (N,) ``H = ½ g^{μν} p_μ p_ν`` (zero for light), ``E``,
    ``L_z`` and ``Q`` (N,) the constants of motion the spacetime has (``None`` otherwise: ``Q``
    is Carter's, for Kerr's family), ``fate`` (``"escaped"``, ``"captured"``, ``"traversed"`` or
    ``"failed"``), ``failure`` (why it failed, else ``None``), ``direction`` (its world direction
    of travel at the escape radius, else NaN), ``steps`` and ``max_abs_hamiltonian``.

    Times and momenta are in the chart in which the photon runs forwards: the spacetime's own
    for static ones, for holes the ingoing Kerr–Schild chart, regular on the future horizon (for
    a spinning hole its positions differ from the world's by a turn about the spin axis that
    vanishes far away). ``rtol`` is the integrator's relative tolerance, ``escape_radius``
    (default a thousand masses, and beyond the start) where the photon has escaped, ``max_steps``
    where it has failed. Raises ``SpacetimeError`` naming a bad argument, and for a metric written
    by a user, whose light cannot be followed forwards."""

def geodesics(
    spacetime: Spacetime,
    positions: _Vectors,
    directions: _Vectors,
    *,
    rtol: float = 1e-10,
    escape_radius: Optional[float] = None,
    max_steps: int = 1_000_000,
    observer: str = "static",
    region: str = "upper",
    threads: Optional[int] = None,
) -> dict[str, np.ndarray]:
    """The fates of many photons, traced in parallel with the tracer the spacetime chooses (in the
    ray's plane for spherical metrics, as ``nullpath bench geodesics`` and the renderer do;
    Kerr's own stepper; 4-D Hamiltonian otherwise), the GIL released.

    ``positions`` and ``directions`` have shape (3,) or (N, 3) (one row is shared by every
    photon); each photon starts as ``geodesic``'s does. Returns a dict of arrays: ``fate`` (N,)
    ``uint8`` codes indexing ``nullpath.FATES`` (escaped, captured, traversed, failed),
    ``direction`` (N, 3) the world direction of travel at the escape radius (NaN for captured
    and failed photons) and ``steps`` (N,). The same for any ``threads`` (default: all cores)."""

def deflections(
    spacetime: Spacetime,
    impacts: npt.ArrayLike,
    inclination: float = 0.0,
    *,
    rtol: float = 1e-10,
    threads: Optional[int] = None,
) -> np.ndarray:
    """The deflection angles (radians, positive towards the centre) of rays coming in from
    infinity with the impact parameters ``impacts`` (N,), in the plane tilted by
    ``inclination`` degrees from the equator: what ``nullpath geodesic --json`` prints as
    ``deflection_rad``, from the same code (``spacetime::scattering``), in parallel. NaN for
    rays that do not come back out. For a spinning hole positive impacts are prograde."""

# --- end spacetimes and geodesics ---
