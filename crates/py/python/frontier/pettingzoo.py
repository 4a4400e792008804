"""A PettingZoo ``ParallelEnv`` for teams: one agent per robot, one team decision per step.

The robots explore together through the one loop (``sim::Session``), so they move
concurrently in the order of their clocks, exactly as in ``frontier.explore(...,
robots=m)``. A step is the team's next decision: the robots whose decision is due
(:meth:`ExploreParallelEnv.deciding`; their ``action_mask`` is not empty) go to their chosen
candidates, and each needs an action; the others' actions are ignored. Every agent gets
the team's reward (newly known reachable free area in m² minus λ × metres travelled by the
team). Each observation is :class:`frontier.gym.ExploreEnv`'s for that robot plus ``team``:
the (x, y, heading) of every robot. :class:`~frontier.gym.Baseline` works here too
(``Baseline("ha-cc")(env)``): the preset's assigner chooses for the deciding robots
together.
"""

from __future__ import annotations

from typing import Any, Dict, List, Mapping, Optional, Tuple

import gymnasium
import numpy as np
from gymnasium import spaces
from gymnasium.utils import seeding
from pettingzoo import ParallelEnv

from . import Pair, _native
from .gym import (
    MapsArg,
    _action,
    _check_run,
    _core_args,
    _episode_seed,
    _map_index,
    _map_option,
    _ONE_CALL,
    _pose_bounds,
    _seed,
    _spaces,
)

__all__ = ["ExploreParallelEnv"]


