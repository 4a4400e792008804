"""Type stubs of the native module `frontier._native` (the Rust side of the package)."""

from os import PathLike
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union, final

import numpy as np

__all__ = [
    "Map",
    "EnvCore",
    "VecEnvCore",
    "TeamEnvCore",
    "explore",
    "explore_many",
    "strategies",
    "load_rows",
    "_restore_map",
    "__version__",
]

__version__: str

@final
class Map:
    """A ground-truth occupancy map: cells (0 unknown, 1 free, 2 occupied), resolution in
    metres per cell, and the name runs report."""

    @staticmethod
    def load(
        path: Union[str, PathLike[str]],
        resolution: Union[None, float, Sequence[float], np.ndarray] = None,
        border: bool = False,
        *,
        topic: Optional[str] = None,
        dungeon: bool = False,
        memory_mb: Optional[int] = None,
    ) -> Map:
        """Load a map file the CLI reads (ROS YAML + PGM/PNG, bare PGM/PNG with
        `resolution`, MovingAI `.map`, HouseExpo `.json`, ASCII `.txt`, the last
        OccupancyGrid of an MCAP recording on `topic`; `dungeon=True`: a dungeon PNG and its
        marked start). `border=True` adds a wall one cell thick around the map, of any
        file but an MCAP recording (the origin and a dungeon PNG's start move with the
        cells). A `resolution` given with a ROS YAML overrides the
        YAML's. A map whose
        loading would need more than `memory_mb` MiB (the CLI's `--memory-mb`) or the memory
        available is refused before it is loaded."""
    @staticmethod
    def from_numpy(array: np.ndarray, resolution: float, name: str = "array") -> Map:
        """A map from a 2-D bool (True = occupied) or uint8 (0 unknown, 1 free, 2 occupied)
        array; row 0 is the top row."""
    @staticmethod
    def generate(
        kind: str,
        seed: int = 0,
        size: Union[None, Sequence[float], np.ndarray] = None,
        resolution: Optional[float] = None,
    ) -> Map:
        """Generate a built-in environment from (kind, seed, size in metres, resolution)."""
    def to_numpy(self) -> np.ndarray:
        """The cells as a (height, width) uint8 array."""
    def save(self, path: Union[str, PathLike[str]]) -> None:
        """Write `.yaml` (ROS YAML + PGM), `.pgm`, `.png`, `.map` (MovingAI: unknown cells
        read back as occupied) or `.txt`; only the YAML keeps the resolution and origin."""
    @property
    def width(self) -> int:
        """Width in cells."""
    @property
    def height(self) -> int:
        """Height in cells."""
    @property
    def shape(self) -> Tuple[int, int]:
        """(height, width)."""
    @property
    def resolution(self) -> float:
        """Metres per cell."""
    @property
    def name(self) -> str:
        """The name runs report."""
    @property
    def origin(self) -> Tuple[float, float, float]:
        """World pose (x, y, yaw) of the lower-left corner."""
    @property
    def free_cells(self) -> int:
        """Number of free cells."""
    @property
    def start(self) -> Optional[Tuple[int, int]]:
        """The start the file marks (x, y), or None; runs start there unless given one."""
    def __eq__(self, other: object, /) -> bool:
        """Equal when name, cells, resolution, origin and marked start are."""
    def __hash__(self) -> int:
        """A hash equal maps share."""
    def __reduce__(
        self,
    ) -> Tuple[
        Callable[..., Map],
        Tuple[bytes, int, int, float, Tuple[float, float, float], str, Optional[Tuple[int, int]]],
    ]:
        """Pickled as its cells, size, resolution, origin, name and start."""
    def __copy__(self) -> Map:
        """The map itself (maps never change)."""
    def __deepcopy__(self, memo: Any, /) -> Map:
        """The map itself (maps never change)."""

def _restore_map(
    cells: bytes,
    width: int,
    height: int,
    resolution: float,
    origin: Tuple[float, float, float],
    name: str,
    start: Optional[Tuple[int, int]],
) -> Map:
    """A map from what `Map.__reduce__` gives (unpickling a map)."""

def explore(
    map: Map,
    kwargs: Optional[Dict[str, Any]] = None,
    timing: bool = False,
    memory_mb: Optional[int] = None,
) -> Tuple[str, np.ndarray, Optional[List[np.ndarray]]]:
    """One run: (summary JSON, final belief, trajectories)."""

def explore_many(
    runs: Sequence[Tuple[Map, Optional[Dict[str, Any]]]],
    threads: Optional[int] = None,
    timing: bool = False,
    memory_mb: Optional[int] = None,
    progress: Optional[Callable[[int, int], Any]] = None,
) -> List[str]:
    """Many runs in parallel; one summary JSON per run, in order; `progress(done, total)`
    about ten times a second (an exception from it, or Ctrl-C, stops the batch)."""

def strategies() -> List[Tuple[str, str]]:
    """The strategy presets: (name, description)."""

def load_rows(path: Union[str, PathLike[str]]) -> str:
    """Every trial of a study store as a JSON array of rows."""

