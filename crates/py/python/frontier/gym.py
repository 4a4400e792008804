"""Gymnasium environments: exploration one decision per step.

``ExploreEnv`` (registered as ``frontier/Explore-v0``) drives one robot. An action is the
index of one of at most K goal candidates — the K cheapest to reach of those the strategy's
candidate generator offers (frontier cells, region centroids, RFE, CC), listed in the
generator's order, with an ``action_mask``. The robot travels to it along its shortest
path, sensing as configured, until the next decision: on arrival, or earlier when the
strategy's re-plan policy calls one (``cf-rr`` re-decides when its goal stops being a
frontier). ``ExploreVectorEnv`` steps N of them on Rust threads in one call.

Baselines are policies: :class:`Baseline` asks a paper's preset (its assigner) which of the
offered candidates it would take, so an agent and the papers' strategies run on the same
maps. With the env's ``strategy`` equal to the preset and K at least the number of
candidates, a baseline episode is exactly ``frontier.explore`` with the same seed.
"""

from __future__ import annotations

import difflib
import math
import os
import sys
import warnings
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import gymnasium
import numpy as np
from gymnasium import spaces
from gymnasium.utils import seeding
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from . import (
    Pair, _check_memory_mb, _count, _flag, _native, _pair, _path, _real, _real_or_none, _text,
)
from ._native import Map

__all__ = ["ExploreEnv", "ExploreVectorEnv", "Baseline", "RandomPolicy", "load_folder"]

MapsArg = Union[
    None, str, "os.PathLike[str]", Map, Sequence[Map], Sequence[Union[str, "os.PathLike[str]"]]
]

_MAP_EXTENSIONS = (".yaml", ".yml", ".png", ".pgm", ".map", ".json", ".txt")


def _folder_files(folder: Union[str, "os.PathLike[str]"], dungeon: bool = False) -> List[str]:
    """The map files of ``folder``, sorted by name: ROS YAML files if there are any (their
    images are read through them), else every bitmap, MovingAI ``.map``, HouseExpo
    ``.json`` and ``.txt``; with ``dungeon`` its PNGs. ValueError when there are none."""
    names = sorted(os.listdir(folder))
    if dungeon:
        chosen = [n for n in names if n.endswith(".png")]
        if not chosen:
            raise ValueError(f"{os.fspath(folder)}: no .png files (dungeon=True)")
    else:
        yaml = [n for n in names if n.endswith((".yaml", ".yml"))]
        chosen = yaml or [n for n in names if n.endswith(_MAP_EXTENSIONS)]
        if not chosen:
            raise ValueError(f"{os.fspath(folder)}: no map files ({', '.join(_MAP_EXTENSIONS)})")
    return [os.path.join(os.fspath(folder), n) for n in chosen]


def load_folder(
    folder: Union[str, "os.PathLike[str]"],
    resolution: Optional[float] = None,
    border: bool = False,
    *,
    dungeon: bool = False,
) -> List[Map]:
    """Every map file of ``folder`` (sorted by name), loaded now: ROS YAML files if there are
    any (their images are loaded through them), else every bitmap, MovingAI ``.map``,
    HouseExpo ``.json`` (needs ``resolution``) and ``.txt``; with ``dungeon=True`` its PNGs
    as dungeon maps (:meth:`Map.load`). ``border`` adds a wall around each map, a dungeon's
    too. (An environment given the folder itself reads each episode's map when the episode
    starts instead.)"""
    _path("folder", folder)
    files = _folder_files(folder, dungeon)
    return [Map.load(p, resolution=resolution, border=border, dungeon=dungeon) for p in files]


_DUNGEON_NEEDS_FILES = (
    "dungeon: reads PNG files as dungeon maps: give a folder, a file or a list of files as "
    "maps (or Map.load(path, dungeon=True) maps)"
)

_Source = Tuple[
    Optional[List[Map]],
    Optional[Tuple[str, Any, Any]],
    Optional[Tuple[List[str], Optional[float], bool]],
]


