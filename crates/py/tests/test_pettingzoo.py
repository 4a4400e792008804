"""frontier.pettingzoo: PettingZoo's API test, determinism, team baselines equal to explore."""

import os

import gymnasium
import numpy as np
import pytest

pytest.importorskip("pettingzoo")
from pettingzoo.test import parallel_api_test  # noqa: E402

import frontier  # noqa: E402
from frontier.gym import Baseline  # noqa: E402
from frontier.pettingzoo import ExploreParallelEnv  # noqa: E402


def play(env, seed, policy):
    obs, infos = env.reset(seed=seed)
    trace = []
    while env.agents:
        actions = policy(env, obs)
        obs, rewards, terms, truncs, infos = env.step(actions)
        trace.append((rewards["robot_0"], tuple(sorted(env.deciding()))))
    return trace, infos["robot_0"]


def test_parallel_api(office):
    parallel_api_test(ExploreParallelEnv(office, robots=3, k=8), num_cycles=50)


def test_observations_are_in_the_space_with_the_team_on_the_map(office):
    env = ExploreParallelEnv(office, robots=3, k=8)
    space = env.observation_space("robot_0")
    h, w = space["belief"].shape
    assert space["team"].high[:, :2].tolist() == [[w - 1, h - 1]] * 3
    obs, _ = env.reset(seed=5)
    while env.agents:
        assert all(space.contains(o) for o in obs.values())
        obs, *_ = env.step({a: 0 for a in env.agents})


def test_same_seed_identical_episodes(office):
    env = ExploreParallelEnv(office, robots=2, k=8)
    first = lambda env, obs: {a: 0 for a in env.agents}  # noqa: E731
    assert play(env, 4, first) == play(env, 4, first)


@pytest.mark.parametrize("preset", ["nearest", "greedy", "ha-cc", "ga-rfe", "sga-rfe"])
def test_team_baseline_equals_explore(office, preset):
    env = ExploreParallelEnv(office, robots=3, strategy=preset, k=4096)
    trace, info = play(env, 2, lambda env, obs: Baseline(preset)(env))
    ref = frontier.explore(office, strategy=preset, robots=3, seed=info["seed"])
    assert info["path_length_m"] == pytest.approx(ref.path_length_m, abs=1e-4)
    assert (info["decisions"], info["moves"]) == (ref.decisions, ref.moves)
    assert info["coverage"] == pytest.approx(ref.coverage, abs=1e-6)


def test_actions_beyond_the_offer_wrap(office):
    """An agent's index beyond (or below) its n offered candidates is taken modulo n."""
    wrapping, plain = (ExploreParallelEnv(office, robots=2, k=8) for _ in range(2))
    obs, _ = wrapping.reset(seed=5)
    plain.reset(seed=5)
    for step in range(12):
        given, wanted = {}, {}
        for agent in wrapping.agents:
            n = int(obs[agent]["action_mask"].sum())
            a = [n + 3, -1, 2 * n, 0][step % 4]
            given[agent], wanted[agent] = a, (a % n if n else 0)
        obs, rewards, terms, truncs, _ = wrapping.step(given)
        want, want_rewards, *_ = plain.step(wanted)
        for agent in obs:
            assert obs[agent]["candidates"].tobytes() == want[agent]["candidates"].tobytes()
        assert rewards == want_rewards
        if not wrapping.agents:
            break


def test_only_deciding_agents_have_candidates(office):
    env = ExploreParallelEnv(office, robots=3, k=8, strategy="nearest")
    obs, _ = env.reset(seed=0)
    for _ in range(10):
        deciding = set(env.deciding())
        for agent, o in obs.items():
            assert (o["action_mask"].sum() > 0) == (agent in deciding)
            assert o["team"].shape == (3, 3)
        obs, *_ = env.step({a: 0 for a in env.agents})
        if not env.agents:
            break
    with pytest.raises(ValueError, match="--robots: expected at least 1, found 0"):
        ExploreParallelEnv(office, robots=0)
    assert np.all(obs["robot_0"]["team"] == obs["robot_1"]["team"])


@pytest.mark.skipif(not os.path.exists("/proc/meminfo"), reason="available memory unknown")
def test_memory_is_estimated_before_it_is_spent():
    with pytest.raises(ValueError, match=r"running this environment of 5 robots \(.*k = 10000000000\) "
                       r"needs about \d+ MiB"):
        ExploreParallelEnv("office", robots=5, k=10**10)


