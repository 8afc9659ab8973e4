"""Type stubs of the Rust extension module ``nullpath._nullpath``."""

__version__: str

import os
from typing import Any, Callable, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

# --- Scenes and their renders ---

_Path = Union[str, "os.PathLike[str]"]

class SceneError(ValueError):
    """A scene that does not load, or a change to one that it refuses. The message is the scene
    reader's: file, line and column, the field, and why
    (``scene.toml:4:7: camera.fov: must be in (0, 180) degrees, got 200``)."""

class SceneTable:
    """One table of a ``Scene``'s document (``scene.camera``, ``scene.spacetime``,
    ``scene.settings``), read and written like a dict. Values are those written in the scene (a
    key left to its default is absent); setting or deleting a key builds the scene again, and an
    invalid value raises ``SceneError`` naming the field, leaving the scene as it was. ``update``
    sets several keys at once, checked together (e.g. a Kerr hole's ``mass`` and ``spin``)."""

    def __getitem__(self, key: str) -> Any: ...
    def __setitem__(self, key: str, value: Any) -> None: ...
    def __delitem__(self, key: str) -> None: ...
    def __contains__(self, key: str) -> bool: ...
    def __len__(self) -> int: ...
    def __iter__(self) -> Iterator[str]: ...
    def keys(self) -> List[str]:
        """The keys written in the table, sorted."""
    def items(self) -> List[Tuple[str, Any]]:
        """The ``(key, value)`` pairs written in the table."""
    def get(self, key: str, default: Any = None) -> Any:
        """The value of ``key``, or ``default`` where the table has none."""
    def update(self, fields: Optional[Mapping[str, Any]] = None, **kwargs: Any) -> None:
        """Sets every key of ``fields`` and of ``kwargs`` at once: the scene is built once, with
        all of them, so values that are valid only together can be set."""
    def to_dict(self) -> Dict[str, Any]:
        """The table as a plain dict."""

class RenderResult:
    """A finished render, as NumPy arrays and a dict."""

    @property
    def image(self) -> npt.NDArray[np.float32]:
        """The image: float32, height × width × 3, linear RGB with the scene's exposure — exactly
        the pixels ``nullpath render -o image.exr`` writes."""
    @property
    def channels(self) -> Dict[str, npt.NDArray[np.float32]]:
        """The data channels the scene asks for (``[render] channels`` and ``spectrum``), by
        name, each float32 height × width. Empty if it asks for none."""
    @property
    def stats(self) -> Dict[str, Any]:
        """The statistics, with the fields of ``nullpath render --stats``'s JSON."""

class Scene:
    """A nullpath scene, read from a TOML file, text or dict, rendered into NumPy arrays.

    The scene's TOML text is the source of truth: ``camera``, ``spacetime`` and ``settings`` read
    and write its ``[camera]`` (or the chosen view's ``[views.NAME]``), ``[spacetime]`` and
    ``[render]`` tables, and each change builds the scene again, checked as the file is: an
    invalid value raises ``SceneError`` naming the field, and leaves the scene as it was."""

    @staticmethod
    def load(path: _Path, view: Optional[str] = None, allow_read: Sequence[_Path] = ()) -> "Scene":
        """Reads the scene file at ``path``. Files it names resolve against its folder and are
        read only inside it, or inside the folders ``allow_read``, as ``nullpath render`` reads
        them; it is seen from the view ``view`` (a ``[views.NAME]`` camera) when given."""
    @staticmethod
    def from_toml(
        text: str, base_dir: _Path = ".", view: Optional[str] = None, allow_read: Sequence[_Path] = ()
    ) -> "Scene":
        """Builds the scene written in ``text`` (TOML, as a scene file); files it names resolve
        against ``base_dir`` and are read only inside it (or ``allow_read``). Errors name it
        ``<string>``."""
    @staticmethod
    def from_dict(
        document: Mapping[str, Any],
        base_dir: _Path = ".",
        view: Optional[str] = None,
        allow_read: Sequence[_Path] = (),
    ) -> "Scene":
        """Builds the scene ``document``: a dict as the scene file's TOML would parse. Files it
        names resolve against ``base_dir``. Errors name it ``<dict>``, with the line of the TOML
        text it is written as (``Scene.toml``)."""
    @property
    def toml(self) -> str:
        """The scene's TOML text, with the changes made since it was read."""
    def to_dict(self) -> Dict[str, Any]:
        """The whole document as a dict (as ``tomllib`` would parse ``Scene.toml``)."""
    @property
    def views(self) -> List[str]:
        """The names of the scene's ``[views.NAME]`` cameras, in file order."""
    @property
    def view(self) -> Optional[str]:
        """The view the scene is seen (and rendered) from, or None for ``[camera]``; setting an
        unknown name raises ``SceneError``."""
    @view.setter
    def view(self, view: Optional[str]) -> None: ...
    @property
    def camera(self) -> SceneTable:
        """The camera's table: ``[camera]``, or ``[views.NAME]`` when a view is chosen."""
    @property
    def spacetime(self) -> SceneTable:
        """The ``[spacetime]`` table: ``type`` and the metric's parameters (``mass``, ``spin``, …)."""
    @property
    def settings(self) -> SceneTable:
        """The ``[render]`` table: ``width``, ``height``, ``spp``, ``seed``, ``integrator``, …"""
    def render(
        self,
        width: Optional[int] = None,
        height: Optional[int] = None,
        spp: Optional[int] = None,
        seed: Optional[int] = None,
        threads: Optional[int] = None,
        progress: Union[bool, None, Callable[[int, int], Any]] = True,
    ) -> RenderResult:
        """Renders the scene as ``nullpath render`` does, on ``threads`` threads (default: all
        cores; the image does not depend on it), with ``width``, ``height``, ``spp`` and ``seed``
        overriding ``[render]``'s (checked as the file's are). The GIL is released while it
        renders; Ctrl-C (KeyboardInterrupt) stops it within a sample. ``progress``: True shows a
        tqdm bar where tqdm is installed, False or None nothing, a callable is called with
        ``(done, total)``."""

def read_exr(
    path: _Path,
) -> Tuple[Optional[npt.NDArray[np.float32]], Dict[str, npt.NDArray[Any]]]:
    """Reads the OpenEXR image at ``path`` (its first layer): returns ``(image, channels)``, the
    image float32 height × width × 3 from its R, G and B channels (None if it has not all three)
    and every other channel by name, height × width (float32, or uint32 for integer channels)."""

# --- Spacetimes and photons ---

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