@final
class EnvCore:
    """One exploration environment (the core of `frontier.gym.ExploreEnv`)."""

    def __new__(
        cls,
        maps: Optional[List[Map]] = None,
        generator: Optional[Tuple[str, Optional[Tuple[float, float]], Optional[float]]] = None,
        files: Optional[Tuple[List[str], Optional[float], bool]] = None,
        kwargs: Optional[Dict[str, Any]] = None,
        candidates: Optional[str] = None,
        k: int = 16,
        view: Optional[int] = None,
        lam: float = 0.0,
        max_path_m: Optional[float] = None,
        max_steps: Optional[int] = None,
        gain: bool = False,
        memory_mb: Optional[int] = None,
    ) -> EnvCore:
        """An environment whose estimated memory, map loading and generation, and episodes
        on maps larger than the first are checked within `memory_mb` MiB (the CLI's
        `--memory-mb`) as well as the memory available."""
    @property
    def shape(self) -> Tuple[int, int]:
        """Observation (height, width)."""
    @property
    def k(self) -> int:
        """The most candidates offered."""
    @property
    def map_names(self) -> Optional[List[str]]:
        """The names of the maps an episode may pick, by index (None for generated maps)."""
    def reset(self, seed: int, map: Optional[int] = None) -> Dict[str, np.ndarray]:
        """Start an episode (on map `map` of the list or folder if given); returns the
        observation."""
    def step(self, action: int, wrap: bool) -> Tuple[Dict[str, np.ndarray], float, bool, bool]:
        """(observation, reward, terminated, truncated); with `wrap` an action outside the n
        offered candidates is taken modulo n."""
    def observation(self) -> Dict[str, np.ndarray]:
        """The current observation."""
    def info(self) -> Dict[str, Any]:
        """Coverage, path length, decisions, moves, steps, candidates, map."""
    def baseline_action(self, preset: str) -> int:
        """The action `preset` would take now."""

@final
class VecEnvCore:
    """N exploration environments stepped together on Rust threads."""

    def __new__(
        cls,
        n: int,
        maps: Optional[List[Map]] = None,
        generator: Optional[Tuple[str, Optional[Tuple[float, float]], Optional[float]]] = None,
        files: Optional[Tuple[List[str], Optional[float], bool]] = None,
        kwargs: Optional[Dict[str, Any]] = None,
        candidates: Optional[str] = None,
        k: int = 16,
        view: Optional[int] = None,
        lam: float = 0.0,
        max_path_m: Optional[float] = None,
        max_steps: Optional[int] = None,
        gain: bool = False,
        threads: Optional[int] = None,
        memory_mb: Optional[int] = None,
    ) -> VecEnvCore: ...
    @property
    def shape(self) -> Tuple[int, int]:
        """Observation (height, width)."""
    @property
    def k(self) -> int:
        """The most candidates offered."""
    @property
    def map_names(self) -> Optional[List[str]]:
        """The names of the maps an episode may pick, by index (None for generated maps)."""
    def reset(
        self, seeds: List[int], maps: Optional[List[Optional[int]]] = None
    ) -> Tuple[Dict[str, np.ndarray], np.ndarray, np.ndarray]:
        """Start every environment's episode (environment i on map `maps[i]` where given);
        (observations, coverage, path lengths)."""
    def step(
        self, actions: np.ndarray, wrap: bool
    ) -> Tuple[Dict[str, np.ndarray], np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(observations, rewards, terminated, truncated, coverage, path lengths); with `wrap`
        an action outside the n offered candidates is taken modulo n."""
    def baseline_actions(self, preset: str) -> List[int]:
        """Each environment's action under `preset`."""

@final
class TeamEnvCore:
    """A team exploring together, one agent per robot (the core of
    `frontier.pettingzoo.ExploreParallelEnv`)."""

    def __new__(
        cls,
        maps: Optional[List[Map]] = None,
        generator: Optional[Tuple[str, Optional[Tuple[float, float]], Optional[float]]] = None,
        files: Optional[Tuple[List[str], Optional[float], bool]] = None,
        kwargs: Optional[Dict[str, Any]] = None,
        candidates: Optional[str] = None,
        k: int = 16,
        view: Optional[int] = None,
        lam: float = 0.0,
        max_path_m: Optional[float] = None,
        max_steps: Optional[int] = None,
        gain: bool = False,
        memory_mb: Optional[int] = None,
    ) -> TeamEnvCore: ...
    @property
    def robots(self) -> int:
        """Number of robots (agents)."""
    @property
    def shape(self) -> Tuple[int, int]:
        """Observation (height, width)."""
    @property
    def k(self) -> int:
        """The most candidates offered to one robot."""
    @property
    def map_names(self) -> Optional[List[str]]:
        """The names of the maps an episode may pick, by index (None for generated maps)."""
    def reset(self, seed: int, map: Optional[int] = None) -> List[Dict[str, np.ndarray]]:
        """Start an episode (on map `map` of the list or folder if given); one observation
        per robot."""
    def step(
        self, actions: List[int], wrap: bool
    ) -> Tuple[List[Dict[str, np.ndarray]], float, bool, bool]:
        """(observations, team reward, terminated, truncated); with `wrap` an action outside
        the n candidates offered to its robot is taken modulo n."""
    def deciding(self) -> List[bool]:
        """Which robots decide now."""
    def info(self) -> Dict[str, Any]:
        """Coverage, per-robot path lengths, decisions, moves, steps, map."""
    def baseline_actions(self, preset: str) -> List[int]:
        """Each robot's action under `preset`."""