def _refuse_unused(
    given: str,
    size: Optional[Pair],
    resolution: Optional[float] = None,
    maps: Sequence[Map] = (),
) -> None:
    """Raise ValueError for a ``size`` that maps of the ``given`` kind would not use, or a
    ``resolution`` other than the given ``maps``' own: taken and ignored, it would mislead.
    (A resolution equal to theirs changes nothing and is taken, so that one set of keyword
    arguments serves maps loaded first and the same maps read episode by episode.)"""
    if size is not None:
        raise ValueError(
            f"size: expected None, as only generated maps take a size and maps is {given}, "
            f"found {size}"
        )
    for m in maps:
        if resolution is not None and not math.isclose(m.resolution, resolution):
            raise ValueError(
                f"resolution: expected None or the maps' own, as a frontier.Map keeps its "
                f"resolution (maps is {given}; {m.name} has {m.resolution} m per cell), "
                f"found {resolution}"
            )


def _source(
    maps: MapsArg,
    size: Optional[Pair],
    resolution: Optional[float],
    dungeon: bool = False,
    memory_mb: Optional[int] = None,
) -> _Source:
    """(list of maps, None, None), (None, generator spec, None) or (None, None, (map files,
    resolution, dungeon)): map files (a folder's, or a list of paths) are read when an
    episode picks one, so that a dataset of thousands of plans is never all in memory (the
    first is read at construction, to check the options and size the observation). A single
    map file is loaded now, within ``memory_mb``."""
    if dungeon and (maps is None or isinstance(maps, Map)):
        raise ValueError(_DUNGEON_NEEDS_FILES)
    if maps is None:
        return None, ("office", size, resolution), None
    if isinstance(maps, Map):
        _refuse_unused("a frontier.Map", size, resolution, [maps])
        return [maps], None, None
    if isinstance(maps, (str, os.PathLike)):
        path = os.fspath(maps)
        if os.path.isdir(path):
            _refuse_unused("a folder", size)
            return None, None, (_folder_files(path, dungeon), resolution, dungeon)
        if os.path.isfile(path):
            _refuse_unused("a map file", size)
            one = Map.load(path, resolution=resolution, dungeon=dungeon, memory_mb=memory_mb)
            return [one], None, None
        if isinstance(maps, os.PathLike) or os.sep in path or path.endswith(_MAP_EXTENSIONS):
            raise ValueError(f"maps: {path}: no such folder or map file")
        if dungeon:
            raise ValueError(f"dungeon: reads PNG files, but maps is the generator kind {path!r}")
        return None, (path, size, resolution), None
    if isinstance(maps, (bytes, bytearray)) or not isinstance(maps, Sequence):
        raise TypeError(
            "maps: expected a frontier.Map, a list of maps, a generator kind, a map file or "
            f"a folder, found {type(maps).__name__}"
        )
    items = list(maps)
    paths = [m for m in items if isinstance(m, (str, os.PathLike))]
    if items and len(paths) == len(items):
        # Map files (a dataset's train or test split): read episode by episode, as a folder's.
        _refuse_unused("a list of map files", size)
        files = [os.fspath(m) for m in paths]
        for i, f in enumerate(files):
            if not os.path.isfile(f):
                raise ValueError(f"maps[{i}]: {f}: no such map file")
        return None, None, (files, resolution, dungeon)
    if dungeon:
        raise ValueError(_DUNGEON_NEEDS_FILES)
    loaded = [m for m in items if isinstance(m, Map)]
    if len(loaded) < len(items):
        i, m = next((i, m) for i, m in enumerate(items) if not isinstance(m, Map))
        raise TypeError(
            f"maps[{i}]: expected a frontier.Map or a map file's path (all of one kind), "
            f"found {type(m).__name__}"
        )
    _refuse_unused("a list of maps", size, resolution, loaded)
    return loaded, None, None


def _map_index(value: Any, name: str = "options['map']") -> Optional[int]:
    """A map index of reset's ``options["map"]``: None, or a non-negative int (one the
    environment can count to; whether its list has that many maps is checked there)."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise TypeError(
            f"{name}: expected the index of a map (an int), found {type(value).__name__}"
        )
    if value < 0:
        raise ValueError(f"{name}: expected the index of a map (0 or more), found {value}")
    if value > sys.maxsize:
        raise ValueError(
            f"{name}: expected the index of a map of the list or folder (see map_names), "
            f"found {value}"
        )
    return int(value)


def _map_option(options: Optional[Mapping[str, Any]]) -> Any:
    """What reset's ``options`` ask for: ``options["map"]`` (None when not given)."""
    if options is None:
        return None
    if not isinstance(options, Mapping):
        raise TypeError(f"options: expected a dict, found {type(options).__name__}")
    for key in options:
        if key != "map":
            # Warned, not refused: API checkers (PettingZoo's) pass options of their own.
            warnings.warn(
                f"options: unknown key {key!r} ignored; reset takes 'map', the index of a map "
                "of the environment's list or folder (see map_names)",
                stacklevel=3,
            )
    return options.get("map")