def test_memory_mb_bounds_the_team_environment(office):
    """Regression: the team environment took no memory_mb; a budget too small for it is
    refused when it is made, naming it, and one that holds it changes no episode."""
    with pytest.raises(ValueError, match=r"running this environment of 3 robots \(.*\) needs "
                       r"about 18 MiB, more than --memory-mb 16; use a smaller k"):
        ExploreParallelEnv(office, robots=3, memory_mb=16)
    with pytest.raises(TypeError, match="memory_mb: expected an int, found bool"):
        ExploreParallelEnv(office, robots=3, memory_mb=True)
    envs = [ExploreParallelEnv(office, robots=3, memory_mb=mb) for mb in (np.int32(64), None)]
    obs = [e.reset(seed=4)[0] for e in envs]
    while True:
        assert all(obs[0][a][key].tobytes() == obs[1][a][key].tobytes()
                   for a in obs[0] for key in obs[0][a])
        acts = Baseline("nearest")(envs[1])
        steps = [e.step(acts) for e in envs]
        assert steps[0][1:4] == steps[1][1:4]
        obs = [s[0] for s in steps]
        if not envs[1].agents:
            break


def test_bad_actions_name_the_agent(office):
    env = ExploreParallelEnv(office, robots=2)
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r"actions: unknown agent 'robot_9' \(agents: robot_0, robot_1\)"):
        env.step({"robot_9": 0})
    with pytest.raises(TypeError, match="actions: expected a dict of agent -> action, found list"):
        env.step([0, 0])
    with pytest.raises(TypeError, match="action: expected an int, found str"):
        env.step({"robot_0": "left"})


def test_team_observations_brought_up_to_date_equal_ones_written_whole(office):
    """Each robot's kept arrays are brought up to date with what changed since they were
    written (the layers are the team's); every observation held, each is written whole."""
    part, whole = (ExploreParallelEnv(office, robots=3, k=8) for _ in range(2))
    got, _ = part.reset(seed=6)
    want, _ = whole.reset(seed=6)
    every = [want]
    rng = np.random.default_rng(2)
    held = []
    while whole.agents:
        for agent in want:
            for key in ("belief", "frontier"):
                assert np.array_equal(got[agent][key], want[agent][key]), (agent, key)
        actions = Baseline("greedy")(whole)
        got, *_ = part.step(actions)
        want, *_ = whole.step(actions)
        every.append(want)
        if rng.random() < 0.4:
            held.append(got[rng.choice(list(got))])
        if held and rng.random() < 0.4:
            held.pop(int(rng.integers(len(held))))
    assert len(every) > 20


def test_regression_team_episode_ended_at_reset_terminates_at_first_step():
    a = np.ones((12, 12), bool)
    a[4:7, 4:7] = False
    env = ExploreParallelEnv(frontier.Map.from_numpy(a, 0.1), robots=2)
    env.reset(seed=1)
    assert env.deciding() == [] and Baseline("nearest")(env) == {"robot_0": 0, "robot_1": 0}
    _, rewards, terms, truncs, _ = env.step({"robot_0": 0, "robot_1": 0})
    assert rewards == {"robot_0": 0.0, "robot_1": 0.0}
    assert all(terms.values()) and not any(truncs.values()) and env.agents == []


def test_regression_arguments_of_a_wrong_type_name_the_argument(office):
    """Regression: a preset of another type gave PyO3's "'int' object is not an instance of
    'str'", and robots=True made a team of one."""
    env = ExploreParallelEnv(office, robots=2)
    env.reset(seed=0)
    with pytest.raises(TypeError, match="^preset: expected a str, found int"):
        env.baseline_actions(3)
    with pytest.raises(TypeError, match="^robots: expected an int, found bool"):
        ExploreParallelEnv(office, robots=True)
    with pytest.raises(TypeError, match="^sensor: expected a str, found float"):
        ExploreParallelEnv(office, sensor=1.0)


