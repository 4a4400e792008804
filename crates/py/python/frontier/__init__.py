"""frontier: frontier-based robot exploration at Rust speed.

Maps (:class:`Map`), single runs (:func:`explore`) that report exactly what
``frontier explore --json --no-timing`` prints, parallel batches (:func:`explore_many`)
on Rust threads with the GIL released, study stores (:mod:`frontier.bench`), Gymnasium
environments (:mod:`frontier.gym`) whose baselines are the papers' strategies, and a
PettingZoo environment for teams (:mod:`frontier.pettingzoo`).
"""

from __future__ import annotations

import difflib
import functools
import json
import os
import sys
import warnings
from typing import (
    AbstractSet,
    Any,
    Callable,
    Dict,
    FrozenSet,
    Iterable,
    List,
    Mapping,
    Optional,
    Sequence,
    Tuple,
    Union,
)

import numpy as np

from . import _native
from ._native import Map

__all__ = [
    "Map",
    "ExploreResult",
    "explore",
    "explore_many",
    "strategies",
    "__version__",
]

__version__: str = _native.__version__


class ExploreResult:
    """One run's result: the fields of ``frontier explore --json`` as attributes (and
    :attr:`summary`), plus the final belief and the robots' trajectories as numpy arrays.
    Results copy and pickle (to send them to another process)."""

    __slots__ = ("summary", "belief", "trajectories")

    def __init__(
        self,
        summary: Dict[str, Any],
        belief: np.ndarray,
        trajectories: Optional[List[np.ndarray]],
    ) -> None:
        #: The JSON summary as a dict, key for key as the CLI prints it.
        self.summary = summary
        #: Final belief, (height, width) uint8: 0 unknown, 1 free, 2 occupied.
        self.belief = belief
        #: Per robot an (n, 2) int32 array of the (x, y) cells it stood on, start first.
        self.trajectories = trajectories

    def __getattr__(self, name: str) -> Any:
        # Reached only for names that are not attributes. Dunder names (copy's and pickle's
        # lookups) and the slots themselves (unset on an instance being copied) are never
        # summary fields: reading ``self.summary`` there would recurse.
        if name.startswith("__") or name in ExploreResult.__slots__:
            raise AttributeError(name)
        try:
            return self.summary[name]
        except KeyError:
            raise AttributeError(name) from None

    def __reduce__(self) -> Tuple[Any, ...]:
        """Pickled and copied as its summary, belief and trajectories."""
        return (ExploreResult, (self.summary, self.belief, self.trajectories))

    def __dir__(self) -> Iterable[str]:
        return list(self.summary) + ["summary", "belief", "trajectories", "to_json", "row"]

    def to_json(self) -> str:
        """The summary as JSON text."""
        return json.dumps(self.summary)

    def row(self) -> Dict[str, Any]:
        """The summary flattened into one row (``map.accuracy`` → ``map_accuracy``)."""
        return _flatten(self.summary)

    def __repr__(self) -> str:
        s = self.summary
        return (
            f"ExploreResult(env={s['env']!r}, strategy={s['strategy']!r}, seed={s['seed']}, "
            f"reason={s['reason']!r}, coverage={s['coverage']}, "
            f"path_length_m={s['path_length_m']})"
        )


def _flatten(d: Mapping[str, Any], prefix: str = "") -> Dict[str, Any]:
    """Nested dicts become prefixed columns; lists stay as values."""
    out: Dict[str, Any] = {}
    for k, v in d.items():
        key = f"{prefix}{k}"
        if isinstance(v, Mapping):
            out.update(_flatten(v, key + "_"))
        else:
            out[key] = v
    return out


def _kwargs(
    strategy: str,
    sensor: str,
    robots: int,
    seed: int,
    start: Optional[CellArg],
    belief: Optional[str],
    sensing: Optional[str],
    clearance: float,
    speed: float,
    s_max: Optional[int],
    goal: Optional[float],
    max_moves: int,
    motion: Optional[str] = None,
    coverage: Optional[str] = None,
) -> Dict[str, Any]:
    return dict(
        motion=motion,
        coverage=coverage,
        strategy=strategy,
        sensor=sensor,
        robots=robots,
        seed=seed,
        start=start,
        belief=belief,
        sensing=sensing,
        clearance=clearance,
        speed=speed,
        s_max=s_max,
        goal=goal,
        max_moves=max_moves,
    )


