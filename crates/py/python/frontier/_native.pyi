"""Type stubs of the native module `frontier._native` (the Rust side of the package)."""

from os import PathLike
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

__version__: str

class Map:
    """A ground-truth occupancy map: cells (0 unknown, 1 free, 2 occupied), resolution in
    metres per cell, and the name runs report."""

    @staticmethod
    def load(
        path: Union[str, PathLike[str]],
        resolution: Union[None, float, Tuple[float, float]] = None,
        border: bool = False,
    ) -> Map:
        """Load a map file the CLI reads (ROS YAML + PGM/PNG, bare PGM/PNG with
        `resolution`, MovingAI `.map`, ASCII `.txt`)."""
    @staticmethod
    def from_numpy(array: np.ndarray, resolution: float, name: str = "array") -> Map:
        """A map from a 2-D bool (True = occupied) or uint8 (0 unknown, 1 free, 2 occupied)
        array; row 0 is the top row."""
    @staticmethod
    def generate(
        kind: str,
        seed: int = 0,
        size: Optional[Tuple[float, float]] = None,
        resolution: Optional[float] = None,
    ) -> Map:
        """Generate a built-in environment from (kind, seed, size in metres, resolution)."""
    def to_numpy(self) -> np.ndarray:
        """The cells as a (height, width) uint8 array."""
    def save(self, path: Union[str, PathLike[str]]) -> None:
        """Write `.yaml` (ROS YAML + PGM), `.pgm` or `.png`."""
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

def explore(
    map: Map, kwargs: Optional[Dict[str, Any]] = None, timing: bool = False
) -> Tuple[str, np.ndarray, Optional[List[np.ndarray]]]:
    """One run: (summary JSON, final belief, trajectories)."""

def explore_many(
    runs: Sequence[Tuple[Map, Optional[Dict[str, Any]]]],
    threads: Optional[int] = None,
    timing: bool = False,
) -> List[str]:
    """Many runs in parallel; one summary JSON per run, in order."""

def strategies() -> List[Tuple[str, str]]:
    """The strategy presets: (name, description)."""

def load_rows(path: Union[str, PathLike[str]]) -> str:
    """Every trial of a study store as a JSON array of rows."""
