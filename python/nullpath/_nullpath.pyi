"""Type stubs of the Rust extension module ``nullpath._nullpath``."""

__version__: str

# --- Scene API and rendering (issue 42, pyscene) ---------------------------------------------

import os
from typing import Any, Callable, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

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

# --- end of Scene API and rendering ------------------------------------------------------------