def _seed(name: str, value: Any) -> Optional[int]:
    """A seed of ``reset``: None, or a non-negative Python or numpy integer as an int (of
    any size, as Gymnasium's seeding takes it); TypeError or ValueError naming ``name``
    otherwise (a bool, a float, a str; Gymnasium's own check raises its ``Error`` for these,
    or takes a bool as 0 or 1)."""
    if value is None:
        return None
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name}: expected an int or None, found {type(value).__name__}")
    if value < 0:
        raise ValueError(f"{name}: expected a non-negative int, found {value}")
    return int(value)


def _action(action: Any, name: str = "action") -> int:
    """An action as an int: a Python or numpy integer, or a 0-d integer array (TypeError
    naming ``name`` for anything else, a float included; ValueError beyond the 64-bit
    integers the environment reads actions as)."""
    if isinstance(action, np.ndarray) and action.ndim == 0 and action.dtype.kind in "iu":
        action = action.item()
    if isinstance(action, bool) or not isinstance(action, (int, np.integer)):
        raise TypeError(f"{name}: expected an int, found {type(action).__name__}")
    value = int(action)
    if not -(2**63) <= value < 2**63:
        raise ValueError(f"{name}: expected an integer in -2^63..2^63, found {value}")
    return value


#: The run options of :func:`frontier.explore` an environment takes as keyword arguments
#: (the seed comes from ``reset``; trajectories and clutter are not recorded or taken).
RUN_OPTIONS = (
    "belief", "sensing", "clearance", "speed", "s_max", "motion", "coverage", "start", "goal",
    "max_moves",
)


def _check_run(who: str, run: Dict[str, Any]) -> None:
    """Raise TypeError for a keyword argument of ``who`` that is not a run option."""
    for key in run:
        if key not in RUN_OPTIONS:
            near = difflib.get_close_matches(str(key), RUN_OPTIONS, n=1, cutoff=0.8)
            hint = f"; did you mean {near[0]!r}?" if near else ""
            if key == "seed":
                hint = "; an episode's seed is reset(seed=...)'s"
            raise TypeError(
                f"{who}() got an unexpected keyword argument {key!r} (run options: "
                f"{', '.join(RUN_OPTIONS)}){hint}"
            )


def _check_invalid_action(invalid_action: str) -> None:
    """Raise TypeError or ValueError unless ``invalid_action`` is 'wrap' or 'raise'."""
    _text("invalid_action", invalid_action, "'wrap' or 'raise'")
    if invalid_action not in ("wrap", "raise"):
        raise ValueError(f"invalid_action: expected 'wrap' or 'raise', found {invalid_action!r}")


def _core_args(
    maps: MapsArg,
    size: Optional[Pair],
    resolution: Optional[float],
    strategy: str,
    sensor: str,
    candidates: Optional[str],
    k: int,
    view: Optional[int],
    lam: float,
    max_path_m: Optional[float],
    max_steps: Optional[int],
    gain: bool,
    run: Dict[str, Any],
    dungeon: bool = False,
    memory_mb: Optional[int] = None,
) -> Dict[str, Any]:
    _count("k", k, 1, " candidate", optional=False)
    _count("view", view, 1, " cell")
    _count("max_steps", max_steps, 1, " decision")
    dungeon = _flag("dungeon", dungeon)
    gain = _flag("gain", gain)
    memory_mb = _check_memory_mb(memory_mb)
    lam = _real("lam", lam, "a number (the reward's price per metre)")
    max_path_m = _real_or_none("max_path_m", max_path_m, "a number of metres")
    resolution = _real_or_none("resolution", resolution, "a number of metres per cell")
    size = _pair("size", size, "(width, height) in metres")
    if candidates is not None:
        _text("candidates", candidates, "a str or None")
    listed, generator, files = _source(maps, size, resolution, dungeon, memory_mb)
    kwargs = dict(run)
    kwargs.update(strategy=strategy, sensor=sensor)
    return dict(
        maps=listed,
        generator=generator,
        files=files,
        kwargs=kwargs,
        candidates=candidates,
        k=k,
        view=view,
        lam=lam,
        max_path_m=max_path_m,
        max_steps=max_steps,
        gain=gain,
        memory_mb=memory_mb,
    )