class ExploreParallelEnv(ParallelEnv):
    """A team of ``robots`` exploring an unknown map; agents ``robot_0`` … ``robot_{m-1}``.

    Takes :class:`frontier.gym.ExploreEnv`'s arguments but ``invalid_action`` (an index
    beyond the offered candidates is always taken modulo their number) and ``render_mode``
    (nothing is rendered); ``strategy`` defaults to ``"nearest"``, whose candidates are
    every frontier cell; plus ``robots``;
    ``memory_mb`` bounds the team's run and its ``robots`` observations together."""

    metadata = {"name": "frontier_explore_v0", "render_modes": [], "is_parallelizable": True}

    def __init__(
        self,
        maps: MapsArg = None,
        *,
        robots: int = 2,
        size: Optional[Pair] = None,
        resolution: Optional[float] = None,
        dungeon: bool = False,
        strategy: str = "nearest",
        sensor: str = "los:r=5",
        candidates: Optional[str] = None,
        k: int = 16,
        view: Optional[int] = None,
        lam: float = 0.0,
        max_path_m: Optional[float] = None,
        max_steps: Optional[int] = None,
        gain: bool = False,
        memory_mb: Optional[int] = None,
        **run: Any,
    ) -> None:
        _check_run("ExploreParallelEnv", run)
        run = dict(run, robots=robots)
        self._core = _native.TeamEnvCore(
            **_core_args(
                maps, size, resolution, strategy, sensor, candidates, k, view, lam,
                max_path_m, max_steps, gain, run, dungeon=dungeon, memory_mb=memory_mb,
            )
        )
        m = self._core.robots
        self.possible_agents: List[str] = [f"robot_{i}" for i in range(m)]
        self.agents: List[str] = []
        single, self._action_space = _spaces(self._core.shape, self._core.k, view)
        low, high = _pose_bounds(None if view is not None else self._core.shape)
        team = spaces.Box(np.tile(low, (m, 1)), np.tile(high, (m, 1)), (m, 3), np.float32)
        self._observation_space = spaces.Dict(dict(single.spaces, team=team))
        self._rng: Optional[np.random.Generator] = None
        self._obs: List[Dict[str, np.ndarray]] = []
        self._seed = 0

    def observation_space(self, agent: str) -> spaces.Dict:
        """Every agent's observation space (the same for all)."""
        return self._observation_space

    def action_space(self, agent: str) -> spaces.Discrete:
        """Every agent's action space: ``Discrete(k)``."""
        return self._action_space

    def _infos(self) -> Dict[str, Dict[str, Any]]:
        info = self._core.info()
        info["seed"] = self._seed
        deciding = self._core.deciding()
        return {a: dict(info, deciding=d) for a, d in zip(self.possible_agents, deciding)}

    def reset(
        self, seed: Optional[int] = None, options: Optional[Dict[str, Any]] = None
    ) -> Tuple[Dict[str, Dict[str, np.ndarray]], Dict[str, Dict[str, Any]]]:
        """Start an episode; the same ``seed`` gives the same map, starts and episode.
        ``options={"map": i}`` runs it on map ``i`` of the list or folder (:attr:`map_names`).
        ``seed`` is None or a non-negative int (Python's or numpy's). A reset that raises
        (a map file that cannot be read) leaves no episode and no agents: ``step`` then
        raises ``ResetNeeded`` until a reset succeeds."""
        seed = _seed("seed", seed)
        index = _map_index(_map_option(options))
        if seed is not None or self._rng is None:
            self._rng = seeding.np_random(seed)[0]
        episode = _episode_seed(self._rng)
        self._obs, self.agents = [], []
        with _ONE_CALL:
            self._obs = self._core.reset(episode, map=index)
            self._seed = episode
            self.agents = list(self.possible_agents)
            return dict(zip(self.possible_agents, self._obs)), self._infos()

    @property
    def map_names(self) -> Optional[List[str]]:
        """The names of the maps of a list or folder, by index (None for generated maps)."""
        return self._core.map_names

    def deciding(self) -> List[str]:
        """The agents whose actions count at this step."""
        return [a for a, d in zip(self.possible_agents, self._core.deciding()) if d]

    def step(self, actions: Dict[str, Any]) -> Tuple[
        Dict[str, Dict[str, np.ndarray]],
        Dict[str, float],
        Dict[str, bool],
        Dict[str, bool],
        Dict[str, Dict[str, Any]],
    ]:
        """The team's next decision: deciding agents go to their candidates (an index beyond
        the offered ones is taken modulo their number). Every deciding agent
        (:meth:`deciding`) needs an action, a ValueError naming it otherwise; the others'
        are ignored (any value, None too) and may be left out."""
        if not isinstance(actions, Mapping):
            raise TypeError(f"actions: expected a dict of agent -> action, found {type(actions).__name__}")
        unknown = [a for a in actions if a not in self.possible_agents]
        if unknown:
            raise ValueError(
                f"actions: unknown agent {unknown[0]!r} (agents: {', '.join(self.possible_agents)})"
            )
        if not self._obs:
            raise gymnasium.error.ResetNeeded("step: call reset() before step()")
        due = self.deciding() if self.agents else []
        acts = [
            _action(actions[a], f"{a}: action") if a in due and a in actions else 0
            for a in self.possible_agents
        ]
        missing = [a for a in due if a not in actions]
        if missing:
            raise ValueError(
                f"actions: missing agent {missing[0]!r}, whose decision is due "
                f"(deciding: {', '.join(due)})"
            )
        with _ONE_CALL:
            self._obs, reward, terminated, truncated = self._core.step(acts, True)
            infos = self._infos()
        agents = self.possible_agents
        obs = dict(zip(agents, self._obs))
        self.agents = [] if terminated or truncated else list(agents)
        return (
            obs,
            {a: reward for a in agents},
            {a: terminated for a in agents},
            {a: truncated for a in agents},
            infos,
        )

    def baseline_actions(self, preset: str) -> Dict[str, int]:
        """Every agent's action under ``preset`` (the deciding ones chosen together)."""
        if not self._obs:
            raise gymnasium.error.ResetNeeded("baseline_actions: call reset() before asking")
        with _ONE_CALL:
            return dict(zip(self.possible_agents, self._core.baseline_actions(preset)))