def _count(
    name: str,
    value: Any,
    least: int,
    what: str = "",
    most: int = sys.maxsize,
    optional: bool = True,
) -> None:
    """Raise TypeError unless ``value`` is an int (or None, if ``optional``), ValueError if
    below ``least`` or above ``most`` (the message names the argument, as the CLI's do)."""
    if value is None and optional:
        return
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name}: expected an int, found {type(value).__name__}")
    if value < least:
        raise ValueError(f"{name}: expected at least {least}{what}, found {value}")
    if value > most:
        many = f"{what}s" if what else ""
        raise ValueError(f"{name}: expected at most {most}{many}, found {value}")


def _flag(name: str, value: Any) -> bool:
    """``value`` as a bool (Python's or numpy's); TypeError naming ``name`` otherwise."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name}: expected a bool, found {type(value).__name__}")
    return bool(value)


def _text(name: str, value: Any, what: str = "a str") -> str:
    """``value`` (a str); TypeError naming ``name`` otherwise (``what`` says what was
    expected)."""
    if not isinstance(value, str):
        raise TypeError(f"{name}: expected {what}, found {type(value).__name__}")
    return value


def _path(name: str, value: Any) -> None:
    """Raise TypeError naming ``name`` unless ``value`` is a path: a str or an
    ``os.PathLike`` (a ``pathlib.Path``)."""
    if not isinstance(value, (str, os.PathLike)):
        raise TypeError(
            f"{name}: expected a path (a str or os.PathLike), found {type(value).__name__}"
        )


def _real(name: str, value: Any, what: str = "a number") -> float:
    """``value`` (an int, a float or a numpy number, not a bool) as a float; TypeError
    naming ``name`` otherwise."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(
        value, (int, float, np.integer, np.floating)
    ):
        raise TypeError(f"{name}: expected {what}, found {type(value).__name__}")
    return _float(value)


def _float(value: Any) -> float:
    """``value`` (a number) as a float: an int beyond a float's range is infinite, as
    ``float("1e400")`` and the CLI's ``1e400`` are, so that the argument's range check
    refuses it with its message."""
    try:
        return float(value)
    except OverflowError:
        return float("-inf") if value < 0 else float("inf")


#: A pair of numbers: a tuple, a list or a numpy array of two.
Pair = Union[Tuple[float, float], Sequence[float], np.ndarray]

#: A cell (x, y): a tuple, a list or a numpy array of two integers.
CellArg = Union[Tuple[int, int], Sequence[int], np.ndarray]


def _pair(name: str, value: Any, what: str) -> Optional[Tuple[float, float]]:
    """None, or ``value`` (any sequence of two numbers: a tuple, a list, a numpy array) as a
    tuple of floats; TypeError or ValueError naming ``name`` otherwise."""
    if value is None:
        return None
    # A mapping or a set has a length of two too, but no first and second item: unpacking
    # gives its keys, or its items in an order of its own ({30, 12} gives 12 first).
    if isinstance(value, (str, bytes, Mapping, AbstractSet)) or not hasattr(value, "__len__"):
        raise TypeError(f"{name}: expected {what}, found {type(value).__name__}")
    if len(value) != 2:
        raise ValueError(f"{name}: expected {what}, found {len(value)} values")
    x, y = value
    for v in (x, y):
        if isinstance(v, (bool, np.bool_)) or not isinstance(
            v, (int, float, np.integer, np.floating)
        ):
            raise TypeError(
                f"{name}: expected {what}, found {v!r} ({type(v).__name__}) among its values"
            )
    return _float(x), _float(y)


def _real_or_none(name: str, value: Any, what: str = "a number") -> Optional[float]:
    """None, or ``value`` as :func:`_real` reads it."""
    return None if value is None else _real(name, value, what + " or None")


def _check_memory_mb(memory_mb: Any) -> Optional[int]:
    """``memory_mb`` (None or a positive Python or numpy int, MiB, as the CLI's
    ``--memory-mb``) as an int."""
    if memory_mb is None:
        return None
    if isinstance(memory_mb, bool) or not isinstance(memory_mb, (int, np.integer)):
        raise TypeError(f"memory_mb: expected an int, found {type(memory_mb).__name__}")
    if memory_mb < 1:
        raise ValueError(f"memory_mb: expected a positive number of MiB, found {memory_mb}")
    if memory_mb >= 2**64:
        raise ValueError(f"memory_mb: expected less than 2^64 MiB, found {memory_mb}")
    return int(memory_mb)