def _pose_bounds(map_shape: Optional[Tuple[int, int]]) -> Tuple[np.ndarray, np.ndarray]:
    """The bounds of a pose (x, y in map cells, heading in radians): the map's cells when
    every episode's map has ``map_shape``, else any cell (a view's maps may differ)."""
    pi = np.float32(np.pi)
    if map_shape is None:
        high = np.array([np.inf, np.inf, pi], np.float32)
    else:
        h, w = map_shape
        high = np.array([w - 1, h - 1, pi], np.float32)
    return np.array([0.0, 0.0, -pi], np.float32), high


def _spaces(
    shape: Tuple[int, int], k: int, view: Optional[int]
) -> Tuple[spaces.Dict, spaces.Discrete]:
    """The observation and action spaces of an environment whose layers have ``shape``
    (the map's, or a ``view``'s crop, whose maps may differ in size)."""
    h, w = shape
    low, high = _pose_bounds(None if view is not None else shape)
    # Candidates: x, y (cells, as a pose's), path cost (m) and gain (m²); padding is 0.
    cand_high = np.tile(np.array([high[0], high[1], np.inf, np.inf], np.float32), (k, 1))
    obs = spaces.Dict(
        {
            "belief": spaces.Box(0, 2, (h, w), np.uint8),
            "frontier": spaces.Box(0, 1, (h, w), np.uint8),
            "pose": spaces.Box(low, high, (3,), np.float32),
            "candidates": spaces.Box(np.zeros((k, 4), np.float32), cand_high, (k, 4), np.float32),
            "action_mask": spaces.Box(0, 1, (k,), np.int8),
        }
    )
    return obs, spaces.Discrete(k)


class _OneCallAtATime:
    """A context that turns PyO3's "Already borrowed" into what happened: an environment's
    native core releases the GIL while it steps, so a second thread calling into it then
    finds it borrowed."""

    __slots__ = ()

    def __enter__(self) -> None:
        return None

    def __exit__(self, kind: Any, err: Any, tb: Any) -> None:
        # Returns None: any other exception goes on as it is.
        if kind is RuntimeError and str(err) in ("Already borrowed", "Already mutably borrowed"):
            raise RuntimeError(
                "this environment is in a call from another thread: an environment takes one "
                "call at a time; give each thread an environment of its own"
            ) from None


_ONE_CALL = _OneCallAtATime()


def _episode_seed(rng: np.random.Generator) -> int:
    """The run seed of the next episode, drawn from the environment's generator."""
    return int(rng.integers(0, 2**63))


def _vector_info(coverage: np.ndarray, path: np.ndarray) -> Dict[str, np.ndarray]:
    """A vector environment's infos in Gymnasium's form: each key's array of one value per
    environment beside ``_key``, the mask of the environments that set it (all of them)."""
    every = np.ones(len(coverage), dtype=bool)
    return {"coverage": coverage, "_coverage": every, "path_length_m": path,
            "_path_length_m": every.copy()}


def _render(obs: Dict[str, np.ndarray], view: Optional[int] = None) -> np.ndarray:
    """An RGB picture of the belief: unknown grey, free white, occupied black, frontier
    red, robot blue (with a robot-centred ``view``, the robot is at the crop's centre)."""
    palette = np.array([[128, 128, 128], [255, 255, 255], [0, 0, 0]], dtype=np.uint8)
    img = palette[obs["belief"]]
    img[obs["frontier"] == 1] = (220, 30, 30)
    h, w = obs["belief"].shape
    if view is None:
        x, y = int(obs["pose"][0]), int(obs["pose"][1])
    else:
        # The crop's cell (view // 2, view // 2) is the robot's (pose is in map cells).
        x = y = view // 2
    if 0 <= x < w and 0 <= y < h:
        img[max(0, y - 1) : y + 2, max(0, x - 1) : x + 2] = (30, 60, 220)
    return img