def test_regression_reset_seed_is_checked_and_numpy_integers_are_taken(office):
    """Regression: Gymnasium's seeding raised its own ``gymnasium.error.Error`` for a str, a
    float, a negative or a numpy integer seed, and took True as the seed 1."""
    env = ExploreParallelEnv(office, robots=2, k=4)
    for seed, error, message in [
        ("x", TypeError, "seed: expected an int or None, found str"),
        (0.5, TypeError, "seed: expected an int or None, found float"),
        (True, TypeError, "seed: expected an int or None, found bool"),
        (-1, ValueError, "seed: expected a non-negative int, found -1"),
    ]:
        with pytest.raises(error, match=f"^{message}"):
            env.reset(seed=seed)
    assert env.reset(seed=np.int64(4))[1] == env.reset(seed=4)[1]


def test_regression_a_bad_action_names_its_agent(office):
    """Regression: an agent's action beyond 64-bit integers raised OverflowError, and a bad
    action's message did not say whose it was."""
    env = ExploreParallelEnv(office, robots=2, k=4)
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r"^robot_1: action: expected an integer in "
                       r"-2\^63..2\^63, found 18446744073709551616$"):
        env.step({"robot_0": 0, "robot_1": 2**64})
    with pytest.raises(TypeError, match="^robot_0: action: expected an int, found NoneType$"):
        env.step({"robot_0": None, "robot_1": 0})


def test_regression_a_deciding_agent_left_out_of_the_actions_is_a_value_error(office):
    """Regression: ``step({})`` sent every deciding robot to its candidate 0, an action no
    policy chose; a deciding agent's action must now be given, the others' may be left out."""
    env = ExploreParallelEnv(office, robots=2, k=4)
    env.reset(seed=0)
    assert env.deciding() == ["robot_0", "robot_1"]
    with pytest.raises(ValueError, match=r"^actions: missing agent 'robot_1', whose decision is "
                       r"due \(deciding: robot_0, robot_1\)$"):
        env.step({"robot_0": 0})
    with pytest.raises(ValueError, match="^actions: missing agent 'robot_0'"):
        env.step({})
    # A step in which one robot decides alone takes its action without the other's.
    for _ in range(200):
        if len(env.deciding()) == 1:
            break
        env.step(Baseline("nearest")(env))
    (alone,) = env.deciding()
    other = next(a for a in env.possible_agents if a != alone)
    with pytest.raises(ValueError, match=f"^actions: missing agent '{alone}'"):
        env.step({other: 0})
    env.step({alone: 0})


def test_regression_run_options_out_of_range_are_refused_at_construction(office):
    """Regression: ``speed=0`` built the team environment, and every reset then failed."""
    with pytest.raises(ValueError, match="^--speed: expected a positive number of metres per "
                       "second, from 0.001 to 1000, found 0"):
        ExploreParallelEnv(office, robots=2, speed=0)


def test_regression_a_failed_reset_leaves_no_agents(office, tmp_path):
    """Regression: a reset that raised (a folder's unreadable file) kept the agents and the
    previous episode, which step() went on with."""
    office.save(tmp_path / "a.pgm")
    office.save(tmp_path / "b.pgm")
    (tmp_path / "c.pgm").write_bytes(b"P5 not a picture")
    env = ExploreParallelEnv(str(tmp_path), robots=2, resolution=0.25, view=16, k=4)
    env.reset(seed=0, options={"map": 0})
    env.step(Baseline("nearest")(env))
    with pytest.raises(ValueError, match="c.pgm"):
        env.reset(seed=9, options={"map": 2})
    assert env.agents == []
    with pytest.raises(gymnasium.error.ResetNeeded):
        env.step({a: 0 for a in env.possible_agents})


def test_regression_agents_not_deciding_may_send_none(office):
    """Regression: the actions of agents whose decision is not due are ignored, yet None
    for them raised a TypeError."""
    env = ExploreParallelEnv(office, robots=3, k=8, strategy="nearest")
    env.reset(seed=0)
    plain = ExploreParallelEnv(office, robots=3, k=8, strategy="nearest")
    plain.reset(seed=0)
    waited = 0
    for _ in range(30):
        due = set(env.deciding())
        waited += len(env.agents) - len(due)
        got = env.step({a: (0 if a in due else None) for a in env.agents})
        want = plain.step({a: 0 for a in plain.agents})
        assert got[1] == want[1]
        if not env.agents:
            break
    assert waited > 0