def explore(
    map: Map,
    strategy: str = "cf-rr",
    sensor: str = "los:r=5",
    robots: int = 1,
    seed: int = 0,
    *,
    start: Optional[CellArg] = None,
    belief: Optional[str] = None,
    sensing: Optional[str] = None,
    clearance: float = 0.0,
    speed: float = 1.0,
    s_max: Optional[int] = None,
    goal: Optional[float] = None,
    max_moves: int = 10_000_000,
    motion: Optional[str] = None,
    coverage: Optional[str] = None,
    trajectories: bool = True,
    timing: bool = False,
    clutter: Optional[Map] = None,
    memory_mb: Optional[int] = None,
) -> ExploreResult:
    """Explore ``map`` once, as ``frontier explore`` does with the same flags.

    Defaults are the CLI's. ``start`` is the first robot's cell (x, y); the others start at
    the nearest free cells around it. ``clutter`` is a map of the same size whose occupied
    cells are obstacles off the laser plane (tables, chairs), as ``--clutter-map``: planar
    sensors miss them, sonar hears them, the robot's body bumps into them. ``motion``
    (``"grid"`` or ``"any-angle"``) and ``coverage`` (``"reachable"`` or ``"known"``,
    Explore-Bench's) are ``--motion`` and ``--coverage``. ``timing=True`` fills the
    wall-clock fields
    (``decide_ms``, ``timing_ms``), which are ``None`` otherwise so that equal runs give
    equal results. A run whose estimated peak memory exceeds ``memory_mb`` MiB (the CLI's
    ``--memory-mb``) or what the machine has available is refused before it starts; one
    whose trajectories outgrow that memory stops there (``reason`` ``"trace limit"``, with a
    ``RuntimeWarning``). Raises
    ``ValueError`` with the CLI's message for a bad argument, ``TypeError`` naming it for
    one of a wrong type."""
    if not isinstance(map, Map):
        raise TypeError(f"map: expected a frontier.Map, found {type(map).__name__}")
    memory_mb = _check_memory_mb(memory_mb)
    trajectories = _flag("trajectories", trajectories)
    timing = _flag("timing", timing)
    kw = _kwargs(
        strategy, sensor, robots, seed, start, belief, sensing, clearance, speed, s_max, goal,
        max_moves, motion, coverage,
    )
    kw["trajectories"] = trajectories
    if clutter is not None:
        kw["clutter"] = clutter
    text, belief_arr, trails = _native.explore(map, kw, timing, memory_mb)
    result = ExploreResult(json.loads(text), belief_arr, trails)
    if result.summary["reason"] == "trace limit":
        warnings.warn(
            f"the run stopped after {result.summary['moves']} moves, before it explored "
            "everything: the trajectories filled the memory left beside the run (the "
            "strategy moved far more than expected); with trajectories=False, or more "
            "memory_mb, it runs to the end",
            RuntimeWarning,
            stacklevel=2,
        )
    return result


#: Keys a run of :func:`explore_many` may not give, and what to do instead: the arguments
#: of the whole batch (a run's own would be copied into its row as a tag and do nothing)
#: and ``trajectories``.
_BATCH_ARGS = {
    "timing": "an argument of the whole batch: explore_many(runs, timing=...)",
    "memory_mb": "an argument of the whole batch: explore_many(runs, memory_mb=...)",
    "threads": "an argument of the whole batch: explore_many(runs, threads=...)",
    "progress": "an argument of the whole batch: explore_many(runs, progress=...)",
    "trajectories": "explore_many returns summaries only (no trajectories): drop it, or "
    "call explore for the runs whose trajectories you need",
}


@functools.lru_cache(maxsize=None)
def _summary_columns() -> FrozenSet[str]:
    """The columns of :func:`explore_many`'s rows (the flattened summary, whose keys every
    run has), read from a run on a 3 x 3 room."""
    room = Map.from_numpy(np.zeros((3, 3), bool), 1.0)
    text, _, _ = _native.explore(room, {"trajectories": False})
    return frozenset(_flatten(json.loads(text)))


#: The most threads :func:`explore_many` takes (far more than any machine's cores).
_MAX_THREADS = 4096