class ExploreEnv(gymnasium.Env):
    """One robot exploring an unknown map, one decision per step.

    Args:
        maps: a :class:`~frontier.Map`, a list of maps (each episode picks one by its seed),
            a generator kind (``"office"``, ``"hospital"``, ``"cave"``, ``"maze"``,
            ``"potholes"``, ``"empty"``; each episode generates one from its seed), a map file
            or a folder of map files, or a list of map files' paths (a dataset's split): each
            episode reads the one its seed picks, so a dataset such as HouseExpo's 35,000
            plans is never all in memory (maps of different sizes need a ``view``). Default:
            generated offices.
        size: (width, height) in metres of generated maps (default: the kind's); a
            ValueError with maps that are not generated, which it would not change.
        resolution: metres per cell of generated maps, or of a bare bitmap or a HouseExpo
            plan (a file or in a folder); with :class:`~frontier.Map` maps, which keep their
            own, None or theirs (a ValueError otherwise).
        dungeon: read the PNGs of ``maps`` (a file or a folder) as dungeon maps of
            learned-exploration work (:meth:`~frontier.Map.load`): episodes start at the
            start each marks. Needs ``resolution``.
        strategy: the preset whose candidate generator, re-plan policy and sensing the
            environment uses (the agent replaces its assigner).
        sensor: sensor spec as the CLI takes it, e.g. ``"lidar:r=3.5,fov=360,res=1"``.
        candidates: override the candidate generator: ``"af"`` (all frontier cells),
            ``"centroids"``, ``"rfe"`` or ``"cc"``.
        k: the most candidates offered (the action space is ``Discrete(k)``).
        view: side in cells of a robot-centred crop of belief and frontier layers (None:
            the whole map; maps of different sizes need a crop).
        lam: λ, the reward's price per metre travelled.
        max_path_m: truncate an episode once the robot travelled this far.
        max_steps: truncate an episode after this many decisions.
        gain: fill the candidates' predicted gain (unknown area a predicted scan from the
            candidate would see). It costs one predicted scan per candidate, about as much
            as the rest of a step each, so it is off by default (the column is then 0).
        invalid_action: ``"wrap"`` (an index beyond the candidates offered is taken modulo
            their number, so every action of the space is legal) or ``"raise"``.
        render_mode: ``"rgb_array"`` or None.
        memory_mb: a budget in MiB (a positive int; the CLI's ``--memory-mb``), or None.
            Every memory check of the environment is made within it as well as within the
            memory the machine has available: the environment's estimated memory (its run
            and observations) when it is made, a ValueError naming the budget if it would
            not fit; the loading of map files and the generation of maps, before they are
            read or generated; and an episode's run on a map read larger than the one the
            environment was sized on.
        **run: more run options of :func:`frontier.explore` (``belief``, ``sensing``,
            ``clearance``, ``speed``, ``s_max``, ``motion``, ``coverage``, ``start``,
            ``goal``, ``max_moves``; :data:`RUN_OPTIONS`).

    Observation (Dict): ``belief`` (H, W) uint8 (0 unknown, 1 free, 2 occupied),
    ``frontier`` (H, W) uint8 mask, ``pose`` (x, y, heading) float32 in cells and radians,
    ``candidates`` (K, 4) float32 rows of (x, y, path cost in m, predicted gain in m²)
    padded with zeros, ``action_mask`` (K,) int8. ``belief`` and ``frontier`` are
    read-only (kept arrays are brought up to date with what changed, so a change made in
    place would stay; ``.copy()`` them to change them). Reward: newly known reachable free area
    in m² minus λ × metres travelled. ``terminated`` when nothing reachable is left (an
    episode whose first scan sees everything reachable ends at its first step, reward 0);
    ``truncated`` at the path or step budget. ``info``: coverage, path_length_m, decisions,
    moves, steps, candidates, map, seed.
    """

    metadata = {"render_modes": ["rgb_array"], "render_fps": 4}

    def __init__(
        self,
        maps: MapsArg = None,
        *,
        size: Optional[Pair] = None,
        resolution: Optional[float] = None,
        dungeon: bool = False,
        strategy: str = "cf-rr",
        sensor: str = "los:r=5",
        candidates: Optional[str] = None,
        k: int = 16,
        view: Optional[int] = None,
        lam: float = 0.0,
        max_path_m: Optional[float] = None,
        max_steps: Optional[int] = None,
        gain: bool = False,
        invalid_action: str = "wrap",
        render_mode: Optional[str] = None,
        memory_mb: Optional[int] = None,
        **run: Any,
    ) -> None:
        _check_invalid_action(invalid_action)
        _check_run("ExploreEnv", run)
        if render_mode is not None:
            _text("render_mode", render_mode, "'rgb_array' or None")
            if render_mode not in self.metadata["render_modes"]:
                raise ValueError(
                    f"render_mode: expected 'rgb_array' or None, found {render_mode!r}"
                )
        self._core = _native.EnvCore(
            **_core_args(
                maps, size, resolution, strategy, sensor, candidates, k, view, lam,
                max_path_m, max_steps, gain, run, dungeon=dungeon, memory_mb=memory_mb,
            )
        )
        self._wrap = invalid_action == "wrap"
        self._view = view
        self.render_mode = render_mode
        self.observation_space, self.action_space = _spaces(self._core.shape, self._core.k, view)
        self._obs: Optional[Dict[str, np.ndarray]] = None
        self._seed = 0

    def _info(self) -> Dict[str, Any]:
        info = self._core.info()
        info["seed"] = self._seed
        return info

    @property
    def map_names(self) -> Optional[List[str]]:
        """The names of the maps of a list or folder, by index (None for generated maps)."""
        return self._core.map_names

    def reset(
        self, *, seed: Optional[int] = None, options: Optional[Dict[str, Any]] = None
    ) -> Tuple[Dict[str, np.ndarray], Dict[str, Any]]:
        """Start an episode; the same ``seed`` gives the same map, start and episode.
        ``options={"map": i}`` runs it on map ``i`` of the list or folder (:attr:`map_names`)
        instead of the one the seed picks, e.g. to evaluate on every test map once.
        ``seed`` is None or a non-negative int (Python's or numpy's). A reset that raises
        (a map file that cannot be read) leaves no episode: ``step`` then raises
        ``ResetNeeded`` until a reset succeeds."""
        seed = _seed("seed", seed)
        index = _map_index(_map_option(options))
        super().reset(seed=seed)
        episode = _episode_seed(self.np_random)
        self._obs = None
        with _ONE_CALL:
            self._obs = self._core.reset(episode, map=index)
            self._seed = episode
            return self._obs, self._info()

    def step(
        self, action: Any
    ) -> Tuple[Dict[str, np.ndarray], float, bool, bool, Dict[str, Any]]:
        """Send the robot to candidate ``action`` and run to the next decision."""
        if self._obs is None:
            raise gymnasium.error.ResetNeeded("step: call reset() before step()")
        with _ONE_CALL:
            obs, reward, terminated, truncated = self._core.step(_action(action), self._wrap)
            self._obs = obs
            return obs, reward, terminated, truncated, self._info()

    def baseline_action(self, preset: str) -> int:
        """The action ``preset`` (a paper's strategy, e.g. ``"cf-rr"``) would take now."""
        if self._obs is None:
            raise gymnasium.error.ResetNeeded("baseline_action: call reset() before asking")
        with _ONE_CALL:
            return self._core.baseline_action(preset)

    def action_masks(self) -> np.ndarray:
        """The current observation's ``action_mask`` as a (K,) bool array: the method
        sb3-contrib's ``MaskablePPO`` asks an environment for."""
        if self._obs is None:
            raise gymnasium.error.ResetNeeded("action_masks: call reset() before asking for masks")
        return self._obs["action_mask"].astype(bool)

    def render(self) -> Optional[np.ndarray]:
        """An RGB array of the current belief (``render_mode="rgb_array"``)."""
        if self.render_mode != "rgb_array" or self._obs is None:
            return None
        return _render(self._obs, self._view)


class ExploreVectorEnv(VectorEnv):
    """``num_envs`` :class:`ExploreEnv` stepped together on Rust threads in one call (the GIL
    released). Takes ExploreEnv's arguments plus ``threads`` (default: one per core, at most
    ``num_envs``; the calling thread and ``threads - 1`` helpers, which keep looking for the
    next call for 0.5 ms before they sleep). An ended episode resets at the next step
    (Gymnasium's next-step autoreset); environment i of ``reset(seed=s)`` starts from seed
    ``s + i``. ``infos`` of ``reset`` and ``step`` hold arrays ``coverage`` and
    ``path_length_m``. ``memory_mb`` bounds the ``num_envs`` environments together."""

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP, "render_modes": []}

    def __init__(
        self,
        num_envs: int,
        maps: MapsArg = None,
        *,
        size: Optional[Pair] = None,
        resolution: Optional[float] = None,
        dungeon: bool = False,
        strategy: str = "cf-rr",
        sensor: str = "los:r=5",
        candidates: Optional[str] = None,
        k: int = 16,
        view: Optional[int] = None,
        lam: float = 0.0,
        max_path_m: Optional[float] = None,
        max_steps: Optional[int] = None,
        gain: bool = False,
        invalid_action: str = "wrap",
        threads: Optional[int] = None,
        memory_mb: Optional[int] = None,
        **run: Any,
    ) -> None:
        _check_invalid_action(invalid_action)
        _check_run("ExploreVectorEnv", run)
        _count("num_envs", num_envs, 1, optional=False)
        _count("threads", threads, 1)
        core = _native.VecEnvCore(
            num_envs,
            threads=threads,
            **_core_args(
                maps, size, resolution, strategy, sensor, candidates, k, view, lam,
                max_path_m, max_steps, gain, run, dungeon=dungeon, memory_mb=memory_mb,
            ),
        )
        self._core: Optional[_native.VecEnvCore] = core
        self._wrap = invalid_action == "wrap"
        self._started = False
        self.num_envs = num_envs
        self.single_observation_space, self.single_action_space = _spaces(
            core.shape, core.k, view
        )
        self.observation_space = batch_space(self.single_observation_space, num_envs)
        self.action_space = batch_space(self.single_action_space, num_envs)

    @property
    def map_names(self) -> Optional[List[str]]:
        """The names of the maps of a list or folder, by index (None for generated maps)."""
        return self._open("map_names").map_names

    def _open(self, what: str) -> _native.VecEnvCore:
        """The native environments, or ClosedEnvironmentError once :meth:`close` ran."""
        if self._core is None:
            raise gymnasium.error.ClosedEnvironmentError(
                f"{what}: the environment is closed"
            )
        return self._core

    def close_extras(self, **kwargs: Any) -> None:
        """Stop the helper threads and free the environments (``close()``); the
        environment cannot be reset or stepped after."""
        self._core = None
        self._started = False

    def reset(
        self,
        *,
        seed: Union[None, int, Sequence[Optional[int]]] = None,
        options: Optional[Dict[str, Any]] = None,
    ) -> Tuple[Dict[str, np.ndarray], Dict[str, Any]]:
        """Start every environment's episode. ``options={"map": m}`` runs them on maps of the
        list or folder (:attr:`map_names`): ``m`` an index for all, or one index (or None:
        the seed's pick) per environment. Episodes after an automatic reset pick by seed.
        ``seed`` is None, a non-negative int (Python's or numpy's), or a sequence of one such
        seed (or None) per environment; a sequence without None also seeds the later
        unseeded resets, as an int does. A reset that raises (a map file that cannot be read)
        leaves no episode: ``step`` then raises ``ResetNeeded`` until a reset succeeds."""
        first: Optional[int] = None
        if seed is None or isinstance(seed, (bool, np.bool_, int, np.integer)):
            first = _seed("seed", seed)
            given: List[Optional[int]] = (
                [None] * self.num_envs if first is None
                else [first + i for i in range(self.num_envs)]
            )
        elif (isinstance(seed, Sequence) and not isinstance(seed, (str, bytes))) or (
            isinstance(seed, np.ndarray) and seed.ndim == 1
        ):
            if len(seed) != self.num_envs:
                raise ValueError(f"seed: expected {self.num_envs} seeds, found {len(seed)}")
            given = [_seed(f"seed[{i}]", s) for i, s in enumerate(seed)]
        else:
            found = type(seed).__name__
            if isinstance(seed, np.ndarray):
                found += f" of shape {seed.shape}"
            raise TypeError(
                f"seed: expected an int, None or a list of one per environment, found {found}"
            )
        wanted = _map_option(options)
        if wanted is None or isinstance(wanted, (int, np.integer)):
            maps = [_map_index(wanted)] * self.num_envs
        elif isinstance(wanted, Sequence) and not isinstance(wanted, (str, bytes)):
            maps = [_map_index(m, f"options['map'][{i}]") for i, m in enumerate(wanted)]
        else:
            raise TypeError(
                "options['map']: expected a map index or one per environment, found "
                f"{type(wanted).__name__}"
            )
        if first is None and given and all(s is not None for s in given):
            # The later unseeded resets draw from the whole list, as from an int.
            state = np.random.SeedSequence([s for s in given if s is not None]).generate_state(
                2, np.uint32
            )
            first = int(state[0]) << 31 | int(state[1]) >> 1
        super().reset(seed=first)
        # Environment i seeded with s starts the episode ExploreEnv.reset(seed=s) starts.
        seeds = [
            _episode_seed(seeding.np_random(int(s))[0] if s is not None else self.np_random)
            for s in given
        ]
        self._started = False
        with _ONE_CALL:
            obs, coverage, path = self._open("reset").reset(seeds, maps)
        self._started = True
        return obs, _vector_info(coverage, path)

    def step(
        self, actions: Any
    ) -> Tuple[Dict[str, np.ndarray], np.ndarray, np.ndarray, np.ndarray, Dict[str, Any]]:
        """Step every environment (an ended one resets instead)."""
        core = self._open("step")
        if not self._started:
            raise gymnasium.error.ResetNeeded("step: call reset() before step()")
        given = np.asarray(actions)
        if given.shape != (self.num_envs,):
            raise ValueError(
                f"actions: expected one action per environment, shape ({self.num_envs},), "
                f"found shape {given.shape}"
            )
        if isinstance(actions, (list, tuple)) or given.dtype == object:
            # Each action as ``step`` of the single environment reads it: numpy would make
            # [True, 0, 0] an int array (a bool is no action), [np.uint64(2), 0] a float one,
            # and [2**64, 0] an object one.
            items = actions if isinstance(actions, (list, tuple)) else given
            given = np.array(
                [_action(a, f"actions[{i}]") for i, a in enumerate(items)], dtype=np.int64
            )
        if given.dtype.kind not in "iu":
            raise TypeError(f"actions: expected integers, found dtype {given.dtype}")
        if given.dtype == np.uint64 and (given >= 2**63).any():
            i = int(np.argmax(given >= 2**63))
            raise ValueError(f"actions[{i}]: expected an integer in -2^63..2^63, found {given[i]}")
        with _ONE_CALL:
            obs, rewards, terminated, truncated, coverage, path = core.step(
                given.astype(np.int64, copy=False), self._wrap
            )
        return obs, rewards, terminated, truncated, _vector_info(coverage, path)

    def baseline_actions(self, preset: str) -> np.ndarray:
        """Each environment's action under ``preset``."""
        core = self._open("baseline_actions")
        if not self._started:
            raise gymnasium.error.ResetNeeded("baseline_actions: call reset() before asking")
        with _ONE_CALL:
            return np.asarray(core.baseline_actions(preset), dtype=np.int64)