def explore_many(
    runs: Sequence[Mapping[str, Any]],
    threads: Optional[int] = None,
    timing: bool = False,
    memory_mb: Optional[int] = None,
    progress: Union[bool, Callable[[int, int], Any], None] = None,
) -> List[Dict[str, Any]]:
    """Run many explorations in parallel on Rust threads (the GIL released).

    ``threads`` (default: one per core, at most 4096) is capped at the number of runs.
    Each run is a mapping with a ``map`` (a :class:`Map`) and any keyword arguments of
    :func:`explore` but ``trajectories``, ``timing`` and ``memory_mb`` (``timing``,
    ``memory_mb``, ``threads`` and ``progress`` are the batch's arguments; a run giving one
    is a TypeError); other keys
    (e.g. ``tag``) are copied into the run's row, and one named as a column of the summary
    (``env``, ``reason``, ``map_accuracy``, ...) is refused with a ValueError, since the
    summary would overwrite it. Returns one flat row per run, in order —
    ``pandas.DataFrame(rows)`` makes the table. All runs are checked before any starts, and
    the batch is refused when its largest runs, one per thread, would need more than
    ``memory_mb`` MiB or the memory the machine has available.

    ``progress=True`` shows a bar (tqdm's when it is installed, else a line on standard
    error); a callable is called as ``progress(done, total)`` about ten times a second and
    at the end. Ctrl-C (``KeyboardInterrupt``), or an exception from the callable, stops the
    batch within milliseconds and is raised; the results are the same with or without
    progress."""
    keys = {
        "strategy", "sensor", "robots", "seed", "start", "belief", "sensing", "clearance",
        "speed", "s_max", "goal", "max_moves", "motion", "coverage", "clutter",
    }
    if isinstance(runs, (str, bytes, Mapping)) or not isinstance(runs, Iterable):
        raise TypeError(
            f"runs: expected a list of runs (mappings with a 'map'), found {type(runs).__name__}"
        )
    native_runs = []
    extras = []
    for i, run in enumerate(runs):
        if not isinstance(run, Mapping):
            raise TypeError(f"run {i}: expected a mapping with a 'map', found {type(run).__name__}")
        if "map" not in run:
            raise TypeError(f"run {i}: missing 'map'")
        m = run["map"]
        if not isinstance(m, Map):
            raise TypeError(f"run {i}: map: expected a frontier.Map, found {type(m).__name__}")
        for k in _BATCH_ARGS:
            if k in run:
                raise TypeError(f"run {i}: {k!r}: {_BATCH_ARGS[k]}")
        native_runs.append((m, {k: v for k, v in run.items() if k in keys}))
        extra = {k: v for k, v in run.items() if k not in keys and k != "map"}
        for k in extra:
            if k in _summary_columns():
                raise ValueError(
                    f"run {i}: the tag {k!r} is also a column of the run's summary, which "
                    "would overwrite it; rename the tag"
                )
            near = difflib.get_close_matches(str(k), sorted(keys), n=1, cutoff=0.8)
            if near:
                warnings.warn(
                    f"run {i}: {k!r} is not an option of explore and is copied into the row "
                    f"as a tag; did you mean {near[0]!r}?",
                    stacklevel=2,
                )
        extras.append(extra)
    memory_mb = _check_memory_mb(memory_mb)
    timing = _flag("timing", timing)
    _count("threads", threads, 1, most=_MAX_THREADS)
    report, close = _progress(progress, len(native_runs))
    try:
        texts = _native.explore_many(native_runs, threads, timing, memory_mb, report)
    finally:
        close()
    rows = []
    for text, extra in zip(texts, extras):
        row = dict(extra)
        row.update(_flatten(json.loads(text)))
        rows.append(row)
    return rows


def _progress(
    progress: Union[bool, Callable[[int, int], Any], None], total: int
) -> Tuple[Optional[Callable[[int, int], Any]], Callable[[], Any]]:
    """The native progress callback for ``explore_many``'s ``progress`` and a function that
    closes the display."""
    if isinstance(progress, np.bool_):
        progress = bool(progress)
    if progress is None or progress is False:
        return None, lambda: None
    if callable(progress) and progress is not True:
        return progress, lambda: None
    if progress is not True:
        raise TypeError(
            f"progress: expected True, False, None or a callable, found {type(progress).__name__}"
        )
    try:
        from tqdm.auto import tqdm
    except ImportError:
        def line(done: int, n: int) -> None:
            sys.stderr.write(f"\rexplore_many: {done}/{n} runs")
            sys.stderr.flush()

        return line, lambda: sys.stderr.write("\n")
    bar = tqdm(total=total, unit="run", desc="explore_many")

    def update(done: int, n: int) -> None:
        bar.update(done - bar.n)

    return update, bar.close


_SUBMODULES = ("bench", "gym", "pettingzoo")


def __getattr__(name: str) -> Any:
    """``frontier.bench``, ``frontier.gym`` and ``frontier.pettingzoo`` work after a bare
    ``import frontier``: each is imported on first use, so that ``import frontier`` needs
    neither pandas nor Gymnasium nor PettingZoo."""
    if name in _SUBMODULES:
        import importlib

        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> List[str]:
    return sorted(set(globals()) | set(_SUBMODULES))


def strategies() -> List[Tuple[str, str]]:
    """Every strategy name a run takes, as (name, description) pairs: the presets ``frontier
    list`` prints, then each team name ``<assigner>-<candidates>`` (``ha-rfe``) spelled out."""
    return list(_native.strategies())