class Baseline:
    """A paper's strategy as a policy: ``Baseline("cf-rr")(env)`` is the action the preset's
    assigner takes among the candidates ``env`` offers (an array for a vector env)."""

    def __init__(self, preset: str) -> None:
        #: The preset's name.
        self.preset = _text("preset", preset)

    def __call__(self, env: Any) -> Any:
        u = getattr(env, "unwrapped", env)
        if hasattr(u, "possible_agents") and hasattr(u, "baseline_actions"):
            return u.baseline_actions(self.preset)
        if isinstance(u, ExploreVectorEnv):
            return u.baseline_actions(self.preset)
        if isinstance(u, ExploreEnv):
            return u.baseline_action(self.preset)
        raise TypeError(
            "env: expected an ExploreEnv, ExploreVectorEnv or ExploreParallelEnv, "
            f"found {type(u).__name__}"
        )


class RandomPolicy:
    """Uniformly one of the offered candidates (by the observation's ``action_mask``)."""

    def __init__(self, seed: Optional[int] = None) -> None:
        self._rng = np.random.default_rng(_seed("seed", seed))

    def __call__(self, obs: Dict[str, np.ndarray]) -> Any:
        mask = obs["action_mask"]
        if mask.ndim == 1:
            n = max(int(mask.sum()), 1)
            return int(self._rng.integers(0, n))
        n = np.maximum(mask.sum(axis=1), 1)
        return (self._rng.random(len(n)) * n).astype(np.int64)


def _register() -> None:
    """Register ``frontier/Explore-v0`` (on import of this module)."""
    if "frontier/Explore-v0" not in gymnasium.registry:
        gymnasium.register(
            id="frontier/Explore-v0",
            entry_point="frontier.gym:ExploreEnv",
            vector_entry_point="frontier.gym:ExploreVectorEnv",
        )


_register()
